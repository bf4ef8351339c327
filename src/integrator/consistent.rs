//! Accelerations and multipliers consistent with a state: at start-up, and as the jump when
//! inputs change at a communication point. Shared by the integrators (through
//! [`super::newton::Newton`]); nothing here depends on the integration method.

use super::{scaled_norm, Counters, EvalRequest, Integrable, State, StateRef, StepFailure};

/// Consistent initial accelerations and multipliers at `s` (q, q̇ given): sets q̈, the
/// algorithmic acceleration a = q̈ and λ. The model's matrix storage is used (a held Newton
/// matrix is gone).
pub(super) fn initialize<M: Integrable + ?Sized>(
    model: &mut M,
    s: &mut State,
    res: &mut [f64],
    counters: &mut Counters,
) -> Result<(), StepFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    let zeros_n = vec![0.0; n];
    let zeros_m = vec![0.0; m];
    let req = EvalRequest {
        sd: 1.0,
        matrix: Some((1.0, 0.0, 0.0)),
        lambda_hessian: false,
    };
    let x = StateRef::new(&s.q, &s.v, &zeros_n, &zeros_m);
    model.eval(x, req, res);
    let mut rhs: Vec<f64> = res.iter().map(|r| -r).collect();
    // acceleration-level constraint: Φ_q q̈ = −d²Φ/dt² at q̈ = 0 (second difference along q̇
    // and the held coordinates' motion)
    if let Some(c) = constraint_drift(model, &s.q, &s.v) {
        for i in 0..m {
            rhs[n + i] = -c[i];
        }
    } else {
        for r in rhs.iter_mut().skip(n) {
            *r = 0.0;
        }
    }
    model
        .factorize()
        .map_err(|_| StepFailure::Singular { h: 0.0 })?;
    counters.factorizations += 1;
    if !model.solve(&mut rhs) {
        return Err(StepFailure::Singular { h: 0.0 });
    }
    s.acc.copy_from_slice(&rhs[..n]);
    s.aux.copy_from_slice(&rhs[..n]);
    s.lambda.copy_from_slice(&rhs[n..]);
    Ok(())
}

/// The jump of q̈ and λ when inputs change at t_n (see [`super::GeneralizedAlpha::change_inputs`]);
/// the model's matrix storage is used (a held Newton matrix is gone).
pub(super) fn change_inputs<M: Integrable + ?Sized>(
    model: &mut M,
    s: &mut State,
    res: &mut [f64],
    counters: &mut Counters,
    change: impl FnOnce(&mut M),
) -> Result<(), StepFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    let zeros_n = vec![0.0; n];
    let zeros_m = vec![0.0; m];
    let x = StateRef::new(&s.q, &s.v, &zeros_n, &zeros_m);
    let mut before = vec![0.0; n + m];
    let req = EvalRequest {
        sd: 1.0,
        matrix: None,
        lambda_hessian: false,
    };
    model.eval(x, req, &mut before);
    // a driven support: the acceleration-level constraint before and after, with the same
    // difference step so that the velocity terms cancel
    let driven = model.is_driven();
    let eps = drift_step(model, &s.v);
    let drift_before = if driven {
        constraint_drift_with(model, &s.q, &s.v, eps)
    } else {
        None
    };
    change(model);
    let drift_after = if driven {
        constraint_drift_with(model, &s.q, &s.v, eps)
    } else {
        None
    };
    let req = EvalRequest {
        sd: 1.0,
        matrix: Some((1.0, 0.0, 0.0)),
        lambda_hessian: false,
    };
    model.eval(x, req, res);
    model
        .factorize()
        .map_err(|_| StepFailure::Singular { h: 0.0 })?;
    counters.factorizations += 1;
    for (r, b) in res.iter_mut().zip(&before).take(n) {
        *r = b - *r;
    }
    // Φ(q_n) is the same both times; a moving support changes the acceleration-level
    // constraint by Φ_h Δḧ: Φ_q Δq̈ = −(d²Φ/dt²⁺ − d²Φ/dt²⁻)
    res[n..].fill(0.0);
    if drift_before.is_some() || drift_after.is_some() {
        let zero = vec![0.0; m];
        let (b, a) = (
            drift_before.as_deref().unwrap_or(&zero),
            drift_after.as_deref().unwrap_or(&zero),
        );
        for j in 0..m {
            res[n + j] = b[j] - a[j];
        }
    }
    if !model.solve(res) || res.iter().any(|x| !x.is_finite()) {
        return Err(StepFailure::Singular { h: 0.0 });
    }
    for i in 0..n {
        s.acc[i] += res[i];
        s.aux[i] += res[i];
    }
    for j in 0..m {
        s.lambda[j] += res[n + j];
    }
    Ok(())
}

/// d²Φ/dt² at q̈ = 0 along (q̇, the held coordinates' motion), by a central second
/// difference; `None` without constraint rows or without motion.
fn constraint_drift<M: Integrable + ?Sized>(
    model: &mut M,
    q: &[f64],
    v: &[f64],
) -> Option<Vec<f64>> {
    let eps = drift_step(model, v);
    constraint_drift_with(model, q, v, eps)
}

/// The time step of [`constraint_drift`]'s second difference: 1e-4 over the largest scaled
/// rate of the coordinates and the held motion (at most 1e-4 s with a driven support).
fn drift_step<M: Integrable + ?Sized>(model: &M, v: &[f64]) -> f64 {
    let vmax = scaled_norm(v, model.scales()).max(model.held_rate());
    // a driven support may start moving in the change the step serves: at most 1e-4 s
    let floor = if model.is_driven() { 1.0 } else { 1e-300 };
    1e-4 / vmax.max(floor)
}

/// [`constraint_drift`] with the difference step `eps` [s].
fn constraint_drift_with<M: Integrable + ?Sized>(
    model: &mut M,
    q: &[f64],
    v: &[f64],
    eps: f64,
) -> Option<Vec<f64>> {
    let m = model.constraints();
    if m == 0 || (model.held_rate() == 0.0 && v.iter().all(|x| *x == 0.0)) {
        return None;
    }
    let mut phi = |q: &[f64], dt: f64| {
        let mut r = vec![0.0; m];
        model.constraint_values(q, dt, &mut r);
        r
    };
    let qp: Vec<f64> = q.iter().zip(v).map(|(q, v)| q + eps * v).collect();
    let qm: Vec<f64> = q.iter().zip(v).map(|(q, v)| q - eps * v).collect();
    let (pp, p0, pm) = (phi(&qp, eps), phi(q, 0.0), phi(&qm, -eps));
    Some(
        (0..m)
            .map(|i| (pp[i] - 2.0 * p0[i] + pm[i]) / (eps * eps))
            .collect(),
    )
}
