//! Kinematics of a spatial port: position and directors as [`Field3`]s over the local
//! coordinates of the component the port sits on.

use super::Spatial;
use crate::model::space::PortKin;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// A 3-vector function v(q) of a component's local coordinates with its first and second
/// derivatives (global axes).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Field3 {
    /// v(q).
    pub v: Vector3<f64>,
    /// ∂v/∂q_k, one per local coordinate.
    pub d: Vec<Vector3<f64>>,
    /// The nonzero second derivatives ∂²v/∂q_i∂q_j as (i, j, vector) with i ≤ j, each
    /// unordered pair at most once.
    pub dd: Vec<(usize, usize, Vector3<f64>)>,
}

impl Field3 {
    /// A field of `len` local coordinates equal to coordinates `first..first + 3` (e.g. an
    /// ANCF node's position or slope): ∂v/∂q is a unit selection, no second derivative.
    pub fn coordinates(q: &[f64], first: usize, len: usize) -> Self {
        let mut d = vec![Vector3::zeros(); len];
        for c in 0..3 {
            d[first + c][c] = 1.0;
        }
        Self {
            v: Vector3::new(q[first], q[first + 1], q[first + 2]),
            d,
            dd: Vec::new(),
        }
    }

    /// Rate v̇ = Σ_k ∂v/∂q_k q̇_k.
    pub fn rate(&self, qd: &[f64]) -> Vector3<f64> {
        self.d.iter().zip(qd).map(|(d, v)| d * *v).sum()
    }

    /// Adds μ·∂²v/∂q_i∂q_j through `add(i, j, value)`, both (i, j) and (j, i) for i ≠ j.
    pub fn add_hessian(&self, mu: &Vector3<f64>, mut add: impl FnMut(usize, usize, f64)) {
        for (i, j, h) in &self.dd {
            let x = mu.dot(h);
            add(*i, *j, x);
            if i != j {
                add(*j, *i, x);
            }
        }
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
    pub rotation: Vec<Vector3<f64>>,
    /// Axis direction (not normalized).
    pub tangent: Field3,
    /// Section y-axis director, if the end carries one.
    pub section: Option<Field3>,
    /// n1, n2, n3 of a modal end.
    pub normals: Option<[Field3; 3]>,
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
