//! Space: [`Spatial`], the spatial components and the build of a spatial model from a scene
//! (`space = "spatial"`). The formulation is `docs/spatial.md`'s: ANCF elements (the director
//! element r, r_x, r_y; the angle element r, r_x, θ; the 3D cable r, r_x), floating-frame
//! modal bodies oriented by Euler parameters, rigid joints of a spherical joint plus three DOT1
//! rows.
//!
//! Port kinematics ([`kin`]): every end exposes its position and its directors as [`Field3`]s
//! (a vector with its first and second derivatives by the local coordinates), so joint rows,
//! loads and outputs are written once over them.

mod angle;
mod body;
mod build;
mod frame;
mod joint;
mod kin;
mod node;

pub use angle::{AngleElement3, AnglePort3};
pub use body::{EulerNormalization, FrameSupport3, ModalElement3, ModalRootPort3, ModalTipPort3};
pub use joint::RigidJoint3;
pub use kin::{EndKin3, EndValues3, Field3};
pub use node::{AncfElement3, NodePort3, NodeSupport3};

use super::dofs::Rigid;
use super::space::Space;
use super::space::{Motion, MotionRates};
use crate::scene::{Mount, SpaceKind};

/// Space: vectors `[x, y, z]` (global axes), moments and angular velocities `[x, y, z]`,
/// orientations as Euler parameters `[e0, e1, e2, e3]` (scalar first, section frame → world).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Spatial;

impl Space for Spatial {
    const KIND: SpaceKind = SpaceKind::Spatial;
    const ATTITUDE: &'static str = "tip.orientation";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &["e0", "e1", "e2", "e3"];
    const MOUNT_ATTITUDE: &'static str = "root.orientation";
    const ANGULAR_SUFFIXES: &'static [&'static str] = Self::MOMENT_AXES;
    const DIM: usize = 3;
    const AXES: &'static [&'static str] = &["x", "y", "z"];
    const MOMENT_AXES: &'static [&'static str] = &["x", "y", "z"];
    const MOMENT_INDICES: &'static [usize] = &[0, 1, 2];
    const INERTIA_COMPONENTS: &'static [(&'static str, usize)] = &[
        ("xx", 0),
        ("yy", 4),
        ("zz", 8),
        ("xy", 1),
        ("xz", 2),
        ("yz", 5),
    ];
    type Vec = [f64; 3];
    type Moment = [f64; 3];
    type Attitude = [f64; 4];
    type PortKin = EndKin3;
    type PortValues = EndValues3;

    fn port_values(k: &EndKin3) -> EndValues3 {
        EndValues3 {
            p: k.p.v,
            tangent: k.tangent.v,
            section: k.section.as_ref().map(|s| s.v),
            normals: k.normals.as_ref().map(|n| n.each_ref().map(|f| f.v)),
        }
    }

    fn moment_components(m: &[f64; 3]) -> &[f64] {
        m
    }

    fn moment_components_mut(m: &mut [f64; 3]) -> &mut [f64] {
        m
    }

    fn attitude_identity() -> [f64; 4] {
        [1.0, 0.0, 0.0, 0.0]
    }

    fn attitude_components(a: &[f64; 4]) -> &[f64] {
        a
    }

    fn attitude_components_mut(a: &mut [f64; 4]) -> &mut [f64] {
        a
    }

    fn attitude_from(m: &Mount) -> [f64; 4] {
        let e = m.orientation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
        Self::normalized_attitude(&e).unwrap_or([1.0, 0.0, 0.0, 0.0])
    }

    fn inertia_to_world(a: &[f64; 4], inertia: &[f64; 9]) -> [[f64; 3]; 3] {
        let mut iw = [[0.0; 3]; 3];
        // column b of A I Aᵀ is A (I (Aᵀ e_b))
        for b in 0..3 {
            let mut e = [0.0; 3];
            e[b] = 1.0;
            let f = Self::to_frame(a, &e);
            let mut v = [0.0; 3];
            for (r, vr) in v.iter_mut().enumerate() {
                *vr = (0..3).map(|k| inertia[3 * r + k] * f[k]).sum();
            }
            let w = Self::from_frame(a, &v);
            for (r, row) in iw.iter_mut().enumerate() {
                row[b] = w[r];
            }
        }
        iw
    }

    fn rigid_len(kind: Rigid) -> usize {
        match kind {
            Rigid::Point | Rigid::Direction => 3,
            Rigid::Angle => 1,
            Rigid::Euler => 4,
        }
    }

    fn carry(kind: Rigid, m: &Motion<Self>, rel: [&[f64]; 3], out: [&mut [f64]; 3]) {
        frame::carry(kind, m, rel, out)
    }

    fn uncarry(kind: Rigid, m: &Motion<Self>, abs: [&[f64]; 3], out: [&mut [f64]; 3]) {
        frame::uncarry(kind, m, abs, out)
    }

    fn advance_motion(m: &Motion<Self>, rates: &MotionRates<Self>, tau: f64) -> Motion<Self> {
        frame::advance(m, rates, tau)
    }

    fn attitude_angle(a: &[f64; 4], b: &[f64; 4]) -> f64 {
        frame::angle_between(a, b)
    }

    fn rotated(a: &[f64; 4], phi: &[f64; 3]) -> [f64; 4] {
        frame::rotated(a, *phi)
    }

    fn normalized_attitude(a: &[f64; 4]) -> Option<[f64; 4]> {
        frame::normalize(*a)
    }

    fn to_frame(a: &[f64; 4], v: &[f64; 3]) -> [f64; 3] {
        frame::rotate_back(a, *v)
    }

    fn from_frame(a: &[f64; 4], v: &[f64; 3]) -> [f64; 3] {
        frame::rotate(a, *v)
    }
}
