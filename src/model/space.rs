//! The dimension of a model, in one place: the generic assembly ([`super::Model`]) and outputs
//! ([`super::Outputs`]) are written once over a [`Space`]; each space supplies its vector
//! types and its port kinematics. [`super::planar::Planar`] is the plane; a spatial model is a
//! second implementation beside it.

use super::dofs::Rigid;
use crate::scene::{Mount, SpaceKind};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::fmt::Debug;
use std::ops::{Index, IndexMut};

/// A space the beam lives in: the one trait that names the dimension (vector types, names of
/// axes and variables, rigid motion, port kinematics). Implemented by
/// [`super::planar::Planar`] and [`super::spatial::Spatial`].
pub trait Space: Copy + Default + Debug + PartialEq + Send + Sync + 'static {
    /// The scene's `space` of this dimension.
    const KIND: SpaceKind;
    /// Number of global axes (2 in the plane).
    const DIM: usize;
    /// Names of the global axes, for variable names and CSV headers (`["x", "y"]`).
    const AXES: &'static [&'static str];
    /// Names of the components of a moment (`["z"]` in the plane).
    const MOMENT_AXES: &'static [&'static str];
    /// Indices of the moment's components among x, y, z (`[2]` in the plane).
    const MOMENT_INDICES: &'static [usize];
    /// The components of a rigid inertia tensor a host reads (`root.inertia.<name>`), each with
    /// its index in [`super::MountInertia::inertia`] (`[("zz", 0)]` in the plane).
    const INERTIA_COMPONENTS: &'static [(&'static str, usize)];
    /// Output name of the tip section's orientation (`tip.angle` in the plane,
    /// `tip.orientation` in space) ...
    const ATTITUDE: &'static str;
    /// ... and the suffixes of its components (`[""]`: a scalar without suffix; `e0`–`e3`).
    const ATTITUDE_COMPONENTS: &'static [&'static str];
    /// Input name of the mount's orientation (`root.angle` in the plane, `root.orientation`).
    const MOUNT_ATTITUDE: &'static str;
    /// Suffixes of the mount's angular velocity and acceleration inputs (`[""]` in the plane:
    /// `root.angular_velocity`; the moment axes in space).
    const ANGULAR_SUFFIXES: &'static [&'static str];
    /// A global vector (position [m], velocity [m/s], force [N], gravity [m/s²]): `[f64; DIM]`.
    type Vec: Copy
        + Default
        + Debug
        + PartialEq
        + Send
        + Sync
        + AsRef<[f64]>
        + AsMut<[f64]>
        + Index<usize, Output = f64>
        + IndexMut<usize>
        + Serialize
        + DeserializeOwned;
    /// A moment [N m] or an angular velocity [rad/s], global axes: the z component in the
    /// plane, `[x, y, z]` in space.
    type Moment: Copy + Default + Debug + PartialEq + Send + Sync + Serialize + DeserializeOwned;
    /// The orientation of a section, for outputs: the angle of the tangent from global x [rad]
    /// in the plane.
    type Attitude: Copy + Default + Debug + PartialEq + Send + Sync + Serialize + DeserializeOwned;
    /// Kinematics of a port (an attachment point) at one state.
    type PortKin: PortKin<Self>;
    /// A port's values alone (position and directors, no derivatives): what a constraint's
    /// values Φ(q) need.
    type PortValues: Debug;

    /// The values of full kinematics.
    fn port_values(k: &Self::PortKin) -> Self::PortValues;

    /// The components of a moment, in the order of [`Space::MOMENT_AXES`].
    fn moment_components(m: &Self::Moment) -> &[f64];
    /// The components of a moment, mutable.
    fn moment_components_mut(m: &mut Self::Moment) -> &mut [f64];

    /// The identity orientation (a frame aligned with the global axes).
    fn attitude_identity() -> Self::Attitude;
    /// The components of an orientation, in the order of [`Space::ATTITUDE_COMPONENTS`].
    fn attitude_components(a: &Self::Attitude) -> &[f64];
    /// The components of an orientation, mutable.
    fn attitude_components_mut(a: &mut Self::Attitude) -> &mut [f64];
    /// The orientation of a scene's `[mount]` table.
    fn attitude_from(m: &Mount) -> Self::Attitude;

    /// An inertia tensor about a point, stored as in [`super::MountInertia::inertia`] in the
    /// axes of a frame at orientation `a`, as a 3×3 tensor in world axes [kg m²] (the plane:
    /// I_zz only, which a turn about z leaves unchanged).
    fn inertia_to_world(a: &Self::Attitude, inertia: &[f64; 9]) -> [[f64; 3]; 3];

    /// Number of coordinates of a [`Rigid`] group.
    fn rigid_len(kind: Rigid) -> usize;

    /// World (q, q̇, q̈) of a group carried by the frame moving as `m`, from its values, rates
    /// and accelerations relative to the frame (in frame axes) `rel`.
    fn carry(kind: Rigid, m: &Motion<Self>, rel: [&[f64]; 3], out: [&mut [f64]; 3]);

    /// The inverse of [`Space::carry`]: values, rates and accelerations relative to the frame
    /// moving as `m` from world ones.
    fn uncarry(kind: Rigid, m: &Motion<Self>, abs: [&[f64]; 3], out: [&mut [f64]; 3]);

    /// The motion `tau` [s] after `m` along a path whose acceleration and angular acceleration
    /// change at the rates `rates` (jerk, snap): positions and plane angles exactly; spatial
    /// orientations by the two-term Magnus expansion of the rotation (exact for an angular
    /// acceleration parallel to the angular velocity, error O(τ⁴|α||ω|²) otherwise).
    fn advance_motion(m: &Motion<Self>, rates: &MotionRates<Self>, tau: f64) -> Motion<Self>;

    /// Angle [rad] of the rotation from orientation `a` to `b`.
    fn attitude_angle(a: &Self::Attitude, b: &Self::Attitude) -> f64;
    /// `a` turned further by the rotation vector `phi` [rad], world axes (the plane: the angle
    /// plus φ_z).
    fn rotated(a: &Self::Attitude, phi: &Self::Moment) -> Self::Attitude;

    /// Unit orientation from any nonzero representation (Euler parameters normalized), `None`
    /// if it has none (zero or not finite).
    fn normalized_attitude(a: &Self::Attitude) -> Option<Self::Attitude>;

    /// `R`ᵀ`v`: a world vector in the axes of the frame at orientation `a`.
    fn to_frame(a: &Self::Attitude, v: &Self::Vec) -> Self::Vec;

    /// `R v`: a vector in the axes of the frame at orientation `a` in world axes.
    fn from_frame(a: &Self::Attitude, v: &Self::Vec) -> Self::Vec;
}

/// Kinematics of a port at one state, over the port's local coordinates: what loads and
/// outputs need from where they attach. Joints of a space read its richer concrete type.
pub trait PortKin<S: Space>: Debug + Clone {
    /// Position p [m], global axes.
    fn position(&self) -> S::Vec;
    /// ∂p/∂q_k for local coordinate k.
    fn jacobian(&self, k: usize) -> S::Vec;
    /// Adds μ·∂²p/∂q_i∂q_j through `add(i, j, value)` (local indices; each pair at most once).
    fn add_point_hessian(&self, mu: &S::Vec, add: impl FnMut(usize, usize, f64));
    /// Orientation of the section at the port.
    fn attitude(&self) -> S::Attitude;
    /// ∂θ/∂q_k: the virtual rotation of the section [rad] per unit of local coordinate k, global
    /// axes (the angular velocity is Σ_k ∂θ/∂q_k q̇_k; a dead moment m does the work m·δθ).
    fn rotation_jacobian(&self, k: usize) -> S::Moment;
}

/// Dot product a·b of two global vectors, summed in axis order.
pub fn dot<S: Space>(a: &S::Vec, b: &S::Vec) -> f64 {
    a.as_ref()
        .iter()
        .zip(b.as_ref())
        .map(|(x, y)| x * y)
        .reduce(|s, t| s + t)
        .unwrap_or(0.0)
}

/// `s·v`.
pub fn scaled<S: Space>(s: f64, v: &S::Vec) -> S::Vec {
    let mut out = *v;
    for x in out.as_mut() {
        *x *= s;
    }
    out
}

/// Whether any component of `v` is nonzero.
pub fn is_nonzero<S: Space>(v: &S::Vec) -> bool {
    v.as_ref().iter().any(|x| *x != 0.0)
}

/// Dot product m·w of two moments (or a moment and a rotation), summed in axis order.
pub fn moment_dot<S: Space>(m: &S::Moment, w: &S::Moment) -> f64 {
    S::moment_components(m)
        .iter()
        .zip(S::moment_components(w))
        .map(|(x, y)| x * y)
        .reduce(|s, t| s + t)
        .unwrap_or(0.0)
}

/// Whether any component of the moment `m` is nonzero.
pub fn is_nonzero_moment<S: Space>(m: &S::Moment) -> bool {
    S::moment_components(m).iter().any(|x| *x != 0.0)
}

/// A space's vector from the components of a list (a scene's table): the first
/// [`Space::DIM`], zero where the list is shorter.
pub fn vec_from<S: Space>(v: &[f64]) -> S::Vec {
    let mut out = S::Vec::default();
    for (o, x) in out.as_mut().iter_mut().zip(v) {
        *o = *x;
    }
    out
}

/// A space's moment from the components of a list, as [`vec_from`].
pub fn moment_from<S: Space>(v: &[f64]) -> S::Moment {
    let mut out = S::Moment::default();
    for (o, x) in S::moment_components_mut(&mut out).iter_mut().zip(v) {
        *o = *x;
    }
    out
}

/// The motion of a frame at one instant, world axes, SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "S::Vec: Serialize, S::Moment: Serialize, S::Attitude: Serialize",
    deserialize = "S::Vec: Deserialize<'de>, S::Moment: Deserialize<'de>, S::Attitude: Deserialize<'de>"
))]
pub struct Motion<S: Space> {
    /// Position of the frame origin [m].
    pub position: S::Vec,
    /// Orientation, frame → world (plane: angle [rad]; space: unit Euler parameters).
    pub attitude: S::Attitude,
    /// Velocity of the origin [m/s].
    pub velocity: S::Vec,
    /// Angular velocity [rad/s], world axes.
    pub angular_velocity: S::Moment,
    /// Acceleration of the origin [m/s²].
    pub acceleration: S::Vec,
    /// Angular acceleration [rad/s²], world axes.
    pub angular_acceleration: S::Moment,
}

impl<S: Space> Default for Motion<S> {
    fn default() -> Self {
        Self::at_rest(S::Vec::default(), S::attitude_identity())
    }
}

impl<S: Space> Motion<S> {
    /// A frame at rest at `position`, `attitude`.
    pub fn at_rest(position: S::Vec, attitude: S::Attitude) -> Self {
        Self {
            position,
            attitude,
            velocity: S::Vec::default(),
            angular_velocity: S::Moment::default(),
            acceleration: S::Vec::default(),
            angular_acceleration: S::Moment::default(),
        }
    }

    /// The same pose and rates with the accelerations of `other`.
    pub fn with_accelerations_of(&self, other: &Self) -> Self {
        Self {
            acceleration: other.acceleration,
            angular_acceleration: other.angular_acceleration,
            ..*self
        }
    }

    /// Every component, for finiteness checks.
    pub fn components(&self) -> Vec<f64> {
        let mut out = Vec::new();
        out.extend_from_slice(self.position.as_ref());
        out.extend_from_slice(self.velocity.as_ref());
        out.extend_from_slice(self.acceleration.as_ref());
        for m in [&self.angular_velocity, &self.angular_acceleration] {
            out.extend_from_slice(S::moment_components(m));
        }
        out
    }
}

/// Rates of change of the accelerations along a path: jerk and snap [m/s³, m/s⁴], angular
/// jerk and snap [rad/s³, rad/s⁴] (a host's input derivatives; zero: constant acceleration).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(bound(
    serialize = "S::Vec: Serialize, S::Moment: Serialize",
    deserialize = "S::Vec: Deserialize<'de>, S::Moment: Deserialize<'de>"
))]
pub struct MotionRates<S: Space> {
    /// d(acceleration)/dt.
    pub jerk: S::Vec,
    /// d²(acceleration)/dt².
    pub snap: S::Vec,
    /// d(angular acceleration)/dt.
    pub angular_jerk: S::Moment,
    /// d²(angular acceleration)/dt².
    pub angular_snap: S::Moment,
}
