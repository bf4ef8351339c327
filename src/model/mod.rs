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
//! * [`walk`], [`build`](mod@build): the segment walk of a build, written once, and the build
//!   of a scene in a space given as a type;
//! * the mounted root, dimension-free: [`Motion`] of the mount frame ([`space`]), the held
//!   coordinates as rigid functions of the motion and the relative static start on a spinning
//!   mount ([`held`]), its rigid inertia ([`MountInertia`], [`inertia`]); the clamped slope
//!   direction of an ANCF root ([`direction`]);
//! * [`shape`], [`sample`]: the beam's shape at one state for viewers ([`Shape`],
//!   [`ShapePoint`]);
//! * [`scratch`]: working memory that evaluations through `&self` reuse (no allocation in a
//!   step).
//!
//! Planar ([`planar`]): [`Planar`], the components wrapping the kernels, the rigid joint, the
//! root support, the rigid motion of planar coordinate groups ([`Space::carry`] in
//! `planar/mod.rs`; the mount's path in `planar/frame.rs`) and the build from a scene. Spatial
//! ([`spatial`]): [`Spatial`], the same parts in 3D (Euler parameters, spherical + DOT1 joint
//! rows). Kernels (pure functions of local coordinates): [`ancf`] (planar ANCF cable),
//! [`ancf3d`] (the spatial ANCF elements: the 3D cable, the director element and the angle
//! element), [`modal`] (shape basis, planar and spatial floating-frame bodies).

pub mod ancf;
pub mod ancf3d;
pub mod ancf_p;
pub mod assembly;
pub mod build;
pub mod component;
pub(crate) mod cut;
pub mod direction;
pub mod dofs;
pub mod element_p;
pub mod held;
pub mod hierarchic;
pub mod inertia;
pub mod lanes;
pub mod load;
pub mod modal;
pub mod output_names;
pub mod outputs;
pub mod planar;
pub mod sample;
pub mod scratch;
pub mod section3;
pub mod section_stress;
pub mod shape;
pub mod space;
pub mod spatial;
pub mod stations;
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
pub use output_names::{OutputId, Quantity};
pub use outputs::{ModelValidity, Outputs};
pub use planar::Planar;
pub use sample::ShapePoint;
pub use shape::{Frame, Shape};
pub use space::{Motion, MotionRates, PortKin, Space};
pub use spatial::Spatial;
pub use stations::{strain_stress, SectionShape, StationLoads, StressSection};
