//! The beam model: components on numbered coordinates, assembled into residuals and a sparse
//! Newton matrix behind the integrators' [`crate::integrator::Integrable`] seam. No FMI, no
//! time stepping.
//!
//! Generic (dimension-free, written once over a [`Space`]):
//! * [`space`]: the [`Space`] trait: vector, moment and orientation types, port kinematics;
//! * [`dofs`]: coordinate numbering, [`LocalDofs`] (gather, scatter, slots);
//! * [`component`]: what an [`Element`], a [`Constraint`], a [`Port`] and a [`Support`] answer;
//! * [`assembly`]: [`Model`], the sparse pattern and `eval` as loops over components;
//! * [`outputs`]: [`Outputs`], energies, the support reaction, validity checks;
//! * [`load`]: the dead point force at a port (tip force).
//!
//! Planar ([`planar`]): [`Planar`], the components wrapping the kernels, the rigid joint, the
//! root support and the build from a scene. Kernels (pure functions of local coordinates):
//! [`ancf`] (planar ANCF cable), [`modal`] (shape basis, planar floating-frame body).

pub mod ancf;
pub mod ancf3d;
pub mod assembly;
pub mod component;
pub mod dofs;
pub mod load;
pub mod modal;
pub mod mount;
pub mod outputs;
pub mod planar;
pub mod space;
pub mod spatial;

pub use assembly::{Model, Parts};
pub use component::{
    Constraint, ConstraintOut, Element, ElementOut, Energies, Env, LocalState, Port, Support,
    Validity,
};
pub use dofs::{Dof, LocalDofs, Numbering, Rigid, RigidGroup};
pub use mount::{Motion, MotionRates, MountInertia};
pub use outputs::{ModelValidity, Outputs};
pub use planar::Planar;
pub use space::{PortKin, Space};
pub use spatial::Spatial;
