//! The beam as a co-simulation model: the variable table derived from the scene and its
//! mapping onto an [`AnySimulator`] (planar or spatial, from the scene's `space`). Implements
//! [`CoSimModel`] for the FMI layer.
//!
//! Its rooms: the variables ([`variables`]), what the scene declares ([`describe`]), the
//! feedthrough and output derivatives ([`feedthrough`]), the FMU state ([`snapshot`]), the
//! views ([`view`]).

pub mod describe;
pub mod feedthrough;
pub mod snapshot;
pub mod variables;
pub mod view;

use fmi2::{CoSimModel, ModelInfo, StepError, StringVariable, Variable};

use hybeam::error::SimError;
use hybeam::scene::Scene;
use hybeam::simulator::{AnyOutputs, AnySimulator};

use feedthrough::{Evaluated, Feedthrough};
use variables::{Access, Table, VISUALIZATION_DIRECTORY};

/// The beam FMU model.
#[derive(Debug)]
pub struct BeamFmu {
    /// Scene text from resources (identity of the FMU).
    scene_text: String,
    /// Scene as built (parameters overridden through the variables).
    base: Scene,
    /// Scene with the current parameter values and the inputs the host set (tip force and
    /// moment: `initialize` rebuilds the simulator from it).
    scene: Scene,
    /// The variables and how each is accessed.
    table: Table,
    sim: AnySimulator,
    /// Outputs of the current state, computed once per state change (setting an input changes
    /// only the reaction of a mounted beam, through the feedthrough).
    outputs: AnyOutputs,
    /// A mounted beam's apparent mass and rigid inertia at the current state, the last step
    /// and the outputs' backward differences.
    feed: Feedthrough,
    /// Started or not; before the start, the outputs of the values set so far.
    start: Start,
    /// The views: `visualization.*` and the files written ([`view::ViewState`]).
    views: view::ViewState,
    /// A warning for the FMI layer to report ([`CoSimModel::take_warning`]).
    warning: Option<String>,
}

/// Before the start (fmi2ExitInitializationMode or a restored state): a host reading outputs
/// in initialization mode, as libcosim does to settle its connections, sees the start the
/// values set so far describe, built at the first read after a change.
#[derive(Debug, Default)]
struct Start {
    /// Initialized (fmi2ExitInitializationMode passed, or a state restored).
    started: bool,
    /// Before initialization: a parameter or input was set since the instance was built.
    changed: bool,
    /// Then the outputs of that start (built at the first read).
    outputs: std::cell::RefCell<Option<Result<AnyOutputs, String>>>,
}

impl Start {
    /// A value was set: before the start, the cached outputs are stale.
    fn changed(&mut self) {
        if !self.started {
            self.changed = true;
            self.outputs.replace(None);
        }
    }

    /// The run started (or a state was restored).
    fn started(&mut self) {
        self.started = true;
        self.outputs.replace(None);
    }
}

impl BeamFmu {
    /// modelDescription.xml of the FMU of `scene_toml` ([`describe::model_description`]).
    pub fn model_description(scene_toml: &str, model_identifier: &str) -> Result<String, String> {
        describe::model_description::<Self>(scene_toml, model_identifier)
    }

    /// A mounted scene's OSP-IS model description ([`describe::osp_model_description`]).
    pub fn osp_model_description(scene_toml: &str) -> Result<Option<(String, String)>, String> {
        describe::osp_model_description(scene_toml)
    }

    /// Records the current state in the views ([`view::ViewState::record`]).
    fn record_view(&mut self) {
        let table = &self.table;
        let tip = || table.outputs_named("tip.");
        self.views
            .record(&self.sim, &self.outputs, &self.scene, tip);
    }

    fn refresh_outputs(&mut self) {
        self.outputs = self.feed.take(Evaluated::outputs_of(&mut self.sim));
    }

    /// The scene a start builds from: the parameters set so far and the inputs the host set
    /// (those that differ from the scene's), taken from the simulator that holds them — the
    /// one place inputs are copied into a scene; a running simulator owns its inputs.
    fn start_scene(&self) -> Scene {
        let mut scene = self.scene.clone();
        self.sim.inputs_into(&mut scene);
        scene
    }
}

/// The error for a variable the simulator's space does not have (a table of another space:
/// cannot happen through the FMI layer, which only passes the table's variables).
fn not_in_space(name: &str, sim: &AnySimulator) -> String {
    format!("{name}: not a variable of this {:?} model", sim.space())
}

impl CoSimModel for BeamFmu {
    const RESOURCE: &'static str = "scene.toml";
    const GUID_NAMESPACE: &'static str = "hybeam.fmi2";
    const BUILD_ID: &'static str = concat!("hybeam/", env!("CARGO_PKG_VERSION"));
    const GENERATION_TOOL: &'static str =
        concat!("hybeam ", env!("CARGO_PKG_VERSION"), " fmu-build");
    const STATE_MAGIC: [u8; 8] = *b"HYBFMI2S";

    fn from_resource(scene_toml: &str) -> Result<Self, String> {
        let scene = Scene::from_toml(scene_toml).map_err(|e| e.0)?;
        let table = Table::of(&scene);
        let sim = AnySimulator::new(scene.clone()).map_err(|e| e.to_string())?;
        let outputs = sim.outputs();
        let step = scene.simulation.output_step;
        let feed = Feedthrough::new(table.variables().len(), step);
        let mut fmu = Self {
            scene_text: scene_toml.to_string(),
            base: scene.clone(),
            scene,
            table,
            sim,
            outputs,
            feed,
            start: Start::default(),
            views: view::ViewState::new(),
            warning: None,
        };
        fmu.refresh_outputs();
        Ok(fmu)
    }

    fn model_info(&self) -> ModelInfo {
        describe::model_info(&self.base)
    }

    fn capabilities(&self) -> fmi2::Capabilities {
        describe::capabilities(&self.base)
    }

    fn variables(&self) -> &[Variable] {
        self.table.variables()
    }

    fn string_variables(&self) -> &[StringVariable] {
        self.table.string_variables()
    }

    fn get_string(&self, index: usize) -> Result<&str, String> {
        match index {
            VISUALIZATION_DIRECTORY => Ok(self.views.dir()),
            _ => Err(format!("no String variable at index {index}")),
        }
    }

    /// `visualization.directory`: stored; the views switch to it at the next state recorded
    /// (a restored FMU state with another directory: the old directory's views are finished
    /// then, and kept to continue if a later state comes back to it). A state the model refuses
    /// after its directory was set therefore changes no file.
    fn set_string(&mut self, index: usize, value: &str) -> Result<(), String> {
        if index != VISUALIZATION_DIRECTORY {
            return Err(format!("no String variable at index {index}"));
        }
        self.views.set_dir(value);
        Ok(())
    }

    fn set_instance_name(&mut self, name: &str) {
        self.views.set_instance_name(name);
    }

    fn terminate(&mut self) {
        self.views.finish();
    }

    /// The model's warning, and the views' (a piece written in the background that failed).
    fn take_warning(&mut self) -> Option<String> {
        let views = self.views.take_warning();
        match (self.warning.take(), views) {
            (Some(a), Some(b)) => Some(format!("{a}; {b}")),
            (a, b) => a.or(b),
        }
    }

    /// The reactions' direct feedthrough needs the apparent mass once the host has set new
    /// mount accelerations since the step.
    fn before_get_real(&mut self) {
        if self.sim.mount_acceleration_change().is_some() {
            self.feed.ensure_apparent(&mut self.sim);
        }
    }

    fn get_real(&self, index: usize) -> Result<f64, String> {
        let access = self.table.access(index);
        let value = match access {
            Access::Input(id) => self.sim.input(id),
            Access::Output(id) if !self.start.started && self.start.changed => {
                let mut cached = self.start.outputs.borrow_mut();
                let outputs = cached.get_or_insert_with(|| {
                    AnySimulator::start_at(self.start_scene(), 0.0)
                        .map(|sim| sim.outputs())
                        .map_err(|e| e.to_string())
                });
                match outputs {
                    Ok(o) => o.value(id),
                    Err(e) => {
                        return Err(format!(
                            "{}: no start with the values set so far: {e}",
                            self.table.variables()[index].name
                        ))
                    }
                }
            }
            Access::Output(id) => self
                .outputs
                .value(id)
                .map(|x| self.feed.value(id, x, &self.sim)),
            Access::Gravity(_) | Access::Scene(_) | Access::Segment(..) | Access::Mass(..) => {
                access.parameter(&self.scene)
            }
            Access::View(setting) => Some(self.views.settings().get(setting)),
        };
        value.ok_or_else(|| not_in_space(&self.table.variables()[index].name, &self.sim))
    }

    fn set_real(&mut self, index: usize, value: f64) -> Result<(), String> {
        let name = &self.table.variables()[index].name;
        if !value.is_finite() {
            return Err(format!("{name} = {value}: must be a finite number"));
        }
        let access = self.table.access(index);
        match access {
            Access::Input(id) => {
                if !self.sim.set_input(id, value) {
                    return Err(not_in_space(name, &self.sim));
                }
            }
            Access::Output(_) => return Err(format!("{name} is an output and cannot be set")),
            Access::View(setting) => return self.views.set(setting, value),
            Access::Gravity(_) | Access::Scene(_) | Access::Segment(..) | Access::Mass(..) => {
                let mut scene = self.scene.clone();
                access.set_parameter(&mut scene, value);
                scene
                    .validate()
                    .map_err(|e| format!("{name} = {value}: {e}"))?;
                if let Access::Gravity(id) = access {
                    // tunable: the running simulator takes it at its next step (the outputs
                    // are the state's, under the gravity it was integrated with, until then)
                    if !self.sim.set_input(id, value) {
                        return Err(not_in_space(name, &self.sim));
                    }
                }
                self.scene = scene;
            }
        }
        self.start.changed();
        Ok(())
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        let scene = self.start_scene();
        // the partner model set before the start is an input a scene does not hold
        let partner = self.sim.partner();
        self.sim = AnySimulator::start_at(scene, start_time).map_err(|e| e.to_string())?;
        self.sim.set_partner(partner);
        self.refresh_outputs();
        self.feed.restart();
        self.start.started();
        // a new run: a new series
        self.views.new_run();
        self.record_view();
        Ok(())
    }

    /// The simulator keeps its state at the start of a failed step; [`step_error`] says which
    /// failures a smaller step, other inputs or a restored state can continue from.
    fn do_step(&mut self, t: f64, h: f64) -> Result<(), StepError> {
        // one clock: the simulator starts at the start time and ends each step at the host's
        // t + h (the FMI layer checked t against its time, which is the simulator's)
        let before = self.outputs;
        self.sim.advance(t + h).map_err(step_error)?;
        self.refresh_outputs();
        self.feed.stepped(h, &before, &self.outputs, &self.table);
        self.record_view();
        Ok(())
    }

    /// First derivatives (`maxOutputDerivativeOrder = 1`, mounted scenes): exact for the tip
    /// kinematics (velocity, acceleration, ė = ½ (0, ω) ⊗ e, angular acceleration, from the
    /// state's accelerations); for the reactions, energies and inertia the change over the
    /// last communication step divided by it (first order; 0 before the first step).
    fn get_output_derivative(&self, index: usize, order: u32) -> Result<f64, String> {
        let name = &self.table.variables()[index].name;
        match (self.table.access(index), order) {
            (Access::Output(id), 1) => Ok(self.feed.derivative(index, self.outputs.rate(id))),
            (Access::Output(_), _) => Err(format!("{name}: derivatives of order 1 only")),
            _ => Err(format!("{name} is not an output")),
        }
    }

    /// A mounted scene's continuous inputs: the mount accelerations' derivatives shape the base
    /// motion over the step (or, with `motion_input = "pose_velocity"`, the velocities'); the
    /// pose's derivatives are implied by the velocities and not used; the tip loads' make them
    /// F + Ḟτ + ½F̈τ² over the step (their values at its end then stay set). Gravity (a
    /// parameter) takes none.
    fn set_input_derivative(&mut self, index: usize, order: u32, value: f64) -> Result<(), String> {
        let name = &self.table.variables()[index].name;
        match self.table.access(index) {
            Access::Input(id) if self.sim.set_input_derivative(id, order, value) => Ok(()),
            _ => Err(format!(
                "{name}: input derivatives are taken for the mount inputs, the tip loads and the line loads"
            )),
        }
    }

    /// The apparent mass: ∂root.force, ∂root.moment by the mount accelerations (or, with
    /// velocity inputs, by the velocities through the backward-difference estimate: divided by
    /// the last communication step).
    fn partial_derivative(&mut self, output: usize, input: usize) -> Result<f64, String> {
        let names = |t: &Table| {
            let v = t.variables();
            format!("∂{}/∂{}", v[output].name, v[input].name)
        };
        let (Access::Output(o), Access::Input(i)) =
            (self.table.access(output), self.table.access(input))
        else {
            return Err(format!(
                "{}: not an output and an input",
                names(&self.table)
            ));
        };
        let dim = self.sim.scene().space.dim();
        self.feed.ensure_apparent(&mut self.sim);
        self.feed
            .partial(o, i, dim)
            .ok_or_else(|| format!("{}: the apparent mass is not available", names(&self.table)))
    }

    /// Back to the instantiated model; the views of the run are discarded (no collection or
    /// page written; the next run starts a new series under the same stem, overwriting), and
    /// `visualization.directory` is back to its start value (empty).
    fn reset(&mut self) -> Result<(), String> {
        let fresh = Self::from_resource(&self.scene_text)?;
        self.views.reset();
        let views = std::mem::take(&mut self.views);
        *self = fresh;
        self.views = views;
        Ok(())
    }

    fn save_state(&self) -> Vec<u8> {
        self.state_bytes()
    }

    fn load_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        self.restore_state(bytes)
    }
}

/// The FMI outcome of a failed `advance`: the simulator kept its state from before the call, so
/// whatever a smaller step, other inputs or a restored state can overcome is
/// [`StepError::Discard`]; the kinds `advance` cannot produce (scene, initialization, statics,
/// snapshot) would mean the instance is broken and are [`StepError::Terminate`].
fn step_error(e: SimError) -> StepError {
    let message = e.to_string();
    match e {
        SimError::Step { .. }
        | SimError::Partner { .. }
        | SimError::Refused { .. }
        | SimError::WorkCap { .. }
        | SimError::NonFinite { .. }
        | SimError::InputJump { .. }
        | SimError::BadTime { .. } => StepError::Discard(message),
        SimError::Scene(_)
        | SimError::InitialStatic(_)
        | SimError::InitialAccelerations(_)
        | SimError::Static(_)
        | SimError::Snapshot(_) => StepError::Terminate(message),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The index of value reference `vr` (the FMI layer's resolution).
    fn at(m: &BeamFmu, vr: u32) -> usize {
        m.variables().iter().position(|v| v.vr == vr).unwrap()
    }

    fn case1() -> String {
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/case1.toml"
        ))
        .unwrap()
    }

    #[test]
    fn variables_follow_the_scene() {
        let m = BeamFmu::from_resource(&case1()).unwrap();
        let names: Vec<&str> = m.variables().iter().map(|v| v.name.as_str()).collect();
        assert!(names.contains(&"modal.diameter") && names.contains(&"ancf.youngs_modulus"));
        assert!(
            !names.iter().any(|n| n.contains("damping")),
            "undamped scene has no damping parameters"
        );
        let case2 = case1().replace("modes = 4", "modes = 4\ndamping_time = 1e-3");
        let m2 = BeamFmu::from_resource(&case2).unwrap();
        assert!(m2
            .variables()
            .iter()
            .any(|v| v.name == "modal.damping_time"));
        let mut vrs: Vec<u32> = m.variables().iter().map(|v| v.vr).collect();
        vrs.sort();
        vrs.dedup();
        assert_eq!(vrs.len(), m.variables().len());
    }

    #[test]
    fn snapshot_restores_bit_for_bit_in_a_fresh_instance() {
        let text = case1();
        let mut a = BeamFmu::from_resource(&text).unwrap();
        a.initialize(0.0).unwrap();
        for k in 0..5 {
            a.do_step(k as f64 * 1e-3, 1e-3).unwrap();
        }
        a.set_real(at(&a, 2), -0.01).unwrap();
        a.set_real(at(&a, 6), 2e-3).unwrap(); // tip.moment.z
        let bytes = a.save_state();
        let mut b = BeamFmu::from_resource(&text).unwrap();
        b.load_state(&bytes).unwrap();
        for k in 5..20 {
            a.do_step(k as f64 * 1e-3, 1e-3).unwrap();
            b.do_step(k as f64 * 1e-3, 1e-3).unwrap();
        }
        for (i, v) in a.variables().iter().enumerate() {
            assert_eq!(
                a.get_real(i).unwrap().to_bits(),
                b.get_real(i).unwrap().to_bits(),
                "{}",
                v.name
            );
        }
        assert_eq!(b.get_real(at(&b, 6)).unwrap(), 2e-3);
        assert_eq!(
            b.start_scene().tip.moment,
            [2e-3],
            "the simulator owns the restored input; a start would begin from it"
        );
        assert!(b.load_state(&bytes[..bytes.len() - 3]).is_err());
        assert!(b.load_state(b"garbage").is_err());
    }

    /// One clock: the simulator starts at the start time, and each step ends at the host's
    /// t + h to the bit (not at the simulator's time + h).
    #[test]
    fn steps_end_at_the_hosts_t_plus_h() {
        let mut m = BeamFmu::from_resource(&case1()).unwrap();
        m.initialize(0.3).unwrap();
        assert_eq!(m.sim.time().to_bits(), 0.3f64.to_bits());
        let (mut t, h) = (0.3, 0.1 / 3.0 * 1e-2);
        for _ in 0..7 {
            m.do_step(t, h).unwrap();
            t += h;
            assert_eq!(m.sim.time().to_bits(), t.to_bits());
        }
    }

    /// A spatial scene's variables: z components, moments about three axes, the quaternion,
    /// gravity.z; no planar angle. From the scene alone (no model is built).
    #[test]
    fn spatial_variables_follow_the_space() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/case1_3d.toml"
        ))
        .unwrap();
        let scene = Scene::from_toml(&text).unwrap();
        let table = Table::of(&scene);
        let names: Vec<&str> = table.variables().iter().map(|v| v.name.as_str()).collect();
        for name in [
            "tip.force.z",
            "tip.moment.x",
            "tip.position.z",
            "tip.orientation.e0",
            "tip.angular_velocity.y",
            "root.moment.x",
            "gravity.z",
        ] {
            assert!(names.contains(&name), "{name} missing");
        }
        assert!(!names.contains(&"tip.angle"));
        let g = table.variables().iter().find(|v| v.name == "gravity.z");
        assert_eq!(g.and_then(|v| v.start), Some(-9.81));
        let planar = Table::of(&Scene::from_toml(&case1()).unwrap());
        let planar: Vec<&str> = planar.variables().iter().map(|v| v.name.as_str()).collect();
        assert!(!planar.iter().any(|n| n.ends_with(".z")
            && *n != "tip.moment.z"
            && *n != "root.moment.z"
            && *n != "tip.angular_velocity.z"));
        assert!(!planar.iter().any(|n| n.contains("orientation")));
    }

    /// A spatial instance of `text`, or `None` while the spatial model is not built yet (any
    /// other error fails).
    fn spatial(text: &str) -> Option<BeamFmu> {
        match BeamFmu::from_resource(text) {
            Ok(m) => Some(m),
            Err(e) if e.contains("spatial model is not built yet") => {
                eprintln!("no spatial model yet: {e}");
                None
            }
            Err(e) => panic!("{e}"),
        }
    }

    /// Through the FMU a spatial scene runs like a planar one: host inputs (tip force along y,
    /// tip moment about x, a torsion) set at t = 0 give the outputs of a scene that holds them
    /// (the jump treatment), and a snapshot restores bit for bit in a fresh instance.
    #[test]
    fn spatial_inputs_jump_and_snapshot_restores() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/case1_3d.toml"
        ))
        .unwrap();
        let loaded = text.replace(
            "[initial]",
            "[tip]\nforce = [0.0, 0.01, 0.0]\nmoment = [2e-3, 0.0, 0.0]\n\n[initial]",
        );
        let (Some(mut a), Some(mut b)) = (spatial(&text), spatial(&loaded)) else {
            return;
        };
        a.initialize(0.0).unwrap();
        b.initialize(0.0).unwrap();
        a.set_real(at(&a, 2), 0.01).unwrap(); // tip.force.y
        a.set_real(at(&a, 4), 2e-3).unwrap(); // tip.moment.x
        let mut worst = 0.0f64;
        for k in 0..30 {
            a.do_step(k as f64 * 1e-3, 1e-3).unwrap();
            b.do_step(k as f64 * 1e-3, 1e-3).unwrap();
            for i in 0..a.variables().len() {
                let d = a.get_real(i).unwrap() - b.get_real(i).unwrap();
                worst = worst.max(d.abs());
            }
        }
        let wx = at(&a, 28); // tip.angular_velocity.x: the moment twists the rod
        println!(
            "largest difference {worst:.3e}; twist rate {:.3e} rad/s",
            a.get_real(wx).unwrap()
        );
        assert!(worst <= 1e-12, "largest difference {worst:e}");
        assert!(a.get_real(wx).unwrap().abs() > 1e-3);
        let bytes = a.save_state();
        let mut c = spatial(&text).unwrap();
        c.load_state(&bytes).unwrap();
        for k in 30..40 {
            a.do_step(k as f64 * 1e-3, 1e-3).unwrap();
            c.do_step(k as f64 * 1e-3, 1e-3).unwrap();
        }
        for (i, v) in a.variables().iter().enumerate() {
            let (x, y) = (a.get_real(i).unwrap(), c.get_real(i).unwrap());
            assert_eq!(x.to_bits(), y.to_bits(), "{}", v.name);
        }
    }

    #[test]
    fn bad_parameter_is_refused_with_its_name() {
        let mut m = BeamFmu::from_resource(&case1()).unwrap();
        let e = m.set_real(at(&m, 1001), -0.2).unwrap_err();
        assert!(e.contains("modal.length") && e.contains("> 0"), "{e}");
        assert!(m.set_real(at(&m, 10), 1.0).unwrap_err().contains("output"));
        assert!(m.set_real(at(&m, 1), f64::NAN).is_err());
    }

    /// `masses.<name>.mass` and `.at` are parameters a start takes (a sweep varies a payload):
    /// the rebuilt simulator carries the value set; a value the scene refuses is refused
    /// naming the mass's field.
    #[test]
    fn mass_parameters_reach_the_start() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/sprayer_boom.toml"
        ))
        .unwrap();
        let mut m = BeamFmu::from_resource(&text).unwrap();
        let mass = at(&m, 500_000 + 10 * 3 + 1);
        assert_eq!(m.variables()[mass].name, "masses.nozzle_3.mass");
        assert_eq!(m.get_real(mass).unwrap(), 0.4);
        m.set_real(mass, 2.5).unwrap();
        let place = at(&m, 500_000 + 10 * 3 + 2);
        m.set_real(place, 0.3).unwrap();
        m.initialize(0.0).unwrap();
        let nozzle = &m.sim.scene().masses[3];
        assert_eq!((nozzle.mass, nozzle.at), (2.5, 0.3));
        let mut m = BeamFmu::from_resource(&text).unwrap();
        let e = m.set_real(mass, -1.0).unwrap_err();
        assert!(e.contains("masses.nozzle_3.mass = -1"), "{e}");
        let e = m.set_real(place, 3.0).unwrap_err();
        assert!(e.contains("masses.nozzle_3.at = 3"), "{e}");
    }

    /// Each kind of simulator failure maps to the FMI outcome the host needs, with the
    /// simulator's message unchanged.
    #[test]
    fn failures_map_to_discard_or_terminate_by_kind() {
        use hybeam::error::{Refusal, SnapshotError, StepLimit};
        use hybeam::integrator::{StaticFailure, StepFailure};
        use hybeam::scene::SceneError;
        let singular = StepFailure::Singular { h: 1e-4 };
        let discard = [
            SimError::Step {
                t: 0.1,
                halvings: 12,
                limit: StepLimit::MaxHalvings,
                source: StepFailure::NoConvergence {
                    h: 1e-4,
                    last_norm: 3.0,
                },
            },
            SimError::Partner {
                t: 0.1,
                halvings: 12,
                limit: StepLimit::MaxHalvings,
                h: 2e-4 / 4096.0,
                residual: 3e-6,
                tolerance: 1e-7,
                correction: 40.0,
            },
            SimError::Refused {
                t: 0.2,
                refusal: Refusal::ModalDeflection {
                    segment: "modal".into(),
                    value: 0.4,
                },
            },
            SimError::Refused {
                t: 0.2,
                refusal: Refusal::AxialStrain {
                    value: 0.06,
                    limit: 0.05,
                },
            },
            SimError::WorkCap {
                t0: 0.0,
                t_end: 100.0,
                needed: 1e5,
                h_max: 1e-3,
                cap: 20_000,
            },
            SimError::NonFinite { t: 0.3 },
            SimError::InputJump {
                t: 0.1,
                source: singular.clone(),
            },
            SimError::BadTime {
                t0: 0.1,
                t_end: 0.1,
            },
        ];
        let terminate = [
            SimError::Scene(SceneError("name = \"\": give the scene a name".into())),
            SimError::InitialStatic(StaticFailure {
                load: 0.5,
                reason: "singular".into(),
            }),
            SimError::InitialAccelerations(singular.clone()),
            SimError::Static(StaticFailure {
                load: 0.5,
                reason: "singular".into(),
            }),
            SimError::Snapshot(SnapshotError::NewtonMatrix(singular)),
        ];
        for e in discard {
            let text = e.to_string();
            assert_eq!(step_error(e), StepError::Discard(text));
        }
        for e in terminate {
            let text = e.to_string();
            assert_eq!(step_error(e), StepError::Terminate(text));
        }
    }
}
