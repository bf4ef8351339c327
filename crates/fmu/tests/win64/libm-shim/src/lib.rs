//! The C library functions the linux64 FMU imports (`objdump -T`: sincos, atan2, tanh, pow,
//! exp, sinh, cosh; sin and cos for completeness), computed by the `libm` crate instead of
//! glibc. Loaded with LD_PRELOAD by scripts/test-win64.sh; never shipped.
#![allow(unsafe_code)]

/// sin(x), x in rad.
#[no_mangle]
pub extern "C" fn sin(x: f64) -> f64 {
    libm::sin(x)
}
/// cos(x), x in rad.
#[no_mangle]
pub extern "C" fn cos(x: f64) -> f64 {
    libm::cos(x)
}
/// sin(x) and cos(x) into `s`, `c` (glibc's sincos, which LLVM calls for a sin/cos pair).
///
/// # Safety
/// `s` and `c` are valid for writes (the C contract).
#[no_mangle]
pub unsafe extern "C" fn sincos(x: f64, s: *mut f64, c: *mut f64) {
    let (sx, cx) = libm::sincos(x);
    unsafe {
        *s = sx;
        *c = cx;
    }
}
/// atan2(y, x) in rad.
#[no_mangle]
pub extern "C" fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}
/// tanh(x).
#[no_mangle]
pub extern "C" fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}
/// sinh(x).
#[no_mangle]
pub extern "C" fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}
/// cosh(x).
#[no_mangle]
pub extern "C" fn cosh(x: f64) -> f64 {
    libm::cosh(x)
}
/// exp(x).
#[no_mangle]
pub extern "C" fn exp(x: f64) -> f64 {
    libm::exp(x)
}
/// x to the power y.
#[no_mangle]
pub extern "C" fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}
