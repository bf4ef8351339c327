//! A beam in time: model + integrator + state behind `advance` and `outputs`.
//! This is what the command-line runner and the FMU adapter drive.

use crate::integrator::{solve_static, Counters, GeneralizedAlpha, IntegratorMemory, State};
use crate::model::{Model, Outputs};
use crate::scene::{InitialState, Scene};

/// Largest number of halvings of the internal step before a communication step fails.
pub const MAX_HALVINGS: u32 = 12;

/// Largest axial strain accepted: beyond it the linear elastic law of the model has no meaning
/// for a metal rod, and the step is refused rather than returning a number.
pub const MAX_AXIAL_STRAIN: f64 = 0.05;

/// A running simulation.
#[derive(Debug)]
pub struct Simulator {
    scene: Scene,
    model: Model,
    integ: GeneralizedAlpha,
    state: State,
    /// Smallest internal step used so far [s].
    pub min_step_used: f64,
}

impl Simulator {
    /// Builds the model and its initial state (straight, or static equilibrium) at t = 0, with
    /// consistent accelerations.
    pub fn new(scene: Scene) -> Result<Self, String> {
        Self::build(scene, true)
    }

    /// Builds the model without computing an initial state (the caller restores a snapshot).
    pub fn for_restore(scene: Scene) -> Result<Self, String> {
        Self::build(scene, false)
    }

    fn build(scene: Scene, initialize: bool) -> Result<Self, String> {
        let mut model = Model::from_scene(&scene).map_err(|e| e.0)?;
        let n = model.coordinates();
        let m = model.constraints();
        let mut state = State::at_rest(0.0, model.initial_coordinates().to_vec(), m);
        let mut integ = GeneralizedAlpha::new(
            scene.solver.rho_inf,
            scene.solver.tolerance,
            scene.solver.max_iterations,
            n,
            m,
        );
        if initialize && scene.initial.state == InitialState::Static {
            solve_static(&mut model, &mut state, scene.solver.tolerance * 1e-2)
                .map_err(|e| format!("initial.state = \"static\": {e}; try initial.state = \"straight\" or smaller loads"))?;
        }
        if initialize {
            integ
                .initialize(&mut model, &mut state)
                .map_err(|e| format!("initial accelerations: {e}"))?;
        }
        Ok(Self {
            scene,
            model,
            integ,
            state,
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

    /// The integrator memory a snapshot must carry besides the state.
    pub fn memory(&self) -> IntegratorMemory {
        self.integ.memory()
    }

    /// Restores a snapshot (state and integrator memory) taken from a simulator of the same
    /// scene; the run then continues bit for bit as the original.
    pub fn restore(&mut self, s: State, mem: &IntegratorMemory) -> Result<(), String> {
        if s.q.len() != self.state.q.len()
            || s.lambda.len() != self.state.lambda.len()
            || [&s.v, &s.acc, &s.aux].iter().any(|x| x.len() != s.q.len())
        {
            return Err("state dimensions do not match this model".into());
        }
        self.integ
            .restore_memory(&mut self.model, mem)
            .map_err(|e| format!("cannot rebuild the Newton matrix of the snapshot: {e}"))?;
        self.state = s;
        Ok(())
    }

    /// Sets gravity [m/s²] (takes effect at the next step).
    pub fn set_gravity(&mut self, g: [f64; 2]) {
        self.model.set_gravity(g);
    }

    /// Work counters.
    pub fn counters(&self) -> Counters {
        self.integ.counters
    }

    /// Input tip force on top of the scene's constant force [N], global axes.
    pub fn set_tip_force(&mut self, f: [f64; 2]) {
        self.model.tip_force = f;
    }

    /// Current input tip force [N].
    pub fn tip_force(&self) -> [f64; 2] {
        self.model.tip_force
    }

    /// Outputs of the current state.
    pub fn outputs(&self) -> Outputs {
        let s = &self.state;
        self.model.outputs(&s.q, &s.v, &s.acc, &s.lambda)
    }

    /// Advances to `t_end` in equal internal steps no larger than `solver.max_step`, halving
    /// a step that fails (at most [`MAX_HALVINGS`] times). On failure the state is the one at
    /// the start of the call and the error says why and what to change.
    pub fn advance(&mut self, t_end: f64) -> Result<(), String> {
        let t0 = self.state.t;
        let span = t_end - t0;
        if span.is_nan() || span <= 0.0 || !span.is_finite() {
            return Err(format!("cannot advance from t = {t0} to t = {t_end}"));
        }
        let h_max = self.scene.solver.max_step;
        let saved = self.state.clone();
        let mut steps = (span / h_max * (1.0 - 1e-12)).ceil().max(1.0) as u64;
        let mut done = 0u64;
        let mut halvings = 0;
        while done < steps {
            let h = span / steps as f64;
            match self.integ.step(&mut self.model, &mut self.state, h) {
                Ok(_) => {
                    done += 1;
                    self.min_step_used = self.min_step_used.min(h);
                    self.state.t = t0 + span * (done as f64 / steps as f64);
                }
                Err(e) => {
                    self.integ.counters.rejected += 1;
                    halvings += 1;
                    if halvings > MAX_HALVINGS {
                        self.state = saved;
                        self.integ.invalidate();
                        return Err(format!(
                            "step from t = {:.6} s failed after {MAX_HALVINGS} halvings of the internal step: {e}. \
                             Reduce the communication step or solver.max_step, add damping, lower solver.rho_inf, or reduce the loads",
                            self.state.t
                        ));
                    }
                    steps *= 2;
                    done *= 2;
                }
            }
        }
        self.state.t = t_end;
        let strain = self.model.max_axial_strain(&self.state.q);
        let finite = self
            .state
            .q
            .iter()
            .chain(&self.state.v)
            .all(|x| x.is_finite());
        if !finite || strain > MAX_AXIAL_STRAIN {
            self.state = saved;
            self.integ.invalidate();
            return Err(if finite {
                format!(
                    "step to t = {t_end:.6} s refused: axial strain {:.1} % exceeds the {:.0} % validity limit of the linear elastic rod; the loads (tip force or gravity) are too large for this beam",
                    100.0 * strain,
                    100.0 * MAX_AXIAL_STRAIN
                )
            } else {
                format!("step to t = {t_end:.6} s produced non-finite coordinates; reduce the communication step or solver.max_step")
            });
        }
        Ok(())
    }

    /// Solves the static equilibrium from the current state under the current loads.
    pub fn solve_static(&mut self) -> Result<usize, String> {
        let tol = self.scene.solver.tolerance * 1e-2;
        let it = solve_static(&mut self.model, &mut self.state, tol).map_err(|e| e.to_string())?;
        self.integ.invalidate();
        Ok(it)
    }
}
