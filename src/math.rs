//! Transcendental functions of the engine, from the `libm` crate (a Rust port of musl's libm):
//! the same code, hence the same bits, on every target. std's `f64::sin` etc. call the
//! platform's C library (glibc on linux64, msvcrt on win64), whose last bits differ: the
//! paper's Case 3 moved by 7.6e-10 m between the two FMU binaries before this module
//! (docs/platforms.md). `tests/portable_math.rs` keeps std's versions out of `src/` (outside test
//! modules). sqrt is correctly rounded everywhere and stays std's. Code generic over num-dual
//! numbers takes sin and cos from [`sin_cos_dual`] (num-dual's own call std's).

use num_dual::DualNum;

/// sin x (x in rad).
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// cos x (x in rad).
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// (sin x, cos x).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// acos x in [0, π] (x in [−1, 1]).
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// atan2(y, x) in (−π, π].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// asin x in [−π/2, π/2].
#[inline]
pub fn asin(x: f64) -> f64 {
    libm::asin(x)
}

/// eˣ.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// sinh x.
#[inline]
pub fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}

/// cosh x.
#[inline]
pub fn cosh(x: f64) -> f64 {
    libm::cosh(x)
}

/// tanh x.
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

/// xʸ.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// (sin x, cos x) of a num-dual number (or f64) from this module's f64 functions: with r the
/// real part and d = x − r the infinitesimal part, sin x = sin r·cos d + cos r·sin d, the
/// series of sin d and cos d ending at d^NDERIV (exact: higher powers of d vanish). For f64,
/// d = 0 and the result is bit for bit [`sin_cos`].
pub fn sin_cos_dual<T: DualNum<Primitive = f64> + Copy>(x: T) -> (T, T) {
    let r = x.re();
    let (s, c) = sin_cos(r);
    let d = x - T::from(r);
    let (mut sd, mut cd) = (T::zero(), T::one());
    let mut term = T::one(); // d^k / k!
    for k in 1..=T::NDERIV {
        term = term * d / k as f64;
        match k % 4 {
            1 => sd += term,
            2 => cd -= term,
            3 => sd -= term,
            _ => cd += term,
        }
    }
    (
        T::from(s) * cd + T::from(c) * sd,
        T::from(c) * cd - T::from(s) * sd,
    )
}

/// atan2(y, x) in (−π, π] of num-dual numbers (or f64), for code generic over them: the real
/// part is [`atan2`] of the real parts; with ρ = √(x² + y²) (dual), sin δ = (y cos r − x sin r)/ρ
/// is the sine of the infinitesimal rest δ = φ − r exactly, and δ = asin(sin δ) by its series
/// (sin δ less its rounding-level real part, so the series ends at power NDERIV: exact, higher
/// powers vanish). For f64 the result is bit for bit [`atan2`]. Derivatives are those of the
/// angle wherever (x, y) ≠ 0.
pub fn atan2_dual<T: DualNum<Primitive = f64> + Copy>(y: T, x: T) -> T {
    let r = atan2(y.re(), x.re());
    if T::NDERIV == 0 {
        return T::from(r);
    }
    let (s, c) = sin_cos(r);
    let rho = (x * x + y * y).sqrt();
    let sd = (y * c - x * s) / rho;
    let d = sd - T::from(sd.re());
    // asin d = Σ_k (2k)!/(4^k (k!)² (2k + 1)) d^(2k+1)
    let mut delta = d;
    let (d2, mut pow, mut coef) = (d * d, d, 1.0);
    let mut k = 1;
    while 2 * k < T::NDERIV {
        coef *= (2 * k - 1) as f64 / (2 * k) as f64;
        pow *= d2;
        delta += pow * (coef / (2 * k + 1) as f64);
        k += 1;
    }
    T::from(r) + delta
}

#[cfg(test)]
mod tests {
    use num_dual::{Dual2_64, Dual3_64, HyperDual64};

    /// The dual version carries the exact derivatives (against the closed forms) and is the
    /// f64 version bit for bit on plain numbers.
    #[test]
    fn sin_cos_dual_has_exact_derivatives() {
        for k in 0..200 {
            let x = -6.0 + 0.061 * k as f64;
            assert_eq!(super::sin_cos_dual(x), super::sin_cos(x));
            let (s, c) = super::sin_cos(x);
            let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON;
            let d3 = Dual3_64::new(x, 1.0, 0.0, 0.0);
            let (s3, c3) = super::sin_cos_dual(d3);
            for (got, want) in [
                (s3.re, s),
                (s3.v1, c),
                (s3.v2, -s),
                (s3.v3, -c),
                (c3.re, c),
                (c3.v1, -s),
                (c3.v2, -c),
                (c3.v3, s),
            ] {
                assert!(close(got, want), "x {x}: {got} vs {want}");
            }
            let d2 = Dual2_64::new(x, 1.0, 0.0);
            let (s2, _) = super::sin_cos_dual(d2);
            assert!(close(s2.v2, -s));
            let h = HyperDual64::new(x, 1.0, 1.0, 0.0);
            let (sh, ch) = super::sin_cos_dual(h);
            assert!(close(sh.eps1, c) && close(sh.eps1eps2, -s));
            assert!(close(ch.eps2, -s) && close(ch.eps1eps2, -c));
        }
    }

    /// atan2 of dual numbers: f64 bit for bit [`atan2`], derivatives against the closed forms
    /// (∂/∂y = x/ρ², ∂/∂x = −y/ρ²; second and third by the chain rule along a line), every
    /// quadrant.
    #[test]
    fn atan2_dual_has_exact_derivatives() {
        for k in 0..200 {
            let a = -3.1 + 0.031 * k as f64;
            let (rho, dy, dx) = (0.7 + 0.01 * k as f64, 0.3, -1.1);
            let (y, x) = (rho * super::sin(a), rho * super::cos(a));
            assert_eq!(super::atan2_dual(y, x), super::atan2(y, x));
            // along the line (x + t dx, y + t dy): φ(t), φ' = (x dy − y dx)/ρ², ...
            let p = |t: f64| super::atan2(y + t * dy, x + t * dx);
            let d3 = super::atan2_dual(
                Dual3_64::new(y, dy, 0.0, 0.0),
                Dual3_64::new(x, dx, 0.0, 0.0),
            );
            let r2 = x * x + y * y;
            let n = x * dy - y * dx;
            let m = x * dx + y * dy;
            let d1 = n / r2;
            let dd = -2.0 * n * m / (r2 * r2);
            // third derivative by central differences of the closed second derivative
            let f2 = |t: f64| {
                let (xt, yt) = (x + t * dx, y + t * dy);
                let r2 = xt * xt + yt * yt;
                -2.0 * (xt * dy - yt * dx) * (xt * dx + yt * dy) / (r2 * r2)
            };
            let h = 1e-5;
            let ddd = (f2(h) - f2(-h)) / (2.0 * h);
            let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.abs().max(1.0);
            assert!(close(d3.re, p(0.0), 1e-15));
            assert!(close(d3.v1, d1, 1e-14), "{a}: {} vs {d1}", d3.v1);
            assert!(close(d3.v2, dd, 1e-13), "{a}: {} vs {dd}", d3.v2);
            assert!(close(d3.v3, ddd, 1e-7), "{a}: {} vs {ddd}", d3.v3);
            let h = HyperDual64::new(y, dy, dy, 0.0);
            let hx = HyperDual64::new(x, dx, dx, 0.0);
            let g = super::atan2_dual(h, hx);
            assert!(close(g.eps1, d1, 1e-14) && close(g.eps1eps2, dd, 1e-13));
        }
    }

    /// Agrees with std's functions to a few ulp (they differ only in the last bits).
    #[test]
    fn agrees_with_std() {
        for k in 0..1000 {
            let x = -7.0 + 0.0141 * k as f64;
            let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs().max(1.0);
            assert!(close(super::sin(x), x.sin()));
            assert!(close(super::cos(x), x.cos()));
            assert!(close(super::sin_cos(x).0, x.sin()));
            assert!(close(super::sin_cos(x).1, x.cos()));
            assert!(close(super::atan2(x, 1.3), x.atan2(1.3)));
            assert!(close(super::exp(x), x.exp()));
            assert!(close(super::sinh(x), x.sinh()));
            assert!(close(super::cosh(x), x.cosh()));
            assert!(close(super::tanh(x), x.tanh()));
            assert!(close(super::pow(x.abs(), 0.8), x.abs().powf(0.8)));
            assert!(close(super::asin(x / 7.1), (x / 7.1).asin()));
        }
    }
}
