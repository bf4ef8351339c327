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
