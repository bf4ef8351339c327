//! Small fixed-size vector helpers, in one place for the kernels, the joints and the mount's
//! rigid motion: generic over the scalar ([`Real`]: f64 on residual paths, a dual number where
//! exact tangents are taken by forward-mode AD), arguments by value or by reference. Hand-written
//! rather than nalgebra's `Vector3` so that the dual-number kernels keep plain arrays on the
//! stack and the operation order (hence the bits) stays the one written here.

use num_dual::DualNum;
use std::borrow::Borrow;

/// A scalar of the generic code: f64, or a dual number over f64.
pub trait Real: DualNum<Primitive = f64> + Copy {}
impl<T: DualNum<Primitive = f64> + Copy> Real for T {}

/// A 3-vector.
pub type V3<T> = [T; 3];

/// a × b.
#[inline(always)]
pub fn cross<T: Real>(a: impl Borrow<V3<T>>, b: impl Borrow<V3<T>>) -> V3<T> {
    let (a, b) = (a.borrow(), b.borrow());
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// a · b.
#[inline(always)]
pub fn dot<T: Real>(a: impl Borrow<V3<T>>, b: impl Borrow<V3<T>>) -> T {
    let (a, b) = (a.borrow(), b.borrow());
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a s.
#[inline(always)]
pub fn scale<T: Real>(a: impl Borrow<V3<T>>, s: T) -> V3<T> {
    let a = a.borrow();
    [a[0] * s, a[1] * s, a[2] * s]
}

/// a + b.
#[inline(always)]
pub fn add<T: Real>(a: impl Borrow<V3<T>>, b: impl Borrow<V3<T>>) -> V3<T> {
    let (a, b) = (a.borrow(), b.borrow());
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// a − b.
#[inline(always)]
pub fn sub<T: Real>(a: impl Borrow<V3<T>>, b: impl Borrow<V3<T>>) -> V3<T> {
    let (a, b) = (a.borrow(), b.borrow());
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a + b in the plane.
#[inline(always)]
pub fn add2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// a − b in the plane.
#[inline(always)]
pub fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// ω × v for ω about z (the plane's cross product of a rate with a vector).
#[inline(always)]
pub fn cross_z(w: f64, v: [f64; 2]) -> [f64; 2] {
    [-w * v[1], w * v[0]]
}
