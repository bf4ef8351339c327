//! Accelerations and multipliers consistent with a state: at start-up, and as the jump when
//! inputs change at a communication point. Shared by the integrators (through
//! [`super::newton::Newton`]); nothing here depends on the integration method.

use super::{scaled_norm, Counters, EvalRequest, Integrable, State, StateRef, StepFailure};

/// The evaluation of the residual alone, at unit row scale.
const RESIDUAL: EvalRequest = EvalRequest {
    sd: 1.0,
    matrix: None,
    lambda_hessian: false,
};

/// The evaluation with the matrix [M Φ_qᵀ; Φ_q 0] (c_a = 1, c_v = c_x = 0).
const MATRIX: EvalRequest = EvalRequest {
    sd: 1.0,
    matrix: Some((1.0, 0.0, 0.0)),
    lambda_hessian: false,
};

/// The working memory of [`initialize`] and [`change_inputs`], owned by the integrator's
/// Newton solver: sized at the first call (the initialization), then reused, so that a jump of
/// the inputs allocates nothing.
#[derive(Debug, Clone, Default)]
pub(super) struct Work {
    /// Zeros: the accelerations and multipliers of the evaluations (max(n, m); only ever zero).
    zeros: Vec<f64>,
    /// The right side of [`initialize`], the residual before the change of [`change_inputs`]
    /// (n + m).
    rhs: Vec<f64>,
    /// The acceleration-level constraint before the change, and [`initialize`]'s (m).
    before: Vec<f64>,
    /// The acceleration-level constraint after the change (m).
    after: Vec<f64>,
    /// [`constraint_drift_with`]'s.
    drift: DriftWork,
}

/// The working memory of [`constraint_drift_with`]: the displaced coordinates (n) and the
/// constraint values at them (m).
#[derive(Debug, Clone, Default)]
struct DriftWork {
    /// Whether `p0` holds Φ(q) of the q at hand already (jumps that leave it: [`input_jumps`]).
    p0_known: bool,
    qp: Vec<f64>,
    qm: Vec<f64>,
    pp: Vec<f64>,
    p0: Vec<f64>,
    pm: Vec<f64>,
}

impl Work {
    /// Sizes the buffers for `n` coordinates and `m` constraint rows (no allocation once
    /// sized).
    fn size(&mut self, n: usize, m: usize) {
        self.zeros.resize(n.max(m), 0.0);
        self.rhs.resize(n + m, 0.0);
        self.before.resize(m, 0.0);
        self.after.resize(m, 0.0);
        let d = &mut self.drift;
        for v in [&mut d.qp, &mut d.qm] {
            v.resize(n, 0.0);
        }
        for v in [&mut d.pp, &mut d.p0, &mut d.pm] {
            v.resize(m, 0.0);
        }
    }
}

/// Consistent initial accelerations and multipliers at `s` (q, q̇ given): sets q̈, the
/// algorithmic acceleration a = q̈ and λ. The model's matrix storage is used (a held Newton
/// matrix is gone).
pub(super) fn initialize<M: Integrable + ?Sized>(
    model: &mut M,
    s: &mut State,
    res: &mut [f64],
    counters: &mut Counters,
    work: &mut Work,
) -> Result<(), StepFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    work.size(n, m);
    let Work {
        zeros,
        rhs,
        before: drift,
        drift: drift_work,
        ..
    } = work;
    let x = StateRef::new(&s.q, &s.v, &zeros[..n], &zeros[..m]);
    model.eval(x, MATRIX, res);
    for (o, r) in rhs.iter_mut().zip(res.iter()) {
        *o = -r;
    }
    // acceleration-level constraint: Φ_q q̈ = −d²Φ/dt² at q̈ = 0 (second difference along q̇
    // and the held coordinates' motion)
    if constraint_drift(model, &s.q, &s.v, drift_work, drift) {
        for i in 0..m {
            rhs[n + i] = -drift[i];
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
    if !model.solve(rhs) {
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
    work: &mut Work,
    change: impl FnOnce(&mut M),
) -> Result<(), StepFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    work.size(n, m);
    let Work {
        zeros,
        rhs: before,
        before: drift_before,
        after: drift_after,
        drift: drift_work,
    } = work;
    let x = StateRef::new(&s.q, &s.v, &zeros[..n], &zeros[..m]);
    before.fill(0.0);
    model.eval(x, RESIDUAL, before);
    // a driven support: the acceleration-level constraint before and after, with the same
    // difference step so that the velocity terms cancel
    let driven = model.is_driven();
    let eps = drift_step(model, &s.v);
    let has_before =
        driven && constraint_drift_with(model, &s.q, &s.v, eps, drift_work, drift_before);
    change(model);
    let has_after =
        driven && constraint_drift_with(model, &s.q, &s.v, eps, drift_work, drift_after);
    model.eval(x, MATRIX, res);
    model
        .factorize()
        .map_err(|_| StepFailure::Singular { h: 0.0 })?;
    counters.factorizations += 1;
    let drifts = (
        has_before.then_some(&drift_before[..]),
        has_after.then_some(&drift_after[..]),
    );
    solve_jump(model, res, before, drifts)?;
    add_jump(s, res);
    Ok(())
}

/// The jump [Δq̈; Δλ] into `res` (n + m; the residual after the change on entry) with the held
/// factorization: the dynamic rows f_ext⁺ − f_ext⁻ = r⁻ − r⁺ (`before` the residual before the
/// change), the constraint rows from the acceleration-level constraint before and after
/// (`drifts`, `None`: zero).
fn solve_jump<M: Integrable + ?Sized>(
    model: &mut M,
    res: &mut [f64],
    before: &[f64],
    (drift_before, drift_after): (Option<&[f64]>, Option<&[f64]>),
) -> Result<(), StepFailure> {
    let n = model.coordinates();
    for (r, b) in res.iter_mut().zip(before).take(n) {
        *r = b - *r;
    }
    // Φ(q_n) is the same both times; a moving support changes the acceleration-level
    // constraint by Φ_h Δḧ: Φ_q Δq̈ = −(d²Φ/dt²⁺ − d²Φ/dt²⁻)
    res[n..].fill(0.0);
    if drift_before.is_some() || drift_after.is_some() {
        // an absent side is zero
        for (j, r) in res[n..].iter_mut().enumerate() {
            let b = drift_before.map_or(0.0, |d| d[j]);
            let a = drift_after.map_or(0.0, |d| d[j]);
            *r = b - a;
        }
    }
    if !model.solve(res) || res.iter().any(|x| !x.is_finite()) {
        return Err(StepFailure::Singular { h: 0.0 });
    }
    Ok(())
}

/// Adds the jump `res` ([Δq̈; Δλ]) to `s`: q̈, the algorithmic acceleration and λ.
fn add_jump(s: &mut State, res: &[f64]) {
    let n = s.acc.len();
    for i in 0..n {
        s.acc[i] += res[i];
        s.aux[i] += res[i];
    }
    for (l, r) in s.lambda.iter_mut().zip(&res[n..]) {
        *l += r;
    }
}

/// The working memory of [`input_jumps`] (sized at build by [`JumpWork::sized`]: no
/// allocation in a step).
#[derive(Debug, Clone, Default)]
pub struct JumpWork {
    work: Work,
    /// The residual and the jump (n + m).
    res: Vec<f64>,
}

impl JumpWork {
    /// Sized for `n` coordinates and `m` constraint rows.
    pub fn sized(n: usize, m: usize) -> Self {
        let mut w = Self::default();
        w.work.size(n, m);
        w.res.resize(n + m, 0.0);
        w
    }
}

/// Several jumps of the inputs from one state `s`, each as `change_inputs` (an integrator's) solves it: for
/// k < `count`, `change(model, k)` alters the inputs, the jump of q̈ and λ is added to a copy of
/// `s` in `out`, and `read(model, out, k)` reads it and returns the model to the inputs of `s`.
/// The residual and the acceleration-level constraint before the changes are evaluated once,
/// and the matrix `[M Φ_qᵀ; Φ_q 0]` at (q, q̇) is factorized for the first jump only: the changes
/// must leave it as it is, to the bit (accelerations of a mount, which enter it only times
/// c_v = c_x = 0), and each jump is then the one `change_inputs` (an integrator's) solves, bit for bit. The
/// model's matrix storage is used. Returns the number of factorizations (one).
pub fn input_jumps<M: Integrable + ?Sized>(
    model: &mut M,
    (s, out): (&State, &mut State),
    jw: &mut JumpWork,
    count: usize,
    mut change: impl FnMut(&mut M, usize),
    mut read: impl FnMut(&mut M, &State, usize),
) -> Result<u64, StepFailure> {
    let n = model.coordinates();
    let m = model.constraints();
    jw.work.size(n, m);
    jw.res.resize(n + m, 0.0);
    let Work {
        zeros,
        rhs: before,
        before: drift_before,
        after: drift_after,
        drift: drift_work,
    } = &mut jw.work;
    let res = &mut jw.res[..];
    let x = StateRef::new(&s.q, &s.v, &zeros[..n], &zeros[..m]);
    before.fill(0.0);
    model.eval(x, RESIDUAL, before);
    let driven = model.is_driven();
    let eps = drift_step(model, &s.v);
    // Φ(q) (the held values) is the same under every change: evaluated once
    drift_work.p0_known = false;
    let has_before =
        driven && constraint_drift_with(model, &s.q, &s.v, eps, drift_work, drift_before);
    drift_work.p0_known = has_before;
    for k in 0..count {
        change(model, k);
        let has_after =
            driven && constraint_drift_with(model, &s.q, &s.v, eps, drift_work, drift_after);
        drift_work.p0_known |= has_after;
        // the residual with the matrix request, as [`change_inputs`] evaluates it (an
        // element may compute its residual along another path with a matrix: not the same bits
        // without); the matrix is the same for every change, factorized for the first
        model.eval(x, MATRIX, res);
        if k == 0 {
            model
                .factorize()
                .map_err(|_| StepFailure::Singular { h: 0.0 })?;
        }
        let drifts = (
            has_before.then_some(&drift_before[..]),
            has_after.then_some(&drift_after[..]),
        );
        solve_jump(model, res, before, drifts)?;
        out.copy_from(s);
        add_jump(out, res);
        read(model, out, k);
    }
    Ok(1)
}

/// d²Φ/dt² at q̈ = 0 along (q̇, the held coordinates' motion), by a central second
/// difference, into `out` (m); false (and `out` untouched) without constraint rows or without
/// motion.
fn constraint_drift<M: Integrable + ?Sized>(
    model: &mut M,
    q: &[f64],
    v: &[f64],
    work: &mut DriftWork,
    out: &mut [f64],
) -> bool {
    let eps = drift_step(model, v);
    constraint_drift_with(model, q, v, eps, work, out)
}

/// The time step of [`constraint_drift`]'s second difference: 1e-4 over the largest scaled
/// rate of the coordinates and the held motion (at most 1e-4 s with a driven support).
fn drift_step<M: Integrable + ?Sized>(model: &M, v: &[f64]) -> f64 {
    let vmax = scaled_norm(v, model.scales()).max(model.held_rate());
    // a driven support may start moving in the change the step serves: at most 1e-4 s
    let floor = if model.is_driven() { 1.0 } else { 1e-300 };
    1e-4 / vmax.max(floor)
}

/// [`constraint_drift`] with the difference step `eps` [s] (working memory `work`, sized).
fn constraint_drift_with<M: Integrable + ?Sized>(
    model: &mut M,
    q: &[f64],
    v: &[f64],
    eps: f64,
    work: &mut DriftWork,
    out: &mut [f64],
) -> bool {
    let m = model.constraints();
    if m == 0 || (model.held_rate() == 0.0 && v.iter().all(|x| *x == 0.0)) {
        return false;
    }
    let DriftWork {
        p0_known,
        qp,
        qm,
        pp,
        p0,
        pm,
    } = work;
    for ((o, q), v) in qp.iter_mut().zip(q).zip(v) {
        *o = q + eps * v;
    }
    for ((o, q), v) in qm.iter_mut().zip(q).zip(v) {
        *o = q - eps * v;
    }
    // each row set written whole by the model (fresh zeros before, as the rows were)
    for (k, (x, dt, p)) in [
        (&qp[..], eps, &mut *pp),
        (q, 0.0, &mut *p0),
        (&qm[..], -eps, &mut *pm),
    ]
    .into_iter()
    .enumerate()
    {
        if k == 1 && *p0_known {
            continue;
        }
        p.fill(0.0);
        model.constraint_values(x, dt, p);
    }
    for i in 0..m {
        out[i] = (pp[i] - 2.0 * p0[i] + pm[i]) / (eps * eps);
    }
    true
}
