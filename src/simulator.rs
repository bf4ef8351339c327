//! A beam in time: model + integrator + state behind `advance` and `outputs`, for either space
//! ([`Simulator<Planar>`], [`Simulator<Spatial>`]). The command-line runner and the FMU adapter
//! drive [`AnySimulator`], the planar|spatial choice made once from `scene.space`, and read and
//! write it through named scalars ([`OutputId`], [`InputId`]: `tip.position.x`,
//! `tip.orientation.e0`, `tip.force.z`, …).

mod any;
mod finite;
pub mod limits;
mod mount;

pub use any::{AnyOutputs, AnySimulator, InputId, InputKind, OutputId, Quantity};
pub use limits::*;
pub use mount::{MountInput, MountState};

use crate::error::{Refusal, SimError, SnapshotError, StepLimit};
use crate::integrator::{
    solve_static, Counters, GeneralizedAlpha, Integrable, IntegratorMemory, State,
    CALM_BEFORE_GROWTH, MAX_HALVINGS, MIN_STEP,
};
use crate::model::{Model, ModelValidity, Motion, MotionRates, Outputs, Planar, Space, Spatial};
use crate::scene::{InitialState, Mount, Scene, SceneError, SpaceKind};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::hash::Hasher;

/// Internal step control carried from one communication step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepControl {
    /// Largest internal step that recently succeeded [s] (≤ `solver.max_step`).
    pub h_ok: f64,
    /// Communication steps completed without a rejected attempt since `h_ok` last changed.
    pub calm: u32,
}

/// Relative rounding guard of the step count: a span of k·h_max computed as a difference of
/// times carries rounding of this order, so an internal step may exceed `solver.max_step` by
/// this fraction.
const STEP_ROUNDING: f64 = 1e-9;

/// A space a [`Simulator`] runs in: builds its model from a scene and names its orientation
/// output. Implemented for [`Planar`] and [`Spatial`].
pub trait SpaceModel:
    Space<
    Vec: Serialize + DeserializeOwned,
    Moment: Serialize + DeserializeOwned,
    Attitude: Serialize + DeserializeOwned,
>
{
    /// The scene's `space` this model is built for.
    const KIND: SpaceKind;
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

    /// The model of a scene of this space (an error naming the space otherwise).
    fn model(scene: &Scene) -> Result<Model<Self>, SceneError>;
    /// The components of an orientation, in the order of [`SpaceModel::ATTITUDE_COMPONENTS`].
    fn attitude_components(a: &Self::Attitude) -> &[f64];
    /// The components of an orientation, mutable.
    fn attitude_components_mut(a: &mut Self::Attitude) -> &mut [f64];
    /// The orientation of a scene's `[mount]` table.
    fn attitude_from(m: &Mount) -> Self::Attitude;
}

impl SpaceModel for Planar {
    const KIND: SpaceKind = SpaceKind::Planar;
    const ATTITUDE: &'static str = "tip.angle";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &[""];
    const MOUNT_ATTITUDE: &'static str = "root.angle";
    const ANGULAR_SUFFIXES: &'static [&'static str] = &[""];

    fn model(scene: &Scene) -> Result<Model<Self>, SceneError> {
        Model::<Planar>::from_scene(scene)
    }

    fn attitude_components(a: &f64) -> &[f64] {
        std::slice::from_ref(a)
    }

    fn attitude_components_mut(a: &mut f64) -> &mut [f64] {
        std::slice::from_mut(a)
    }

    fn attitude_from(m: &Mount) -> f64 {
        m.angle
    }
}

impl SpaceModel for Spatial {
    const KIND: SpaceKind = SpaceKind::Spatial;
    const ATTITUDE: &'static str = "tip.orientation";
    const ATTITUDE_COMPONENTS: &'static [&'static str] = &["e0", "e1", "e2", "e3"];
    const MOUNT_ATTITUDE: &'static str = "root.orientation";
    const ANGULAR_SUFFIXES: &'static [&'static str] = Spatial::MOMENT_AXES;

    fn model(scene: &Scene) -> Result<Model<Self>, SceneError> {
        if scene.space != SpaceKind::Spatial {
            return Err(SceneError(
                "space = \"planar\": this scene builds a planar model, not a spatial one".into(),
            ));
        }
        Model::<Spatial>::from_scene(scene)
    }

    fn attitude_components(a: &[f64; 4]) -> &[f64] {
        a
    }

    fn attitude_components_mut(a: &mut [f64; 4]) -> &mut [f64] {
        a
    }

    fn attitude_from(m: &Mount) -> [f64; 4] {
        let e = m.orientation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
        Self::normalized_attitude(&e).unwrap_or([1.0, 0.0, 0.0, 0.0])
    }
}

/// The inputs of the equations a host may change between communication steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct Inputs<S: SpaceModel> {
    /// Total tip force [N], global axes.
    pub tip_force: S::Vec,
    /// Total dead tip moment [N m], global axes (in the plane: about z, counter-clockwise).
    pub tip_moment: S::Moment,
    /// Gravity [m/s²], global axes.
    pub gravity: S::Vec,
}

impl<S: SpaceModel> Inputs<S> {
    fn of(model: &Model<S>) -> Self {
        Self {
            tip_force: model.tip_force(),
            tip_moment: model.tip_moment(),
            gravity: model.gravity(),
        }
    }

    fn apply(&self, model: &mut Model<S>) {
        model.set_tip_force(self.tip_force);
        model.set_tip_moment(self.tip_moment);
        if model.gravity() != self.gravity {
            model.set_gravity(self.gravity);
        }
    }
}

/// First and second time derivatives of the tip loads over the coming communication step (FMI
/// input derivatives; zero: the loads are held): the step integrates
/// F(t₀ + τ) = F + Ḟτ + ½F̈τ² (and the moment likewise) at every internal step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct LoadRates<S: SpaceModel> {
    /// Ḟ [N/s], F̈ [N/s²], global axes.
    pub force: [S::Vec; 2],
    /// Ṁ [N m/s], M̈ [N m/s²].
    pub moment: [S::Moment; 2],
}

impl<S: SpaceModel> LoadRates<S> {
    /// Whether any rate is nonzero.
    fn any(&self) -> bool {
        self.force
            .iter()
            .any(|f| f.as_ref().iter().any(|x| *x != 0.0))
            || self
                .moment
                .iter()
                .any(|m| S::moment_components(m).iter().any(|x| *x != 0.0))
    }

    /// The loads `tau` [s] after `at`, whose loads are the values at the start.
    fn advanced(&self, at: &Inputs<S>, tau: f64) -> Inputs<S> {
        let mut out = *at;
        let (c1, c2) = (tau, 0.5 * tau * tau);
        for k in 0..S::DIM {
            out.tip_force[k] += c1 * self.force[0][k] + c2 * self.force[1][k];
        }
        let (d1, d2) = (
            S::moment_components(&self.moment[0]),
            S::moment_components(&self.moment[1]),
        );
        for ((m, a), b) in S::moment_components_mut(&mut out.tip_moment)
            .iter_mut()
            .zip(d1)
            .zip(d2)
        {
            *m += c1 * a + c2 * b;
        }
        out
    }
}

/// Everything beyond the state that a snapshot must carry for a bit-identical restart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct Memory<S: SpaceModel> {
    /// Integrator memory.
    pub integrator: IntegratorMemory,
    /// Step control.
    pub step: StepControl,
    /// The inputs the state's accelerations and multipliers are consistent with (those of the
    /// last step); the next [`Simulator::advance`] treats a difference from the current
    /// inputs as a jump at the current time.
    pub applied: Inputs<S>,
    /// The mount's path and pending input (`None` for a fixed root).
    pub mount: Option<MountState<S>>,
    /// The mount motion the held Newton matrix was evaluated at (mounted scenes).
    pub mount_at_matrix: Option<Motion<S>>,
    /// The tip loads' derivatives set for the next step.
    pub load_rates: LoadRates<S>,
}

/// How far a restored orientation of the mount's path may be from unit Euler parameters (per
/// component): the path keeps them normalized to rounding, so more means a crafted state.
const ATTITUDE_TOLERANCE: f64 = 1e-9;

/// Format version of [`Simulator::snapshot`]; raise it when a field of [`Snapshot`] (or of the
/// structs it holds) changes.
pub const SNAPSHOT_VERSION: u32 = 4;

/// The payload of [`Simulator::snapshot`], encoded with `postcard` (f64 as 8 little-endian
/// bytes, so restored values are bit-identical).
#[derive(Serialize, Deserialize)]
#[serde(bound = "")]
struct Snapshot<S: SpaceModel> {
    /// [`SNAPSHOT_VERSION`]; first, so that another version is reported as such.
    version: u32,
    /// Coordinates of the model.
    coordinates: u64,
    /// Constraints of the model.
    constraints: u64,
    /// [`scene_key`] of the simulator's scene.
    scene: u64,
    /// The inputs set for the next step (tip force [N], tip moment [N m], gravity [m/s²]).
    inputs: Inputs<S>,
    /// The state.
    state: State,
    /// The memory beyond the state.
    memory: Memory<S>,
}

/// FNV-1a 64 of the canonical TOML of `scene` without its inputs (tip force, tip moment and
/// gravity, which
/// a snapshot carries and a host may change): what binds a snapshot to its model.
fn scene_key(scene: &Scene) -> u64 {
    let mut scene = scene.clone();
    scene.tip.force.clear();
    scene.tip.moment.clear();
    scene.gravity.clear();
    let mut h = fnv::FnvHasher::default();
    h.write(scene.to_toml().as_bytes());
    h.finish()
}

/// A running simulation in the space `S`.
#[derive(Debug)]
pub struct Simulator<S: SpaceModel> {
    scene: Scene,
    model: Model<S>,
    integ: GeneralizedAlpha,
    state: State,
    step: StepControl,
    /// Inputs the state's q̈ and λ are consistent with (see [`Memory::applied`]).
    applied: Inputs<S>,
    /// The mount's motion (`root = "mounted"`; boxed: a fixed root carries no more than a
    /// pointer).
    mount: Option<Box<MountState<S>>>,
    /// The tip loads' derivatives over the next step (zero: held).
    load_rates: LoadRates<S>,
    /// Smallest internal step used so far [s].
    pub min_step_used: f64,
}

impl<S: SpaceModel> Simulator<S> {
    /// [`Simulator::start_at`] t = 0.
    pub fn new(scene: Scene) -> Result<Self, SimError> {
        Self::start_at(scene, 0.0)
    }

    /// Builds the model and its initial state (straight, or static equilibrium), with
    /// consistent accelerations, the clock starting at `t0` [s] (e.g. an FMU's start time).
    pub fn start_at(scene: Scene, t0: f64) -> Result<Self, SimError> {
        let mut sim = Self::build(scene, true)?;
        sim.state.t = t0;
        if let Some(m) = &mut sim.mount {
            m.t0 = t0;
        }
        Ok(sim)
    }

    /// Builds the model without computing an initial state (the caller restores a snapshot).
    pub fn restorable(scene: Scene) -> Result<Self, SimError> {
        Self::build(scene, false)
    }

    fn build(scene: Scene, initialize: bool) -> Result<Self, SimError> {
        let mut model = S::model(&scene)?;
        let n = model.coordinates();
        let m = model.constraints();
        let mut state = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
        let mut integ = GeneralizedAlpha::new(&scene.solver, n, m);
        let mount = MountState::<S>::of_scene(&scene, 0.0);
        let static_start = initialize && scene.initial.state == InitialState::Static;
        // a spinning mount's static state is relative: solved after the carry, below
        let spinning = scene.mount_turns().0;
        if static_start && !spinning {
            // in the mount frame (built there, at rest): gravity minus the mount's acceleration
            // (this mount does not turn)
            let g = model.gravity();
            if let Some(ms) = &mount {
                let mut ge = g;
                for k in 0..S::DIM {
                    ge[k] -= ms.base.acceleration[k];
                }
                model.set_gravity(S::to_frame(&ms.base.attitude, &ge));
            }
            let solved = solve_static(&mut model, &mut state, scene.solver.static_tolerance());
            if mount.is_some() {
                model.set_gravity(g);
            }
            solved.map_err(SimError::InitialStatic)?;
        }
        if let Some(ms) = &mount {
            // at rest relative to the mount: carried to its pose with its rigid velocity field
            model.carry_state(&ms.base, &mut state.q, &mut state.v);
            model.set_mount(&ms.base);
            if static_start && spinning {
                // at rest in the spinning frame: centrifugal field, gravity, the mount's
                // acceleration, from the straight beam carried there
                model
                    .solve_relative_static(&ms.base, &mut state, scene.solver.static_tolerance())
                    .map_err(SimError::InitialStatic)?;
            }
        }
        if initialize {
            integ
                .initialize(&mut model, &mut state)
                .map_err(SimError::InitialAccelerations)?;
        }
        let step = StepControl {
            h_ok: scene.solver.max_step,
            calm: 0,
        };
        let applied = Inputs::of(&model);
        Ok(Self {
            scene,
            model,
            integ,
            state,
            step,
            applied,
            mount: mount.map(Box::new),
            load_rates: LoadRates::default(),
            min_step_used: f64::INFINITY,
        })
    }

    /// The scene this simulator was built from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The model.
    pub fn model(&self) -> &Model<S> {
        &self.model
    }

    /// Current time [s].
    pub fn time(&self) -> f64 {
        self.state.t
    }

    /// Current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The memory a snapshot must carry besides the state.
    pub fn memory(&self) -> Memory<S> {
        Memory {
            integrator: self.integ.memory(),
            step: self.step,
            applied: self.applied,
            mount: self.mount.as_deref().cloned(),
            mount_at_matrix: self.model.mount_at_matrix(),
            load_rates: self.load_rates,
        }
    }

    /// Restores a state and memory taken from a simulator of the same scene (checked:
    /// dimensions, step sizes, the convergence estimate, the mount path's orientations; the
    /// caller checked every value for finiteness); the run then continues bit for bit as the
    /// original.
    fn restore(&mut self, s: State, mem: &Memory<S>) -> Result<(), SimError> {
        if s.q.len() != self.state.q.len()
            || s.lambda.len() != self.state.lambda.len()
            || [&s.v, &s.acc, &s.aux].iter().any(|x| x.len() != s.q.len())
        {
            return Err(SnapshotError::Dimensions.into());
        }
        let h_max = self.scene.solver.max_step;
        let h = mem.step.h_ok;
        if !(h >= MIN_STEP && h <= h_max) {
            return Err(SnapshotError::StepSize { h, h_max }.into());
        }
        if let Some(j) = &mem.integrator.jacobian {
            // the step of the held Newton matrix may be a communication step below MIN_STEP
            if !(j.h > 0.0 && j.h <= h_max * (1.0 + 2.0 * STEP_ROUNDING)) {
                return Err(SnapshotError::JacobianStep { h: j.h, h_max }.into());
            }
            if [&j.q, &j.v, &j.acc].iter().any(|x| x.len() != s.q.len())
                || j.lam.len() != s.lambda.len()
            {
                return Err(SnapshotError::Dimensions.into());
            }
        }
        if mem.integrator.eta < 0.0 {
            return Err(SnapshotError::Field {
                field: "memory.integrator.eta",
                value: mem.integrator.eta,
                expected: "a convergence-rate estimate >= 0",
            }
            .into());
        }
        let unit = |a: &S::Attitude| {
            S::normalized_attitude(a).is_some_and(|n| {
                S::attitude_components(&n)
                    .iter()
                    .zip(S::attitude_components(a))
                    .all(|(x, y)| (x - y).abs() <= ATTITUDE_TOLERANCE)
            })
        };
        let attitudes = mem
            .mount
            .iter()
            .flat_map(|m| {
                [("memory.mount.base", Some(&m.base.attitude))]
                    .into_iter()
                    .chain([("memory.mount.last", m.last.as_ref().map(|l| &l.1.attitude))])
            })
            .chain([(
                "memory.mount_at_matrix",
                mem.mount_at_matrix.as_ref().map(|m| &m.attitude),
            )]);
        for (field, a) in attitudes {
            if let Some(a) = a.filter(|a| !unit(a)) {
                return Err(SnapshotError::Attitude {
                    field,
                    components: S::attitude_components(a).to_vec(),
                }
                .into());
            }
        }
        // a pending input is checked (and normalized) when the next step takes it: it only
        // needs a defined orientation
        if let Some(input) = mem.mount.as_ref().and_then(|m| m.pending.as_ref()) {
            if S::normalized_attitude(&input.motion.attitude).is_none() {
                return Err(SnapshotError::Attitude {
                    field: "memory.mount.pending",
                    components: S::attitude_components(&input.motion.attitude).to_vec(),
                }
                .into());
            }
        }
        if let Some(r) = self.section_refusal(&self.model.validity(&s.q), false) {
            return Err(SnapshotError::Refused(r).into());
        }
        // the held Newton matrix was evaluated under the inputs of the last step (a dead tip
        // moment adds stiffness): rebuild it under those, whatever is set for the next step
        if mem.mount.is_some() != self.mount.is_some() {
            return Err(SnapshotError::OtherModel.into());
        }
        let next = Inputs::of(&self.model);
        mem.applied.apply(&mut self.model);
        let current_mount = self.model.mount_motion().copied();
        if let Some(m) = &mem.mount_at_matrix {
            self.model.set_mount(m);
        }
        if let Err(e) = self.integ.restore_memory(&mut self.model, &mem.integrator) {
            next.apply(&mut self.model);
            if let Some(m) = &current_mount {
                self.model.set_mount(m);
            }
            return Err(SnapshotError::NewtonMatrix(e).into());
        }
        next.apply(&mut self.model);
        if let Some(ms) = &mem.mount {
            self.model.set_mount(&ms.at(s.t));
        }
        self.state = s;
        self.step = mem.step;
        self.applied = mem.applied;
        self.mount = mem.mount.clone().map(Box::new);
        self.load_rates = mem.load_rates;
        Ok(())
    }

    /// The simulator's state, memory and current inputs as bytes (format [`SNAPSHOT_VERSION`],
    /// bound to the scene apart from its inputs, tip force, tip moment and gravity):
    /// [`Simulator::restore_snapshot`] into a simulator of the same scene continues bit for
    /// bit as this one.
    pub fn snapshot(&self) -> Vec<u8> {
        let snapshot = Snapshot {
            version: SNAPSHOT_VERSION,
            coordinates: self.state.q.len() as u64,
            constraints: self.state.lambda.len() as u64,
            scene: scene_key(&self.scene),
            inputs: Inputs::of(&self.model),
            state: self.state.clone(),
            memory: self.memory(),
        };
        // encoding into a Vec fails only on allocation failure, which aborts anyway
        postcard::to_allocvec(&snapshot).unwrap_or_default()
    }

    /// Restores bytes of [`Simulator::snapshot`] taken from a simulator of the same scene
    /// (tip force, tip moment and gravity may differ: the snapshot sets them). Checks the format version,
    /// the scene, the dimensions, finiteness and the step sizes; on error the simulator is
    /// unchanged.
    pub fn restore_snapshot(&mut self, bytes: &[u8]) -> Result<(), SimError> {
        let malformed = |e: postcard::Error| SnapshotError::Malformed(e.to_string());
        let (found, _) = postcard::take_from_bytes::<u32>(bytes).map_err(malformed)?;
        if found != SNAPSHOT_VERSION {
            return Err(SnapshotError::Version {
                found,
                expected: SNAPSHOT_VERSION,
            }
            .into());
        }
        let (snap, rest) = postcard::take_from_bytes::<Snapshot<S>>(bytes).map_err(malformed)?;
        if !rest.is_empty() {
            return Err(SnapshotError::Malformed(format!("{} trailing bytes", rest.len())).into());
        }
        if snap.scene != scene_key(&self.scene) {
            return Err(SnapshotError::OtherModel.into());
        }
        if snap.coordinates != self.state.q.len() as u64
            || snap.constraints != self.state.lambda.len() as u64
        {
            return Err(SnapshotError::Dimensions.into());
        }
        // every f64 of it: state, inputs, integrator memory and its Newton-matrix point, the
        // mount's path and pending input, the load rates
        if let Some((field, value)) = finite::first_non_finite(&snap) {
            return Err(SnapshotError::NonFiniteField { field, value }.into());
        }
        self.restore(snap.state, &snap.memory)?;
        snap.inputs.apply(&mut self.model);
        Ok(())
    }

    /// Sets gravity [m/s²] (takes effect at the next step, as a jump of the inputs).
    pub fn set_gravity(&mut self, g: S::Vec) {
        self.model.set_gravity(g);
    }

    /// Work counters.
    pub fn counters(&self) -> Counters {
        self.integ.counters
    }

    /// Sets the total tip force [N], global axes (replaces the scene's; takes effect at the
    /// next step, as a jump of the inputs at the current time: see [`Simulator::advance`]).
    pub fn set_tip_force(&mut self, f: S::Vec) {
        self.model.set_tip_force(f);
    }

    /// The total tip force the model applies [N], global axes.
    pub fn tip_force(&self) -> S::Vec {
        self.model.tip_force()
    }

    /// Sets the total dead tip moment [N m], global axes (in the plane: about z,
    /// counter-clockwise; replaces the scene's; takes effect at the next step, as a jump of the
    /// inputs like the tip force).
    pub fn set_tip_moment(&mut self, m: S::Moment) {
        self.model.set_tip_moment(m);
    }

    /// The total tip moment the model applies [N m], global axes.
    pub fn tip_moment(&self) -> S::Moment {
        self.model.tip_moment()
    }

    /// Gravity [m/s²], global axes.
    pub fn gravity(&self) -> S::Vec {
        self.model.gravity()
    }

    /// The inputs set for the next step (tip force, tip moment, gravity).
    pub fn inputs(&self) -> Inputs<S> {
        Inputs::of(&self.model)
    }

    /// Sets all inputs (each takes effect at the next step, as a jump of the inputs).
    pub fn set_inputs(&mut self, inputs: &Inputs<S>) {
        inputs.apply(&mut self.model);
    }

    /// The tip loads' derivatives for the next step ([`LoadRates`]); they hold for that step
    /// only (zero after it).
    pub fn set_load_rates(&mut self, rates: LoadRates<S>) {
        self.load_rates = rates;
    }

    /// The tip loads' derivatives set for the next step.
    pub fn load_rates(&self) -> LoadRates<S> {
        self.load_rates
    }

    /// Outputs of the current state.
    pub fn outputs(&self) -> Outputs<S> {
        let s = &self.state;
        self.model.outputs(&s.q, &s.v, &s.acc, &s.lambda)
    }

    /// Returns to the state, step control and mount path of the start of an `advance` call
    /// after a failed or refused communication step (the held Newton matrix belongs to the
    /// abandoned attempt).
    fn roll_back(
        &mut self,
        saved: State,
        saved_step: StepControl,
        mount: Option<Box<MountState<S>>>,
        inputs: &Inputs<S>,
    ) {
        // the loads set for the step (an attempt may have left them at a time within it)
        inputs.apply(&mut self.model);
        if let Some(ms) = &mount {
            self.model.set_mount(&ms.at(saved.t));
        }
        self.mount = mount;
        self.state = saved;
        self.step = saved_step;
        self.integ.invalidate();
    }

    /// Sets the mount's motion at the current time for the next step (`root = "mounted"`):
    /// checked (finite, a defined orientation, which is normalized), with accelerations
    /// estimated from the velocities when `input.accelerations` is false. It takes effect at
    /// the next [`Simulator::advance`]: a pose or velocity that differs from the path's
    /// prediction re-anchors the beam rigidly, an acceleration that differs is a jump of the
    /// inputs; a pose further than [`MAX_MOUNT_JUMP_LENGTH`] · length or
    /// [`MAX_MOUNT_JUMP_ANGLE`] from the prediction is refused there.
    pub fn set_mount(&mut self, input: MountInput<S>) -> Result<(), SimError> {
        let t = self.state.t;
        let Some(ms) = &mut self.mount else {
            return Err(SimError::Refused {
                t,
                refusal: Refusal::MountInput(
                    "this scene's root is not mounted (set root = \"mounted\" to drive it)".into(),
                ),
            });
        };
        ms.checked(input, t)
            .map_err(|refusal| SimError::Refused { t, refusal })?;
        ms.pending = Some(input);
        Ok(())
    }

    /// The mount input set for the next step, else the motion now (`None` for a fixed root).
    pub fn mount_input(&self) -> Option<MountInput<S>> {
        self.mount.as_ref().map(|m| m.input_or_now(self.state.t))
    }

    /// Sets the mount input for the next step without checking it (a host writing one scalar
    /// at a time; [`Simulator::advance`] checks it): `false` for a fixed root.
    pub fn set_mount_unchecked(&mut self, input: MountInput<S>) -> bool {
        match &mut self.mount {
            Some(m) => {
                m.pending = Some(input);
                true
            }
            None => false,
        }
    }

    /// The beam's apparent mass at the mount: the exact partial derivatives of the reaction
    /// (`root.force` then `root.moment` components, rows) with respect to the mount's
    /// acceleration and angular acceleration (columns), at the current state — what the
    /// reaction's direct feedthrough is ([`Outputs::root_force`] after an acceleration input
    /// changes by Δa is the current one plus this matrix times Δa). Each column is the
    /// acceleration jump of a unit input change (`[M Φ_qᵀ; Φ_q 0]` solve, linear in it) on a
    /// scratch state; the held Newton matrix is then rebuilt where it was, so the run continues
    /// bit for bit. `None` for a fixed root or when the solve fails.
    pub fn apparent_mass(&mut self) -> Option<Vec<Vec<f64>>> {
        let m0 = *self.model.mount_motion()?;
        let mem = self.integ.memory();
        let at_matrix = self.model.mount_at_matrix();
        let base = self.outputs();
        let rot = S::moment_components(&m0.angular_velocity).len();
        let mut cols = Vec::new();
        for k in 0..S::DIM + rot {
            let mut m1 = m0;
            if k < S::DIM {
                m1.acceleration[k] += 1.0;
            } else {
                S::moment_components_mut(&mut m1.angular_acceleration)[k - S::DIM] += 1.0;
            }
            let mut s = self.state.clone();
            let ok = self
                .integ
                .change_inputs(&mut self.model, &mut s, |m| m.set_mount(&m1))
                .is_ok();
            let o = self.model.outputs(&s.q, &s.v, &s.acc, &s.lambda);
            self.model.set_mount(&m0);
            if !ok {
                self.rebuild_matrix(&mem, at_matrix);
                return None;
            }
            let mut col: Vec<f64> = (0..S::DIM)
                .map(|c| o.root_force[c] - base.root_force[c])
                .collect();
            let (mo, mb) = (
                S::moment_components(&o.root_moment),
                S::moment_components(&base.root_moment),
            );
            col.extend(mo.iter().zip(mb).map(|(a, b)| a - b));
            cols.push(col);
        }
        self.rebuild_matrix(&mem, at_matrix);
        let n = cols.len();
        Some(
            (0..n)
                .map(|r| (0..n).map(|c| cols[c][r]).collect())
                .collect(),
        )
    }

    /// The mass matrix at the mount of the rigid inertia in `outputs` (this state's,
    /// [`Simulator::outputs`]; [`MountInertia::mass_matrix`](crate::model::MountInertia::mass_matrix),
    /// ordered as [`Simulator::apparent_mass`]): the rigid reaction's partials by the mount
    /// accelerations, so the elastic part's are the apparent mass minus these. `None` for a
    /// fixed root.
    pub fn rigid_mass_matrix(&self, outputs: &Outputs<S>) -> Option<Vec<Vec<f64>>> {
        let m = self.model.mount_motion()?;
        Some(outputs.mount?.mass_matrix(&m.attitude))
    }

    /// Rebuilds the held Newton matrix of `mem` under the inputs and mount motion it was
    /// evaluated with, then returns the model to the current ones.
    fn rebuild_matrix(&mut self, mem: &IntegratorMemory, at_matrix: Option<Motion<S>>) {
        let next = Inputs::of(&self.model);
        let now = self.model.mount_motion().copied();
        self.applied.apply(&mut self.model);
        if let Some(m) = &at_matrix {
            self.model.set_mount(m);
        }
        if self.integ.restore_memory(&mut self.model, mem).is_err() {
            self.integ.invalidate();
        }
        next.apply(&mut self.model);
        if let Some(m) = &now {
            self.model.set_mount(m);
        }
    }

    /// How the mount input set for the next step changes the accelerations now (the
    /// acceleration then the angular acceleration components, as checked and estimated by the
    /// next [`Simulator::advance`]): what the reaction's direct feedthrough multiplies. `None`
    /// without a pending input or when it would be refused.
    pub fn mount_acceleration_change(&self) -> Option<Vec<f64>> {
        let ms = self.mount.as_ref()?;
        let input = ms.checked(ms.pending?, self.state.t).ok()?;
        let now = ms.at(self.state.t);
        let (a, b) = (input.motion, now);
        let mut d: Vec<f64> = (0..S::DIM)
            .map(|k| a.acceleration[k] - b.acceleration[k])
            .collect();
        let (wa, wb) = (
            S::moment_components(&a.angular_acceleration),
            S::moment_components(&b.angular_acceleration),
        );
        d.extend(wa.iter().zip(wb).map(|(x, y)| x - y));
        Some(d)
    }

    /// The mount's motion now (`None` for a fixed root).
    pub fn mount(&self) -> Option<Motion<S>> {
        self.mount.as_ref().map(|m| m.at(self.state.t))
    }

    /// Whether mount accelerations are inputs (else estimated from velocities).
    pub fn mount_accelerations_given(&self) -> Option<bool> {
        self.mount.as_ref().map(|m| m.accelerations_given)
    }

    /// Takes the pending mount input at the start of a communication step: refuses a jump,
    /// re-anchors a pose or velocity that differs from the prediction, and returns the motion
    /// whose accelerations differ from the prediction (a jump of the inputs), if any.
    fn take_mount_input(&mut self) -> Result<Option<Motion<S>>, SimError> {
        let t0 = self.state.t;
        let length = self.scene.total_length();
        let Some(ms) = &mut self.mount else {
            return Ok(None);
        };
        let Some(raw) = ms.pending.take() else {
            // input derivatives hold for one step: continue the path without them
            if ms.rates != MotionRates::default() {
                ms.base = ms.at(t0);
                ms.t0 = t0;
                ms.rates = MotionRates::default();
            }
            return Ok(None);
        };
        let input = match ms.checked(raw, t0) {
            Ok(i) => i,
            Err(refusal) => {
                ms.pending = Some(raw);
                return Err(SimError::Refused { t: t0, refusal });
            }
        };
        let pred = ms.at(t0);
        let target = input.motion;
        let d2: f64 = (0..S::DIM)
            .map(|k| (target.position[k] - pred.position[k]).powi(2))
            .sum();
        let (distance, angle) = (
            d2.sqrt(),
            S::attitude_angle(&pred.attitude, &target.attitude),
        );
        if !(distance <= MAX_MOUNT_JUMP_LENGTH * length && angle <= MAX_MOUNT_JUMP_ANGLE) {
            ms.pending = Some(raw);
            return Err(SimError::Refused {
                t: t0,
                refusal: Refusal::MountJump { distance, angle },
            });
        }
        let mid = target.with_accelerations_of(&pred);
        if mid != pred {
            let s = &mut self.state;
            self.model.reanchor(
                &pred,
                &mid,
                &mut s.q,
                &mut s.v,
                &mut [&mut s.acc, &mut s.aux],
            );
            self.model.set_mount(&mid);
        }
        ms.t0 = t0;
        ms.base = target;
        ms.rates = input.rates;
        ms.last = Some((t0, target));
        Ok((target != mid).then_some(target))
    }

    /// Advances to `t_end` in equal internal steps no larger than `solver.max_step`, halving
    /// a step that fails (at most [`MAX_HALVINGS`] times, never below [`MIN_STEP`]), with at
    /// most `solver.max_internal_steps` internal steps, accepted or rejected, in the call. A
    /// span that needs more steps of `solver.max_step` is refused before any work. On failure
    /// the state is the one at the start of the call and the error says why and what to
    /// change.
    ///
    /// Inputs set since the last step (tip force, tip moment, gravity) are a discontinuity at the current
    /// time: the step starts from accelerations and multipliers consistent with them
    /// ([`GeneralizedAlpha::change_inputs`]), so a force held over a communication step is
    /// integrated as exactly that force. Constant inputs leave the integrator untouched.
    pub fn advance(&mut self, t_end: f64) -> Result<(), SimError> {
        let t0 = self.state.t;
        let span = t_end - t0;
        if span.is_nan() || span <= 0.0 || !span.is_finite() {
            return Err(SimError::BadTime { t0, t_end });
        }
        let h_max = self.scene.solver.max_step;
        let cap = self.scene.solver.max_internal_steps;
        let needed = (span / h_max * (1.0 - STEP_ROUNDING)).ceil();
        if needed > cap as f64 {
            return Err(SimError::WorkCap {
                t0,
                t_end,
                needed,
                h_max,
                cap,
            });
        }
        // start from the step that last worked; grow back after a few calm calls
        if self.step.h_ok < h_max && self.step.calm >= CALM_BEFORE_GROWTH {
            self.step = StepControl {
                h_ok: (2.0 * self.step.h_ok).min(h_max),
                calm: 0,
            };
        }
        let h_start = self.step.h_ok;
        let saved = self.state.clone();
        let saved_step = self.step;
        let saved_mount = self.mount.clone();
        let inputs = Inputs::of(&self.model);
        let mount_jump = match self.take_mount_input() {
            Ok(j) => j,
            Err(e) => {
                self.roll_back(saved, saved_step, saved_mount, &inputs);
                return Err(e);
            }
        };
        if inputs != self.applied || mount_jump.is_some() {
            self.applied.apply(&mut self.model);
            let changed = self
                .integ
                .change_inputs(&mut self.model, &mut self.state, |m| {
                    inputs.apply(m);
                    if let Some(j) = &mount_jump {
                        m.set_mount(j);
                    }
                })
                .map_err(|source| SimError::InputJump { t: t0, source });
            if let Err(e) = changed {
                self.roll_back(saved, saved_step, saved_mount, &inputs);
                return Err(e);
            }
        }
        // more steps of a reduced h_ok than the cap allows: start from span / cap (≤ h_max)
        let mut steps = ((span / h_start * (1.0 - STEP_ROUNDING)).ceil().max(1.0) as u64).min(cap);
        let mut done = 0u64;
        let mut attempts = 0u64;
        let mut halvings = 0;
        let varying = self.load_rates.any();
        while done < steps {
            let h = span / steps as f64;
            attempts += 1;
            let t_next = if done + 1 == steps {
                t_end
            } else {
                t0 + span * ((done + 1) as f64 / steps as f64)
            };
            if let Some(ms) = &self.mount {
                self.model.set_mount(&ms.at(t_next));
            }
            if varying {
                // the loads at the step's end, where its equations hold
                self.load_rates
                    .advanced(&inputs, t_next - t0)
                    .apply(&mut self.model);
            }
            match self.integ.step(&mut self.model, &mut self.state, h) {
                Ok(_) => {
                    done += 1;
                    self.min_step_used = self.min_step_used.min(h);
                    self.state.t = t0 + span * (done as f64 / steps as f64);
                }
                Err(e) => {
                    self.integ.counters.rejected += 1;
                    halvings += 1;
                    // a halving doubles the steps still to go
                    let limit = if halvings > MAX_HALVINGS {
                        Some(StepLimit::MaxHalvings)
                    } else if 0.5 * h < MIN_STEP {
                        Some(StepLimit::MinStep { h })
                    } else if attempts + 2 * (steps - done) > cap {
                        Some(StepLimit::WorkCap {
                            halvings: halvings - 1,
                            cap,
                        })
                    } else {
                        None
                    };
                    if let Some(limit) = limit {
                        self.roll_back(saved, saved_step, saved_mount, &inputs);
                        return Err(SimError::Step {
                            t: self.state.t,
                            halvings: halvings - 1,
                            limit,
                            source: e,
                        });
                    }
                    steps *= 2;
                    done *= 2;
                }
            }
        }
        self.state.t = t_end;
        let validity = self.model.validity(&self.state.q);
        let strain = validity.max_axial_strain;
        let finite = self
            .state
            .q
            .iter()
            .chain(&self.state.v)
            .all(|x| x.is_finite());
        let modal = validity
            .modal_deflection
            .filter(|&(_, d)| finite && d > MAX_MODAL_DEFLECTION);
        if let Some((si, d)) = modal {
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(SimError::Refused {
                t: t_end,
                refusal: Refusal::ModalDeflection {
                    segment: self.scene.segments[si].name.clone(),
                    value: d,
                },
            });
        }
        if let Some(refusal) = self.section_refusal(&validity, true).filter(|_| finite) {
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(SimError::Refused { t: t_end, refusal });
        }
        if !finite || strain > MAX_AXIAL_STRAIN {
            self.roll_back(saved, saved_step, saved_mount, &inputs);
            return Err(if finite {
                SimError::Refused {
                    t: t_end,
                    refusal: Refusal::AxialStrain { value: strain },
                }
            } else {
                SimError::NonFinite { t: t_end }
            });
        }
        self.applied = if varying {
            // the loads went on to their values at t_end, which stay set (the derivatives held
            // for this step)
            let end = self.load_rates.advanced(&inputs, span);
            self.load_rates = LoadRates::default();
            end
        } else {
            inputs
        };
        if halvings > 0 {
            self.step = StepControl {
                h_ok: span / steps as f64,
                calm: 0,
            };
        } else {
            self.step.calm = self.step.calm.saturating_add(1);
        }
        Ok(())
    }

    /// The refusal of a configuration whose ANCF section directors the elements cannot
    /// represent: a director (nearly) parallel to its slope ([`MIN_SECTION_SINE`]) and, with
    /// `twist`, more twist within one element than [`MAX_TWIST_PER_ELEMENT`].
    fn section_refusal(&self, v: &ModelValidity, twist: bool) -> Option<Refusal> {
        let name = |si: usize| self.scene.segments[si].name.clone();
        if let Some((si, value)) = v.min_section_sine.filter(|&(_, s)| s < MIN_SECTION_SINE) {
            return Some(Refusal::SectionDirector {
                segment: name(si),
                value,
            });
        }
        v.max_twist
            .filter(|&(_, w)| twist && w > MAX_TWIST_PER_ELEMENT)
            .map(|(si, value)| Refusal::Twist {
                segment: name(si),
                value,
            })
    }

    /// Solves the static equilibrium from the current state under the current loads.
    pub fn solve_static(&mut self) -> Result<usize, SimError> {
        let tol = self.scene.solver.static_tolerance();
        let it = solve_static(&mut self.model, &mut self.state, tol)?;
        self.integ.invalidate();
        Ok(it)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case1() -> Scene {
        Scene::from_toml(include_str!("../scenes/case1.toml")).unwrap()
    }

    /// Replaces every little-endian occurrence of `old` in `bytes` by `new`; returns how many.
    fn replace_f64(bytes: &mut [u8], old: f64, new: f64) -> usize {
        let mut n = 0;
        for i in 0..bytes.len().saturating_sub(7) {
            if bytes[i..i + 8] == old.to_le_bytes() {
                bytes[i..i + 8].copy_from_slice(&new.to_le_bytes());
                n += 1;
            }
        }
        n
    }

    #[test]
    fn snapshot_restores_bit_for_bit_with_its_inputs() {
        let mut a = Simulator::<Planar>::new(case1()).unwrap();
        a.advance(2e-3).unwrap();
        a.set_tip_force([0.3, -0.7]);
        a.set_gravity([0.5, -9.0]);
        a.set_tip_moment(0.01);
        let bytes = a.snapshot();
        let mut b = Simulator::<Planar>::restorable(case1()).unwrap();
        b.restore_snapshot(&bytes).unwrap();
        assert_eq!(
            (b.tip_force(), b.tip_moment(), b.gravity()),
            ([0.3, -0.7], 0.01, [0.5, -9.0])
        );
        a.advance(5e-3).unwrap();
        b.advance(5e-3).unwrap();
        let bits = |s: &State| -> Vec<u64> {
            let vs = [&s.q, &s.v, &s.acc, &s.aux, &s.lambda];
            vs.iter()
                .flat_map(|x| x.iter().map(|x| x.to_bits()))
                .collect()
        };
        assert_eq!(bits(a.state()), bits(b.state()));
        assert_eq!(a.time().to_bits(), b.time().to_bits());
    }

    /// A snapshot taken after steps under a tip moment (which adds stiffness to the held Newton
    /// matrix) restores bit for bit: the matrix is rebuilt under the inputs it was built with.
    #[test]
    fn snapshot_under_a_tip_moment_restores_bit_for_bit() {
        let mut a = Simulator::<Planar>::new(case1()).unwrap();
        a.set_tip_moment(0.01);
        a.advance(3e-3).unwrap();
        let bytes = a.snapshot();
        let mut b = Simulator::<Planar>::restorable(case1()).unwrap();
        b.restore_snapshot(&bytes).unwrap();
        for k in 4..=8 {
            a.advance(k as f64 * 1e-3).unwrap();
            b.advance(k as f64 * 1e-3).unwrap();
            assert_eq!(a.state(), b.state(), "t = {k} ms");
        }
    }

    #[test]
    fn snapshot_of_another_version_scene_or_shape_is_refused() {
        let mut a = Simulator::<Planar>::new(case1()).unwrap();
        a.advance(1e-3).unwrap();
        a.set_gravity([0.25, -9.5]);
        let bytes = a.snapshot();
        let mut b = Simulator::<Planar>::restorable(case1()).unwrap();
        let err = |b: &mut Simulator<Planar>, bytes: &[u8]| match b.restore_snapshot(bytes) {
            Err(SimError::Snapshot(e)) => e,
            other => panic!("{other:?}"),
        };
        let cut = &bytes[..bytes.len() - 3];
        assert!(matches!(err(&mut b, cut), SnapshotError::Malformed(_)));
        let mut long = bytes.clone();
        long.push(0);
        assert!(matches!(err(&mut b, &long), SnapshotError::Malformed(_)));
        let mut other = bytes.clone();
        other[0] = SNAPSHOT_VERSION as u8 + 1;
        let found = SNAPSHOT_VERSION + 1;
        let expected = SNAPSHOT_VERSION;
        assert_eq!(
            err(&mut b, &other),
            SnapshotError::Version { found, expected }
        );
        let mut nan = bytes.clone();
        assert_eq!(replace_f64(&mut nan, -9.5, f64::NAN), 1);
        match err(&mut b, &nan) {
            SnapshotError::NonFiniteField { field, value } => {
                assert_eq!(field, "inputs.gravity[1]");
                assert!(value.is_nan());
            }
            other => panic!("{other:?}"),
        }
        let mut scene = case1();
        scene.solver.tolerance *= 2.0;
        let mut c = Simulator::<Planar>::restorable(scene).unwrap();
        assert_eq!(err(&mut c, &bytes), SnapshotError::OtherModel);
        // gravity and tip force are carried, not bound: another gravity restores
        let mut scene = case1();
        scene.gravity = vec![1.0, 2.0];
        let mut d = Simulator::<Planar>::restorable(scene).unwrap();
        d.restore_snapshot(&bytes).unwrap();
        assert_eq!(d.gravity(), [0.25, -9.5]);
        // b is untouched by the refusals and restores the intact bytes
        b.restore_snapshot(&bytes).unwrap();
        assert_eq!(b.state(), a.state());
    }
}
