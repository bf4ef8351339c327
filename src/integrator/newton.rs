//! The modified-Newton loop both integrators share: one implicit solve for the coordinates of
//! a trial state, with the Newton matrix held across iterations, stages and steps while it
//! contracts well (refreshed at the current iterate otherwise).

use super::consistent::{change_inputs, initialize, Work};
use super::{scaled_norm, Counters, EvalRequest, Integrable, State, StateRef, REFRESH_RATE};

/// Why a step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum StepFailure {
    /// Real-time mode: the last of the fixed iterations left an increment above the bound.
    FixedWorkUnconverged {
        /// Step size [s].
        h: f64,
        /// The iterations done.
        iterations: usize,
        /// The last scaled increment norm (1 = tolerance).
        last_norm: f64,
        /// `solver.realtime_bound`.
        bound: f64,
    },
    /// Newton did not converge within the iteration limit.
    NoConvergence {
        /// Step size tried [s].
        h: f64,
        /// Last scaled increment norm (1 = tolerance).
        last_norm: f64,
    },
    /// The Newton matrix is singular or produced non-finite values.
    Singular {
        /// Step size tried [s].
        h: f64,
    },
    /// Error control (`solver.error_tolerance`): the step's local error estimate is above the
    /// tolerance (the step is rejected and retried with a smaller one).
    ErrorEstimate {
        /// Step size tried [s].
        h: f64,
        /// The estimate in units of `solver.error_tolerance`.
        error: f64,
    },
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepFailure::NoConvergence { h, last_norm } => write!(
                f,
                "Newton did not converge at step {h:.3e} s (last increment {last_norm:.2e} x tolerance)"
            ),
            StepFailure::FixedWorkUnconverged {
                h,
                iterations,
                last_norm,
                bound,
            } => write!(
                f,
                "real-time step {h:.3e} s: the last of {iterations} Newton iterations moved {last_norm:.2e} x tolerance, above solver.realtime_bound = {bound:.2e} (raise solver.realtime_iterations, refresh the matrix more often with a smaller solver.realtime_refresh, or use a smaller solver.max_step)"
            ),
            StepFailure::Singular { h } => {
                write!(f, "singular or non-finite Newton matrix at step {h:.3e} s")
            }
            StepFailure::ErrorEstimate { h, error } => write!(
                f,
                "the local error estimate at step {h:.3e} s is {error:.2e} x solver.error_tolerance (raise solver.error_tolerance)"
            ),
        }
    }
}

impl std::error::Error for StepFailure {}

/// The state and step size at which the held Newton matrix was evaluated.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JacobianPoint {
    /// Step size [s].
    pub h: f64,
    /// Coordinates, velocities, accelerations and scaled multipliers of the evaluation.
    pub q: Vec<f64>,
    /// q̇.
    pub v: Vec<f64>,
    /// q̈.
    pub acc: Vec<f64>,
    /// λ̃ = βh²λ.
    pub lam: Vec<f64>,
}

/// Integrator memory beyond the state: what a snapshot must carry for a bit-identical restart.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IntegratorMemory {
    /// Convergence-rate estimate.
    pub eta: f64,
    /// Jacobian evaluation point, if a factorization is held.
    pub jacobian: Option<JacobianPoint>,
}

/// The held Newton matrix, its evaluation point and the residual work array.
#[derive(Debug, Clone)]
pub(super) struct Newton {
    /// Relative tolerance on scaled increments.
    pub(super) tol: f64,
    /// Iteration limit per solve.
    pub(super) max_iter: usize,
    /// Step size of the held factorization (None = must refactor).
    pub(super) factored_h: Option<f64>,
    /// Where the held Jacobian was evaluated (for a snapshot's bit-identical restart).
    pub(super) jac_at: Option<JacobianPoint>,
    /// Residual and increment (n + m).
    pub(super) res: Vec<f64>,
    /// Work counters.
    pub(super) counters: Counters,
    /// Real-time mode: the fixed work of a solve (`None`: iterate to the tolerance).
    pub(super) fixed: Option<super::FixedWork>,
    /// Real-time mode: solves since the matrix was last refreshed.
    pub(super) solves_since_refresh: u32,
    /// The consistent accelerations' working memory (sized at the first use).
    work: Work,
}

/// How an increment Δq of the coordinates moves the trial's other unknowns: q̇ += dv·Δq,
/// q̈ += da·Δq and, with `aux_div`, the algorithmic acceleration += Δq / aux_div.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rates {
    pub(super) dv: f64,
    pub(super) da: f64,
    pub(super) aux_div: Option<f64>,
}

impl Newton {
    pub(super) fn new(tol: f64, max_iter: usize, rows: usize) -> Self {
        Self {
            tol,
            max_iter,
            factored_h: None,
            jac_at: None,
            res: vec![0.0; rows],
            counters: Counters::default(),
            fixed: None,
            solves_since_refresh: 0,
            work: Work::default(),
        }
    }

    /// With the real-time mode's fixed work (`None`: the normal mode).
    pub(super) fn with_fixed(mut self, fixed: Option<super::FixedWork>) -> Self {
        self.fixed = fixed;
        self
    }

    /// Forgets the held matrix (the storage of its evaluation point is kept, to be refilled
    /// without allocating; [`Newton::memory`] reads it only with a held matrix).
    pub(super) fn invalidate(&mut self) {
        self.factored_h = None;
    }

    /// The memory a snapshot must carry: `eta` and the held matrix's evaluation point.
    pub(super) fn memory(&self, eta: f64) -> IntegratorMemory {
        IntegratorMemory {
            eta,
            jacobian: self.factored_h.and(self.jac_at.clone()),
        }
    }

    /// Rebuilds the held matrix of `mem` (evaluated with `request(true)` at its step size),
    /// so that the next steps are bit-identical to those of the original run.
    pub(super) fn restore<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        mem: &IntegratorMemory,
        request: impl Fn(f64) -> EvalRequest,
    ) -> Result<(), StepFailure> {
        self.invalidate();
        if let Some(jp) = &mem.jacobian {
            let (n, m) = (model.coordinates(), model.constraints());
            if [&jp.q, &jp.v, &jp.acc].iter().any(|x| x.len() != n) || jp.lam.len() != m {
                return Err(StepFailure::Singular { h: jp.h });
            }
            let h = jp.h;
            let x = StateRef::new(&jp.q, &jp.v, &jp.acc, &jp.lam);
            model.eval(x, request(h), &mut self.res);
            model.factorize().map_err(|_| StepFailure::Singular { h })?;
            self.factored_h = Some(h);
            match &mut self.jac_at {
                Some(held) => {
                    // field by field (a derived clone_from would allocate anew)
                    held.h = jp.h;
                    held.q.clone_from(&jp.q);
                    held.v.clone_from(&jp.v);
                    held.acc.clone_from(&jp.acc);
                    held.lam.clone_from(&jp.lam);
                }
                None => self.jac_at = Some(jp.clone()),
            }
        }
        Ok(())
    }

    /// Consistent accelerations and multipliers at `s` (its algorithmic acceleration = q̈),
    /// in the model's matrix storage: the held matrix is dropped.
    pub(super) fn consistent<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
    ) -> Result<(), StepFailure> {
        self.invalidate();
        initialize(model, s, &mut self.res, &mut self.counters, &mut self.work)
    }

    /// The jump of q̈ and λ when `change` alters the inputs at t_n
    /// ([`super::GeneralizedAlpha::change_inputs`]); the held matrix is dropped.
    pub(super) fn jump<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        change: impl FnOnce(&mut M),
    ) -> Result<(), StepFailure> {
        self.invalidate();
        change_inputs(
            model,
            s,
            &mut self.res,
            &mut self.counters,
            &mut self.work,
            change,
        )
    }

    /// Iterates on `t` (its coordinates, rates, accelerations and scaled multipliers) at step
    /// size `h` until the estimated remaining error η‖Δq‖ is within tolerance; `request(m)`
    /// is the evaluation request, with the Newton matrix if `m`. `eta` is the contraction
    /// estimate to start from; returns the iterations and the estimate for the next solve (the
    /// last measured rate, not below `eta` if the matrix was refreshed here: see
    /// docs/engine-findings.md, the damped Case 3). On failure the held matrix is dropped (`t`
    /// is then a failed iterate).
    pub(super) fn iterate<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        t: &mut State,
        h: f64,
        request: impl Fn(bool) -> EvalRequest,
        rates: Rates,
        mut eta: f64,
    ) -> Result<(usize, f64), StepFailure> {
        if let Some(fixed) = self.fixed {
            return self.iterate_fixed(model, t, h, request, rates, fixed, eta);
        }
        let eta_start = eta;
        let mut fresh = false;
        let mut last = f64::INFINITY;
        for it in 0..self.max_iter {
            // the held matrix steers modified Newton only: a step size that differs in its last
            // bits (t_end − t0 of consecutive communication steps) does not call for a new one
            let refresh = !self.holds(h);
            model.eval(
                StateRef::new(&t.q, &t.v, &t.acc, &t.lambda),
                request(refresh),
                &mut self.res,
            );
            self.counters.iterations += 1;
            if refresh {
                self.factorize_at(model, t, h)?;
                fresh = true;
            }
            let norm = self.apply_increment(model, t, h, rates)?;
            if it > 0 {
                let rate = norm / last;
                eta = if rate < 1.0 {
                    rate / (1.0 - rate)
                } else {
                    f64::INFINITY
                };
            }
            // converged when the estimated remaining error η‖Δq‖ is within tolerance
            if eta * norm <= 1.0 || norm <= 1e-3 {
                // a matrix refreshed in this solve converges quadratically: its rate says
                // nothing of the held matrix the next solves iterate with, so the estimate
                // handed on is not below the one this solve started from
                let handed = if fresh { eta.max(eta_start) } else { eta };
                return Ok((it + 1, handed));
            }
            let rate = norm / last;
            last = norm;
            if it > 0 && rate > REFRESH_RATE && !fresh {
                // stale Jacobian contracts poorly: refresh at the current iterate
                self.factored_h = None;
            } else if it > 0 && rate > 1.0 && fresh {
                break; // diverging with a fresh Jacobian
            }
        }
        self.invalidate();
        Err(StepFailure::NoConvergence { h, last_norm: last })
    }

    /// The real-time mode's solve: exactly `fixed.iterations` iterations, the matrix evaluated
    /// and factorized at the first of them when the schedule says so (every `fixed.refresh`
    /// solves, or when none is held for this step size), whatever the contraction; fails if
    /// the last increment is above `fixed.bound` × tolerance. Returns the iterations and `eta`
    /// unchanged (no estimate steers the work).
    #[allow(clippy::too_many_arguments)]
    fn iterate_fixed<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        t: &mut State,
        h: f64,
        request: impl Fn(bool) -> EvalRequest,
        rates: Rates,
        fixed: super::FixedWork,
        eta: f64,
    ) -> Result<(usize, f64), StepFailure> {
        let due = !self.holds(h) || self.solves_since_refresh + 1 >= fixed.refresh;
        let mut last = f64::INFINITY;
        for it in 0..fixed.iterations {
            let refresh = it == 0 && due;
            model.eval(
                StateRef::new(&t.q, &t.v, &t.acc, &t.lambda),
                request(refresh),
                &mut self.res,
            );
            self.counters.iterations += 1;
            if refresh {
                self.factorize_at(model, t, h)?;
                self.solves_since_refresh = 0;
            }
            last = self.apply_increment(model, t, h, rates)?;
        }
        if !due {
            self.solves_since_refresh += 1;
        }
        if last > fixed.bound {
            return Err(StepFailure::FixedWorkUnconverged {
                h,
                iterations: fixed.iterations,
                last_norm: last,
                bound: fixed.bound,
            });
        }
        Ok((fixed.iterations, eta))
    }

    /// Whether the held matrix serves step size `h` (the same to 1e-9 relative).
    fn holds(&self, h: f64) -> bool {
        self.factored_h.is_some_and(|hf| (hf - h).abs() <= 1e-9 * h)
    }

    /// Factorizes the matrix the model just evaluated at the iterate `t` for step size `h`,
    /// counts it and keeps its evaluation point (refilled in place: no allocation once sized).
    fn factorize_at<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        t: &State,
        h: f64,
    ) -> Result<(), StepFailure> {
        if model.factorize().is_err() {
            self.factored_h = None;
            return Err(StepFailure::Singular { h });
        }
        self.counters.factorizations += 1;
        self.factored_h = Some(h);
        match &mut self.jac_at {
            Some(jp) => {
                jp.h = h;
                jp.q.clone_from(&t.q);
                jp.v.clone_from(&t.v);
                jp.acc.clone_from(&t.acc);
                jp.lam.clone_from(&t.lambda);
            }
            None => {
                self.jac_at = Some(JacobianPoint {
                    h,
                    q: t.q.clone(),
                    v: t.v.clone(),
                    acc: t.acc.clone(),
                    lam: t.lambda.clone(),
                })
            }
        }
        Ok(())
    }

    /// Solves for the increment from the residual in `res` with the held matrix and applies it
    /// to `t` (coordinates through the model's increment, rates and accelerations by `rates`,
    /// multipliers); returns its scaled norm in units of the tolerance. A singular solve or a
    /// non-finite increment drops the held matrix.
    fn apply_increment<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        t: &mut State,
        h: f64,
        rates: Rates,
    ) -> Result<f64, StepFailure> {
        let (n, m) = (t.q.len(), t.lambda.len());
        for r in self.res.iter_mut() {
            *r = -*r;
        }
        if !model.solve(&mut self.res) {
            self.factored_h = None;
            return Err(StepFailure::Singular { h });
        }
        model.increment(&mut t.q, &self.res[..n]);
        for i in 0..n {
            let d = self.res[i];
            t.v[i] += rates.dv * d;
            t.acc[i] += rates.da * d;
            if let Some(div) = rates.aux_div {
                t.aux[i] += d / div;
            }
        }
        for j in 0..m {
            t.lambda[j] += self.res[n + j];
        }
        let norm = scaled_norm(&self.res[..n], model.scales()) / self.tol;
        if !norm.is_finite() {
            self.factored_h = None;
            return Err(StepFailure::Singular { h });
        }
        Ok(norm)
    }
}
