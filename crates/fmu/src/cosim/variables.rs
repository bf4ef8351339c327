//! The beam FMU's variable table: one declared row per variable (name, value reference,
//! causality, variability, unit, description and how the model reads and writes it). The table
//! is a function of the [`Scene`] alone: listing the variables needs no simulator.
//!
//! Value references come from the scene's structure, never from an enumeration order that could
//! shift: inputs 1–2, outputs 10–20, gravity 100–101, solver 110–112, and segment i's field k at
//! 1000·(i + 1) + k (k: length 1, diameter 2, width 3, height 4, youngs_modulus 5, density 6,
//! damping_time 7, damping_ratio 8). A scene only gets the variables it needs: no damping
//! parameters without damping, no width/height on a round section. `docs/fmu-variables.md` is
//! checked against this table by `tests/variables_doc.rs`.

use fmi2::{Causality, Variability, Variable};
use hybeam::model::Outputs;
use hybeam::scene::{Scene, Section, Segment, SegmentKind};
use hybeam::simulator::Simulator;

/// How the model reads and writes one variable.
#[derive(Debug, Clone, Copy)]
pub enum Access {
    /// Component `k` (0 = global x, 1 = global y) of the input tip force [N].
    TipForce(usize),
    /// An output of the current state (read only).
    Output(fn(&Outputs) -> f64),
    /// A scene-wide parameter.
    Scene(&'static SceneParameter),
    /// A field of the segment with this index (root = 0).
    Segment(usize, &'static SegmentField),
}

impl Access {
    /// The parameter's value in `scene`; `None` for inputs and outputs.
    pub fn parameter(self, scene: &Scene) -> Option<f64> {
        match self {
            Access::Scene(p) => Some((p.get)(scene)),
            Access::Segment(i, f) => Some((f.get)(&scene.segments[i])),
            Access::TipForce(_) | Access::Output(_) => None,
        }
    }

    /// Sets the parameter in `scene` (not validated); no effect for inputs and outputs.
    pub fn set_parameter(self, scene: &mut Scene, x: f64) {
        match self {
            Access::Scene(p) => (p.set)(scene, x),
            Access::Segment(i, f) => (f.set)(&mut scene.segments[i], x),
            Access::TipForce(_) | Access::Output(_) => {}
        }
    }
}

/// An output row.
#[derive(Debug)]
pub struct OutputRow {
    /// Variable name.
    pub name: &'static str,
    /// Value reference.
    pub vr: u32,
    /// Unit symbol.
    pub unit: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Reads it from the outputs of a state.
    pub read: fn(&Outputs) -> f64,
}

/// A scene-wide parameter row.
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
    /// For a tunable parameter: passes the scene's new value on to the running simulator.
    pub tune: Option<fn(&Scene, &mut Simulator)>,
}

/// A segment field exposed as a fixed parameter `<segment>.<name>` with value reference
/// 1000·(i + 1) + `k`.
#[derive(Debug)]
pub struct SegmentField {
    /// Field name (the scene's key).
    pub name: &'static str,
    /// Offset of the value reference within the segment's block.
    pub k: u32,
    /// Unit symbol, `None` for dimensionless.
    pub unit: Option<&'static str>,
    /// Whether a segment has this parameter.
    pub applies: fn(&Segment) -> bool,
    /// Reads it from a segment.
    pub get: fn(&Segment) -> f64,
    /// Writes it into a segment (not validated).
    pub set: fn(&mut Segment, f64),
}

/// Input tip force: (name, value reference, component).
const INPUTS: [(&str, u32, usize); 2] = [("tip.force.x", 1, 0), ("tip.force.y", 2, 1)];

/// Outputs, value references 10–20 (no direct feedthrough).
pub const OUTPUTS: [OutputRow; 11] = [
    OutputRow {
        name: "tip.position.x",
        vr: 10,
        unit: "m",
        description: "free end position, global x",
        read: |o| o.tip_position[0],
    },
    OutputRow {
        name: "tip.position.y",
        vr: 11,
        unit: "m",
        description: "free end position, global y",
        read: |o| o.tip_position[1],
    },
    OutputRow {
        name: "tip.velocity.x",
        vr: 12,
        unit: "m/s",
        description: "free end velocity, global x",
        read: |o| o.tip_velocity[0],
    },
    OutputRow {
        name: "tip.velocity.y",
        vr: 13,
        unit: "m/s",
        description: "free end velocity, global y",
        read: |o| o.tip_velocity[1],
    },
    OutputRow {
        name: "tip.angle",
        vr: 14,
        unit: "rad",
        description: "angle of the end tangent from global x, counter-clockwise, in (-pi, pi]",
        read: |o| o.tip_angle,
    },
    OutputRow {
        name: "root.force.x",
        vr: 15,
        unit: "N",
        description: "force of the support on the beam, global x",
        read: |o| o.root_force[0],
    },
    OutputRow {
        name: "root.force.y",
        vr: 16,
        unit: "N",
        description: "force of the support on the beam, global y",
        read: |o| o.root_force[1],
    },
    OutputRow {
        name: "root.moment.z",
        vr: 17,
        unit: "N.m",
        description: "moment of the support on the beam about the root, counter-clockwise",
        read: |o| o.root_moment,
    },
    OutputRow {
        name: "energy.kinetic",
        vr: 18,
        unit: "J",
        description: "kinetic energy",
        read: |o| o.kinetic,
    },
    OutputRow {
        name: "energy.strain",
        vr: 19,
        unit: "J",
        description: "elastic strain energy",
        read: |o| o.strain,
    },
    OutputRow {
        name: "energy.potential",
        vr: 20,
        unit: "J",
        description: "gravity potential energy (zero at the origin)",
        read: |o| o.potential,
    },
];

/// Scene-wide parameters: gravity 100–101 (tunable), solver 110–112 (fixed).
const SCENE_PARAMETERS: [SceneParameter; 5] = [
    SceneParameter {
        name: "gravity.x",
        vr: 100,
        unit: Some("m/s2"),
        description: "gravity, global axes",
        get: |s| s.gravity_vec::<2>()[0],
        set: |s, x| {
            s.gravity = s.gravity_vec::<2>().to_vec();
            s.gravity[0] = x
        },
        tune: Some(|s, sim| sim.set_gravity(s.gravity_vec())),
    },
    SceneParameter {
        name: "gravity.y",
        vr: 101,
        unit: Some("m/s2"),
        description: "gravity, global axes",
        get: |s| s.gravity_vec::<2>()[1],
        set: |s, x| {
            s.gravity = s.gravity_vec::<2>().to_vec();
            s.gravity[1] = x
        },
        tune: Some(|s, sim| sim.set_gravity(s.gravity_vec())),
    },
    SceneParameter {
        name: "solver.rho_inf",
        vr: 110,
        unit: None,
        description: "generalized-alpha spectral radius at infinity, [0, 1)",
        get: |s| s.solver.rho_inf,
        set: |s, x| s.solver.rho_inf = x,
        tune: None,
    },
    SceneParameter {
        name: "solver.max_step",
        vr: 111,
        unit: Some("s"),
        description: "largest internal step",
        get: |s| s.solver.max_step,
        set: |s, x| s.solver.max_step = x,
        tune: None,
    },
    SceneParameter {
        name: "solver.tolerance",
        vr: 112,
        unit: None,
        description: "relative Newton tolerance",
        get: |s| s.solver.tolerance,
        set: |s, x| s.solver.tolerance = x,
        tune: None,
    },
];

fn round(s: &Segment) -> bool {
    s.section == Section::Round
}

fn rectangle(s: &Segment) -> bool {
    s.section == Section::Rectangle
}

/// Segment fields, in value-reference order.
pub const SEGMENT_FIELDS: [SegmentField; 8] = [
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
        get: |s| s.diameter.unwrap_or(0.0),
        set: |s, x| s.diameter = Some(x),
    },
    SegmentField {
        name: "width",
        k: 3,
        unit: Some("m"),
        applies: rectangle,
        get: |s| s.width.unwrap_or(0.0),
        set: |s, x| s.width = Some(x),
    },
    SegmentField {
        name: "height",
        k: 4,
        unit: Some("m"),
        applies: rectangle,
        get: |s| s.height.unwrap_or(0.0),
        set: |s, x| s.height = Some(x),
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
];

/// The variables of a scene and how each is accessed; `access(i)` belongs to `variables()[i]`.
#[derive(Debug, Clone)]
pub struct Table {
    variables: Vec<Variable>,
    access: Vec<Access>,
}

impl Table {
    /// The table of `scene`: inputs, outputs, scene parameters, then each segment's fields.
    pub fn of(scene: &Scene) -> Self {
        let mut t = Table {
            variables: Vec::new(),
            access: Vec::new(),
        };
        for (name, vr, k) in INPUTS {
            t.push(
                Variable {
                    name: name.into(),
                    vr,
                    causality: Causality::Input,
                    variability: Variability::Continuous,
                    start: Some(scene.tip.force[k]),
                    unit: Some("N"),
                    description: "force applied at the free end, global axes".into(),
                },
                Access::TipForce(k),
            );
        }
        for o in &OUTPUTS {
            t.push(
                Variable {
                    name: o.name.into(),
                    vr: o.vr,
                    causality: Causality::Output,
                    variability: Variability::Continuous,
                    start: None,
                    unit: Some(o.unit),
                    description: o.description.into(),
                },
                Access::Output(o.read),
            );
        }
        for p in &SCENE_PARAMETERS {
            t.push(
                Variable {
                    name: p.name.into(),
                    vr: p.vr,
                    causality: Causality::Parameter,
                    variability: if p.tune.is_some() {
                        Variability::Tunable
                    } else {
                        Variability::Fixed
                    },
                    start: Some((p.get)(scene)),
                    unit: p.unit,
                    description: p.description.into(),
                },
                Access::Scene(p),
            );
        }
        for (i, seg) in scene.segments.iter().enumerate() {
            for f in SEGMENT_FIELDS.iter().filter(|f| (f.applies)(seg)) {
                t.push(
                    Variable {
                        name: format!("{}.{}", seg.name, f.name),
                        vr: 1000 * (i as u32 + 1) + f.k,
                        causality: Causality::Parameter,
                        variability: Variability::Fixed,
                        start: Some((f.get)(seg)),
                        unit: f.unit,
                        description: format!("segment '{}' {}", seg.name, f.name),
                    },
                    Access::Segment(i, f),
                );
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

    /// How `variables()[index]` is accessed (`index` < the number of variables).
    pub fn access(&self, index: usize) -> Access {
        self.access[index]
    }

    /// The parameters' accesses, in table order (the order of a snapshot's parameter block).
    pub fn parameters(&self) -> impl Iterator<Item = Access> + '_ {
        self.access
            .iter()
            .copied()
            .filter(|a| matches!(a, Access::Scene(_) | Access::Segment(..)))
    }
}
