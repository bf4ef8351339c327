//! Static equilibrium f(q) − f_ext(q) + Φ_qᵀλ = 0, Φ(q) = 0 by Newton with load stepping:
//! gravity and tip force are scaled by a load factor raised from 0 to 1, the increment halved
//! when Newton fails and doubled after an easy success.

use super::{
    scaled_norm, EvalRequest, Integrable, State, StateRef, STATIC_MAX_ITER, STATIC_MIN_INCREMENT,
};

/// Why the static solve failed.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticFailure {
    /// Load factor reached (0..1).
    pub load: f64,
    /// Human-readable reason.
    pub reason: String,
}

impl std::fmt::Display for StaticFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "static equilibrium not found ({}) after reaching {:.1} % of the load",
            self.reason,
            100.0 * self.load
        )
    }
}

impl std::error::Error for StaticFailure {}

/// Solves for equilibrium starting from `s.q`; on success `s` holds it (at rest, q̈ = 0) and the
/// function returns the number of Newton iterations. `tol` is relative to coordinate scales.
pub fn solve_static<M: Integrable + ?Sized>(
    model: &mut M,
    s: &mut State,
    tol: f64,
) -> Result<usize, StaticFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    let zeros = vec![0.0; n];
    let scale = model.scales().to_vec();
    let mut res = vec![0.0; n + m];
    let mut load = 0.0;
    let mut inc: f64 = 1.0;
    let mut total_iter = 0;
    let mut q = s.q.clone();
    let mut lam = s.lambda.clone();
    while load < 1.0 {
        let target = (load + inc).min(1.0);
        let (q_save, lam_save) = (q.clone(), lam.clone());
        let mut converged = false;
        let mut iters = 0;
        for _ in 0..STATIC_MAX_ITER {
            iters += 1;
            let req = EvalRequest {
                sd: 1.0,
                matrix: Some((0.0, 0.0, 1.0)),
                lambda_hessian: true,
            };
            let x = StateRef::new(&q, &zeros, &zeros, &lam).with_load(target);
            model.eval(x, req, &mut res);
            if model.factorize().is_err() {
                break;
            }
            for r in res.iter_mut() {
                *r = -*r;
            }
            if !model.solve(&mut res) {
                break;
            }
            model.increment(&mut q, &res[..n]);
            for j in 0..m {
                lam[j] += res[n + j];
            }
            let norm = scaled_norm(&res[..n], &scale);
            if !norm.is_finite() {
                break;
            }
            if norm <= tol {
                converged = true;
                break;
            }
        }
        total_iter += iters;
        if converged {
            load = target;
            if iters <= 6 {
                inc *= 2.0;
            }
        } else {
            q = q_save;
            lam = lam_save;
            inc *= 0.5;
            if inc < STATIC_MIN_INCREMENT {
                return Err(StaticFailure {
                    load,
                    reason: "Newton did not converge even with tiny load increments".into(),
                });
            }
        }
    }
    s.q = q;
    s.lambda = lam;
    s.v.fill(0.0);
    s.acc.fill(0.0);
    s.aux.fill(0.0);
    Ok(total_iter)
}
