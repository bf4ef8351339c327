//! A beam in time: model + integrator + state behind `advance` and `outputs`.
//! This is what the command-line runner and the FMU adapter drive.

use crate::error::{Refusal, SimError, SnapshotError, StepLimit};
use crate::integrator::{
    solve_static, Counters, GeneralizedAlpha, Integrable, IntegratorMemory, State,
    CALM_BEFORE_GROWTH, MAX_HALVINGS, MIN_STEP,
};
use crate::model::{Model, Outputs};
use crate::scene::{InitialState, Scene};

/// Largest elastic deflection of a modal segment accepted, as tip deflection over length or tip
/// slope [rad]: a linear floating frame is a small-deformation model.
pub const MAX_MODAL_DEFLECTION: f64 = 0.3;

/// Largest axial strain accepted: beyond it the linear elastic law of the model has no meaning
/// for a metal rod, and the step is refused rather than returning a number.
pub const MAX_AXIAL_STRAIN: f64 = 0.05;

/// Internal step control carried from one communication step to the next.
#[derive(Debug, Clone, Copy, PartialEq)]
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

/// The inputs of the equations a host may change between communication steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs {
    /// Total tip force [N], global axes.
    pub tip_force: [f64; 2],
    /// Gravity [m/s²], global axes.
    pub gravity: [f64; 2],
}

impl Inputs {
    fn of(model: &Model) -> Self {
        Self {
            tip_force: model.tip_force(),
            gravity: model.gravity(),
        }
    }

    fn apply(&self, model: &mut Model) {
        model.set_tip_force(self.tip_force);
        if model.gravity() != self.gravity {
            model.set_gravity(self.gravity);
        }
    }
}

/// Everything beyond the state that a snapshot must carry for a bit-identical restart.
#[derive(Debug, Clone, PartialEq)]
pub struct Memory {
    /// Integrator memory.
    pub integrator: IntegratorMemory,
    /// Step control.
    pub step: StepControl,
    /// The inputs the state's accelerations and multipliers are consistent with (those of the
    /// last step); the next [`Simulator::advance`] treats a difference from the current
    /// inputs as a jump at the current time.
    pub applied: Inputs,
}

/// A running simulation.
#[derive(Debug)]
pub struct Simulator {
    scene: Scene,
    model: Model,
    integ: GeneralizedAlpha,
    state: State,
    step: StepControl,
    /// Inputs the state's q̈ and λ are consistent with (see [`Memory::applied`]).
    applied: Inputs,
    /// Smallest internal step used so far [s].
    pub min_step_used: f64,
}

impl Simulator {
    /// Builds the model and its initial state (straight, or static equilibrium) at t = 0, with
    /// consistent accelerations.
    pub fn new(scene: Scene) -> Result<Self, SimError> {
        Self::new_at(scene, 0.0)
    }

    /// As [`Simulator::new`], with the clock starting at `t0` [s] (e.g. an FMU's start time).
    pub fn new_at(scene: Scene, t0: f64) -> Result<Self, SimError> {
        let mut sim = Self::build(scene, true)?;
        sim.state.t = t0;
        Ok(sim)
    }

    /// Builds the model without computing an initial state (the caller restores a snapshot).
    pub fn for_restore(scene: Scene) -> Result<Self, SimError> {
        Self::build(scene, false)
    }

    fn build(scene: Scene, initialize: bool) -> Result<Self, SimError> {
        let mut model = Model::from_scene(&scene)?;
        let n = model.coordinates();
        let m = model.constraints();
        let mut state = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
        let mut integ = GeneralizedAlpha::new(&scene.solver, n, m);
        if initialize && scene.initial.state == InitialState::Static {
            solve_static(&mut model, &mut state, scene.solver.static_tolerance())
                .map_err(SimError::InitialStatic)?;
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
            min_step_used: f64::INFINITY,
        })
    }

    /// The scene this simulator was built from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The model.
    pub fn model(&self) -> &Model {
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
    pub fn memory(&self) -> Memory {
        Memory {
            integrator: self.integ.memory(),
            step: self.step,
            applied: self.applied,
        }
    }

    /// Restores a snapshot (state and integrator memory) taken from a simulator of the same
    /// scene; the run then continues bit for bit as the original.
    pub fn restore(&mut self, s: State, mem: &Memory) -> Result<(), SimError> {
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
        }
        let finite = |x: &[f64]| x.iter().all(|x| x.is_finite());
        if !(s.t.is_finite()
            && [&s.q, &s.v, &s.acc, &s.aux, &s.lambda]
                .iter()
                .all(|x| finite(x)))
        {
            return Err(SnapshotError::NonFinite.into());
        }
        self.integ
            .restore_memory(&mut self.model, &mem.integrator)
            .map_err(SnapshotError::NewtonMatrix)?;
        self.state = s;
        self.step = mem.step;
        self.applied = mem.applied;
        Ok(())
    }

    /// Sets gravity [m/s²] (takes effect at the next step, as a jump of the inputs).
    pub fn set_gravity(&mut self, g: [f64; 2]) {
        self.model.set_gravity(g);
    }

    /// Work counters.
    pub fn counters(&self) -> Counters {
        self.integ.counters
    }

    /// Sets the total tip force [N], global axes (replaces the scene's; takes effect at the
    /// next step, as a jump of the inputs at the current time: see [`Simulator::advance`]).
    pub fn set_tip_force(&mut self, f: [f64; 2]) {
        self.model.set_tip_force(f);
    }

    /// The total tip force the model applies [N], global axes.
    pub fn tip_force(&self) -> [f64; 2] {
        self.model.tip_force()
    }

    /// Gravity [m/s²], global axes.
    pub fn gravity(&self) -> [f64; 2] {
        self.model.gravity()
    }

    /// Outputs of the current state.
    pub fn outputs(&self) -> Outputs {
        let s = &self.state;
        self.model.outputs(&s.q, &s.v, &s.acc, &s.lambda)
    }

    /// Advances to `t_end` in equal internal steps no larger than `solver.max_step`, halving
    /// a step that fails (at most [`MAX_HALVINGS`] times, never below [`MIN_STEP`]), with at
    /// most `solver.max_internal_steps` internal steps, accepted or rejected, in the call. A
    /// span that needs more steps of `solver.max_step` is refused before any work. On failure
    /// the state is the one at the start of the call and the error says why and what to
    /// change.
    ///
    /// Inputs set since the last step (tip force, gravity) are a discontinuity at the current
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
        let inputs = Inputs::of(&self.model);
        if inputs != self.applied {
            self.applied.apply(&mut self.model);
            self.integ
                .change_inputs(&mut self.model, &mut self.state, |m| inputs.apply(m))
                .map_err(|source| SimError::InputJump { t: t0, source })?;
        }
        // more steps of a reduced h_ok than the cap allows: start from span / cap (≤ h_max)
        let mut steps = ((span / h_start * (1.0 - STEP_ROUNDING)).ceil().max(1.0) as u64).min(cap);
        let mut done = 0u64;
        let mut attempts = 0u64;
        let mut halvings = 0;
        while done < steps {
            let h = span / steps as f64;
            attempts += 1;
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
                        self.state = saved;
                        self.step = saved_step;
                        self.integ.invalidate();
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
            self.state = saved;
            self.step = saved_step;
            self.integ.invalidate();
            return Err(SimError::Refused {
                t: t_end,
                refusal: Refusal::ModalDeflection {
                    segment: self.scene.segments[si].name.clone(),
                    value: d,
                },
            });
        }
        if !finite || strain > MAX_AXIAL_STRAIN {
            self.state = saved;
            self.step = saved_step;
            self.integ.invalidate();
            return Err(if finite {
                SimError::Refused {
                    t: t_end,
                    refusal: Refusal::AxialStrain { value: strain },
                }
            } else {
                SimError::NonFinite { t: t_end }
            });
        }
        self.applied = inputs;
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

    /// Solves the static equilibrium from the current state under the current loads.
    pub fn solve_static(&mut self) -> Result<usize, SimError> {
        let tol = self.scene.solver.static_tolerance();
        let it = solve_static(&mut self.model, &mut self.state, tol)?;
        self.integ.invalidate();
        Ok(it)
    }
}
