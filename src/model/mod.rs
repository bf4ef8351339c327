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
//! * [`load`]: the dead point force at a port (tip force);
//! * [`mount`]: the mounted root, dimension-free: [`Motion`] of the mount frame, its rigid
//!   inertia ([`MountInertia`]), the held coordinates as rigid functions of the motion, the
//!   relative static solve on a spinning mount.
//!
//! Planar ([`planar`]): [`Planar`], the components wrapping the kernels, the rigid joint, the
//! root support, the mount's rigid motion of planar coordinate groups (`planar/mount.rs`) and
//! the build from a scene. Spatial ([`spatial`]): [`Spatial`], the same parts in 3D (Euler
//! parameters, spherical + DOT1 joint rows). Kernels (pure functions of local coordinates):
//! [`ancf`] (planar ANCF cable), [`ancf3d`] (3D cable with a twist director), [`modal`] (shape
//! basis, planar and spatial floating-frame bodies).

pub mod ancf;
pub mod ancf3d;
pub mod assembly;
pub mod build;
pub mod component;
pub mod direction;
pub mod dofs;
pub mod held;
pub mod inertia;
pub mod load;
pub mod modal;
pub mod outputs;
pub mod planar;
pub mod sample;
pub mod shape;
pub mod space;
pub mod spatial;
pub mod vector;
pub mod walk;

pub use assembly::{Model, Parts};
pub use build::build;
pub use component::{
    Constraint, ConstraintOut, Element, ElementOut, Energies, Env, LocalState, Port, Support,
    Validity,
};
pub use dofs::{Dof, LocalDofs, Numbering, Rigid, RigidGroup};
pub use inertia::MountInertia;
pub use outputs::{ModelValidity, Outputs};
pub use planar::Planar;
pub use sample::ShapePoint;
pub use shape::{Frame, Shape};
pub use space::{Motion, MotionRates, PortKin, Space};
pub use spatial::Spatial;
