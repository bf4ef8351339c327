//! Time integration and statics. The integrators know the model only through [`Integrable`]
//! (Chrono's `ChIntegrableIIorder` seam): residual and Newton matrix at a state, LU solve, and
//! the coordinate update. Nothing here imports the model.

mod generalized_alpha;
mod parameters;
mod seam;
mod statics;

pub use generalized_alpha::{
    AlphaParams, GeneralizedAlpha, IntegratorMemory, JacobianPoint, StepFailure,
};
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
