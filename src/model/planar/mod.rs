//! The plane: [`Planar`] and the planar components (ANCF cable element, floating-frame modal
//! body, their ports, the rigid joint between segments, the root support) and the build of a
//! planar model from a scene. The kernels these wrap are [`super::ancf`] and
//! [`super::modal::ModalBody`].

mod build;
mod elements;
mod ends;
mod frame;
mod joint;

pub use elements::{AncfElement, ModalElement};
pub use ends::{
    EndKin, ModalRootPort, ModalTipPort, NodePort, Orientation, RootSupport, TipCurvature,
};
pub use joint::RigidJoint;

use super::dofs::Rigid;
use super::space::Space;
use super::space::{Motion, MotionRates};
use crate::scene::{Mount, SpaceKind};

pub(crate) use frame::poly;

/// The x–y plane: vectors `[x, y]`, moments about z (counter-clockwise positive), orientations
/// as the angle from global x [rad].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Planar;

impl Space for Planar {
    const KIND: SpaceKind = SpaceKind::Planar;
    const ATTITUDE: &'static str = "tip.angle";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &[""];
    const MOUNT_ATTITUDE: &'static str = "root.angle";
    const ANGULAR_SUFFIXES: &'static [&'static str] = &[""];
    const DIM: usize = 2;
    const AXES: &'static [&'static str] = &["x", "y"];
    const MOMENT_AXES: &'static [&'static str] = &["z"];
    const MOMENT_INDICES: &'static [usize] = &[2];
    const INERTIA_COMPONENTS: &'static [(&'static str, usize)] = &[("zz", 0)];
    type Vec = [f64; 2];
    type Moment = f64;
    type Attitude = f64;
    type PortKin = EndKin;

    fn moment_components(m: &f64) -> &[f64] {
        std::slice::from_ref(m)
    }

    fn moment_components_mut(m: &mut f64) -> &mut [f64] {
        std::slice::from_mut(m)
    }

    fn attitude_identity() -> f64 {
        0.0
    }

    fn attitude_components(a: &f64) -> &[f64] {
        std::slice::from_ref(a)
    }

    fn attitude_components_mut(a: &mut f64) -> &mut [f64] {
        std::slice::from_mut(a)
    }

    fn attitude_from(m: &Mount) -> f64 {
        m.angle
    }

    fn inertia_to_world(_: &f64, inertia: &[f64; 9]) -> [[f64; 3]; 3] {
        let mut iw = [[0.0; 3]; 3];
        iw[2][2] = inertia[0];
        iw
    }

    fn rigid_len(kind: Rigid) -> usize {
        match kind {
            Rigid::Point | Rigid::Direction => 2,
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

    fn attitude_angle(a: &f64, b: &f64) -> f64 {
        (b - a).abs()
    }

    fn rotated(a: &f64, phi: &f64) -> f64 {
        a + phi
    }

    fn normalized_attitude(a: &f64) -> Option<f64> {
        a.is_finite().then_some(*a)
    }

    fn to_frame(a: &f64, v: &[f64; 2]) -> [f64; 2] {
        frame::to_frame(*a, v)
    }

    fn from_frame(a: &f64, v: &[f64; 2]) -> [f64; 2] {
        frame::to_frame(-*a, v)
    }
}
