//! Time integration and statics. The integrators know the model only through [`Integrable`]
//! (Chrono's `ChIntegrableIIorder` seam): residual and Newton matrix at a state, LU solve, and
//! the coordinate update. Nothing here imports the model.

mod consistent;
pub mod control;
mod esdirk;
mod generalized_alpha;
mod newton;
mod parameters;
mod seam;
mod statics;

pub use consistent::{input_jumps, JumpWork};
pub use esdirk::{Esdirk, Tableau, ESDIRK4};
pub use generalized_alpha::{AlphaParams, GeneralizedAlpha};
pub use newton::{IntegratorMemory, JacobianPoint, StepFailure};
pub use parameters::*;
pub use seam::{constraint_rows, EvalRequest, Integrable, StateRef};
pub use statics::{solve_relative_static, solve_static, StaticFailure};

/// Dynamic state of the model.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Time [s].
    pub t: f64,
    /// Coordinates q (mixed units: positions and modal amplitudes [m], slopes [-], angles
    /// [rad]; see [`Integrable::scales`]).
    pub q: Vec<f64>,
    /// Velocities q̇.
    pub v: Vec<f64>,
    /// Accelerations q̈.
    pub acc: Vec<f64>,
    /// Generalized-α pseudo-accelerations (integrator memory).
    pub aux: Vec<f64>,
    /// Joint multipliers λ (unscaled) [N, N m].
    pub lambda: Vec<f64>,
}

impl State {
    /// Copies `other` into this state, reusing its vectors' memory (no allocation when the
    /// sizes match).
    pub fn copy_from(&mut self, other: &State) {
        self.t = other.t;
        self.q.clone_from(&other.q);
        self.v.clone_from(&other.v);
        self.acc.clone_from(&other.acc);
        self.aux.clone_from(&other.aux);
        self.lambda.clone_from(&other.lambda);
    }

    /// At rest at coordinates `q`, with `m` multipliers.
    pub fn at_rest(t: f64, q: Vec<f64>, m: usize) -> Self {
        let n = q.len();
        Self {
            t,
            q,
            v: vec![0.0; n],
            acc: vec![0.0; n],
            aux: vec![0.0; n],
            lambda: vec![0.0; m],
        }
    }
}

/// `$body` with `$i` bound to the integrator of either method (the [`Integrator`] forwarders).
macro_rules! each {
    ($any:expr, $i:ident => $body:expr) => {
        match $any {
            Integrator::Alpha($i) => $body,
            Integrator::Esdirk($i) => $body,
        }
    };
}

/// The integrator a scene asks for ([`Method`]), behind one interface.
#[derive(Debug, Clone)]
pub enum Integrator {
    /// Generalized-α.
    Alpha(GeneralizedAlpha),
    /// The order-4 ESDIRK.
    Esdirk(Esdirk),
}

impl Integrator {
    /// The integrator of `params.method` for `n` coordinates and `m` constraints.
    pub fn new(params: &IntegrationParameters, n: usize, m: usize) -> Self {
        match params.method {
            Method::GeneralizedAlpha => Self::Alpha(GeneralizedAlpha::new(params, n, m)),
            Method::Esdirk4 => Self::Esdirk(Esdirk::new(params, &ESDIRK4, n, m)),
        }
    }

    /// Work counters.
    pub fn counters(&self) -> &Counters {
        each!(self, i => i.counters())
    }

    /// Work counters, to count rejections.
    pub fn counters_mut(&mut self) -> &mut Counters {
        each!(self, i => i.counters_mut())
    }

    /// Forgets the held Jacobian.
    pub fn invalidate(&mut self) {
        each!(self, i => i.invalidate())
    }

    /// The memory a snapshot must carry.
    pub fn memory(&self) -> IntegratorMemory {
        each!(self, i => i.memory())
    }

    /// The Newton convergence-rate estimate the next step starts from.
    pub fn rate_estimate(&self) -> f64 {
        each!(self, i => i.eta)
    }

    /// The last step's local error estimate in units of `solver.error_tolerance` (`None`
    /// without error control: generalized-α, or the ESDIRK without `error_tolerance`).
    pub fn step_error(&self) -> Option<f64> {
        match self {
            Self::Alpha(_) => None,
            Self::Esdirk(k) => k.step_error(),
        }
    }

    /// Sets [`Integrator::rate_estimate`]: a step repeated from the same state then stops its
    /// Newton iteration by the same rule as the first attempt.
    pub fn set_rate_estimate(&mut self, eta: f64) {
        each!(self, i => i.eta = eta)
    }

    /// Restores memory (the held Newton matrix rebuilt where it was evaluated).
    pub fn restore_memory<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        mem: &IntegratorMemory,
    ) -> Result<(), StepFailure> {
        each!(self, i => i.restore_memory(model, mem))
    }

    /// Consistent initial accelerations and multipliers ([`GeneralizedAlpha::initialize`]).
    pub fn initialize<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
    ) -> Result<(), StepFailure> {
        each!(self, i => i.initialize(model, s))
    }

    /// A jump of the inputs at t_n ([`GeneralizedAlpha::change_inputs`]; for the ESDIRK, a
    /// one-step method, only q̈ and λ at t_n follow, the next step's first guess).
    pub fn change_inputs<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        change: impl FnOnce(&mut M),
    ) -> Result<(), StepFailure> {
        each!(self, i => i.change_inputs(model, s, change))
    }

    /// One step of size `h` from `s`; `at(model, dt)` sets the model's time-dependent inputs
    /// at t_n + dt: once at dt = h for generalized-α, before each implicit stage for the ESDIRK (the last
    /// at dt = h). On failure `s` is untouched; with error control a step whose estimate is
    /// above the tolerance fails ([`StepFailure::ErrorEstimate`]).
    pub fn step<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        h: f64,
        mut at: impl FnMut(&mut M, f64),
    ) -> Result<usize, StepFailure> {
        match self {
            Self::Alpha(g) => {
                at(model, h);
                g.step(model, s, h)
            }
            Self::Esdirk(k) => k.step(model, s, h, at),
        }
    }
}

/// Counters of integrator work.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts.
    pub rejected: u64,
    /// Newton iterations (accepted and rejected attempts).
    pub iterations: u64,
    /// Numeric factorizations.
    pub factorizations: u64,
}

/// Scaled max-norm of a coordinate increment: max |Δq_i| / scale_i.
pub(crate) fn scaled_norm(dq: &[f64], scale: &[f64]) -> f64 {
    dq.iter()
        .zip(scale)
        .map(|(d, s)| (d / s).abs())
        .fold(0.0, f64::max)
}
