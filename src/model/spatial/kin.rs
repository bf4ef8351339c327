//! Kinematics of a spatial port: position and directors as [`Field3`]s over the local
//! coordinates of the component the port sits on.
//!
//! Nothing here allocates: first derivatives are held inline up to [`END_INLINE`] local
//! coordinates, and the second derivatives of a modal body's fields A(p)·v̄(a) — hundreds of
//! pairs on a body with many modes — are kept as their factors ([`FrameSecond`]) and
//! produced pair by pair where they are used.

use super::Spatial;
use crate::model::space::{dot, PortKin};
use crate::scene::MAX_MODES;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use smallvec::SmallVec;
use std::ops::Deref;
use std::sync::{Arc, OnceLock};

/// Bending amplitudes per plane of a modal body at most: [`MAX_MODES`] and the two interface
/// modes.
pub const MAX_AMPLITUDES: usize = MAX_MODES + 2;

/// The local coordinates of one end held inline: a spatial modal body's end has at most 37
/// (7 frame coordinates, 2 × (12 + 2) bending amplitudes, 2 torsion amplitudes), an ANCF node's
/// element 26. Smaller than [`crate::model::component::LOCAL_INLINE`] on purpose: an [`EndKin3`] holds seven of these
/// and is moved by value.
pub const END_INLINE: usize = 40;

/// One 3-vector per local coordinate of an end (inline up to [`END_INLINE`]).
pub type Grad3 = SmallVec<[Vector3<f64>; END_INLINE]>;

/// (local index, coefficient) of a variable linear in a modal body's amplitudes (inline up to
/// [`MAX_AMPLITUDES`]).
pub type Coef = SmallVec<[(usize, f64); MAX_AMPLITUDES]>;

/// (local index, vector) of a field's first derivatives by the amplitudes of one modal body:
/// both bending planes and the two twist amplitudes at most.
pub type Sparse3 = SmallVec<[(usize, Vector3<f64>); 2 * MAX_AMPLITUDES + 4]>;

/// A 3-vector function v(q) of a component's local coordinates with its first and second
/// derivatives (global axes).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Field3 {
    /// v(q).
    pub v: Vector3<f64>,
    /// ∂v/∂q_k, one per local coordinate.
    pub d: Grad3,
    /// The nonzero second derivatives ∂²v/∂q_i∂q_j, i ≤ j, each unordered pair at most once.
    pub dd: Second3,
}

/// The nonzero second derivatives of a [`Field3`]: the listed ones, then those of its
/// [`FrameSecond`] part, in that order ([`Second3::for_each`]).
///
/// Read as a slice (`&field.dd`, [`Deref`]) it lists every pair (i, j, h): built on the first
/// such read, allocating — an inspection aid (tests); the evaluation paths use
/// [`Second3::for_each`].
#[derive(Debug, Clone, Default)]
pub struct Second3 {
    /// (i, j, ∂²v/∂q_i∂q_j) with i ≤ j.
    pub list: SmallVec<[(usize, usize, Vector3<f64>); 10]>,
    /// The part of a field A(p)·v̄(a) beyond the list, kept as its factors.
    pub frame: Option<FrameSecond>,
    /// Every pair, once read as a slice.
    all: OnceLock<Vec<(usize, usize, Vector3<f64>)>>,
}

impl PartialEq for Second3 {
    fn eq(&self, other: &Self) -> bool {
        (&self.list, &self.frame) == (&other.list, &other.frame)
    }
}

impl Deref for Second3 {
    type Target = [(usize, usize, Vector3<f64>)];

    fn deref(&self) -> &Self::Target {
        self.all.get_or_init(|| {
            let mut all = Vec::new();
            self.for_each(|i, j, h| all.push((i, j, h)));
            all
        })
    }
}

/// The second derivatives of a field A(p)·v̄(a) that involve v̄'s derivatives, as their factors:
/// ∂A/∂p_i·∂v̄/∂q_k (each k of `dv`, then i = 0..4), then A·∂²v̄/∂q_k∂q_l ([`BarSecond`]);
/// the zero ones are skipped.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameSecond {
    /// Local index of p_0 (p at `p0..p0 + 4`).
    pub p0: usize,
    /// A(p).
    pub a: Matrix3<f64>,
    /// ∂A/∂p_i.
    pub da: [Matrix3<f64>; 4],
    /// (k, ∂v̄/∂q_k) over the coordinates v̄ depends on.
    pub dv: Sparse3,
    /// ∂²v̄/∂q_k∂q_l.
    pub ddv: BarSecond,
}

/// ∂²v̄/∂q_k∂q_l (k ≤ l) of a modal body's field v̄(a) in the body frame.
// inline, not boxed: the variants live on the stack, a box would allocate in the step
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Default, PartialEq)]
pub enum BarSecond {
    /// None.
    #[default]
    Zero,
    /// The foreshortening of the tip position: for n ≤ m with g_nm ≠ 0, (−g_nm/ℓ, 0, 0) at
    /// (y_n, y_m), then at (z_n, z_m); y_n = `first[0] + n`, z_n = `first[1] + n`, `gram`
    /// row-major `nb` × `nb`.
    Gram {
        /// The Gram matrix of the mode slopes.
        gram: Arc<[f64]>,
        /// Number of bending amplitudes per plane.
        nb: usize,
        /// Local index of the first amplitude of each plane.
        first: [usize; 2],
        /// Body length ℓ [m].
        length: f64,
    },
    /// A function of variables x_i = Σ_k c_ik q_k (`coef[i]`, the indices increasing): for each
    /// pair (i, j) of `pairs` with h_ij = ∂²v̄/∂x_i∂x_j ≠ 0, h_ij·c_ik·c_jl at (k, l) over
    /// the entries of `coef[j]` from k's on (i = j) or from the first (i ≠ j).
    Chain {
        /// The variables' coefficients.
        coef: [Coef; 3],
        /// (i, j) and ∂²v̄/∂x_i∂x_j.
        pairs: [((usize, usize), Vector3<f64>); 6],
    },
}

impl FrameSecond {
    /// Calls `f(i, j, h)` for each nonzero h = ∂²(Av̄)/∂q_i∂q_j of this part, in order.
    fn for_each(&self, f: &mut impl FnMut(usize, usize, Vector3<f64>)) {
        let mut push = |i: usize, j: usize, h: Vector3<f64>| {
            if h != Vector3::zeros() {
                f(i, j, h);
            }
        };
        let (a, p0) = (&self.a, self.p0);
        for &(k, b) in &self.dv {
            for (i, da) in self.da.iter().enumerate() {
                push(p0 + i, k, da * b);
            }
        }
        match &self.ddv {
            BarSecond::Zero => {}
            BarSecond::Gram {
                gram,
                nb,
                first,
                length,
            } => {
                let nb = *nb;
                for n in 0..nb {
                    for m in n..nb {
                        let g = gram[n * nb + m];
                        if g != 0.0 {
                            let h = Vector3::new(-g / length, 0.0, 0.0);
                            push(first[0] + n, first[0] + m, a * h);
                            push(first[1] + n, first[1] + m, a * h);
                        }
                    }
                }
            }
            BarSecond::Chain { coef, pairs } => {
                for &((i, j), h) in pairs {
                    if h == Vector3::zeros() {
                        continue;
                    }
                    for (a_i, &(k, x)) in coef[i].iter().enumerate() {
                        // each unordered pair once: k ≤ l (the variables' indices increase)
                        let from = if i == j { a_i } else { 0 };
                        for &(kl, y) in &coef[j][from..] {
                            push(k, kl, a * (h * (x * y)));
                        }
                    }
                }
            }
        }
    }
}

impl Second3 {
    /// Calls `f(i, j, h)` for each nonzero h = ∂²v/∂q_i∂q_j (i ≤ j), in order.
    pub fn for_each(&self, mut f: impl FnMut(usize, usize, Vector3<f64>)) {
        for &(i, j, h) in &self.list {
            f(i, j, h);
        }
        if let Some(frame) = &self.frame {
            frame.for_each(&mut f);
        }
    }
}

impl Field3 {
    /// A field of `len` local coordinates equal to coordinates `first..first + 3` (e.g. an
    /// ANCF node's position or slope): ∂v/∂q is a unit selection, no second derivative.
    pub fn coordinates(q: &[f64], first: usize, len: usize) -> Self {
        let mut d = Grad3::from_elem(Vector3::zeros(), len);
        for c in 0..3 {
            d[first + c][c] = 1.0;
        }
        Self {
            v: Vector3::new(q[first], q[first + 1], q[first + 2]),
            d,
            dd: Second3::default(),
        }
    }

    /// The residual r_k = −F·∂p/∂q_k of a dead force F at a position p that is coordinates
    /// 0..3 ([`Self::coordinates`]`(q, 0, r.len())`): ∂p/∂q_k is the unit vector e_k for k < 3
    /// and zero beyond, dotted with F as [`crate::model::load::point_force_residual`] does (the
    /// same bits, without building the field).
    pub fn selection_force_residual(force: &[f64; 3], r: &mut [f64]) {
        for (k, rk) in r.iter_mut().enumerate() {
            let mut e = [0.0; 3];
            if k < 3 {
                e[k] = 1.0;
            }
            *rk = -dot::<Spatial>(&e, force);
        }
    }

    /// Rate v̇ = Σ_k ∂v/∂q_k q̇_k.
    pub fn rate(&self, qd: &[f64]) -> Vector3<f64> {
        self.d.iter().zip(qd).map(|(d, v)| d * *v).sum()
    }

    /// Adds μ·∂²v/∂q_i∂q_j through `add(i, j, value)`, both (i, j) and (j, i) for i ≠ j.
    pub fn add_hessian(&self, mu: &Vector3<f64>, mut add: impl FnMut(usize, usize, f64)) {
        self.dd.for_each(|i, j, h| {
            let x = mu.dot(&h);
            add(i, j, x);
            if i != j {
                add(j, i, x);
            }
        });
    }
}

/// Kinematics of a spatial end (port) at one state.
///
/// Directors for the rigid joint's DOT1 rows: a modal end gives the three `normals` n1, n2 (⟂
/// its deformed tangent) and n3 (⟂ its section's y axis); every end gives its `tangent` (the
/// axis direction, not normalized: r_x at an ANCF node) and, if it carries one, its `section`
/// director (the section's y axis: r_y at a node with torsion). A joint between a normals-end and
/// another end is n1·t = n2·t = n3·s = 0.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EndKin3 {
    /// Position [m].
    pub p: Field3,
    /// Section frame → world at the end: columns tangent t, section axes d2 (y) and d3 (z),
    /// orthonormal.
    pub frame: Matrix3<f64>,
    /// ∂θ/∂q_k: virtual rotation of the section frame per unit local coordinate [rad].
    pub rotation: Grad3,
    /// Axis direction (not normalized).
    pub tangent: Field3,
    /// Section y-axis director, if the end carries one.
    pub section: Option<Field3>,
    /// n1, n2, n3 of a modal end.
    pub normals: Option<[Field3; 3]>,
}

/// The values of an [`EndKin3`] alone (no derivatives): what the joint's Φ(q) needs, without
/// the derivatives' work and without moving the large kinematics.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EndValues3 {
    /// Position [m].
    pub p: Vector3<f64>,
    /// Axis direction (not normalized).
    pub tangent: Vector3<f64>,
    /// Section y-axis director, if the end carries one.
    pub section: Option<Vector3<f64>>,
    /// n1, n2, n3 of a modal end.
    pub normals: Option<[Vector3<f64>; 3]>,
}

impl PortKin<Spatial> for EndKin3 {
    fn position(&self) -> [f64; 3] {
        self.p.v.into()
    }

    fn jacobian(&self, k: usize) -> [f64; 3] {
        self.p.d[k].into()
    }

    fn add_point_hessian(&self, mu: &[f64; 3], add: impl FnMut(usize, usize, f64)) {
        self.p.add_hessian(&Vector3::from(*mu), add)
    }

    /// Euler parameters of `frame`, scalar first, with e0 ≥ 0.
    fn attitude(&self) -> [f64; 4] {
        let q = UnitQuaternion::from_matrix(&self.frame);
        let (w, v) = (q.w, q.imag());
        let s = if w < 0.0 { -1.0 } else { 1.0 };
        [s * w, s * v[0], s * v[1], s * v[2]]
    }

    fn rotation_jacobian(&self, k: usize) -> [f64; 3] {
        self.rotation[k].into()
    }
}
