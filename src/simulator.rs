//! A beam in time: model + integrator + state behind `advance` and `outputs`, for either space
//! ([`Simulator<Planar>`], [`Simulator<Spatial>`]). The command-line runner and the FMU adapter
//! drive [`AnySimulator`], the planar|spatial choice made once from `scene.space`, and read and
//! write it through named scalars ([`OutputId`], [`InputId`]: `tip.position.x`,
//! `tip.orientation.e0`, `tip.force.z`, …).

mod any;
mod finite;
mod inputs;
pub mod limits;
mod mount;
mod names;
mod partner;
mod snapshot;
mod step;

pub use crate::model::output_names::{OutputId, Quantity};
pub use any::{AnyOutputs, AnySimulator, MountMatrix};
pub use inputs::{Inputs, LoadRates};
pub use limits::*;
pub use limits::{PARTNER_ITERATIONS, PARTNER_TOLERANCE};
pub use mount::{MountInput, MountState};
pub use names::{InputId, InputKind};
pub use partner::{Partner, PARTNER_COMPONENTS};
pub use snapshot::{Memory, SNAPSHOT_VERSION};
pub use step::StepControl;

use crate::error::{Refusal, SimError, SnapshotError, StepLimit};
use crate::integrator::{
    solve_static, Counters, Integrable, Integrator, IntegratorMemory, State, CALM_BEFORE_GROWTH,
    MAX_HALVINGS, MIN_STEP,
};
use crate::model::{Model, ModelValidity, Motion, Outputs, Space};
use crate::scene::{InitialState, Scene};
use serde::{Deserialize, Serialize};

/// A running simulation in the space `S`.
#[derive(Debug)]
pub struct Simulator<S: Space> {
    scene: Scene,
    model: Model<S>,
    integ: Integrator,
    state: State,
    step: StepControl,
    /// Inputs the state's q̈ and λ are consistent with (see [`Memory::applied`]): the ones
    /// the model holds.
    applied: Inputs<S>,
    /// Inputs set for the next step (a host's; the model takes them at the step's start).
    pending: Inputs<S>,
    /// The mount's motion (`root = "mounted"`; boxed: a fixed root carries no more than a
    /// pointer).
    mount: Option<Box<MountState<S>>>,
    /// The tip loads' derivatives over the next step (zero: held).
    load_rates: LoadRates<S>,
    /// Smallest internal step used so far [s].
    pub min_step_used: f64,
    /// Where a communication step keeps the state and mount it returns to on failure (kept
    /// between steps: saving copies into it, no allocation in the step).
    backup: (State, Option<Box<MountState<S>>>),
    /// Working states of a communication step, kept between steps (copied into: no allocation
    /// in the step): the apparent mass's column ([`Simulator::apparent_mass`]) and the partner
    /// model's internal step start ([`Simulator::step_with_partner`]), and the apparent mass's
    /// solves' working memory.
    work: (State, State, crate::integrator::JumpWork),
}

impl<S: Space> Simulator<S> {
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
        let mut model = crate::model::build::<S>(&scene)?;
        let n = model.coordinates();
        let m = model.constraints();
        let mut state = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
        let mut integ = Integrator::new(&scene.solver, n, m);
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
        let mount = mount.map(Box::new);
        Ok(Self {
            scene,
            model,
            integ,
            backup: (state.clone(), mount.clone()),
            work: (
                state.clone(),
                state.clone(),
                crate::integrator::JumpWork::sized(n, m),
            ),
            state,
            step,
            applied,
            pending: applied,
            mount,
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

    /// Outputs of the current state.
    pub fn outputs(&self) -> Outputs<S> {
        let s = &self.state;
        self.model.outputs(&s.q, &s.v, &s.acc, &s.lambda)
    }

    /// The beam's shape at the current state, `per_element` intervals per element
    /// ([`crate::model::Shape`], for viewers).
    pub fn shape(&self, per_element: usize) -> crate::model::Shape {
        let s = &self.state;
        self.model.shape((&s.q, &s.v, &s.acc), per_element)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Planar;

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
        scene.solver.tolerance = Some(2.0 * scene.solver.newton_tolerance());
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
