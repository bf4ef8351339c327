//! Snapshots: the state and the memory beyond it ([`Memory`]) as bytes of a versioned format
//! bound to the scene, and their restore, checked completely (every value finite, every
//! length the model's, the mount path's orientations usable) before anything is changed.

use super::step::STEP_ROUNDING;
use super::*;
use crate::scene::Mount;
use std::hash::Hasher;

/// Everything beyond the state that a snapshot must carry for a bit-identical restart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound = "")]
pub struct Memory<S: Space> {
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
pub(super) const ATTITUDE_TOLERANCE: f64 = 1e-9;

/// Format version of [`Simulator::snapshot`]; raise it when a field of [`Snapshot`] (or of the
/// structs it holds) changes.
pub const SNAPSHOT_VERSION: u32 = 7;

/// The payload of [`Simulator::snapshot`], encoded with `postcard` (f64 as 8 little-endian
/// bytes, so restored values are bit-identical).
#[derive(Serialize, Deserialize)]
#[serde(bound = "")]
struct Snapshot<S: Space> {
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

/// FNV-1a 64 of the canonical TOML of `scene` without its inputs (tip force, tip moment,
/// gravity and the mount's start motion, which a snapshot carries, as inputs and as the mount's
/// path, and a host may change; the model does not depend on them): what binds a snapshot to
/// its model. The Newton tolerance in use is written out: a scene that leaves
/// `solver.tolerance` to its default or to `solver.error_tolerance` steps as one that gives the
/// same value.
pub(super) fn scene_key(scene: &Scene) -> u64 {
    let mut scene = scene.clone();
    scene.solver.tolerance = Some(scene.solver.newton_tolerance());
    scene.tip.force.clear();
    scene.tip.moment.clear();
    scene.gravity.clear();
    if let Some(m) = &mut scene.mount {
        let kept = m.motion_input;
        *m = Mount {
            motion_input: kept,
            ..Mount::default()
        };
    }
    let mut h = fnv::FnvHasher::default();
    h.write(scene.to_toml().as_bytes());
    h.finish()
}

impl<S: Space> Simulator<S> {
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
    pub(super) fn restore(&mut self, s: State, mem: &Memory<S>) -> Result<(), SimError> {
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
        let mut attitudes = Vec::new();
        if let Some(m) = &mem.mount {
            attitudes.push(("memory.mount.base", &m.base.attitude));
            if let Some((_, last)) = &m.last {
                attitudes.push(("memory.mount.last", &last.attitude));
            }
        }
        if let Some(m) = &mem.mount_at_matrix {
            attitudes.push(("memory.mount_at_matrix", &m.attitude));
        }
        for (field, a) in attitudes {
            if !unit(a) {
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
        mem.applied.apply(&mut self.model);
        let current_mount = self.model.mount_motion().copied();
        if let Some(m) = &mem.mount_at_matrix {
            self.model.set_mount(m);
        }
        if let Err(e) = self.integ.restore_memory(&mut self.model, &mem.integrator) {
            self.applied.apply(&mut self.model);
            if let Some(m) = &current_mount {
                self.model.set_mount(m);
            }
            return Err(SnapshotError::NewtonMatrix(e).into());
        }
        if let Some(ms) = &mem.mount {
            self.model.set_mount(&ms.held(s.t));
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
            inputs: self.pending,
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
        self.pending = snap.inputs;
        Ok(())
    }
}
