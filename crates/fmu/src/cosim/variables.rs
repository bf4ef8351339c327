//! The beam FMU's variable table: one declared row per variable (name, value reference,
//! causality, variability, unit, description and how the model reads and writes it). The table
//! is a function of the [`Scene`] alone: listing the variables needs no simulator.
//!
//! The names come from the simulator ([`InputId::named`], [`OutputId::named`]: the scene's
//! space decides which exist); this file gives each name its value reference, unit and
//! description. Value references belong to the name, the same in both spaces, never to an
//! enumeration order that could shift: inputs 1–6, outputs 10–32, gravity 100–102, solver
//! 110–113, and segment i's field k at 1000·(i + 1) + k (k: length 1, diameter 2, width 3,
//! height 4, youngs_modulus 5, density 6, damping_time 7, damping_ratio 8, inner_diameter 9;
//! the inputs `<segment>.line_load.<axis>` at 20–22). A scene only gets
//! the variables it needs: no z or quaternion in the plane, no `tip.angle` in space, no damping
//! parameters without damping, no width/height on a round section, an inner diameter on a tube only. `docs/fmu-variables.md` is
//! checked against this table by `tests/variables_doc.rs`.

use fmi2::{Causality, StringVariable, Variability, Variable};
use hybeam::integrator::Mode;
use hybeam::scene::{Dim, Mass, MotionInput, Root, Scene, Section, Segment, SegmentKind};
use hybeam::simulator::{InputId, InputKind, OutputId, Quantity};

use super::view::{Setting, Settings};

/// How the model reads and writes one variable.
#[derive(Debug, Clone, Copy)]
pub enum Access {
    /// An input of the simulator set by the host (tip force, tip moment).
    Input(InputId),
    /// An output of the current state (read only).
    Output(OutputId),
    /// A component of gravity: a tunable parameter, passed on to the running simulator.
    Gravity(InputId),
    /// A scene-wide fixed parameter.
    Scene(&'static SceneParameter),
    /// A field of the segment with this index (root = 0).
    Segment(usize, &'static SegmentField),
    /// A field of the attached mass with this index (`[[masses]]` order).
    Mass(usize, &'static MassField),
    /// A Real parameter of the FMU's views (owned by [`super::view::ViewState`], not the
    /// scene; not part of an FMU state).
    View(Setting),
}

impl Access {
    /// The parameter's value in `scene`; `None` for inputs and outputs.
    pub fn parameter(self, scene: &Scene) -> Option<f64> {
        match self {
            Access::Gravity(id) => Some(id.scene_value(scene)),
            Access::Scene(p) => Some((p.get)(scene)),
            Access::Segment(i, f) => Some((f.get)(&scene.segments[i])),
            Access::Mass(i, f) => Some((f.get)(&scene.masses[i])),
            Access::Input(_) | Access::Output(_) | Access::View(_) => None,
        }
    }

    /// Sets the parameter in `scene` (not validated); no effect for inputs and outputs.
    pub fn set_parameter(self, scene: &mut Scene, x: f64) {
        match self {
            Access::Gravity(id) => id.set_in_scene(scene, x),
            Access::Scene(p) => (p.set)(scene, x),
            Access::Segment(i, f) => (f.set)(&mut scene.segments[i], x),
            Access::Mass(i, f) => (f.set)(&mut scene.masses[i], x),
            Access::Input(_) | Access::Output(_) | Access::View(_) => {}
        }
    }
}

/// A named variable of the simulator: (name, value reference, unit, description).
pub type Row = (&'static str, u32, Option<&'static str>, &'static str);

/// A fixed parameter's declaration (`causality = parameter`, `variability = fixed`).
fn fixed_parameter(
    name: String,
    vr: u32,
    start: f64,
    unit: Option<&'static str>,
    description: String,
) -> Variable {
    Variable {
        name,
        vr,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(start),
        unit,
        description,
        depends_on: Vec::new(),
    }
}

/// Inputs of both spaces (the plane has `tip.force.{x,y}` and `tip.moment.z`).
pub const INPUTS: [Row; 6] = [
    (
        "tip.force.x",
        1,
        Some("N"),
        "force applied at the free end, global axes",
    ),
    (
        "tip.force.y",
        2,
        Some("N"),
        "force applied at the free end, global axes",
    ),
    (
        "tip.force.z",
        3,
        Some("N"),
        "force applied at the free end, global axes",
    ),
    (
        "tip.moment.x",
        4,
        Some("N.m"),
        "moment applied at the free end, global axes",
    ),
    (
        "tip.moment.y",
        5,
        Some("N.m"),
        "moment applied at the free end, global axes",
    ),
    (
        "tip.moment.z",
        6,
        Some("N.m"),
        "moment applied at the free end, global axes (counter-clockwise in the plane)",
    ),
];

/// Outputs of both spaces (no direct feedthrough), in the order of the description: the
/// plane's 10–20 first as before, its `tip.angular_velocity.z` appended at 21.
pub const OUTPUTS: [Row; 23] = [
    ("tip.position.x", 10, Some("m"), "free end position, global x"),
    ("tip.position.y", 11, Some("m"), "free end position, global y"),
    ("tip.position.z", 22, Some("m"), "free end position, global z"),
    ("tip.velocity.x", 12, Some("m/s"), "free end velocity, global x"),
    ("tip.velocity.y", 13, Some("m/s"), "free end velocity, global y"),
    ("tip.velocity.z", 23, Some("m/s"), "free end velocity, global z"),
    ("tip.angle", 14, Some("rad"), "angle of the end tangent from global x, counter-clockwise, in (-pi, pi]"),
    ("tip.orientation.e0", 24, None, "Euler parameter e0 (scalar) of the tip section frame to world rotation"),
    ("tip.orientation.e1", 25, None, "Euler parameter e1 of the tip section frame to world rotation"),
    ("tip.orientation.e2", 26, None, "Euler parameter e2 of the tip section frame to world rotation"),
    ("tip.orientation.e3", 27, None, "Euler parameter e3 of the tip section frame to world rotation"),
    ("root.force.x", 15, Some("N"), "force of the support on the beam, global x"),
    ("root.force.y", 16, Some("N"), "force of the support on the beam, global y"),
    ("root.force.z", 30, Some("N"), "force of the support on the beam, global z"),
    ("root.moment.x", 31, Some("N.m"), "moment of the support on the beam about the root, global x"),
    ("root.moment.y", 32, Some("N.m"), "moment of the support on the beam about the root, global y"),
    ("root.moment.z", 17, Some("N.m"), "moment of the support on the beam about the root, global z (counter-clockwise in the plane)"),
    ("energy.kinetic", 18, Some("J"), "kinetic energy"),
    ("energy.strain", 19, Some("J"), "elastic strain energy"),
    ("energy.potential", 20, Some("J"), "potential energy of gravity and the line loads (zero at the origin)"),
    ("tip.angular_velocity.x", 28, Some("rad/s"), "angular velocity of the tip section, global x"),
    ("tip.angular_velocity.y", 29, Some("rad/s"), "angular velocity of the tip section, global y"),
    ("tip.angular_velocity.z", 21, Some("rad/s"), "angular velocity of the tip section, global z (counter-clockwise in the plane)"),
];

/// Mount inputs of a `root = "mounted"` scene (world axes, SI; the plane's angular ones
/// without an axis suffix): 40–61.
pub const MOUNT_INPUTS: [Row; 22] = [
    ("root.position.x", 40, Some("m"), "mount point, world x"),
    ("root.position.y", 41, Some("m"), "mount point, world y"),
    ("root.position.z", 42, Some("m"), "mount point, world z"),
    ("root.angle", 43, Some("rad"), "angle of the mount frame's x axis from world x, counter-clockwise"),
    ("root.orientation.e0", 44, None, "Euler parameter e0 (scalar) of the mount frame to world rotation (renormalized; all zero is refused)"),
    ("root.orientation.e1", 45, None, "Euler parameter e1 of the mount frame to world rotation"),
    ("root.orientation.e2", 46, None, "Euler parameter e2 of the mount frame to world rotation"),
    ("root.orientation.e3", 47, None, "Euler parameter e3 of the mount frame to world rotation"),
    ("root.velocity.x", 48, Some("m/s"), "velocity of the mount point, world x"),
    ("root.velocity.y", 49, Some("m/s"), "velocity of the mount point, world y"),
    ("root.velocity.z", 50, Some("m/s"), "velocity of the mount point, world z"),
    ("root.angular_velocity", 51, Some("rad/s"), "angular velocity of the mount frame, counter-clockwise"),
    ("root.angular_velocity.x", 52, Some("rad/s"), "angular velocity of the mount frame, world x"),
    ("root.angular_velocity.y", 53, Some("rad/s"), "angular velocity of the mount frame, world y"),
    ("root.angular_velocity.z", 54, Some("rad/s"), "angular velocity of the mount frame, world z"),
    ("root.acceleration.x", 55, Some("m/s2"), "acceleration of the mount point, world x"),
    ("root.acceleration.y", 56, Some("m/s2"), "acceleration of the mount point, world y"),
    ("root.acceleration.z", 57, Some("m/s2"), "acceleration of the mount point, world z"),
    ("root.angular_acceleration", 58, Some("rad/s2"), "angular acceleration of the mount frame, counter-clockwise"),
    ("root.angular_acceleration.x", 59, Some("rad/s2"), "angular acceleration of the mount frame, world x"),
    ("root.angular_acceleration.y", 60, Some("rad/s2"), "angular acceleration of the mount frame, world y"),
    ("root.angular_acceleration.z", 61, Some("rad/s2"), "angular acceleration of the mount frame, world z"),
];

/// The beam's rigid inertia at the mount and the reaction beyond it, outputs of a mounted
/// scene: 70–85.
pub const MOUNT_OUTPUTS: [Row; 16] = [
    (
        "root.mass",
        70,
        Some("kg"),
        "mass of the beam (for interface-mass coupling)",
    ),
    (
        "root.center_of_mass.x",
        71,
        Some("m"),
        "centre of mass of the beam relative to the mount point, mount frame x",
    ),
    (
        "root.center_of_mass.y",
        72,
        Some("m"),
        "centre of mass of the beam relative to the mount point, mount frame y",
    ),
    (
        "root.center_of_mass.z",
        73,
        Some("m"),
        "centre of mass of the beam relative to the mount point, mount frame z",
    ),
    (
        "root.inertia.xx",
        74,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame xx",
    ),
    (
        "root.inertia.yy",
        75,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame yy",
    ),
    (
        "root.inertia.zz",
        76,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame zz",
    ),
    (
        "root.inertia.xy",
        77,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame xy",
    ),
    (
        "root.inertia.xz",
        78,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame xz",
    ),
    (
        "root.inertia.yz",
        79,
        Some("kg.m2"),
        "inertia of the beam about the mount point, mount frame yz",
    ),
    ("root.force_elastic.x", 80, Some("N"), "root.force minus the rigid reaction of root.mass etc. at the mount motion and gravity (what a host carrying the rigid inertia applies), global x"),
    ("root.force_elastic.y", 81, Some("N"), "root.force minus the rigid reaction, global y"),
    ("root.force_elastic.z", 82, Some("N"), "root.force minus the rigid reaction, global z"),
    ("root.moment_elastic.x", 83, Some("N.m"), "root.moment minus the rigid reaction's moment about the mount point, global x"),
    ("root.moment_elastic.y", 84, Some("N.m"), "root.moment minus the rigid reaction's moment, global y"),
    ("root.moment_elastic.z", 85, Some("N.m"), "root.moment minus the rigid reaction's moment, global z (counter-clockwise in the plane)"),
];

/// The value reference, unit and description of a partner-model input of a mounted scene
/// (`None` for another name): `root.mobility.<a>_<r>` at 200 + 6·i + j and
/// `root.reaction_reference.<r>` at 240 + j, with i the index of `a` in (ax, ay, az, alphax,
/// alphay, alphaz) and j that of `r` in (fx, fy, fz, mx, my, mz), the same in both spaces (the
/// plane has ax, ay, alphaz and fx, fy, mz).
pub fn partner_row(name: &str) -> Option<(u32, &'static str, String)> {
    const ACC: [&str; 6] = ["ax", "ay", "az", "alphax", "alphay", "alphaz"];
    const REACTION: [&str; 6] = ["fx", "fy", "fz", "mx", "my", "mz"];
    let index = |list: &[&str; 6], x: &str| list.iter().position(|l| *l == x);
    if let Some(r) = name.strip_prefix("root.reaction_reference.") {
        let j = index(&REACTION, r)?;
        let unit = if j < 3 { "N" } else { "N.m" };
        let what = if j < 3 { "force" } else { "moment" };
        let description = format!(
            "partner model: the reaction {what} (support on the beam, world axes) the host's \
             acceleration input was computed with"
        );
        return Some((240 + j as u32, unit, description));
    }
    let (a, r) = name.strip_prefix("root.mobility.")?.split_once('_')?;
    let (i, j) = (index(&ACC, a)?, index(&REACTION, r)?);
    let unit = match (i < 3, j < 3) {
        (true, true) => "1/kg",
        (false, false) => "1/(kg.m2)",
        _ => "1/(kg.m)",
    };
    let description = format!(
        "partner model: the host's mobility at the mount, d{a}/d{r} (mount acceleration by the \
         reaction of the support on the beam, world axes; zero: off)"
    );
    Some((200 + 6 * i as u32 + j as u32, unit, description))
}

/// Gravity, tunable parameters of both spaces.
pub const GRAVITY: [Row; 3] = [
    ("gravity.x", 100, Some("m/s2"), "gravity, global axes"),
    ("gravity.y", 101, Some("m/s2"), "gravity, global axes"),
    ("gravity.z", 102, Some("m/s2"), "gravity, global axes"),
];

/// A scene-wide fixed parameter row.
#[derive(Debug)]
pub struct SceneParameter {
    /// Variable name.
    pub name: &'static str,
    /// Value reference.
    pub vr: u32,
    /// Unit symbol, `None` for dimensionless.
    pub unit: Option<&'static str>,
    /// One-line description.
    pub description: &'static str,
    /// Reads it from a scene.
    pub get: fn(&Scene) -> f64,
    /// Writes it into a scene (not validated).
    pub set: fn(&mut Scene, f64),
}

/// A field of a scene item (a segment, an attached mass) exposed as a fixed parameter: its
/// block of value references is the item's, `k` its offset in it.
#[derive(Debug)]
pub struct Field<T> {
    /// Field name (the scene's key).
    pub name: &'static str,
    /// Offset of the value reference within the item's block.
    pub k: u32,
    /// Unit symbol, `None` for dimensionless.
    pub unit: Option<&'static str>,
    /// Whether an item has this parameter.
    pub applies: fn(&T) -> bool,
    /// Reads it from an item.
    pub get: fn(&T) -> f64,
    /// Writes it into an item (not validated).
    pub set: fn(&mut T, f64),
}

/// The first value reference of the stations' outputs: station i's field k at
/// 600000 + 10·i + k (force x 1, y 2, z 3, moment x 4, y 5, z 6, stress 7).
pub const STATION_VR: u32 = 600_000;

/// The offset of a segment's line-load inputs `<segment>.line_load.<axis>` in its block of value
/// references: 1000·(i + 1) + 20 + axis (x 0, y 1, z 2).
pub const LINE_LOAD_K: u32 = 20;

/// A segment field, the parameter `<segment>.<name>` with value reference 1000·(i + 1) + `k`.
pub type SegmentField = Field<Segment>;

/// Scene-wide fixed parameters: solver 110–114.
const SCENE_PARAMETERS: [SceneParameter; 5] = [
    SceneParameter {
        name: "solver.rho_inf",
        vr: 110,
        unit: None,
        description: "generalized-alpha spectral radius at infinity, [0, 1)",
        get: |s| s.solver.rho_inf,
        set: |s, x| s.solver.rho_inf = x,
    },
    SceneParameter {
        name: "solver.max_step",
        vr: 111,
        unit: Some("s"),
        description: "largest internal step",
        get: |s| s.solver.max_step,
        set: |s, x| s.solver.max_step = x,
    },
    SceneParameter {
        name: "solver.tolerance",
        vr: 112,
        unit: None,
        description: "relative Newton tolerance",
        get: |s| s.solver.newton_tolerance(),
        set: set_tolerance,
    },
    SceneParameter {
        name: "solver.max_axial_strain",
        vr: 113,
        unit: None,
        description: "largest axial strain a state may reach before the step is refused, (0, 1]",
        get: |s| s.solver.max_axial_strain,
        set: |s, x| s.solver.max_axial_strain = x,
    },
    SceneParameter {
        name: "solver.realtime_iterations",
        vr: 114,
        unit: None,
        description: "0: the normal mode (Newton to the tolerance, steps halved on failure); 1-20: the real-time mode, a fixed work per step with this many Newton iterations per solve",
        get: |s| realtime_iterations(&s.solver),
        set: set_realtime_iterations,
    },
];

/// Sets `solver.tolerance` from the FMU parameter, whose value is the tolerance in use
/// ([`hybeam::scene::Solver::newton_tolerance`]): the value it shows leaves the scene as it
/// is (a host that sets every parameter to its start value, or a restored FMU state, keeps a
/// tolerance the scene leaves to `solver.error_tolerance`); another value is given explicitly.
fn set_tolerance(s: &mut Scene, x: f64) {
    if x != s.solver.newton_tolerance() {
        s.solver.tolerance = Some(x);
    }
}

/// `solver.realtime_iterations` as the FMU parameter: 0 in the normal mode.
fn realtime_iterations(s: &hybeam::scene::Solver) -> f64 {
    match s.mode {
        Mode::Normal => 0.0,
        Mode::Realtime => s.realtime_iterations as f64,
    }
}

/// Sets the mode from the FMU parameter: 0 the normal mode, an integer k in 1..=20 the
/// real-time mode with k iterations; anything else leaves the real-time mode with 0 iterations,
/// which the scene's validation refuses naming the field.
fn set_realtime_iterations(s: &mut Scene, x: f64) {
    if x == 0.0 {
        s.solver.mode = Mode::Normal;
    } else {
        s.solver.mode = Mode::Realtime;
        s.solver.realtime_iterations = if x.fract() == 0.0 && (1.0..=20.0).contains(&x) {
            x as usize
        } else {
            0
        };
    }
}

fn round(s: &Segment) -> bool {
    matches!(s.section, Section::Round | Section::Tube)
}

fn tube(s: &Segment) -> bool {
    s.section == Section::Tube
}

fn rectangle(s: &Segment) -> bool {
    s.section == Section::Rectangle
}

/// Segment fields, in value-reference order.
pub const SEGMENT_FIELDS: [SegmentField; 9] = [
    SegmentField {
        name: "length",
        k: 1,
        unit: Some("m"),
        applies: |_| true,
        get: |s| s.length,
        set: |s, x| s.length = x,
    },
    SegmentField {
        name: "diameter",
        k: 2,
        unit: Some("m"),
        applies: round,
        get: |s| s.diameter.as_ref().map_or(0.0, Dim::start),
        set: |s, x| match &mut s.diameter {
            Some(d) => d.set_start(x),
            None => s.diameter = Some(Dim::Uniform(x)),
        },
    },
    SegmentField {
        name: "width",
        k: 3,
        unit: Some("m"),
        applies: rectangle,
        get: |s| s.width.as_ref().map_or(0.0, Dim::start),
        set: |s, x| match &mut s.width {
            Some(d) => d.set_start(x),
            None => s.width = Some(Dim::Uniform(x)),
        },
    },
    SegmentField {
        name: "height",
        k: 4,
        unit: Some("m"),
        applies: rectangle,
        get: |s| s.height.as_ref().map_or(0.0, Dim::start),
        set: |s, x| match &mut s.height {
            Some(d) => d.set_start(x),
            None => s.height = Some(Dim::Uniform(x)),
        },
    },
    SegmentField {
        name: "youngs_modulus",
        k: 5,
        unit: Some("Pa"),
        applies: |_| true,
        get: |s| s.youngs_modulus,
        set: |s, x| s.youngs_modulus = x,
    },
    SegmentField {
        name: "density",
        k: 6,
        unit: Some("kg/m3"),
        applies: |_| true,
        get: |s| s.density,
        set: |s, x| s.density = x,
    },
    SegmentField {
        name: "damping_time",
        k: 7,
        unit: Some("s"),
        applies: |s| s.damping_time > 0.0,
        get: |s| s.damping_time,
        set: |s, x| s.damping_time = x,
    },
    SegmentField {
        name: "damping_ratio",
        k: 8,
        unit: None,
        applies: |s| s.kind == SegmentKind::Modal && s.damping_ratio > 0.0,
        get: |s| s.damping_ratio,
        set: |s, x| s.damping_ratio = x,
    },
    SegmentField {
        name: "inner_diameter",
        k: 9,
        unit: Some("m"),
        applies: tube,
        get: |s| s.inner_diameter.as_ref().map_or(0.0, Dim::start),
        set: |s, x| match &mut s.inner_diameter {
            Some(d) => d.set_start(x),
            None => s.inner_diameter = Some(Dim::Uniform(x)),
        },
    },
];

/// A field of an attached mass, the parameter `masses.<name>.<field>` with value reference
/// 500000 + 10·i + `k` (i its index in the scene's `[[masses]]`).
pub type MassField = Field<Mass>;

/// The attached masses' fields, in value-reference order: a sweep can vary a payload and
/// where it sits.
pub const MASS_FIELDS: [MassField; 2] = [
    MassField {
        name: "mass",
        k: 1,
        unit: Some("kg"),
        applies: |_| true,
        get: |m| m.mass,
        set: |m, x| m.mass = x,
    },
    MassField {
        name: "at",
        k: 2,
        unit: Some("m"),
        applies: |_| true,
        get: |m| m.at,
        set: |m, x| m.at = x,
    },
];

/// The String parameters (fmi2String, fixed, every scene): (name, VR, description). Declared
/// after the Real variables in modelDescription.xml.
pub const STRING_PARAMETERS: [Row; 1] = [(
    "visualization.directory",
    900,
    None,
    "directory the FMU writes the beam's shape to at every communication point (ParaView \
     series <instance>.pvd and animation page <instance>.html); empty: off",
)];

/// The Real parameters of the views (tunable; value references 901–902): (name, VR, unit,
/// description), the setting.
pub const VIEW_PARAMETERS: [(Row, Setting); 2] = [
    (
        (
            "visualization.interval",
            901,
            Some("s"),
            "the views record a communication point when at least this long after the last one \
             recorded (0: every one)",
        ),
        Setting::Interval,
    ),
    (
        (
            "visualization.max_bytes",
            902,
            None,
            "the ParaView series' pieces on disk at most [bytes]: the piece that could pass it is \
             not written, with one warning, nor any after it in the run",
        ),
        Setting::MaxBytes,
    ),
];

/// The index of `visualization.directory` in [`Table::string_variables`].
pub const VISUALIZATION_DIRECTORY: usize = 0;

/// The variables of a scene and how each is accessed; `access(i)` belongs to `variables()[i]`.
#[derive(Debug, Clone)]
pub struct Table {
    variables: Vec<Variable>,
    access: Vec<Access>,
    strings: Vec<StringVariable>,
}

impl Table {
    /// The table of `scene`: inputs, outputs, gravity, solver parameters, then each segment's
    /// fields. Inputs, outputs and gravity are the simulator's named scalars of the scene's
    /// space, in the order of [`INPUTS`], [`OUTPUTS`] and [`GRAVITY`].
    pub fn of(scene: &Scene) -> Self {
        let mut t = Table {
            variables: Vec::new(),
            access: Vec::new(),
            strings: STRING_PARAMETERS
                .iter()
                .map(|(name, vr, _, description)| StringVariable {
                    name: (*name).into(),
                    vr: *vr,
                    variability: Variability::Fixed,
                    start: String::new(),
                    description: (*description).into(),
                })
                .collect(),
        };
        let mounted = scene.root == Root::Mounted;
        let inputs = InputId::named_with(scene.space, mounted);
        let outputs = OutputId::named_with(scene.space, mounted);
        // the rows whose name the simulator has in this space, with its id
        fn present<'a, I: Copy>(
            rows: &'a [Row],
            ids: &'a [(String, I)],
        ) -> impl Iterator<Item = (&'a Row, I)> + 'a {
            rows.iter().filter_map(move |row| {
                let (_, id) = ids.iter().find(|(name, _)| name == row.0)?;
                Some((row, *id))
            })
        }
        let variable =
            |(name, vr, unit, description): &Row, causality, variability, start| Variable {
                name: (*name).into(),
                vr: *vr,
                causality,
                variability,
                start,
                unit: *unit,
                description: (*description).into(),
                depends_on: Vec::new(),
            };
        // with motion_input = "pose_velocity" the accelerations are estimated, not inputs
        let velocity_mode = scene
            .mount_start()
            .is_some_and(|m| m.motion_input == MotionInput::PoseVelocity);
        let estimated = |id: &InputId| {
            velocity_mode
                && matches!(
                    id.kind,
                    InputKind::MountAcceleration | InputKind::MountAngularAcceleration
                )
        };
        let rows = present(&INPUTS, &inputs).chain(present(&MOUNT_INPUTS, &inputs));
        for (row, id) in rows.filter(|(_, id)| !estimated(id)) {
            let start = Some(id.scene_value(scene));
            let v = variable(row, Causality::Input, Variability::Continuous, start);
            t.push(v, Access::Input(id));
        }
        let line_segments = scene.line_load_segments();
        for (name, id) in InputId::line_loads(scene) {
            let (slot, axis) = InputId::line_load_slot(id.component);
            let seg = &scene.segments[line_segments[slot]];
            let v = Variable {
                name,
                vr: 1000 * (line_segments[slot] as u32 + 1) + LINE_LOAD_K + axis as u32,
                causality: Causality::Input,
                variability: Variability::Continuous,
                start: Some(id.scene_value(scene)),
                unit: Some("N/m"),
                description: format!(
                    "uniform dead line load on segment '{}', global axes (takes input derivatives)",
                    seg.name
                ),
                depends_on: Vec::new(),
            };
            t.push(v, Access::Input(id));
        }
        for (name, id) in inputs.iter().filter(|(_, id)| id.kind.is_partner()) {
            let Some((vr, unit, description)) = partner_row(name) else {
                continue;
            };
            let v = Variable {
                name: name.clone(),
                vr,
                causality: Causality::Input,
                variability: Variability::Continuous,
                start: Some(id.scene_value(scene)),
                unit: Some(unit),
                description,
                depends_on: Vec::new(),
            };
            t.push(v, Access::Input(*id));
        }
        // the reaction depends directly on the inputs that define the mount's accelerations
        let drives: Vec<u32> = t
            .access
            .iter()
            .zip(&t.variables)
            .filter(|(a, _)| match a {
                Access::Input(id) => match id.kind {
                    InputKind::MountAcceleration | InputKind::MountAngularAcceleration => {
                        !velocity_mode
                    }
                    InputKind::MountVelocity | InputKind::MountAngularVelocity => velocity_mode,
                    _ => false,
                },
                _ => false,
            })
            .map(|(_, v)| v.vr)
            .collect();
        for (row, id) in present(&OUTPUTS, &outputs).chain(present(&MOUNT_OUTPUTS, &outputs)) {
            let mut v = variable(row, Causality::Output, Variability::Continuous, None);
            if matches!(
                id.quantity,
                Quantity::RootForce
                    | Quantity::RootMoment
                    | Quantity::ElasticForce
                    | Quantity::ElasticMoment
            ) {
                v.depends_on = drives.clone();
            }
            t.push(v, Access::Output(id));
        }
        // the stations' loads: 600000 + 10·i + k (force x 1, y 2, z 3, moment x 4, y 5, z 6,
        // stress 7), i the station's index in [[stations]]; they depend on the mount's
        // accelerations as the reaction does; and the beam's largest stress (120, 121)
        for (name, id) in OutputId::of_scene(scene) {
            let station = |k: u32, what: &str| {
                let slot = match id.quantity {
                    Quantity::StationStress => id.component,
                    _ => id.component / 3,
                };
                let description = format!("station '{}': {what}", scene.stations[slot].name);
                (
                    STATION_VR + 10 * slot as u32 + k,
                    description,
                    drives.clone(),
                )
            };
            let (unit, (vr, description, depends_on)) = match id.quantity {
                Quantity::StationForce => ("N", station(
                    1 + (id.component % 3) as u32,
                    "force of the part beyond the station on the part before it, section frame (x axial, tension positive; y, z shear)",
                )),
                Quantity::StationMoment => ("N.m", station(
                    4 + (id.component % 3) as u32,
                    "moment of the part beyond the station on the part before it about the cut, section frame (x torsion, y and z bending)",
                )),
                Quantity::StationStress => ("Pa", station(
                    7,
                    "largest von Mises stress over the section's boundary from the station's loads (docs/stations.md)",
                )),
                Quantity::BeamStressMax => ("Pa", (
                    120,
                    "largest von Mises stress along the beam from the local strains (outputs.stress; docs/stations.md)".to_string(),
                    Vec::new(),
                )),
                Quantity::BeamStressMaxAt => ("m", (
                    121,
                    "arc length from the root where beam.stress_max is".to_string(),
                    Vec::new(),
                )),
                _ => continue,
            };
            let v = Variable {
                name,
                vr,
                causality: Causality::Output,
                variability: Variability::Continuous,
                start: None,
                unit: Some(unit),
                description,
                depends_on,
            };
            t.push(v, Access::Output(id));
        }
        for (row, id) in present(&GRAVITY, &inputs) {
            let start = Some(id.scene_value(scene));
            let v = variable(row, Causality::Parameter, Variability::Tunable, start);
            t.push(v, Access::Gravity(id));
        }
        for p in &SCENE_PARAMETERS {
            let start = (p.get)(scene);
            let v = fixed_parameter(p.name.into(), p.vr, start, p.unit, p.description.into());
            t.push(v, Access::Scene(p));
        }
        for (i, mass) in scene.masses.iter().enumerate() {
            for f in MASS_FIELDS.iter().filter(|f| (f.applies)(mass)) {
                let v = fixed_parameter(
                    format!("masses.{}.{}", mass.name, f.name),
                    500_000 + 10 * i as u32 + f.k,
                    (f.get)(mass),
                    f.unit,
                    format!(
                        "attached mass '{}' {} (segment '{}')",
                        mass.name, f.name, mass.segment
                    ),
                );
                t.push(v, Access::Mass(i, f));
            }
        }
        let defaults = Settings::default();
        for (row, setting) in &VIEW_PARAMETERS {
            let start = Some(defaults.get(*setting));
            let v = variable(row, Causality::Parameter, Variability::Tunable, start);
            t.push(v, Access::View(*setting));
        }
        for (i, seg) in scene.segments.iter().enumerate() {
            for f in SEGMENT_FIELDS.iter().filter(|f| (f.applies)(seg)) {
                let v = fixed_parameter(
                    format!("{}.{}", seg.name, f.name),
                    1000 * (i as u32 + 1) + f.k,
                    (f.get)(seg),
                    f.unit,
                    format!("segment '{}' {}", seg.name, f.name),
                );
                t.push(v, Access::Segment(i, f));
            }
        }
        t
    }

    fn push(&mut self, v: Variable, a: Access) {
        self.variables.push(v);
        self.access.push(a);
    }

    /// The variables, in table order.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// The String parameters ([`STRING_PARAMETERS`]).
    pub fn string_variables(&self) -> &[StringVariable] {
        &self.strings
    }

    /// How `variables()[index]` is accessed (`index` < the number of variables).
    pub fn access(&self, index: usize) -> Access {
        self.access[index]
    }

    /// The outputs whose names start with `prefix` (name, id), in table order.
    pub fn outputs_named(&self, prefix: &str) -> Vec<(String, OutputId)> {
        self.variables
            .iter()
            .zip(&self.access)
            .filter_map(|(v, a)| match a {
                Access::Output(id) if v.name.starts_with(prefix) => Some((v.name.clone(), *id)),
                _ => None,
            })
            .collect()
    }

    /// The parameters' accesses, in table order (the order of a snapshot's parameter block).
    pub fn parameters(&self) -> impl Iterator<Item = Access> + '_ {
        self.access.iter().copied().filter(|a| {
            matches!(
                a,
                Access::Gravity(_) | Access::Scene(_) | Access::Segment(..) | Access::Mass(..)
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hybeam::scene::SpaceKind;

    /// Every named scalar of the simulator, in both spaces, has exactly one row (a name without
    /// a row would silently not be exported), every row is a name of some space, and no two
    /// rows share a value reference.
    #[test]
    fn every_named_scalar_has_one_row_and_vrs_are_unique() {
        let rows: Vec<&Row> = INPUTS
            .iter()
            .chain(&OUTPUTS)
            .chain(&GRAVITY)
            .chain(&MOUNT_INPUTS)
            .chain(&MOUNT_OUTPUTS)
            .collect();
        let mut names = Vec::new();
        for space in [SpaceKind::Planar, SpaceKind::Spatial] {
            let inputs = InputId::named_with(space, true).into_iter().map(|(n, _)| n);
            let outputs = OutputId::named_with(space, true)
                .into_iter()
                .map(|(n, _)| n);
            names.extend(inputs.chain(outputs));
        }
        names.sort();
        names.dedup();
        let mut vrs: Vec<u32> = rows.iter().map(|r| r.1).collect();
        let mut partner_vrs = Vec::new();
        for name in &names {
            if let Some((vr, ..)) = partner_row(name) {
                partner_vrs.push(vr);
                continue;
            }
            let n = rows.iter().filter(|r| r.0 == name).count();
            assert_eq!(n, 1, "{name}: {n} rows");
        }
        assert_eq!(partner_vrs.len(), 36 + 6, "the spatial partner inputs");
        vrs.extend(partner_vrs);
        for row in &rows {
            assert!(names.iter().any(|n| n == row.0), "{} is in no space", row.0);
        }
        vrs.extend(SCENE_PARAMETERS.iter().map(|p| p.vr));
        vrs.extend(STRING_PARAMETERS.iter().map(|p| p.1));
        vrs.extend(VIEW_PARAMETERS.iter().map(|p| p.0 .1));
        vrs.sort();
        let n = vrs.len();
        vrs.dedup();
        assert_eq!(vrs.len(), n, "duplicate value references");
    }

    /// A tapered dimension's parameter is its start value; setting it scales both ends
    /// (docs/fmu-variables.md); a uniform one is its value.
    #[test]
    fn a_tapered_dimension_parameter_scales_both_ends() {
        let text = "name = \"t\"\n[[segments]]\nname = \"a\"\nkind = \"ancf\"\nlength = 0.5\n\
                    section = \"tube\"\ndiameter = [0.004, 0.002]\ninner_diameter = 0.001\n\
                    youngs_modulus = 2.1e11\ndensity = 7850\nelements = 4\n";
        let mut seg = Scene::from_toml(text).unwrap().segments[0].clone();
        let field = |name: &str| SEGMENT_FIELDS.iter().find(|f| f.name == name).unwrap();
        let (d, di) = (field("diameter"), field("inner_diameter"));
        assert_eq!((d.get)(&seg), 0.004);
        (d.set)(&mut seg, 0.006);
        assert_eq!(seg.diameter, Some(Dim::Taper(vec![0.006, 0.003])));
        assert_eq!((di.get)(&seg), 0.001);
        (di.set)(&mut seg, 0.0015);
        assert_eq!(seg.inner_diameter, Some(Dim::Uniform(0.0015)));
    }
}
