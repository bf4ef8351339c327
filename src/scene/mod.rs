//! Scene files: one beam set-up in TOML (see `docs/scene-format.md`).
//!
//! A scene is parsed with serde (unknown fields are refused), then [`Scene::validate`] checks
//! every value and names the field, the value and what is allowed. Nothing here panics on bad
//! input. [`Scene::from_toml_with_overrides`] applies `--set key.path=value` overrides on the
//! TOML tree before typing it, so any field can be overridden by its dotted path.

mod overrides;
mod section;
mod validate;

use serde::{Deserialize, Serialize};
use std::fmt;

pub use crate::integrator::{IntegrationParameters, MIN_STEP, MIN_TOLERANCE};
pub use overrides::apply_override;
pub use section::{rectangle_torsion_constant, Dim, Section, SectionProps};
pub use validate::{MAX_DEGREE, MAX_ELEMENTS, MAX_MODES};

/// A scene error: a message that names the field and what to change.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError(pub String);

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}

/// The space a scene lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum SpaceKind {
    /// The x–y plane: vectors `[x, y]`, moments about z.
    #[default]
    Planar,
    /// Space: vectors `[x, y, z]`.
    Spatial,
}

impl SpaceKind {
    /// Number of components of a vector (2 or 3).
    pub fn dim(self) -> usize {
        match self {
            SpaceKind::Planar => 2,
            SpaceKind::Spatial => 3,
        }
    }

    /// Number of components of a moment (1: z in the plane, or 3).
    pub fn moment_dim(self) -> usize {
        match self {
            SpaceKind::Planar => 1,
            SpaceKind::Spatial => 3,
        }
    }
}

/// The spatial ANCF element that carries the twist (`torsion = true`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum TorsionElement {
    /// Nodes [r, r_x, r_y]: a section director vector (any section).
    #[default]
    Director,
    /// Nodes [r, r_x, θ]: a twist angle about the tangent from the smallest rotation of the
    /// initial axis (round sections; not on a mounted root).
    Angle,
}

/// How the beam root is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Root {
    /// Position and orientation fixed (cantilever).
    #[default]
    Clamped,
    /// Position fixed, free to rotate in the plane (planar scenes).
    Pinned,
    /// Position fixed, orientation free (spatial scenes: a spherical joint to the ground).
    Ball,
    /// Clamped to a moving mount frame that a host drives (position, orientation, their rates
    /// and accelerations: the `[mount]` table gives the start values). The beam is built in the
    /// mount frame: root at the mount point, along the frame's x axis turned by `initial.angle`
    /// (planar) or `initial.orientation` (spatial).
    Mounted,
}

/// Which mount inputs define the base motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum MotionInput {
    /// Pose, velocities and accelerations are inputs (exact base motion).
    #[default]
    PoseVelocityAcceleration,
    /// Pose and velocities only: the accelerations are estimated by backward differences of
    /// the velocity inputs between communication points (or taken from the velocities' first
    /// input derivatives when a host gives them).
    PoseVelocity,
}

/// The `[mount]` table of a `root = "mounted"` scene: the mount frame's motion at the start,
/// world axes, SI (an FMU takes these as the start values of its mount inputs). Vectors have
/// 2 components `[x, y]` in a planar scene, 3 in a spatial one; angular quantities 1 (`[z]`) or
/// 3. Missing vectors are zero.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Mount {
    /// Mount point [m].
    #[serde(default)]
    pub position: Vec<f64>,
    /// Planar scenes: angle of the mount frame's x axis from global x [rad], counter-clockwise.
    #[serde(default)]
    pub angle: f64,
    /// Spatial scenes: mount frame → world, Euler parameters `[e0, e1, e2, e3]` (scalar first,
    /// normalized on reading; identity if not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<[f64; 4]>,
    /// Velocity of the mount point [m/s].
    #[serde(default)]
    pub velocity: Vec<f64>,
    /// Angular velocity of the mount frame [rad/s], world axes.
    #[serde(default)]
    pub angular_velocity: Vec<f64>,
    /// Acceleration of the mount point [m/s²].
    #[serde(default)]
    pub acceleration: Vec<f64>,
    /// Angular acceleration of the mount frame [rad/s²], world axes.
    #[serde(default)]
    pub angular_acceleration: Vec<f64>,
    /// `pose_velocity_acceleration` (default) or `pose_velocity`.
    #[serde(default)]
    pub motion_input: MotionInput,
}

/// Kind of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SegmentKind {
    /// Floating frame with transverse modal coordinates (small elastic deformation).
    Modal,
    /// Chain of planar ANCF cable elements (large deformation).
    Ancf,
}

/// Strain measures of the ANCF cable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum StrainModel {
    /// ε = |r′| − 1 and signed material curvature e₃·(r′×r″)/|r′|² (Gerstmayr & Irschik).
    #[default]
    Exact,
    /// The paper's simplified model: ε = ½(r′ᵀr′ − 1), κ ≈ |r″| (constant bending stiffness).
    Paper,
}

/// One segment of the beam, root to tip.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Unique name; prefixes the segment's FMU parameters.
    pub name: String,
    /// `modal` or `ancf`.
    pub kind: SegmentKind,
    /// Undeformed length [m].
    pub length: f64,
    /// Cross-section shape.
    #[serde(default)]
    pub section: Section,
    /// Diameter of a round section [m]. This and the other dimensions: a number, or
    /// `[at_start, at_end]` for a linear taper along the segment ([`Dim`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter: Option<Dim>,
    /// Width of a rectangle, out of the bending plane [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<Dim>,
    /// Height of a rectangle, in the bending plane [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<Dim>,
    /// Inner diameter of a tube [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_diameter: Option<Dim>,
    /// Young's modulus E [Pa].
    pub youngs_modulus: f64,
    /// Poisson's ratio ν [-]: shear modulus G = E/(2(1 + ν)) (torsion in spatial scenes).
    #[serde(default = "Segment::default_poisson_ratio")]
    pub poisson_ratio: f64,
    /// Density ρ [kg/m³].
    pub density: f64,
    /// Kelvin–Voigt retardation time τ [s]: stress E(ε + τ ε̇), bending likewise. On a modal
    /// segment the same law acts on the modes (damping ratio τ ω_k / 2). 0 = none.
    #[serde(default)]
    pub damping_time: f64,
    /// Modal damping ratio ζ applied to every mode (modal segments only). 0 = none.
    #[serde(default)]
    pub damping_ratio: f64,
    /// Number of clamped–free bending modes (modal segments only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Add the two static interface (Craig–Bampton constraint) modes at the tip end.
    #[serde(default)]
    pub interface_modes: bool,
    /// A modal segment as the linear floating frame (ū = [x; w] inside the segment, strain
    /// energy ½EI∫w″²dx, tip angle θ + w′(L), the held frame's geometric stiffness added;
    /// spatial: ū = (x, v, w), the tip directors turned by the rotation vector (0, −w′, v′)),
    /// instead of the geometrically nonlinear body (modal segments only). For comparisons with
    /// linear theory and with the linear bodies of earlier versions.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub linear: bool,
    /// Number of ANCF elements (ANCF segments only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// Strain model of the ANCF elements.
    #[serde(default)]
    pub strain: StrainModel,
    /// Polynomial degree of the ANCF elements (ANCF segments only): 3 (the default) is the
    /// cubic Hermite cable element; 4 … [`MAX_DEGREE`] add hierarchic C¹ bubbles, one vector
    /// amplitude each, as element-internal coordinates (the nodes stay [r, r′]).
    #[serde(
        default = "Segment::default_degree",
        skip_serializing_if = "Segment::is_cubic"
    )]
    pub degree: usize,
    /// Uniform distributed dead load on the segment [N/m], world axes: `[qx, qy]` or
    /// `[qx, qy, qz]` (none: zero). It enters every element of the segment as gravity does (a
    /// dead load of density q per unit length beside ρA g). A segment that sets it (zero
    /// allowed) gets the FMU input `<segment>.line_load.<axis>`, at most [`MAX_LINE_LOADS`]
    /// segments per scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_load: Option<Vec<f64>>,
    /// Initial curvature of the unstressed segment [1/m], constant along it (ANCF segments
    /// only; none: straight). Planar: a number κ, the segment an arc turning counter-clockwise
    /// (towards +y of its start tangent, about +z) for κ > 0. Spatial: `[κ_y, κ_z]` about the
    /// section axes y, z of the segment's start frame, right-handed: κ_z > 0 turns the tangent
    /// towards +y, κ_y > 0 towards −z. The segment is that arc and strains count from it; the
    /// next segment starts on its end position, end tangent and end section frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_curvature: Option<Curvature>,
}

/// A segment's initial curvature as written in the scene: a number (planar) or a list
/// `[κ_y, κ_z]` (spatial) [1/m] ([`Segment::initial_curvature`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Curvature {
    /// Planar: κ [1/m], positive counter-clockwise.
    Number(f64),
    /// Spatial: `[κ_y, κ_z]` [1/m] about the section axes.
    List(Vec<f64>),
}

impl Curvature {
    /// The components as written (one for a number).
    pub fn values(&self) -> Vec<f64> {
        match self {
            Curvature::Number(k) => vec![*k],
            Curvature::List(v) => v.clone(),
        }
    }
}

/// Initial state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum InitialState {
    /// Straight at `angle`, at rest.
    #[default]
    Straight,
    /// Static equilibrium under gravity and the tip force, at rest.
    Static,
}

/// Initial condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    /// `straight` or `static`.
    #[serde(default)]
    pub state: InitialState,
    /// Planar scenes: angle of the root (and of the straight beam) from the global x axis
    /// [rad], counter-clockwise.
    #[serde(default)]
    pub angle: f64,
    /// Spatial scenes: orientation of the root frame, Euler parameters `[e0, e1, e2, e3]`
    /// (scalar first, root frame → world; normalized on reading). The beam's axis is the
    /// frame's x axis, the section axes its y and z. Default: identity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<[f64; 4]>,
}

/// Loads at the free end.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Tip {
    /// Constant (dead) force at the tip, global axes [N]: `[x, y]` or `[x, y, z]`.
    #[serde(default)]
    pub force: Vec<f64>,
    /// Constant (dead) moment at the tip, global axes [N m]: `[z]` in a planar scene,
    /// `[x, y, z]` in a spatial one.
    #[serde(default)]
    pub moment: Vec<f64>,
}

/// The `[solver]` table: the integrator's settings, each default documented where it is
/// defined ([`IntegrationParameters`]).
pub type Solver = IntegrationParameters;

/// Run settings used by the command-line runner and as the FMU's default experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Simulation {
    /// End time [s].
    #[serde(default = "Simulation::default_t_end")]
    pub t_end: f64,
    /// Output (communication) step [s].
    #[serde(default = "Simulation::default_output_step")]
    pub output_step: f64,
}

impl Simulation {
    fn default_t_end() -> f64 {
        2.0
    }
    fn default_output_step() -> f64 {
        1e-3
    }
}

impl Default for Simulation {
    fn default() -> Self {
        Self {
            t_end: Self::default_t_end(),
            output_step: Self::default_output_step(),
        }
    }
}

/// The most segments of a scene that may carry a `line_load` (each is an FMU input
/// `<segment>.line_load.<axis>`, held in a fixed-size slot so that a step allocates nothing).
pub const MAX_LINE_LOADS: usize = 8;

/// A beam set-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Scene name (model name of the FMU).
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// `planar` (default) or `spatial`.
    #[serde(default)]
    pub space: SpaceKind,
    /// Spatial scenes: whether the ANCF elements carry torsion (the director element, a section
    /// director r_y: 9 coordinates per node; or the angle element) or are 3D cables (r, r_x; 6
    /// per node, no torque about the axis).
    #[serde(default = "Scene::default_torsion")]
    pub torsion: bool,
    /// Spatial scenes with torsion: the ANCF element that carries the twist, `"director"`
    /// (default: nodes [r, r_x, r_y], any section) or `"angle"` (nodes [r, r_x, θ], one
    /// 7 coordinates per node instead of 9; round sections, clamped or ball roots).
    #[serde(default)]
    pub torsion_element: TorsionElement,
    /// Gravity vector, global axes [m/s²]: `[x, y]` or `[x, y, z]` (default zero).
    #[serde(default)]
    pub gravity: Vec<f64>,
    /// Root boundary condition.
    #[serde(default)]
    pub root: Root,
    /// The mount's start motion (`root = "mounted"` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mount: Option<Mount>,
    /// Initial condition.
    #[serde(default)]
    pub initial: Initial,
    /// Tip loads.
    #[serde(default)]
    pub tip: Tip,
    /// Integrator settings.
    #[serde(default)]
    pub solver: Solver,
    /// Run settings.
    #[serde(default)]
    pub simulation: Simulation,
    /// Optional outputs (`[outputs]`).
    #[serde(default, skip_serializing_if = "OutputOptions::is_default")]
    pub outputs: OutputOptions,
    /// Segments from root to tip.
    #[serde(default)]
    pub segments: Vec<Segment>,
    /// Attached masses: rigid bodies riding on the centreline (`[[masses]]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub masses: Vec<Mass>,
    /// Stations: sections whose loads and stress are outputs (`[[stations]]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stations: Vec<Station>,
}

/// Optional outputs of a scene (`[outputs]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct OutputOptions {
    /// `beam.stress_max` [Pa] and `beam.stress_max_at` [m]: the largest von Mises stress
    /// along the beam from the local strains and where (docs/stations.md).
    #[serde(default)]
    pub stress: bool,
}

impl OutputOptions {
    fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// The most stations a scene may have (their loads are held in fixed-size slots of the outputs).
pub const MAX_STATIONS: usize = 16;

/// A station: a cross-section of a segment whose section loads (the force and moment that the
/// outboard part exerts on the inboard part, section frame) and largest von Mises stress are
/// outputs (`station.<name>.force.*`, `.moment.*`, `.stress`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Station {
    /// Unique name (letters, digits, `_`); prefixes its outputs.
    pub name: String,
    /// The segment it cuts (a segment name).
    pub segment: String,
    /// Arc length from that segment's start [m]: its start, its end, or (ANCF) a node
    /// between two of its elements.
    pub at: f64,
}

impl Mass {
    /// Whether it is a point mass: no offset and no rotary inertia (or all zeros).
    pub fn is_point(&self) -> bool {
        let zero = |v: &Option<Vec<f64>>| v.as_ref().is_none_or(|v| v.iter().all(|x| *x == 0.0));
        zero(&self.inertia) && zero(&self.offset)
    }

    /// Spatial: the rotary inertia [I_xx, I_yy, I_zz] about its centre [kg m²] and the offset
    /// [x, y, z] [m], section axes (zeros where not given).
    pub fn spatial_body(&self) -> ([f64; 3], [f64; 3]) {
        let get = |v: &Option<Vec<f64>>| -> [f64; 3] {
            std::array::from_fn(|k| v.as_ref().and_then(|v| v.get(k)).copied().unwrap_or(0.0))
        };
        (get(&self.inertia), get(&self.offset))
    }

    /// Planar: the rotary inertia I_zz [kg m²] and the offset (along the tangent, along the
    /// section's y axis) [m] (zeros where not given).
    pub fn planar_body(&self) -> (f64, [f64; 2]) {
        let get = |v: &Option<Vec<f64>>, k: usize| v.as_ref().and_then(|v| v.get(k)).copied();
        (
            get(&self.inertia, 0).unwrap_or(0.0),
            [
                get(&self.offset, 0).unwrap_or(0.0),
                get(&self.offset, 1).unwrap_or(0.0),
            ],
        )
    }
}

/// An attached mass (`[[masses]]`): a rigid body riding on a segment's centreline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mass {
    /// Unique name (letters, digits, `_`); prefixes its FMU parameters.
    pub name: String,
    /// The segment it sits on (a segment name).
    pub segment: String,
    /// Arc length from that segment's start [m], 0 ≤ at ≤ its length.
    pub at: f64,
    /// Mass [kg], > 0.
    pub mass: f64,
    /// Rotary inertia about its centre, section axes [kg m²]: `[Ixx, Iyy, Izz]` in a spatial
    /// scene, `[Izz]` in a planar one (a spatial build refuses a non-zero value on a 3D cable,
    /// `torsion = false`, whose section has no frame about its axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<Vec<f64>>,
    /// Its centre from the centreline point, section axes [m] (`[x, y]` or `[x, y, z]`; a
    /// spatial build refuses a non-zero value on a 3D cable, as `inertia`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<Vec<f64>>,
}

impl Segment {
    /// The line load [N/m] with `N` components, `None` when the segment has none or a zero
    /// one (so that a segment without a line load computes exactly as before).
    pub fn line_load_vec<const N: usize>(&self) -> Option<[f64; N]> {
        let q = self.line_load.as_ref()?;
        q.iter().any(|x| *x != 0.0).then(|| padded(q))
    }

    /// The segment's initial curvature as `[κ_y, κ_z]` about the section axes [1/m] (planar:
    /// `[0, κ]`, bending in the x–y plane about z), `None` when straight (absent or all zero).
    /// Valid after `validate`.
    pub fn curvature(&self) -> Option<[f64; 2]> {
        let v = self.initial_curvature.as_ref()?.values();
        let k = match v.as_slice() {
            [k] => [0.0, *k],
            [ky, kz] => [*ky, *kz],
            _ => return None,
        };
        (k != [0.0, 0.0]).then_some(k)
    }

    fn default_poisson_ratio() -> f64 {
        0.3
    }

    fn default_degree() -> usize {
        3
    }

    fn is_cubic(degree: &usize) -> bool {
        *degree == 3
    }
}

impl Scene {
    /// The segments that declare a `line_load` (zero included), in segment order: slot k of the
    /// line-load inputs belongs to segment `line_load_segments()[k]`.
    pub fn line_load_segments(&self) -> Vec<usize> {
        (self.segments.iter().enumerate())
            .filter(|(_, s)| s.line_load.is_some())
            .map(|(i, _)| i)
            .collect()
    }

    /// Parses and validates a scene.
    pub fn from_toml(text: &str) -> Result<Self, SceneError> {
        Self::from_toml_with_overrides(text, &[])
    }

    /// Parses a scene, applies `key.path=value` overrides, then validates.
    pub fn from_toml_with_overrides(
        text: &str,
        overrides: &[(String, String)],
    ) -> Result<Self, SceneError> {
        let mut value: toml::Table = toml::from_str(text)
            .map_err(|e| SceneError(format!("scene is not valid TOML: {e}")))?;
        for (key, val) in overrides {
            apply_override(&mut value, key, val)?;
        }
        let scene: Scene = Scene::deserialize(toml::Value::Table(value))
            .map_err(|e| SceneError(format!("scene: {}", e.to_string().trim())))?;
        let mut scene = scene;
        scene.validate()?;
        scene.fill_vectors();
        Ok(scene)
    }

    /// Serializes the scene back to TOML.
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// Whether the mount's spin matters at the start (`[mount]`): (its centrifugal field
    /// |ω|²L, its Euler field |α|L) against gravity minus the mount's acceleration, above 1e-9
    /// of it (a host at rest reports rounding-level rates, which do not count). `(false,
    /// false)` unless mounted.
    pub fn mount_turns(&self) -> (bool, bool) {
        let Some(m) = self.mount_start() else {
            return (false, false);
        };
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let field: Vec<f64> = (0..self.space.dim())
            .map(|k| {
                let g = self.gravity.get(k).copied().unwrap_or(0.0);
                g - m.acceleration.get(k).copied().unwrap_or(0.0)
            })
            .collect();
        let floor = 1e-9 * norm(&field).max(1.0);
        let l = self.total_length();
        (
            norm(&m.angular_velocity).powi(2) * l > floor,
            norm(&m.angular_acceleration) * l > floor,
        )
    }

    /// The mount's start motion (`[mount]`, or at rest at the origin), every vector with all its
    /// components; `None` unless `root = "mounted"`.
    pub fn mount_start(&self) -> Option<Mount> {
        if self.root != Root::Mounted {
            return None;
        }
        let mut m = self.mount.clone().unwrap_or_default();
        let (n, nm) = (self.space.dim(), self.space.moment_dim());
        for (v, k) in [
            (&mut m.position, n),
            (&mut m.velocity, n),
            (&mut m.acceleration, n),
            (&mut m.angular_velocity, nm),
            (&mut m.angular_acceleration, nm),
        ] {
            v.resize(k, 0.0);
        }
        if self.space == SpaceKind::Spatial {
            let e = m.orientation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
            let norm = e.iter().map(|x| x * x).sum::<f64>().sqrt();
            m.orientation = Some(e.map(|x| x / norm));
        }
        Some(m)
    }

    /// Total undeformed length [m].
    pub fn total_length(&self) -> f64 {
        self.segments.iter().map(|s| s.length).sum()
    }

    /// Writes every load vector with all its components (zeros where the file left it out).
    pub fn fill_vectors(&mut self) {
        let (n, nm) = (self.space.dim(), self.space.moment_dim());
        for (v, n) in [
            (&mut self.gravity, n),
            (&mut self.tip.force, n),
            (&mut self.tip.moment, nm),
        ] {
            v.resize(n, 0.0);
        }
    }

    fn default_torsion() -> bool {
        true
    }

    /// The point masses on segment `si` (no offset, no rotary inertia, [`Mass::is_point`]):
    /// (arc length from the segment's start [m], mass [kg]), in scene order.
    pub fn point_masses(&self, si: usize) -> Vec<(f64, f64)> {
        self.masses_on(si)
            .filter(|m| m.is_point())
            .map(|m| (m.at, m.mass))
            .collect()
    }

    /// The attached masses on segment `si`, in scene order.
    pub fn masses_on(&self, si: usize) -> impl Iterator<Item = &Mass> + '_ {
        let name = self.segments.get(si).map(|s| s.name.as_str());
        self.masses
            .iter()
            .filter(move |m| Some(m.segment.as_str()) == name)
    }

    /// Gravity [m/s²] with `N` components (a scene without gravity: zero).
    pub fn gravity_vec<const N: usize>(&self) -> [f64; N] {
        padded(&self.gravity)
    }

    /// Tip force [N] with `N` components (none: zero).
    pub fn tip_force_vec<const N: usize>(&self) -> [f64; N] {
        padded(&self.tip.force)
    }

    /// Tip moment [N m] with `N` components (none: zero).
    pub fn tip_moment_vec<const N: usize>(&self) -> [f64; N] {
        padded(&self.tip.moment)
    }

    /// Orientation of the root frame as unit Euler parameters `[e0, e1, e2, e3]` (scalar first,
    /// root frame → world; identity if not given).
    pub fn root_orientation(&self) -> [f64; 4] {
        let e = self.initial.orientation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
        let n = e.iter().map(|x| x * x).sum::<f64>().sqrt();
        e.map(|x| x / n)
    }
}

/// The first `N` components of `v`, zero where `v` is shorter.
fn padded<const N: usize>(v: &[f64]) -> [f64; N] {
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(v) {
        *o = *x;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const OK: &str = r#"
name = "t"
gravity = [0.0, -9.81]
[[segments]]
name = "a"
kind = "ancf"
length = 0.4
diameter = 0.002
youngs_modulus = 2.1e11
density = 7850.0
elements = 4
"#;

    #[test]
    fn parses_a_minimal_scene() {
        let s = Scene::from_toml(OK).unwrap();
        assert_eq!(s.segments[0].elements, Some(4));
        assert_eq!(s.solver.rho_inf, 0.9);
    }

    fn err_of(overrides: &[(&str, &str)]) -> String {
        let o: Vec<(String, String)> = overrides
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        Scene::from_toml_with_overrides(OK, &o).unwrap_err().0
    }

    #[test]
    fn bad_values_name_the_field() {
        assert!(err_of(&[("segments.0.length", "-0.2")]).contains("segments[0].length = -0.2"));
        assert!(err_of(&[("segments.0.elements", "0")]).contains("segments[0].elements = 0"));
        assert!(err_of(&[("segments.0.kind", "\"beam\"")]).contains("kind"));
        assert!(err_of(&[("segments.0.youngs_modulus", "0.0")]).contains("youngs_modulus"));
        assert!(err_of(&[("segments.0.density", "nan")]).contains("density = NaN"));
        assert!(err_of(&[("solver.rho_inf", "1.0")]).contains("solver.rho_inf"));
        assert!(err_of(&[("segments", "[]")]).contains("empty"));
        assert!(err_of(&[("segments.0.lenght", "1.0")]).contains("lenght"));
        assert!(err_of(&[("segments.0.linear", "true")]).contains("segments[0].linear = true"));
    }

    #[test]
    fn masses_are_parsed_and_checked() {
        let with = |extra: &str| Scene::from_toml(&format!("{OK}\n[[masses]]\n{extra}"));
        let s = with("name = \"lamp\"\nsegment = \"a\"\nat = 0.35\nmass = 1.2").unwrap();
        assert_eq!(s.point_masses(0), vec![(0.35, 1.2)]);
        assert!(s.to_toml().contains("[[masses]]"));
        assert!(Scene::from_toml(OK).unwrap().point_masses(0).is_empty());
        assert!(!Scene::from_toml(OK).unwrap().to_toml().contains("masses"));
        let err = |extra: &str| with(extra).unwrap_err().0;
        let base = "name = \"m\"\nsegment = \"a\"\nmass = 1.0\n";
        assert!(err(&format!("{base}at = 0.5")).contains("masses[0].at = 0.5: must be in [0, 0.4]"));
        assert!(err(&format!("{base}at = -0.1")).contains("masses[0].at = -0.1"));
        assert!(err("name = \"m\"\nsegment = \"b\"\nmass = 1.0\nat = 0.1")
            .contains("masses[0].segment = \"b\": no segment has this name; use one of [\"a\"]"));
        assert!(err("name = \"m\"\nsegment = \"a\"\nmass = 0.0\nat = 0.1")
            .contains("masses[0].mass = 0"));
        assert!(err("name = \"m\"\nsegment = \"a\"\nmass = nan\nat = 0.1")
            .contains("masses[0].mass = NaN"));
        assert!(err("name = \"m-1\"\nsegment = \"a\"\nmass = 1.0\nat = 0.1")
            .contains("masses[0].name = \"m-1\""));
        assert!(err(&format!("{base}at = 0.1\ninertia = [0.1, 0.1, 0.1]"))
            .contains("masses[0].inertia = [0.1, 0.1, 0.1]: a planar scene takes 1 components"));
        assert!(err(&format!("{base}at = 0.1\noffset = [0.1]"))
            .contains("masses[0].offset = [0.1]: a planar scene takes 2 components"));
        assert!(err(&format!("{base}at = 0.1\nspeed = 1.0")).contains("speed"));
        assert!(err(&format!("{base}at = 0.1\n[[masses]]\n{base}at = 0.2"))
            .contains("masses[1].name = \"m\": mass names must be unique"));
    }

    #[test]
    fn vector_lengths_roots_and_orientation_follow_the_space() {
        assert!(err_of(&[("gravity", "[0.0, 0.0, -9.81]")])
            .contains("gravity = [0.0, 0.0, -9.81]: a planar scene takes 2 components"));
        assert!(err_of(&[("space", "\"spatial\"")]).contains("a spatial scene takes 3 components"));
        assert!(err_of(&[("tip.moment", "[0.0, 1.0]")]).contains("tip.moment"));
        assert!(err_of(&[("root", "\"ball\"")]).contains("root = \"ball\""));
        let spatial = [("space", "\"spatial\""), ("gravity", "[0.0, 0.0, -9.81]")];
        let with = |extra: (&str, &str)| err_of(&[spatial[0], spatial[1], extra]);
        assert!(with(("root", "\"pinned\"")).contains("root = \"pinned\""));
        assert!(
            with(("initial.orientation", "[0.0, 0.0, 0.0, 0.0]")).contains("initial.orientation")
        );
        assert!(
            with(("initial.orientation", "[1.0, nan, 0.0, 0.0]")).contains("initial.orientation")
        );
        assert!(with(("initial.angle", "0.3")).contains("initial.orientation"));
        assert!(err_of(&[("segments.0.poisson_ratio", "0.7")]).contains("poisson_ratio = 0.7"));
        let o: Vec<(String, String)> = spatial
            .iter()
            .chain(&[("initial.orientation", "[2.0, 0.0, 0.0, 2.0]")])
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        let s = Scene::from_toml_with_overrides(OK, &o).unwrap();
        let e = s.root_orientation();
        assert!((e[0] - 0.5f64.sqrt()).abs() < 1e-15 && (e[3] - 0.5f64.sqrt()).abs() < 1e-15);
        // missing loads are written with all their components
        assert_eq!((s.tip.force.len(), s.tip.moment.len()), (3, 3));
    }

    #[test]
    fn section_properties_match_closed_forms() {
        use std::f64::consts::PI;
        let tube = Scene::from_toml_with_overrides(
            OK,
            &[
                ("segments.0.section".into(), "\"tube\"".into()),
                ("segments.0.inner_diameter".into(), "0.0015".into()),
            ],
        )
        .unwrap();
        let p = tube.segments[0].section_props();
        let (d, di) = (0.002f64, 0.0015f64);
        let i = PI * (d.powi(4) - di.powi(4)) / 64.0;
        assert!((p.area / (PI * (d * d - di * di) / 4.0) - 1.0).abs() < 1e-14);
        assert!((p.i_y / i - 1.0).abs() < 1e-14 && (p.i_z / i - 1.0).abs() < 1e-14);
        assert!((p.torsion / (2.0 * i) - 1.0).abs() < 1e-14);
        assert!(err_of(&[("segments.0.section", "\"tube\"")]).contains("inner_diameter is missing"));
        assert!(err_of(&[
            ("segments.0.section", "\"tube\""),
            ("segments.0.inner_diameter", "0.002")
        ])
        .contains("inner_diameter = 0.002"));
        // Saint-Venant: J = k a b³ with k = 0.1406 (square), 0.2287 (a/b = 2), 0.3123 (a/b = 10)
        // (Timoshenko & Goodier, Theory of Elasticity, §109 table), → 1/3 for a thin strip
        for (ratio, k) in [(1.0, 0.1406), (2.0, 0.2287), (10.0, 0.3123)] {
            let j = rectangle_torsion_constant(1.0, ratio) / ratio;
            assert!((j - k).abs() < 1e-4, "a/b = {ratio}: {j}");
        }
        let j = rectangle_torsion_constant(1000.0, 1.0) / 1000.0;
        assert!(
            (j - (1.0 / 3.0) * (1.0 - 0.630_2 / 1000.0)).abs() < 1e-6,
            "{j}"
        );
    }
}
