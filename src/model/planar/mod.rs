//! The plane: [`Planar`] and the planar components (ANCF cable element, floating-frame modal
//! body, their ports, the rigid joint between segments, the root support) and the build of a
//! planar model from a scene. The kernels these wrap are [`super::ancf`] and
//! [`super::modal::ModalBody`].

mod build;
mod elements;
mod ends;
mod joint;

pub use elements::{AncfElement, ModalElement};
pub use ends::{
    EndKin, ModalRootPort, ModalTipPort, NodePort, Orientation, RootSupport, TipCurvature,
};
pub use joint::RigidJoint;

use super::space::Space;

/// The x–y plane: vectors `[x, y]`, moments about z (counter-clockwise positive), orientations
/// as the angle from global x [rad].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Planar;

impl Space for Planar {
    const DIM: usize = 2;
    const AXES: &'static [&'static str] = &["x", "y"];
    const MOMENT_AXES: &'static [&'static str] = &["z"];
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
}
