//! Static equilibrium f(q) − f_ext(q) + Φ_qᵀλ = 0, Φ(q) = 0 by Newton with load stepping:
//! gravity and tip force are scaled by a load factor raised from 0 to 1, the increment halved
//! when Newton fails and doubled after an easy success; and the relative equilibrium in a
//! frame turning at a constant rate ([`solve_relative_static`]).

use super::{
    scaled_norm, EvalRequest, Integrable, State, StateRef, RELATIVE_STATIC_MAX, STATIC_MAX_ITER,
    STATIC_MIN_INCREMENT,
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

/// Static equilibrium relative to a frame turning at a constant rate: the coordinates
/// `state.q` and multipliers such that the equations of motion hold with the rates and
/// accelerations of the frame's rigid field, `rest_rates(model, q, v, a)` (the model at rest in
/// the frame: centrifugal, Coriolis-free), whose partials by q are `rate_jacobians(model, q)`
/// ((row, column, value) entries of ∂v/∂q, ∂a/∂q). Newton on q and λ with the exact Jacobian
/// K + C ∂v/∂q + M ∂a/∂q, assembled dense from [`Integrable::dense_matrix`] (O((n + m)²)
/// memory; up to [`RELATIVE_STATIC_MAX`] unknowns). On success `state` holds q, the rest
/// rates, accelerations and λ.
pub fn solve_relative_static<M: Integrable + ?Sized>(
    model: &mut M,
    rest_rates: impl Fn(&M, &[f64], &mut [f64], &mut [f64]),
    rate_jacobians: impl Fn(&M, &[f64]) -> [Vec<(usize, usize, f64)>; 2],
    state: &mut State,
    tol: f64,
) -> Result<usize, StaticFailure> {
    let (n, mc) = (model.coordinates(), model.constraints());
    let d = n + mc;
    let fail = |reason: String| StaticFailure { load: 0.0, reason };
    if d > RELATIVE_STATIC_MAX {
        return Err(fail(format!(
                "{d} unknowns: the static start on a turning mount is solved dense, up to {RELATIVE_STATIC_MAX}"
            )));
    }
    let scale = model.scales().to_vec();
    let (mut q, mut lam) = (state.q.clone(), state.lambda.clone());
    let (mut v, mut a) = (vec![0.0; n], vec![0.0; n]);
    let mut res = vec![0.0; d];
    for iter in 1..=STATIC_MAX_ITER {
        rest_rates(&*model, &q, &mut v, &mut a);
        let mut dense = |model: &mut M, c: (f64, f64, f64), hessian: bool| {
            let req = EvalRequest {
                sd: 1.0,
                matrix: Some(c),
                lambda_hessian: hessian,
            };
            model.eval(StateRef::new(&q, &v, &a, &lam), req, &mut res);
            model
                .dense_matrix()
                .ok_or_else(|| fail("the model gives no dense matrix".into()))
        };
        let mass = dense(model, (1.0, 0.0, 0.0), false)?;
        let damping = dense(model, (0.0, 1.0, 0.0), false)?;
        let stiffness = dense(model, (0.0, 0.0, 1.0), true)?;
        let mut j = nalgebra::DMatrix::from_fn(d, d, |r, c| stiffness[r][c]);
        let [dv, da] = rate_jacobians(&*model, &q);
        for (jac, mat) in [(&dv, &damping), (&da, &mass)] {
            for &(k, col, x) in jac {
                for row in 0..n {
                    j[(row, col)] += mat[row][k] * x;
                }
            }
        }
        let rhs = nalgebra::DVector::from_iterator(d, res.iter().map(|r| -r));
        let step = j
            .lu()
            .solve(&rhs)
            .ok_or_else(|| fail("singular Jacobian".into()))?;
        model.increment(&mut q, &step.as_slice()[..n]);
        for (l, s) in lam.iter_mut().zip(&step.as_slice()[n..]) {
            *l += s;
        }
        let norm = scaled_norm(&step.as_slice()[..n], &scale);
        if !norm.is_finite() {
            break;
        }
        if norm <= tol {
            rest_rates(&*model, &q, &mut v, &mut a);
            state.q = q;
            state.v = v;
            state.acc = a;
            state.aux.fill(0.0);
            state.lambda = lam;
            return Ok(iter);
        }
    }
    Err(fail(
        "Newton did not converge in the turning mount's frame".into(),
    ))
}
