//! Scene files: one beam set-up in TOML (see `docs/scene-format.md`).
//!
//! A scene is parsed with serde (unknown fields are refused), then [`Scene::validate`] checks
//! every value and names the field, the value and what is allowed. Nothing here panics on bad
//! input. [`Scene::from_toml_with_overrides`] applies `--set key.path=value` overrides on the
//! TOML tree before typing it, so any field can be overridden by its dotted path.

mod overrides;

use crate::math;
use serde::{Deserialize, Serialize};
use std::fmt;

pub use crate::integrator::{IntegrationParameters, MIN_STEP, MIN_TOLERANCE};
pub use overrides::apply_override;

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

/// Cross-section shape. Section axes: y (the bending plane of a planar scene) and z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Section {
    /// Solid round rod of `diameter`.
    #[default]
    Round,
    /// Solid rectangle `width` (along z, out of the planar bending plane) × `height` (along y).
    Rectangle,
    /// Round tube of outer `diameter` and `inner_diameter`.
    Tube,
}

/// Properties of a cross-section (valid after [`Scene::validate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionProps {
    /// Area A [m²].
    pub area: f64,
    /// Second moment about the section's y axis [m⁴] (bending in the x–z plane).
    pub i_y: f64,
    /// Second moment about the section's z axis [m⁴] (bending in the x–y plane: the planar I).
    pub i_z: f64,
    /// Torsion constant J [m⁴] (GJ is the torsional stiffness): I_p for round sections and
    /// tubes, Saint-Venant's series for a rectangle.
    pub torsion: f64,
    /// Polar moment I_p = I_y + I_z [m⁴] (torsional rotary inertia ρI_p per length).
    pub polar: f64,
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
    /// Diameter of a round section [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter: Option<f64>,
    /// Width of a rectangle, out of the bending plane [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Height of a rectangle, in the bending plane [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Inner diameter of a tube [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_diameter: Option<f64>,
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
    /// Number of ANCF elements (ANCF segments only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// Strain model of the ANCF elements.
    #[serde(default)]
    pub strain: StrainModel,
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
    /// Spatial scenes: whether the ANCF elements carry a twist director r_y (torsion; 9
    /// coordinates per node) or are 3D cables (r, r_x; 6 per node, no torque about the axis).
    #[serde(default = "Scene::default_torsion")]
    pub torsion: bool,
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
    /// Segments from root to tip.
    #[serde(default)]
    pub segments: Vec<Segment>,
}

impl Segment {
    fn default_poisson_ratio() -> f64 {
        0.3
    }

    /// Area A [m²] and second moment I [m⁴] of the cross-section in the planar bending plane
    /// (about z; valid after `validate`).
    pub fn area_inertia(&self) -> (f64, f64) {
        let p = self.section_props();
        (p.area, p.i_z)
    }

    /// Shear modulus G = E/(2(1 + ν)) [Pa].
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Properties of the cross-section (valid after `validate`).
    pub fn section_props(&self) -> SectionProps {
        use std::f64::consts::PI;
        let round = |d: f64| {
            let a = PI * d * d / 4.0;
            (a, a * d * d / 16.0)
        };
        match self.section {
            Section::Round | Section::Tube => {
                let (ao, io) = round(self.diameter.unwrap_or(0.0));
                let (ai, ii) = match self.section {
                    Section::Tube => round(self.inner_diameter.unwrap_or(0.0)),
                    _ => (0.0, 0.0),
                };
                let i = io - ii;
                SectionProps {
                    area: ao - ai,
                    i_y: i,
                    i_z: i,
                    torsion: 2.0 * i,
                    polar: 2.0 * i,
                }
            }
            Section::Rectangle => {
                let (b, h) = (self.width.unwrap_or(0.0), self.height.unwrap_or(0.0));
                let (i_y, i_z) = (h * b * b * b / 12.0, b * h * h * h / 12.0);
                SectionProps {
                    area: b * h,
                    i_y,
                    i_z,
                    torsion: rectangle_torsion_constant(b, h),
                    polar: i_y + i_z,
                }
            }
        }
    }
}

/// Saint-Venant torsion constant of a solid `b` × `h` rectangle [m⁴]:
/// J = a b³ [1/3 − (64/π⁵)(b/a) Σ_{n odd} tanh(nπa/(2b))/n⁵], a ≥ b (Timoshenko & Goodier §109);
/// the series is summed to n = 99 (relative remainder below 1e-10).
pub fn rectangle_torsion_constant(b: f64, h: f64) -> f64 {
    use std::f64::consts::PI;
    let (a, b) = if h >= b { (h, b) } else { (b, h) };
    let sum: f64 = (0..50)
        .map(|k| {
            let n = (2 * k + 1) as f64;
            math::tanh(n * PI * a / (2.0 * b)) / n.powi(5)
        })
        .sum();
    a * b * b * b * (1.0 / 3.0 - 64.0 / PI.powi(5) * (b / a) * sum)
}

fn check_positive(field: &str, v: f64, what: &str) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number > 0 ({what})"
        )))
    }
}

fn check_nonnegative(field: &str, v: f64, what: &str) -> Result<(), SceneError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number >= 0 ({what})"
        )))
    }
}

fn check_finite(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SceneError(format!(
            "{field} = {v}: must be a finite number"
        )))
    }
}

/// Largest number of modes and elements accepted per segment.
pub const MAX_MODES: usize = 12;
/// Largest number of ANCF elements accepted per segment.
pub const MAX_ELEMENTS: usize = 4096;

impl Scene {
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

    /// Checks every value; the error names the field, its value and what is allowed.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.name.trim().is_empty() {
            return Err(SceneError("name = \"\": give the scene a name".into()));
        }
        let sp = self.space;
        let (axes, moment_axes) = match sp {
            SpaceKind::Planar => ("[x, y]", "[z] (the z component)"),
            SpaceKind::Spatial => ("[x, y, z]", "[x, y, z]"),
        };
        for (field, v, n, how) in [
            ("gravity", &self.gravity, sp.dim(), axes),
            ("tip.force", &self.tip.force, sp.dim(), axes),
            ("tip.moment", &self.tip.moment, sp.moment_dim(), moment_axes),
        ] {
            if !v.is_empty() && v.len() != n {
                return Err(SceneError(format!(
                    "{field} = {v:?}: a {sp:?} scene takes {n} components {how} (or leave it out for zero)"
                ).replace("Planar", "planar").replace("Spatial", "spatial")));
            }
            for (i, x) in v.iter().enumerate() {
                check_finite(&format!("{field}[{i}]"), *x)?;
            }
        }
        check_finite("initial.angle", self.initial.angle)?;
        match sp {
            SpaceKind::Planar => {
                if self.root == Root::Ball {
                    return Err(SceneError(
                        "root = \"ball\": a planar scene has clamped or pinned roots (a ball root needs space = \"spatial\")".into(),
                    ));
                }
                if self.initial.orientation.is_some() {
                    return Err(SceneError(
                        "initial.orientation: a planar scene gives the root direction as initial.angle [rad]; remove orientation or set space = \"spatial\"".into(),
                    ));
                }
                if !self.torsion {
                    return Err(SceneError(
                        "torsion = false: torsion is a switch of spatial scenes; remove it or set space = \"spatial\"".into(),
                    ));
                }
            }
            SpaceKind::Spatial => {
                if self.root == Root::Pinned {
                    return Err(SceneError(
                        "root = \"pinned\": a spatial scene has clamped or ball roots (a ball root holds the position and leaves the orientation free)".into(),
                    ));
                }
                if self.initial.angle != 0.0 {
                    return Err(SceneError(format!(
                        "initial.angle = {}: a spatial scene gives the root frame as initial.orientation = [e0, e1, e2, e3]",
                        self.initial.angle
                    )));
                }
                if let Some(e) = self.initial.orientation {
                    let n = e.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if !(n.is_finite() && n > 1e-6) {
                        return Err(SceneError(format!(
                            "initial.orientation = {e:?}: Euler parameters must be finite and not all zero (identity: [1, 0, 0, 0])"
                        )));
                    }
                }
            }
        }
        self.validate_mount()?;
        let s = &self.solver;
        if !(s.rho_inf.is_finite() && (0.0..1.0).contains(&s.rho_inf)) {
            return Err(SceneError(format!(
                "solver.rho_inf = {}: must be in [0, 1) (index-3 constraints need numerical damping; 0.9 is the default)",
                s.rho_inf
            )));
        }
        if !(s.max_step.is_finite() && s.max_step >= MIN_STEP) {
            return Err(SceneError(format!(
                "solver.max_step = {}: must be a finite number of seconds >= {MIN_STEP:e} (the smallest internal step: a shorter one resolves nothing of a beam and only multiplies the work)",
                s.max_step
            )));
        }
        if !(s.tolerance.is_finite() && s.tolerance >= MIN_TOLERANCE && s.tolerance < 1e-2) {
            return Err(SceneError(format!(
                "solver.tolerance = {}: must be in [{MIN_TOLERANCE:e}, 0.01) (relative Newton tolerance; 1e-11 is the default)",
                s.tolerance
            )));
        }
        if s.max_internal_steps == 0 {
            return Err(SceneError(
                "solver.max_internal_steps = 0: must be >= 1 (internal steps allowed in one communication step; 20000 is the default)".into(),
            ));
        }
        if s.max_iterations == 0 || s.max_iterations > 100 {
            return Err(SceneError(format!(
                "solver.max_iterations = {}: must be in 1..=100",
                s.max_iterations
            )));
        }
        check_positive("simulation.t_end", self.simulation.t_end, "seconds")?;
        check_positive(
            "simulation.output_step",
            self.simulation.output_step,
            "seconds",
        )?;
        if self.segments.is_empty() {
            return Err(SceneError(
                "segments: the list is empty: add at least one [[segments]] table with kind = \"modal\" or \"ancf\"".into(),
            ));
        }
        for (i, seg) in self.segments.iter().enumerate() {
            let p = format!("segments[{i}]");
            if seg.name.trim().is_empty()
                || !seg
                    .name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_')
            {
                return Err(SceneError(format!(
                    "{p}.name = {:?}: must be non-empty and use only letters, digits and '_' (it prefixes FMU variable names)",
                    seg.name
                )));
            }
            if self.segments[..i].iter().any(|o| o.name == seg.name) {
                return Err(SceneError(format!(
                    "{p}.name = {:?}: segment names must be unique",
                    seg.name
                )));
            }
            check_positive(&format!("{p}.length"), seg.length, "metres")?;
            check_positive(&format!("{p}.youngs_modulus"), seg.youngs_modulus, "Pa")?;
            check_positive(&format!("{p}.density"), seg.density, "kg/m3")?;
            check_nonnegative(&format!("{p}.damping_time"), seg.damping_time, "seconds")?;
            if !(seg.poisson_ratio.is_finite()
                && seg.poisson_ratio > -1.0
                && seg.poisson_ratio <= 0.5)
            {
                return Err(SceneError(format!(
                    "{p}.poisson_ratio = {}: must be in (-1, 0.5] (steel: 0.3, the default)",
                    seg.poisson_ratio
                )));
            }
            if seg.section != Section::Tube && seg.inner_diameter.is_some() {
                return Err(SceneError(format!(
                    "{p}.inner_diameter: only a section = \"tube\" has an inner diameter"
                )));
            }
            match seg.section {
                Section::Round | Section::Tube => {
                    let d = seg.diameter.ok_or_else(|| {
                        SceneError(format!(
                            "{p}.diameter is missing: a round section or a tube needs diameter = <metres> (outer)"
                        ))
                    })?;
                    check_positive(&format!("{p}.diameter"), d, "metres")?;
                    if seg.section == Section::Tube {
                        let di = seg.inner_diameter.ok_or_else(|| {
                            SceneError(format!(
                                "{p}.inner_diameter is missing: a tube needs inner_diameter = <metres>, below diameter"
                            ))
                        })?;
                        if !(di.is_finite() && di >= 0.0 && di < d) {
                            return Err(SceneError(format!(
                                "{p}.inner_diameter = {di}: must be in [0, diameter = {d}) metres"
                            )));
                        }
                    }
                }
                Section::Rectangle => {
                    for (f, v) in [("width", seg.width), ("height", seg.height)] {
                        let v = v.ok_or_else(|| {
                            SceneError(format!(
                                "{p}.{f} is missing: a rectangle section needs width and height in metres"
                            ))
                        })?;
                        check_positive(&format!("{p}.{f}"), v, "metres")?;
                    }
                }
            }
            match seg.kind {
                SegmentKind::Modal => {
                    let n = seg.modes.ok_or_else(|| {
                        SceneError(format!(
                            "{p}.modes is missing: a modal segment needs modes = 1..={MAX_MODES}"
                        ))
                    })?;
                    if n == 0 || n > MAX_MODES {
                        return Err(SceneError(format!(
                            "{p}.modes = {n}: must be in 1..={MAX_MODES}"
                        )));
                    }
                    if seg.elements.is_some() {
                        return Err(SceneError(format!(
                            "{p}.elements: a modal segment has no elements; use modes, or kind = \"ancf\""
                        )));
                    }
                    if !(seg.damping_ratio.is_finite() && (0.0..=1.0).contains(&seg.damping_ratio))
                    {
                        return Err(SceneError(format!(
                            "{p}.damping_ratio = {}: must be in [0, 1]",
                            seg.damping_ratio
                        )));
                    }
                }
                SegmentKind::Ancf => {
                    let n = seg.elements.ok_or_else(|| {
                        SceneError(format!(
                            "{p}.elements is missing: an ancf segment needs elements = 1..={MAX_ELEMENTS}"
                        ))
                    })?;
                    if n == 0 || n > MAX_ELEMENTS {
                        return Err(SceneError(format!(
                            "{p}.elements = {n}: must be in 1..={MAX_ELEMENTS}"
                        )));
                    }
                    if seg.modes.is_some() || seg.interface_modes {
                        return Err(SceneError(format!(
                            "{p}.modes: an ancf segment has no modes; use elements, or kind = \"modal\""
                        )));
                    }
                    if seg.damping_ratio != 0.0 {
                        return Err(SceneError(format!(
                            "{p}.damping_ratio = {}: only modal segments take a damping ratio; use damping_time (Kelvin-Voigt, seconds) on an ancf segment",
                            seg.damping_ratio
                        )));
                    }
                }
            }
        }
        Ok(())
    }

    fn validate_mount(&self) -> Result<(), SceneError> {
        let sp = self.space;
        let Some(m) = &self.mount else {
            return Ok(());
        };
        if self.root != Root::Mounted {
            return Err(SceneError(format!(
                "[mount]: only a root = \"mounted\" scene has a mount (root = {:?}); remove the table or set root = \"mounted\"",
                self.root
            ).replace("Clamped", "\"clamped\"").replace("Pinned", "\"pinned\"").replace("Ball", "\"ball\"")));
        }
        let (n, nm) = (sp.dim(), sp.moment_dim());
        for (field, v, k) in [
            ("mount.position", &m.position, n),
            ("mount.velocity", &m.velocity, n),
            ("mount.acceleration", &m.acceleration, n),
            ("mount.angular_velocity", &m.angular_velocity, nm),
            ("mount.angular_acceleration", &m.angular_acceleration, nm),
        ] {
            if !v.is_empty() && v.len() != k {
                let space = if sp == SpaceKind::Planar {
                    "planar"
                } else {
                    "spatial"
                };
                return Err(SceneError(format!(
                    "{field} = {v:?}: a {space} scene takes {k} components here (or leave it out for zero)"
                )));
            }
            for (i, x) in v.iter().enumerate() {
                check_finite(&format!("{field}[{i}]"), *x)?;
            }
        }
        check_finite("mount.angle", m.angle)?;
        match sp {
            SpaceKind::Planar => {
                if m.orientation.is_some() {
                    return Err(SceneError(
                        "mount.orientation: a planar scene gives the mount frame as mount.angle [rad]; remove orientation or set space = \"spatial\"".into(),
                    ));
                }
            }
            SpaceKind::Spatial => {
                if m.angle != 0.0 {
                    return Err(SceneError(format!(
                        "mount.angle = {}: a spatial scene gives the mount frame as mount.orientation = [e0, e1, e2, e3]",
                        m.angle
                    )));
                }
                if let Some(e) = m.orientation {
                    let norm = e.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if !(norm.is_finite() && norm > 1e-6) {
                        return Err(SceneError(format!(
                            "mount.orientation = {e:?}: Euler parameters must be finite and not all zero (identity: [1, 0, 0, 0])"
                        )));
                    }
                }
            }
        }
        if self.initial.state == InitialState::Static && self.mount_turns().1 {
            return Err(SceneError(
                "initial.state = \"static\" with mount.angular_acceleration nonzero: a spin that changes has no static state in the mount frame; use initial.state = \"straight\", or start at a constant spin".into(),
            ));
        }
        Ok(())
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
