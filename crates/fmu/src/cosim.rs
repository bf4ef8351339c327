//! The beam as a co-simulation model: the variable table derived from the scene and its
//! mapping onto an [`AnySimulator`] (planar or spatial, from the scene's `space`). Implements
//! [`CoSimModel`] for the FMI layer.
//!
//! The variables are declared in [`variables`].

pub mod variables;
pub mod view;

use std::path::Path;

use fmi2::{CoSimModel, ModelInfo, StepError, StringVariable, Variable};

use hybeam::error::SimError;
use hybeam::scene::{Root, Scene};
use hybeam::simulator::{AnyOutputs, AnySimulator, InputKind, Quantity};

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
    /// only the reaction of a mounted beam, through `apparent`).
    outputs: AnyOutputs,
    /// A mounted beam's apparent mass at the current state (the reaction's partials by the
    /// mount accelerations), computed with the outputs.
    apparent: Option<Vec<Vec<f64>>>,
    /// The mass matrix of its rigid inertia at the mount (the rigid reaction's partials), for
    /// the elastic outputs' feedthrough: apparent minus this.
    rigid: Option<Vec<Vec<f64>>>,
    /// The last communication step [s] (the velocity-input mode's partials divide by it).
    last_step: f64,
    /// Initialized (fmi2ExitInitializationMode passed, or a state restored).
    started: bool,
    /// Before initialization: a parameter or input was set since the instance was built.
    changed_before_start: bool,
    /// Then the outputs of the start the scene now describes, built at the first read after a
    /// change (a host reading outputs in initialization mode, as libcosim does to settle its
    /// connections, sees the values set).
    pre_start: std::cell::RefCell<Option<Result<AnyOutputs, String>>>,
    /// Per variable (table order): the change of an output over the last communication step
    /// divided by it, the first-order output derivative of the outputs without an exact one
    /// (reactions, energies, inertia); 0 before the first step.
    backward: Vec<f64>,
    /// `visualization.directory` (empty: no views).
    vis_dir: String,
    /// The views of this run, opened at the first state recorded with `vis_dir` set.
    views: Option<view::Views>,
    /// A view could not be written in this run: no more views until fmi2Reset (or another
    /// directory).
    views_off: bool,
    /// The file stem of the views: the instance name, sanitized ([`view::stem_of`]).
    stem: String,
    /// A warning for the FMI layer to report ([`CoSimModel::take_warning`]).
    warning: Option<String>,
}

impl BeamFmu {
    /// Records the current state in the views, if `visualization.directory` is set (opening
    /// them at the first state). A failure becomes the warning of the call and turns the views
    /// off for the rest of the run.
    fn record_view(&mut self) {
        if self.vis_dir.is_empty() || self.views_off {
            return;
        }
        if self.views.is_none() {
            let dir = Path::new(&self.vis_dir);
            match view::Views::open(dir, &self.stem, &self.scene, &self.table) {
                Ok(v) => self.views = Some(v),
                Err(e) => return self.view_failed(e),
            }
        }
        if let Some(v) = &mut self.views {
            if let Err(e) = v.record(&self.sim, &self.outputs) {
                self.view_failed(e);
            }
        }
    }

    /// A view could not be written: the warning, and no more views in this run.
    fn view_failed(&mut self, e: String) {
        // dropping the views tries to write the collection and page of what was recorded
        self.views = None;
        self.views_off = true;
        self.warning = Some(format!(
            "visualization.directory = \"{}\": {e}; visualization is off for the rest of \
             this run (until fmi2Reset)",
            self.vis_dir
        ));
    }

    /// Writes the views' collection and page (fmi2Terminate; a later step after fmi2SetFMUstate
    /// reopens them, and the next fmi2Terminate or fmi2FreeInstance rewrites them).
    fn finish_views(&mut self) {
        if let Some(v) = &mut self.views {
            if let Err(e) = v.finish() {
                self.view_failed(e);
            }
        }
    }

    /// The `.pvd` collection of the views, if they are open.
    pub fn view_collection(&self) -> Option<std::path::PathBuf> {
        self.views.as_ref().map(|v| v.collection())
    }
    /// modelDescription.xml of the FMU of `scene_toml` with this modelIdentifier, from the
    /// scene alone (its variable table and default experiment): no simulator is built.
    pub fn model_description(scene_toml: &str, model_identifier: &str) -> Result<String, String> {
        let scene = Scene::from_toml(scene_toml).map_err(|e| e.0)?;
        let guid = fmi2::guid::guid::<Self>(scene_toml.as_bytes());
        let ids = fmi2::xml::Identity {
            model_identifier,
            guid: &guid,
            generation_tool: Self::GENERATION_TOOL,
        };
        let table = Table::of(&scene);
        fmi2::xml::model_description_with_strings(
            &model_info(&scene),
            table.variables(),
            table.string_variables(),
            &ids,
        )
    }

    /// A mounted scene's OSP-IS extended model description: its file name
    /// (`<modelName>_OspModelDescription.xml`, where libcosim looks beside the FMU) and text.
    /// The mount's groups: `LinearDisplacement` `mount.position`; the orientation
    /// (`AngularDisplacement` `mount.angle` in the plane, `Generic` `mount.orientation` in
    /// space); a `LinearMechanicalPort` `mount.linear` (Force `mount.force` = `root.force.*`,
    /// LinearVelocity `mount.velocity`); an `AngularMechanicalPort` `mount.angular` (Torque
    /// `mount.moment`, AngularVelocity `mount.angular_velocity`); with acceleration inputs,
    /// `Generic` `mount.acceleration` and `mount.angular_acceleration`. All at the top level
    /// (libcosim connects the groups nested in a connected group, not deeper). A host body
    /// that declares the mirror groups (its outputs where the beam has inputs) connects each
    /// with one `<VariableGroupConnection>`. `None` for a fixed root.
    pub fn osp_model_description(scene_toml: &str) -> Result<Option<(String, String)>, String> {
        let scene = Scene::from_toml(scene_toml).map_err(|e| e.0)?;
        let Some(groups) = Self::osp_groups(&scene) else {
            return Ok(None);
        };
        let text = fmi2::osp::model_description(&groups, Table::of(&scene).variables())?;
        Ok(Some((
            format!("{}_OspModelDescription.xml", scene.name),
            text,
        )))
    }

    /// The mount's OSP-IS groups of a scene ([`BeamFmu::osp_model_description`]), `None` for a
    /// fixed root.
    pub fn osp_groups(scene: &Scene) -> Option<Vec<fmi2::osp::VariableGroup>> {
        use fmi2::osp::VariableGroup as G;
        if scene.root != Root::Mounted {
            return None;
        }
        let table = Table::of(scene);
        let vars = table.variables();
        let named = |stem: &str| -> Vec<&str> {
            vars.iter()
                .map(|v| v.name.as_str())
                .filter(|n| *n == stem || n.strip_prefix(stem).is_some_and(|r| r.starts_with('.')))
                .collect()
        };
        let group = |kind, name: &str, stem: &str| G::of(kind, name, &named(stem));
        let orientation = if named("root.angle").is_empty() {
            group("Generic", "mount.orientation", "root.orientation")
        } else {
            group("AngularDisplacement", "mount.angle", "root.angle")
        };
        let mut groups = vec![
            group("LinearDisplacement", "mount.position", "root.position"),
            orientation,
            G::nest(
                "LinearMechanicalPort",
                "mount.linear",
                vec![
                    group("Force", "mount.force", "root.force"),
                    group("LinearVelocity", "mount.velocity", "root.velocity"),
                ],
            ),
            G::nest(
                "AngularMechanicalPort",
                "mount.angular",
                vec![
                    group("Torque", "mount.moment", "root.moment"),
                    group(
                        "AngularVelocity",
                        "mount.angular_velocity",
                        "root.angular_velocity",
                    ),
                ],
            ),
        ];
        if !named("root.acceleration").is_empty() {
            groups.push(group("Generic", "mount.acceleration", "root.acceleration"));
            groups.push(group(
                "Generic",
                "mount.angular_acceleration",
                "root.angular_acceleration",
            ));
        }
        Some(groups)
    }

    fn refresh_outputs(&mut self) {
        (self.outputs, self.apparent, self.rigid) = evaluated(&mut self.sim);
    }

    /// The partials of reaction component `row` (force then moment) by the mount accelerations
    /// (columns): the apparent mass, minus the rigid inertia's mass matrix for the elastic
    /// part. `None` when not available.
    fn feedthrough(&self, row: usize, elastic: bool) -> Option<Vec<f64>> {
        let j = self.apparent.as_ref()?;
        if !elastic {
            return Some(j[row].clone());
        }
        let r = self.rigid.as_ref()?;
        Some(j[row].iter().zip(&r[row]).map(|(a, b)| a - b).collect())
    }

    /// The reaction component `row` (force then moment; `elastic`: its part beyond the rigid
    /// inertia's) with the direct feedthrough of the mount accelerations set for the next step:
    /// exact, both being linear in them.
    fn reaction_now(&self, row: usize, elastic: bool, cached: f64) -> f64 {
        match (
            self.feedthrough(row, elastic),
            self.sim.mount_acceleration_change(),
        ) {
            (Some(j), Some(d)) => cached + j.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>(),
            _ => cached,
        }
    }

    /// The scene a start builds from: the parameters set so far and the inputs the host set
    /// (those that differ from the scene's), taken from the simulator that holds them — the
    /// one place inputs are copied into a scene; a running simulator owns its inputs.
    fn start_scene(&self) -> Scene {
        let mut scene = self.scene.clone();
        self.sim.inputs_into(&mut scene);
        scene
    }

    /// The parameter values, in table order.
    fn parameters(&self) -> Vec<f64> {
        self.table
            .parameters()
            .filter_map(|a| a.parameter(&self.scene))
            .collect()
    }

    fn build_scene_with_parameters(&self, params: &[f64]) -> Result<Scene, String> {
        let mut scene = self.base.clone();
        if self.table.parameters().count() != params.len() {
            return Err("snapshot parameter count does not match this model".into());
        }
        for (a, x) in self.table.parameters().zip(params) {
            a.set_parameter(&mut scene, *x);
        }
        scene.validate().map_err(|e| e.0)?;
        Ok(scene)
    }
}

/// The outputs of `sim`'s current state, its apparent mass and its rigid inertia's mass matrix
/// at the mount (see [`BeamFmu::outputs`](BeamFmu)).
type Evaluated = (AnyOutputs, Option<Vec<Vec<f64>>>, Option<Vec<Vec<f64>>>);

fn evaluated(sim: &mut AnySimulator) -> Evaluated {
    let outputs = sim.outputs();
    let apparent = sim.apparent_mass();
    let rigid = sim.rigid_mass_matrix(&outputs);
    (outputs, apparent, rigid)
}

/// The error for a variable the simulator's space does not have (a table of another space:
/// cannot happen through the FMI layer, which only passes the table's variables).
fn not_in_space(name: &str, sim: &AnySimulator) -> String {
    format!("{name}: not a variable of this {:?} model", sim.space())
}

/// Model name, description and default experiment of a scene.
fn model_info(scene: &Scene) -> ModelInfo {
    ModelInfo {
        model_name: scene.name.clone(),
        description: scene.description.clone(),
        start_time: 0.0,
        stop_time: scene.simulation.t_end,
        step_size: scene.simulation.output_step,
        // a fixed-root beam has no direct feedthrough and no input interpolation; a mounted
        // one's reaction depends directly on the mount accelerations, which the host may
        // interpolate with derivatives
        capabilities: if scene.root == Root::Mounted {
            fmi2::Capabilities {
                input_derivative_order: 2,
                output_derivative_order: 1,
                directional_derivative: true,
            }
        } else {
            fmi2::Capabilities::default()
        },
    }
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
        let backward = vec![0.0; table.variables().len()];
        let mut fmu = Self {
            scene_text: scene_toml.to_string(),
            base: scene.clone(),
            scene,
            table,
            sim,
            outputs,
            apparent: None,
            rigid: None,
            started: false,
            changed_before_start: false,
            pre_start: std::cell::RefCell::new(None),
            last_step: step,
            backward,
            vis_dir: String::new(),
            views: None,
            views_off: false,
            stem: view::stem_of(""),
            warning: None,
        };
        fmu.refresh_outputs();
        Ok(fmu)
    }

    fn model_info(&self) -> ModelInfo {
        model_info(&self.base)
    }

    fn variables(&self) -> &[Variable] {
        self.table.variables()
    }

    fn string_variables(&self) -> &[StringVariable] {
        self.table.string_variables()
    }

    fn get_string(&self, index: usize) -> Result<&str, String> {
        match index {
            VISUALIZATION_DIRECTORY => Ok(&self.vis_dir),
            _ => Err(format!("no String variable at index {index}")),
        }
    }

    /// `visualization.directory`: before the start it is only stored. After it (a restored FMU
    /// state with another directory) the views of the old directory are finished and the next
    /// state recorded opens the new one.
    fn set_string(&mut self, index: usize, value: &str) -> Result<(), String> {
        if index != VISUALIZATION_DIRECTORY {
            return Err(format!("no String variable at index {index}"));
        }
        if value != self.vis_dir {
            self.finish_views();
            self.views = None;
            self.views_off = false;
            self.vis_dir = value.to_owned();
        }
        Ok(())
    }

    fn set_instance_name(&mut self, name: &str) {
        self.stem = view::stem_of(name);
    }

    fn terminate(&mut self) {
        self.finish_views();
    }

    fn take_warning(&mut self) -> Option<String> {
        self.warning.take()
    }

    fn get_real(&self, index: usize) -> Result<f64, String> {
        let access = self.table.access(index);
        let value = match access {
            Access::Input(id) => self.sim.input(id),
            Access::Output(id) if !self.started && self.changed_before_start => {
                let mut cached = self.pre_start.borrow_mut();
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
            Access::Output(id) => {
                let value = self.outputs.value(id);
                let dim = self.sim.scene().space.dim();
                match (id.quantity, value) {
                    (Quantity::RootForce, Some(x)) => {
                        Some(self.reaction_now(id.component, false, x))
                    }
                    (Quantity::RootMoment, Some(x)) => {
                        Some(self.reaction_now(dim + id.component, false, x))
                    }
                    (Quantity::ElasticForce, Some(x)) => {
                        Some(self.reaction_now(id.component, true, x))
                    }
                    (Quantity::ElasticMoment, Some(x)) => {
                        Some(self.reaction_now(dim + id.component, true, x))
                    }
                    _ => value,
                }
            }
            Access::Gravity(_) | Access::Scene(_) | Access::Segment(..) => {
                access.parameter(&self.scene)
            }
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
            Access::Gravity(_) | Access::Scene(_) | Access::Segment(..) => {
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
        if !self.started {
            self.changed_before_start = true;
            self.pre_start.replace(None);
        }
        Ok(())
    }

    fn initialize(&mut self, start_time: f64) -> Result<(), String> {
        let scene = self.start_scene();
        // the partner model set before the start is an input a scene does not hold
        let partner = self.sim.partner();
        self.sim = AnySimulator::start_at(scene, start_time).map_err(|e| e.to_string())?;
        self.sim.set_partner(partner);
        self.refresh_outputs();
        self.backward.fill(0.0);
        self.started = true;
        self.pre_start.replace(None);
        // a new run: a new series (after fmi2Reset the views were discarded)
        if let Some(v) = &mut self.views {
            v.discard();
        }
        self.views = None;
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
        self.last_step = h;
        self.refresh_outputs();
        for (index, rate) in self.backward.iter_mut().enumerate() {
            if let Access::Output(id) = self.table.access(index) {
                if let (Some(a), Some(b)) = (before.value(id), self.outputs.value(id)) {
                    *rate = (b - a) / h;
                }
            }
        }
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
            (Access::Output(id), 1) => Ok(self.outputs.rate(id).unwrap_or(self.backward[index])),
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
                "{name}: input derivatives are taken for the mount inputs and the tip loads"
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
        let (row, elastic) = match o.quantity {
            Quantity::RootForce => (o.component, false),
            Quantity::RootMoment => (dim + o.component, false),
            Quantity::ElasticForce => (o.component, true),
            Quantity::ElasticMoment => (dim + o.component, true),
            _ => return Ok(0.0),
        };
        let (col, scale) = match i.kind {
            InputKind::MountAcceleration => (i.component, 1.0),
            InputKind::MountAngularAcceleration => (dim + i.component, 1.0),
            InputKind::MountVelocity => (i.component, 1.0 / self.last_step),
            InputKind::MountAngularVelocity => (dim + i.component, 1.0 / self.last_step),
            _ => return Ok(0.0),
        };
        let j = self
            .feedthrough(row, elastic)
            .ok_or_else(|| format!("{}: the apparent mass is not available", names(&self.table)))?;
        Ok(j[col] * scale)
    }

    /// Back to the instantiated model; the views of the run are discarded (no collection or
    /// page written; the next run starts a new series under the same stem, overwriting), and
    /// `visualization.directory` is back to its start value (empty).
    fn reset(&mut self) -> Result<(), String> {
        let fresh = Self::from_resource(&self.scene_text)?;
        if let Some(v) = &mut self.views {
            v.discard();
        }
        let stem = std::mem::take(&mut self.stem);
        *self = fresh;
        self.stem = stem;
        Ok(())
    }

    /// The FMU's part (the parameter values, in table order) around the simulator's snapshot
    /// (state, memory, inputs; versioned and bound to the scene), encoded with `postcard`.
    fn save_state(&self) -> Vec<u8> {
        let snapshot: FmuSnapshot = (
            self.parameters(),
            self.sim.snapshot(),
            self.backward.clone(),
        );
        postcard::to_allocvec(&snapshot).unwrap_or_default()
    }

    fn load_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let (snapshot, rest) = postcard::take_from_bytes::<FmuSnapshot>(bytes)
            .map_err(|e| format!("not a hybeam FMU snapshot: {e}"))?;
        if !rest.is_empty() {
            return Err(format!(
                "not a hybeam FMU snapshot: {} trailing bytes",
                rest.len()
            ));
        }
        let (params, sim_bytes, backward) = snapshot;
        if backward.len() != self.backward.len() {
            return Err("snapshot output count does not match this model".into());
        }
        let variables = self.table.variables();
        if let Some((k, x)) = backward.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(format!(
                "snapshot backward difference of {} = {x} is not finite",
                variables[k].name
            ));
        }
        let scene = self.build_scene_with_parameters(&params)?;
        // a rollback (the running simulator's parameters) restores into it, keeping its own
        // state to return to if the snapshot is refused; other parameters build a model anew
        let rollback = self.started && params == self.parameters();
        let (mut fresh, backup) = if rollback {
            (None, Some(self.sim.snapshot()))
        } else {
            let sim = AnySimulator::restorable(scene.clone()).map_err(|e| e.to_string())?;
            (Some(sim), None)
        };
        let sim = fresh.as_mut().unwrap_or(&mut self.sim);
        let checked = checked_restore(sim, &sim_bytes, &self.table);
        let (outputs, apparent, rigid) = match checked {
            Ok(evaluated) => evaluated,
            Err(e) => {
                if let Some(b) = backup {
                    // its own snapshot of a moment ago: restores
                    let _ = self.sim.restore_snapshot(&b);
                }
                return Err(e);
            }
        };
        if let Some(sim) = fresh {
            self.sim = sim;
        }
        self.scene = scene;
        self.backward = backward;
        self.outputs = outputs;
        self.apparent = apparent;
        self.rigid = rigid;
        self.started = true;
        self.pre_start.replace(None);
        Ok(())
    }
}

/// Restores `bytes` of [`AnySimulator::snapshot`] into `sim` and evaluates the state: a
/// snapshot that does not fit is an error of the call (fmi2Error), not of a step, and so is
/// a state whose values are finite but whose outputs overflow (coordinates of 1e300: infinite
/// energies) or whose apparent mass is not finite.
fn checked_restore(
    sim: &mut AnySimulator,
    bytes: &[u8],
    table: &Table,
) -> Result<Evaluated, String> {
    sim.restore_snapshot(bytes).map_err(|e| e.to_string())?;
    let (outputs, apparent, rigid) = evaluated(sim);
    for (index, var) in table.variables().iter().enumerate() {
        if let Access::Output(id) = table.access(index) {
            match outputs.value(id) {
                Some(x) if !x.is_finite() => {
                    return Err(format!(
                        "the snapshot's state gives {} = {x}: its values are beyond what the \
                         model can evaluate",
                        var.name
                    ))
                }
                _ => {}
            }
        }
    }
    if apparent.iter().flatten().flatten().any(|x| !x.is_finite()) {
        return Err(
            "the snapshot's state gives a non-finite apparent mass at the mount: its values are \
             beyond what the model can evaluate"
                .into(),
        );
    }
    Ok((outputs, apparent, rigid))
}

/// A serialized FMU state: the parameter values in table order, the bytes of
/// [`AnySimulator::snapshot`], and the outputs' backward differences (table order).
type FmuSnapshot = (Vec<f64>, Vec<u8>, Vec<f64>);

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
                refusal: Refusal::AxialStrain { value: 0.06 },
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
