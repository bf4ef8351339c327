//! A diagonally implicit Runge–Kutta method of order 4 for the index-3 system of
//! [`Integrable`]: Kennedy & Carpenter's L-stable, stiffly accurate six-stage ESDIRK of stage
//! order 2 ([`ESDIRK4`]; docs/references.md §5), behind `solver.method = "esdirk4"`.
//!
//! Written on y = (q, q̇) with stage accelerations A_j: Q_i = q_n + c_i h q̇_n + h² Σ_j (𝔄²)_ij A_j,
//! V_i = q̇_n + h Σ_j 𝔄_ij A_j, where 𝔄 is the method's matrix; stage i solves the equations of
//! motion and Φ(Q_i) = 0 at t_n + c_i h for A_i, which enters Q_i with (γh)² and V_i with γh:
//! Newton on ΔQ_i with the matrix M + γh C + (γh)² K (the dynamic rows scaled by (γh)², the
//! multipliers λ̃ = (γh)²λ), the same matrix for every stage, held across stages and steps while
//! Newton contracts well. The first stage is explicit: A_1 = q̈_n. Stiffly accurate: the step
//! ends on the last stage (c = 1), so Φ(q_{n+1}) = 0 holds as in generalized-α, and R(∞) = 0
//! damps the unresolved modes.
//!
//! Why: generalized-α's phase error (ωh)²/12 per unit of phase is what limits a released rod's
//! accuracy at common steps (its 3rd bending mode at 160 Hz drifts by 1.6 rad over 2 s at
//! h = 1e-4 s); this method's is of order (ωh)⁴, at five solves per step with one matrix.
//! Why stage order 2: on index-3 constraints with a curved manifold (a pendulum's rod, the
//! joints between segments) a method of stage order 1 such as Hairer & Wanner's SDIRK4 falls to
//! first order (`tests::order_on_a_curved_constraint`: 4.2e-5 rad at 8 steps per 10 ms, where
//! this one has 2.2e-8 rad), and on a stiffly damped beam (Case 3) it loses its accuracy.

use super::newton::{Newton, Rates};
use super::{
    Counters, EvalRequest, Integrable, IntegrationParameters, IntegratorMemory, State, StateRef,
    StepFailure, MIN_TOLERANCE,
};
use crate::math;

/// Most stages of a tableau here.
const MAX_STAGES: usize = 6;

/// A stiffly accurate diagonally implicit Runge–Kutta tableau with one γ on the diagonal of
/// its implicit stages (the first stage explicit, c₁ = 0, for an ESDIRK).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau {
    /// Stages (explicit first stage included).
    pub stages: usize,
    /// The method's matrix 𝔄 (lower triangular; its last row is b).
    pub a: [[f64; MAX_STAGES]; MAX_STAGES],
    /// First stage explicit (a₁ⱼ = 0): its acceleration is q̈ₙ, the previous step's last stage.
    pub explicit_first: bool,
    /// The weights b̂ of the embedded solution of lower order, if the tableau has one: the
    /// error estimate of `solver.error_tolerance` ([`Esdirk::step`]).
    pub embedded: Option<[f64; MAX_STAGES]>,
    /// The stages' Newton tolerance as a fraction of `solver.tolerance`.
    pub tolerance_factor: f64,
}

/// Kennedy & Carpenter's ESDIRK4(3)6L[2]SA (the implicit half of ARK4(3)6L[2]SA, Appl. Numer.
/// Math. 44 (2003) 139–181; SUNDIALS' ARK436L2SA_DIRK_6_3_4): six stages, the first explicit
/// (first same as last: no solve), L-stable, stiffly accurate, order 4 with an embedded order
/// 3 (b̂, the error estimate of `solver.error_tolerance`; SUNDIALS' `d` of the table),
/// **stage order 2** (Σⱼ aᵢⱼ cⱼ = cᵢ²/2), all weights below 1 in magnitude.
/// Stage tolerance = `solver.tolerance`: its small weights carry a stage's error into the step
/// as generalized-α's own does; measured on the spatial Case 1 cable (16 elements, h = 5e-4 s),
/// the tip error against the reference is 9.018e-6 m at stage tolerance 1e-13 and 9.017e-6 m
/// at 1e-11, with 72 077 and 57 235 Newton iterations.
pub const ESDIRK4: Tableau = Tableau::from_rows(
    &[
        &[],
        &[0.25, 0.25],
        &[8611.0 / 62500.0, -1743.0 / 31250.0, 0.25],
        &[
            5012029.0 / 34652500.0,
            -654441.0 / 2922500.0,
            174375.0 / 388108.0,
            0.25,
        ],
        &[
            15267082809.0 / 155376265600.0,
            -71443401.0 / 120774400.0,
            730878875.0 / 902184768.0,
            2285395.0 / 8070912.0,
            0.25,
        ],
        &[
            82889.0 / 524892.0,
            0.0,
            15625.0 / 83664.0,
            69875.0 / 102672.0,
            -2260.0 / 8211.0,
            0.25,
        ],
    ],
    true,
    1.0,
)
.with_embedded([
    4586570599.0 / 29645900160.0,
    0.0,
    178811875.0 / 945068544.0,
    814220225.0 / 1159782912.0,
    -3700637.0 / 11593932.0,
    61727.0 / 225920.0,
]);

impl Tableau {
    /// The tableau of the lower-triangular rows `rows` (the last is b).
    const fn from_rows(rows: &[&[f64]], explicit_first: bool, tolerance_factor: f64) -> Self {
        let mut a = [[0.0; MAX_STAGES]; MAX_STAGES];
        let mut i = 0;
        while i < rows.len() {
            let mut j = 0;
            while j < rows[i].len() {
                a[i][j] = rows[i][j];
                j += 1;
            }
            i += 1;
        }
        Self {
            stages: rows.len(),
            a,
            explicit_first,
            embedded: None,
            tolerance_factor,
        }
    }

    /// With the embedded weights `b_hat`.
    const fn with_embedded(self, b_hat: [f64; MAX_STAGES]) -> Self {
        Self {
            embedded: Some(b_hat),
            ..self
        }
    }

    /// γ, the diagonal of the implicit stages.
    pub fn gamma(&self) -> f64 {
        self.a[self.stages - 1][self.stages - 1]
    }

    /// The stage times c_i = Σ_j 𝔄_ij as fractions of the step.
    pub fn nodes(&self) -> [f64; MAX_STAGES] {
        let mut c = [0.0; MAX_STAGES];
        for (ci, row) in c.iter_mut().zip(&self.a) {
            *ci = row.iter().sum();
        }
        c
    }

    /// 𝔄² (the positions' weights of the stage accelerations).
    fn a_squared(&self) -> [[f64; MAX_STAGES]; MAX_STAGES] {
        let mut a2 = [[0.0; MAX_STAGES]; MAX_STAGES];
        for (i, row) in a2.iter_mut().enumerate() {
            for (k, x) in row.iter_mut().enumerate() {
                *x = (0..MAX_STAGES).map(|j| self.a[i][j] * self.a[j][k]).sum();
            }
        }
        a2
    }

    /// The error estimate's weights of the stage accelerations (`None` without an embedded
    /// solution): with d = b − b̂, the positions' (dᵀ𝔄, times h²) and the velocities' (d, times
    /// h). The step's solution is q = q_n + h q̇_n + h² Σ_k (bᵀ𝔄)_k A_k, q̇ = q̇_n + h Σ_k b_k
    /// A_k (b the last row of 𝔄: the last stage), the embedded one the same with b̂ (Σ b̂ = 1,
    /// so q̇_n enters both alike): their differences are these sums.
    fn error_weights(&self) -> Option<ErrorWeights> {
        let b_hat = self.embedded?;
        let b = self.a[self.stages - 1];
        let mut w = ErrorWeights {
            q: [0.0; MAX_STAGES],
            v: [0.0; MAX_STAGES],
        };
        for j in 0..self.stages {
            let d = b[j] - b_hat[j];
            w.v[j] = d;
            for k in 0..self.stages {
                w.q[k] += d * self.a[j][k];
            }
        }
        Some(w)
    }
}

/// The weights of the stage accelerations in the error estimate ([`Tableau::error_weights`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ErrorWeights {
    /// Positions' (dᵀ𝔄), times h².
    q: [f64; MAX_STAGES],
    /// Velocities' (d), times h.
    v: [f64; MAX_STAGES],
}

/// Error control: the tolerance, the estimate's weights and its working memory (sized once:
/// no allocation in a step).
#[derive(Debug, Clone, PartialEq)]
struct ErrorControl {
    /// `solver.error_tolerance`.
    tolerance: f64,
    weights: ErrorWeights,
    /// The last step's estimate in units of the tolerance.
    last: f64,
    /// The raw estimate's position part e_q, then the filtered estimate (n).
    e_q: Vec<f64>,
    /// Its velocity part e_v (n), then the perturbed accelerations.
    e_v: Vec<f64>,
    /// The perturbed coordinates (n).
    q: Vec<f64>,
    /// The residuals at the step's end and at the perturbed state (n + m each).
    r0: Vec<f64>,
    r1: Vec<f64>,
}

/// The integrator with its work arrays and Jacobian policy.
#[derive(Debug, Clone)]
pub struct Esdirk {
    tableau: &'static Tableau,
    nodes: [f64; MAX_STAGES],
    /// 𝔄² by rows.
    a2: Vec<[f64; MAX_STAGES]>,
    /// Per stage, the weights of its acceleration's first guess ([`guess_weights`]).
    guesses: Vec<(f64, [f64; MAX_STAGES])>,
    /// The Newton loop with its held matrix (tolerance and iteration limit per stage) and the
    /// work counters (an accepted step counts once, its Newton iterations over all stages).
    newton: Newton,
    pub(super) eta: f64,
    /// Stage accelerations A_j (n each).
    stage_acc: Vec<Vec<f64>>,
    trial: State,
    /// With `solver.error_tolerance` (and an embedded solution): every step's error estimate.
    control: Option<Box<ErrorControl>>,
}

impl Esdirk {
    /// New integrator of `tableau` for `n` coordinates and `m` constraints, with the Newton
    /// tolerance and iteration limit of `params`, and its error control if `params` has an
    /// `error_tolerance` and `tableau` an embedded solution.
    pub fn new(
        params: &IntegrationParameters,
        tableau: &'static Tableau,
        n: usize,
        m: usize,
    ) -> Self {
        Self {
            tableau,
            nodes: tableau.nodes(),
            a2: tableau.a_squared().to_vec(),
            guesses: (0..tableau.stages)
                .map(|i| guess_weights(&tableau.nodes(), usize::from(tableau.explicit_first), i))
                .collect(),
            newton: Newton::new(
                (params.newton_tolerance() * tableau.tolerance_factor).max(MIN_TOLERANCE),
                params.max_iterations,
                n + m,
            )
            .with_fixed(params.fixed_work()),
            eta: 1.0,
            stage_acc: vec![vec![0.0; n]; tableau.stages],
            trial: State::at_rest(0.0, vec![0.0; n], m),
            control: params.error_tolerance.and_then(|tolerance| {
                tableau.error_weights().map(|weights| {
                    Box::new(ErrorControl {
                        tolerance,
                        weights,
                        last: 0.0,
                        e_q: vec![0.0; n],
                        e_v: vec![0.0; n],
                        q: vec![0.0; n],
                        r0: vec![0.0; n + m],
                        r1: vec![0.0; n + m],
                    })
                })
            }),
        }
    }

    /// The last step's local error estimate in units of `solver.error_tolerance` (`None`
    /// without error control). Of an accepted step, or of the rejected attempt after it.
    pub fn step_error(&self) -> Option<f64> {
        self.control.as_ref().map(|c| c.last)
    }

    /// Work counters.
    pub fn counters(&self) -> &Counters {
        &self.newton.counters
    }

    /// Work counters, to count rejections.
    pub fn counters_mut(&mut self) -> &mut Counters {
        &mut self.newton.counters
    }

    /// Forgets the held Jacobian.
    pub fn invalidate(&mut self) {
        self.newton.invalidate();
    }

    /// The memory a snapshot must carry.
    pub fn memory(&self) -> IntegratorMemory {
        self.newton.memory(self.eta)
    }

    /// Restores memory: re-evaluates and factorizes the Newton matrix at its recorded point.
    pub fn restore_memory<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        mem: &IntegratorMemory,
    ) -> Result<(), StepFailure> {
        self.eta = mem.eta;
        let gamma = self.tableau.gamma();
        self.newton
            .restore(model, mem, |h| request(gamma * h, true))
    }

    /// Consistent initial accelerations and multipliers at `s` (q, q̇ given).
    pub fn initialize<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
    ) -> Result<(), StepFailure> {
        self.newton.consistent(model, s)
    }

    /// Inputs change at t_n: q̈ and λ there follow (a one-step method keeps no other memory;
    /// they are the next step's first guess, and an ESDIRK's first stage).
    pub fn change_inputs<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        change: impl FnOnce(&mut M),
    ) -> Result<(), StepFailure> {
        self.newton.jump(model, s, change)
    }

    /// One step of size `h` from `s`; `at(model, dt)` sets the model's time-dependent inputs
    /// (a mount's motion, varying loads) at t_n + dt before each implicit stage, the last one
    /// at t_n + h. On success `s` holds the new state (q̈ and the algorithmic acceleration those
    /// of the last stage); on failure `s` is untouched (the model holds the inputs of the stage
    /// that failed). An ESDIRK's explicit first stage is q̈ₙ of `s`: consistent at t_n, as the
    /// last stage of a stiffly accurate step, [`Self::initialize`] and [`Self::change_inputs`]
    /// leave it. With error control the step fails, `s` untouched, when its error estimate
    /// ([`Self::error_estimate`]) is above the tolerance.
    pub fn step<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        h: f64,
        mut at: impl FnMut(&mut M, f64),
    ) -> Result<usize, StepFailure> {
        let n = s.q.len();
        let m = s.lambda.len();
        let g = self.tableau.gamma() * h;
        let g2 = g * g;
        let stages = self.tableau.stages;
        let first = usize::from(self.tableau.explicit_first);
        let mut iterations = 0;
        // the rate estimate of earlier steps is trusted less as steps go by (Hairer & Wanner)
        let mut eta = math::pow(self.eta.max(f64::EPSILON), 0.8);
        for j in 0..m {
            self.trial.lambda[j] = g2 * s.lambda[j];
        }
        if first == 1 {
            self.stage_acc[0].copy_from_slice(&s.acc);
        }
        for i in first..stages {
            let c = self.nodes[i];
            at(model, c * h);
            // the stage's predictors without its own acceleration, then with the guess: the
            // accelerations known in this step (q̈_n at 0, the stages before) interpolated at c_i
            let guess = &self.guesses[i];
            let t = &mut self.trial;
            for k in 0..n {
                let (mut dq, mut dv) = (0.0, 0.0);
                for j in 0..i {
                    dq += self.a2[i][j] * self.stage_acc[j][k];
                    dv += self.tableau.a[i][j] * self.stage_acc[j][k];
                }
                let mut a = guess.0 * s.acc[k];
                for (j, w) in guess.1.iter().enumerate().take(i) {
                    a += w * self.stage_acc[j][k];
                }
                t.acc[k] = a;
                t.q[k] = s.q[k] + c * h * s.v[k] + h * h * dq + g2 * a;
                t.v[k] = s.v[k] + h * dv + g * a;
            }
            let (its, rate) = self.stage(model, h, eta)?;
            iterations += its;
            eta = rate;
            self.stage_acc[i].copy_from_slice(&self.trial.acc);
        }
        if let Some(mut c) = self.control.take() {
            let error = self.error_estimate(model, &mut c, h) / c.tolerance;
            c.last = error;
            self.control = Some(c);
            // a NaN estimate fails too
            if error.is_nan() || error > 1.0 {
                return Err(StepFailure::ErrorEstimate { h, error });
            }
        }
        self.eta = eta;
        let t = &mut self.trial;
        t.t = s.t + h;
        t.aux.copy_from_slice(&t.acc);
        for j in 0..m {
            t.lambda[j] /= g2;
        }
        std::mem::swap(s, t);
        self.newton.counters.steps += 1;
        Ok(iterations)
    }

    /// The local error estimate of the step of size `h` just solved (its end in the trial
    /// state), as the largest over the coordinates relative to their `scales`: the difference
    /// E = (e_q, e_v) between the step's solution and the embedded one
    /// ([`Tableau::error_weights`]), filtered by (I − γhJ)⁻¹ (J the Jacobian of the first-order
    /// system in (q, q̇)), as Hairer & Wanner recommend for stiff problems (*Solving ODEs II*,
    /// §IV.8, eq. (8.20), after Shampine): unfiltered, a stiff mode the L-stable step damps
    /// (an axial mode a tip force excites) shows in E at its full amplitude, whatever the step.
    /// Its position part x = e_q + γh w with (M + γhC + (γh)²K) w = M e_v − γhK e_q is the
    /// held Newton matrix's solve of r(q − γh e_q, q̇, q̈ + e_v) − r(q, q̇, q̈) (the residual's
    /// difference, rows scaled by (γh)², the constraint rows' too: x is tangent to the
    /// constraints) — two evaluations and one solve per step. Without stiffness x ≈ e_q + γh
    /// e_v: a velocity's error counts with γh, the distance it moves the position within the
    /// step; a stiff mode's x is its E over (γhω)². Only x is measured: the filtered velocity
    /// of a stiff mode is −e_q/(γh), no error of the step (Hairer & Wanner measure the
    /// filtered vector in the norm of y, where ω scales it; here no scale of time is known).
    fn error_estimate<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        c: &mut ErrorControl,
        h: f64,
    ) -> f64 {
        let (n, g) = (c.e_q.len(), self.tableau.gamma() * h);
        let t = &self.trial;
        for k in 0..n {
            let (mut eq, mut ev) = (0.0, 0.0);
            for (j, acc) in self.stage_acc.iter().enumerate() {
                eq += c.weights.q[j] * acc[k];
                ev += c.weights.v[j] * acc[k];
            }
            c.e_q[k] = h * h * eq;
            c.e_v[k] = h * ev;
        }
        // the perturbed state: q − γh e_q (through the model's increment), q̈ + e_v
        c.q.copy_from_slice(&t.q);
        for k in 0..n {
            c.r0[k] = -g * c.e_q[k];
            c.e_v[k] += t.acc[k];
        }
        model.increment(&mut c.q, &c.r0[..n]);
        let req = request(g, false);
        model.eval(StateRef::new(&t.q, &t.v, &t.acc, &t.lambda), req, &mut c.r0);
        model.eval(StateRef::new(&c.q, &t.v, &c.e_v, &t.lambda), req, &mut c.r1);
        for (r1, r0) in c.r1.iter_mut().zip(&c.r0) {
            *r1 -= r0;
        }
        if !model.solve(&mut c.r1) {
            return f64::NAN;
        }
        let mut worst = 0.0f64;
        for (k, scale) in model.scales().iter().enumerate() {
            let e = (c.e_q[k] + c.r1[k] / g).abs() / scale;
            // a NaN stays (f64::max would drop it)
            if e > worst || e.is_nan() {
                worst = e;
            }
        }
        worst
    }

    /// Newton on one stage from the trial state's guess; returns its iterations and the
    /// contraction estimate.
    fn stage<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        h: f64,
        eta: f64,
    ) -> Result<(usize, f64), StepFailure> {
        let g = self.tableau.gamma() * h;
        let rates = Rates {
            dv: 1.0 / g,
            da: 1.0 / (g * g),
            aux_div: None,
        };
        let done = self.newton.iterate(
            model,
            &mut self.trial,
            h,
            |matrix| request(g, matrix),
            rates,
            eta,
        );
        if matches!(done, Err(StepFailure::NoConvergence { .. })) {
            self.eta = 1.0;
        }
        done
    }
}

/// Weights of the first guess of stage i's acceleration: (on q̈_n at τ = 0, on the stages
/// j < i at τ = c_j), the Lagrange polynomial through the (up to) three of these points nearest
/// to c_i, evaluated there. With an explicit first stage (`first` = 1) q̈_n is that stage.
fn guess_weights(nodes: &[f64; MAX_STAGES], first: usize, i: usize) -> (f64, [f64; MAX_STAGES]) {
    // the points: index 0 is q̈_n, index j + 1 stage j
    let mut pts: Vec<(usize, f64)> = std::iter::repeat_n((0, 0.0), 1 - first)
        .chain((0..i).map(|j| (j + 1, nodes[j])))
        .collect();
    let c = nodes[i];
    pts.sort_by(|a, b| (a.1 - c).abs().total_cmp(&(b.1 - c).abs()));
    pts.truncate(3);
    let mut w = (0.0, [0.0; MAX_STAGES]);
    for &(k, tk) in &pts {
        let l: f64 = pts
            .iter()
            .filter(|p| p.0 != k)
            .map(|&(_, tj)| (c - tj) / (tk - tj))
            .product();
        if k == 0 {
            w.0 = l;
        } else {
            w.1[k - 1] = l;
        }
    }
    w
}

/// The evaluation request of a stage with `g` = γh: rows scaled by (γh)², the matrix
/// M + γh C + (γh)² K if `matrix`.
fn request(g: f64, matrix: bool) -> EvalRequest {
    EvalRequest {
        sd: g * g,
        matrix: matrix.then_some((1.0, g, g * g)),
        lambda_hessian: true,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{GeneralizedAlpha, Integrator, StateRef};
    use super::*;

    /// Hairer & Wanner's five-stage L-stable SDIRK of order 4 and stage order 1 (*Solving ODEs
    /// II*, §IV.6, Table 6.5), the integrator `solver.method = "sdirk4"` ran before [`ESDIRK4`]
    /// replaced it: kept here to show why. Its stage tolerance had to be 1/100 of `solver.tolerance` (its last row, weights up to
    /// 125/16, carries a stage's coordinate error ε into the step's velocity as ~160 ε/h).
    const SDIRK4: Tableau = Tableau::from_rows(
        &[
            &[0.25],
            &[0.5, 0.25],
            &[17.0 / 50.0, -1.0 / 25.0, 0.25],
            &[371.0 / 1360.0, -137.0 / 2720.0, 15.0 / 544.0, 0.25],
            &[25.0 / 24.0, -49.0 / 48.0, 125.0 / 16.0, -85.0 / 12.0, 0.25],
        ],
        false,
        0.01,
    );

    /// A swinging pendulum in its angle θ (no constraint rows): m L² θ̈ = −m g L sin θ +
    /// F(t) L cos θ, with F a smooth 3 Hz sine.
    struct Swing {
        force: f64,
        k: f64,
    }

    const M: f64 = 0.3;
    const L: f64 = 0.5;
    const G: f64 = 9.81;

    impl Integrable for Swing {
        fn coordinates(&self) -> usize {
            1
        }
        fn constraints(&self) -> usize {
            0
        }
        fn scales(&self) -> &[f64] {
            &[1.0]
        }
        fn eval(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]) {
            let (th, a) = (x.q[0], x.a[0]);
            let f = x.load * self.force;
            res[0] = req.sd * (M * L * L * a + M * G * L * th.sin() - f * L * th.cos());
            if let Some((ca, _, cx)) = req.matrix {
                self.k = ca * M * L * L + cx * (M * G * L * th.cos() + f * L * th.sin());
            }
        }
        fn factorize(&mut self) -> Result<(), crate::linalg::SingularMatrix> {
            Ok(())
        }
        fn solve(&mut self, rhs: &mut [f64]) -> bool {
            rhs[0] /= self.k;
            rhs[0].is_finite()
        }
    }

    fn force(t: f64) -> f64 {
        2.0 * (2.0 * std::f64::consts::PI * 3.0 * t).sin()
    }

    fn params() -> IntegrationParameters {
        IntegrationParameters {
            tolerance: Some(1e-14),
            max_iterations: 20,
            ..Default::default()
        }
    }

    /// A forced pendulum model: the force F(t) it is driven by.
    trait Forced: Integrable {
        fn set_force(&mut self, f: f64);
    }

    impl Forced for Swing {
        fn set_force(&mut self, f: f64) {
            self.force = f;
        }
    }

    /// `angle(state)` every 10 ms over 0.4 s from `s`, `k` steps per 10 ms, with the tableau
    /// (the force set at every stage time) or generalized-α (None: at every step's end).
    fn drive<M: Forced>(
        mut model: M,
        mut s: State,
        k: usize,
        tableau: Option<&'static Tableau>,
        angle: fn(&State) -> f64,
    ) -> Vec<f64> {
        let (n, m) = (model.coordinates(), model.constraints());
        let mut integ = match tableau {
            Some(tab) => Integrator::Esdirk(Esdirk::new(&params(), tab, n, m)),
            None => Integrator::Alpha(GeneralizedAlpha::new(&params(), n, m)),
        };
        model.set_force(force(0.0));
        integ.initialize(&mut model, &mut s).unwrap();
        let h = 0.01 / k as f64;
        let mut out = Vec::new();
        for _ in 0..40 {
            for _ in 0..k {
                let t0 = s.t;
                integ
                    .step(&mut model, &mut s, h, |m, dt| m.set_force(force(t0 + dt)))
                    .unwrap();
            }
            out.push(angle(&s));
        }
        out
    }

    /// θ of the angle pendulum from rest at 0.5 rad ([`drive`]).
    fn swing(k: usize, tableau: Option<&'static Tableau>) -> Vec<f64> {
        let model = Swing { force: 0.0, k: 0.0 };
        drive(model, State::at_rest(0.0, vec![0.5], 0), k, tableau, |s| {
            s.q[0]
        })
    }

    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// Each tableau's error against its own converged run (128 steps per 10 ms) falls at about
    /// fourth order as the step halves; that run meets generalized-α converged (4096 steps, second
    /// order: its error is ~4e-11 rad from its 2.4e-6 at 16 steps), an independent integrator,
    /// to 1e-10 rad; and 2 steps per 10 ms beat generalized-α at 16.
    #[test]
    fn converges_at_fourth_order_to_generalized_alpha() {
        let reference = swing(4096, None);
        let ga16 = max_diff(&swing(16, None), &reference);
        for tab in [&SDIRK4, &ESDIRK4] {
            let fine = swing(128, Some(tab));
            let errors: Vec<f64> = [1, 2, 4, 8]
                .into_iter()
                .map(|k| max_diff(&swing(k, Some(tab)), &fine))
                .collect();
            let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
            let agree = max_diff(&fine, &reference);
            println!(
                "{} stages: errors {errors:?} rad, orders {orders:.2?}; generalized-α at 16: \
                 {ga16:e}; 128 steps vs generalized-α 4096: {agree:e}",
                tab.stages
            );
            // SDIRK4 3.88, 3.00, 3.93: fourth order, one pre-asymptotic halving
            let mean = (errors[0] / errors[3]).log2() / 3.0;
            assert!(mean > 3.5 && orders.iter().all(|p| *p > 2.8), "{orders:?}");
            assert!(agree < 1e-10, "{agree}");
            assert!(errors[1] < ga16, "{} vs {ga16}", errors[1]);
        }
    }

    /// The same pendulum in Cartesian coordinates (x, y) of its bob held by the index-3 rod
    /// constraint (x² + y² − L²)/(2L) = 0: a curved constraint manifold.
    struct Rod {
        force: f64,
        k: [[f64; 3]; 3],
    }

    impl Integrable for Rod {
        fn coordinates(&self) -> usize {
            2
        }
        fn constraints(&self) -> usize {
            1
        }
        fn scales(&self) -> &[f64] {
            &[L, L]
        }
        fn eval(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]) {
            let (px, py, lam) = (x.q[0], x.q[1], x.lambda[0]);
            let f = x.load * self.force;
            res[0] = req.sd * (M * x.a[0] - f) + lam * px / L;
            res[1] = req.sd * (M * x.a[1] + M * G) + lam * py / L;
            res[2] = (px * px + py * py - L * L) / (2.0 * L);
            if let Some((ca, _, _)) = req.matrix {
                let d = ca * M + lam / L;
                self.k = [[d, 0.0, px / L], [0.0, d, py / L], [px / L, py / L, 0.0]];
            }
        }
        fn factorize(&mut self) -> Result<(), crate::linalg::SingularMatrix> {
            Ok(())
        }
        fn solve(&mut self, rhs: &mut [f64]) -> bool {
            // Cramer's rule on the 3×3 saddle point matrix
            let k = &self.k;
            let det = |m: [[f64; 3]; 3]| {
                m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
            };
            let d = det(*k);
            let b = [rhs[0], rhs[1], rhs[2]];
            for (c, r) in rhs.iter_mut().enumerate().take(3) {
                let mut m = *k;
                for i in 0..3 {
                    m[i][c] = b[i];
                }
                *r = det(m) / d;
            }
            rhs.iter().all(|x| x.is_finite())
        }
    }

    impl Forced for Rod {
        fn set_force(&mut self, f: f64) {
            self.force = f;
        }
    }

    /// θ = atan2(x, −y) of the rod pendulum from rest at 0.5 rad ([`drive`]).
    fn rod(k: usize, tableau: Option<&'static Tableau>) -> Vec<f64> {
        let model = Rod {
            force: 0.0,
            k: [[0.0; 3]; 3],
        };
        let s = State::at_rest(0.0, vec![L * 0.5f64.sin(), -L * 0.5f64.cos()], 1);
        drive(model, s, k, tableau, |s| s.q[0].atan2(-s.q[1]))
    }

    /// On the rod's curved constraint, against the angle pendulum converged with
    /// generalized-α (an independent formulation and integrator): the stage-order-1 SDIRK4 falls
    /// to first order (1.02); ESDIRK4 (stage order 2) converges at about second order (1.9 from
    /// 2 to 8 steps per 10 ms; at 16 steps, ~3e-8 rad, it meets the round-off of its stage
    /// accelerations, ε/(γh)²), is at 2 steps per 10 ms already more accurate than
    /// generalized-α at 16, and at 8 steps 1900 times closer than SDIRK4.
    #[test]
    fn order_on_a_curved_constraint() {
        let reference = swing(4096, None);
        let ks = [2, 4, 8, 16];
        let errors = |tab: Option<&'static Tableau>| -> Vec<f64> {
            ks.iter()
                .map(|&k| max_diff(&rod(k, tab), &reference))
                .collect()
        };
        let order = |e: &[f64]| (e[0] / e[2]).log2() / 2.0;
        let (sd, es, ga) = (errors(Some(&SDIRK4)), errors(Some(&ESDIRK4)), errors(None));
        println!(
            "rod at {ks:?} steps per 10 ms: SDIRK4 {sd:?} (order {:.2}), ESDIRK4 {es:?} \
             (order {:.2}), generalized-α {ga:?} (order {:.2}) rad",
            order(&sd),
            order(&es),
            order(&ga)
        );
        assert!(order(&sd) < 1.3, "{sd:?}");
        assert!(order(&es) > 1.5, "{es:?}");
        assert!(es[0] < ga[3], "{es:?} vs {ga:?}");
        assert!(es[2] * 100.0 < sd[2], "{es:?} vs {sd:?}");
    }

    /// Σ b_i Φ_i(c, 𝔄) for the order conditions of `tab` up to order 4 with weights `b`
    /// (Hairer & Wanner Table 6.5 / Butcher trees), against their values.
    fn order_conditions(tab: &Tableau, b: &[f64; MAX_STAGES], order: usize) {
        let s = tab.stages;
        let a = &tab.a;
        let c = tab.nodes();
        let dot = |f: &dyn Fn(usize) -> f64| (0..s).map(|i| b[i] * f(i)).sum::<f64>();
        let ac = |i: usize| (0..s).map(|j| a[i][j] * c[j]).sum::<f64>();
        let ac2 = |i: usize| (0..s).map(|j| a[i][j] * c[j] * c[j]).sum::<f64>();
        let aac = |i: usize| (0..s).map(|j| a[i][j] * ac(j)).sum::<f64>();
        let checks = [
            (1, dot(&|_| 1.0), 1.0),
            (2, dot(&|i| c[i]), 0.5),
            (3, dot(&|i| c[i] * c[i]), 1.0 / 3.0),
            (3, dot(&ac), 1.0 / 6.0),
            (4, dot(&|i| c[i].powi(3)), 0.25),
            (4, dot(&|i| c[i] * ac(i)), 0.125),
            (4, dot(&ac2), 1.0 / 12.0),
            (4, dot(&aac), 1.0 / 24.0),
        ];
        for (k, (p, got, want)) in checks.iter().enumerate() {
            if *p <= order {
                assert!((got - want).abs() < 1e-14, "condition {k}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn tableaus_are_stiffly_accurate_and_of_order_four() {
        for tab in [SDIRK4, ESDIRK4] {
            let c = tab.nodes();
            assert!(
                (c[tab.stages - 1] - 1.0).abs() < 1e-15,
                "stiffly accurate: c_s = 1"
            );
            for i in 0..tab.stages {
                let first = i == 0 && tab.explicit_first;
                assert_eq!(
                    tab.a[i][i],
                    if first { 0.0 } else { tab.gamma() },
                    "diagonal {i}"
                );
                assert!(tab.a[i][i + 1..].iter().all(|x| *x == 0.0), "row {i}");
            }
            order_conditions(&tab, &tab.a[tab.stages - 1], 4);
        }
        // ESDIRK4 has stage order 2: Σ_j a_ij c_j = c_i²/2 at every stage
        let c = ESDIRK4.nodes();
        for i in 0..ESDIRK4.stages {
            let ac: f64 = (0..ESDIRK4.stages).map(|j| ESDIRK4.a[i][j] * c[j]).sum();
            assert!(
                (ac - c[i] * c[i] / 2.0).abs() < 1e-15,
                "stage order 2 at {i}"
            );
        }
        // the published nodes
        let want = [0.0, 0.5, 83.0 / 250.0, 31.0 / 50.0, 17.0 / 20.0, 1.0];
        for (got, want) in c.iter().zip(want) {
            assert!((got - want).abs() < 1e-15);
        }
        assert!((SDIRK4.nodes()[2] - 11.0 / 20.0).abs() < 1e-15);
    }

    /// The embedded weights b̂ (SUNDIALS' `d` of ARK436L2SA_DIRK_6_3_4) meet the order
    /// conditions up to 3 and miss one of order 4 (else the estimate would vanish at h⁴).
    /// The largest error estimate (`error_tolerance` = 1: in absolute units of the scales)
    /// over 0.1 s of the forced pendulum `model` from `s`, in steps of 10 ms / k.
    fn largest_estimate<M: Forced>(mut model: M, mut s: State, k: usize) -> f64 {
        let (n, m) = (model.coordinates(), model.constraints());
        let p = IntegrationParameters {
            error_tolerance: Some(1.0),
            ..params()
        };
        let mut integ = Esdirk::new(&p, &ESDIRK4, n, m);
        model.set_force(force(0.0));
        integ.initialize(&mut model, &mut s).unwrap();
        let h = 0.01 / k as f64;
        let mut worst = 0.0f64;
        for _ in 0..10 * k {
            let t0 = s.t;
            integ
                .step(&mut model, &mut s, h, |m, dt| m.set_force(force(t0 + dt)))
                .unwrap();
            worst = worst.max(integ.step_error().unwrap());
        }
        worst
    }

    /// The error estimate of the embedded solution goes as h⁴ on the angle pendulum (the
    /// local error of order 3: measured 4.00 per halving), the exponent of the step control
    /// ([`super::super::control`]), and so on the rod's curved index-3 constraint (4.01, 4.01,
    /// 3.91, then the round-off of its 1e-14 Newton tolerance, ~1e-12): the filtered estimate
    /// is tangent to the constraint. Unfiltered its normal part, the embedded solution's
    /// violation of the constraint, went as h³ (3.28, 3.08, 3.02, 3.00), the order reduction
    /// of [`order_on_a_curved_constraint`].
    #[test]
    fn the_estimate_goes_as_the_fourth_power_of_the_step() {
        let ks = [1, 2, 4, 8, 16];
        let orders =
            |e: &[f64]| -> Vec<f64> { e.windows(2).map(|w| (w[0] / w[1]).log2()).collect() };
        let swing: Vec<f64> = ks
            .iter()
            .map(|&k| {
                largest_estimate(
                    Swing { force: 0.0, k: 0.0 },
                    State::at_rest(0.0, vec![0.5], 0),
                    k,
                )
            })
            .collect();
        let rod: Vec<f64> = ks
            .iter()
            .map(|&k| {
                let q = vec![L * 0.5f64.sin(), -L * 0.5f64.cos()];
                largest_estimate(
                    Rod {
                        force: 0.0,
                        k: [[0.0; 3]; 3],
                    },
                    State::at_rest(0.0, q, 1),
                    k,
                )
            })
            .collect();
        let (os, or) = (orders(&swing), orders(&rod));
        println!("estimates: angle {swing:?} (orders {os:.2?}), rod {rod:?} (orders {or:.2?})");
        assert!(os.iter().all(|p| (p - 4.0).abs() < 0.2), "{os:?}");
        assert!(or[..3].iter().all(|p| (p - 4.0).abs() < 0.2), "{or:?}");
    }

    #[test]
    fn the_embedded_solution_is_of_order_three() {
        let b_hat = ESDIRK4.embedded.unwrap();
        order_conditions(&ESDIRK4, &b_hat, 3);
        let c = ESDIRK4.nodes();
        let fourth: f64 = (0..6).map(|i| b_hat[i] * c[i].powi(3)).sum();
        assert!((fourth - 0.25).abs() > 1e-4, "{fourth}");
    }
}
