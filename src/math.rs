//! Transcendental functions of the engine, from the `libm` crate (a Rust port of musl's libm):
//! the same code, hence the same bits, on every target. std's `f64::sin` etc. call the
//! platform's C library (glibc on linux64, msvcrt on win64), whose last bits differ: the
//! paper's Case 3 moved by 7.6e-10 m between the two FMU binaries before this module
//! (docs/platforms.md). `tests/portable_math.rs` keeps std's versions out of `src/` (outside test
//! modules). sqrt is correctly rounded everywhere and stays std's. The dual-number (num-dual)
//! paths of the spatial model still use std's functions inside num-dual.

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

#[cfg(test)]
mod tests {
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
