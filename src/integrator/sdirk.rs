//! A singly diagonally implicit Runge–Kutta method of order 4 for the index-3 system of
//! [`Integrable`]: Hairer & Wanner's L-stable, stiffly accurate five-stage SDIRK (γ = 1/4;
//! *Solving ODEs II*, §IV.6, Table 6.5; docs/references.md §8).
//!
//! Written on y = (q, q̇) with stage accelerations A_j: Q_i = q_n + c_i h q̇_n + h² Σ_j (𝔄²)_ij A_j,
//! V_i = q̇_n + h Σ_j 𝔄_ij A_j, where 𝔄 is the method's matrix; stage i solves the equations of
//! motion and Φ(Q_i) = 0 at t_n + c_i h for A_i, which enters Q_i with (γh)² and V_i with γh:
//! Newton on ΔQ_i with the matrix M + γh C + (γh)² K (the dynamic rows scaled by (γh)², the
//! multipliers λ̃ = (γh)²λ), the same matrix for every stage, held across stages and steps while
//! Newton contracts well. Stiffly accurate: the step ends on the last stage (c = 1), so
//! Φ(q_{n+1}) = 0 holds as in generalized-α, and R(∞) = 0 damps the unresolved modes.
//!
//! Why: generalized-α's phase error (ωh)²/12 per unit of phase is what limits a released rod's
//! accuracy at common steps (its 3rd bending mode at 160 Hz drifts by 1.6 rad over 2 s at
//! h = 1e-4 s); this method's is of order (ωh)⁴, at five solves per step with one matrix.

use super::newton::{Newton, Rates};
use super::{
    Counters, EvalRequest, Integrable, IntegrationParameters, IntegratorMemory, State, StepFailure,
    MIN_TOLERANCE,
};
use crate::math;

/// Stages of the method.
pub const STAGES: usize = 5;

/// The stages' Newton tolerance as a fraction of `solver.tolerance`. A stage's coordinate
/// error ε becomes an acceleration error ε/(γh)², which the last row of 𝔄 (weights up to
/// 125/16) carries into the step's velocity as ~160 ε/h, about 80 times what generalized-α
/// makes of the same ε (2ε/h); measured on the spatial Case 1 cable (16 elements, h = 5e-4 s):
/// at stage tolerance 1e-11 the tip error against the reference depended on the Newton's first
/// guesses by 3e-5 m, at 1e-13 and 1e-14 it stays 9.2–9.9e-6 m.
const STAGE_TOLERANCE_FACTOR: f64 = 0.01;

/// γ, the diagonal of the method's matrix.
const GAMMA: f64 = 0.25;

/// The method's matrix 𝔄 (lower triangular, γ on the diagonal; its last row is b).
const A: [[f64; STAGES]; STAGES] = [
    [0.25, 0.0, 0.0, 0.0, 0.0],
    [0.5, 0.25, 0.0, 0.0, 0.0],
    [17.0 / 50.0, -1.0 / 25.0, 0.25, 0.0, 0.0],
    [371.0 / 1360.0, -137.0 / 2720.0, 15.0 / 544.0, 0.25, 0.0],
    [25.0 / 24.0, -49.0 / 48.0, 125.0 / 16.0, -85.0 / 12.0, 0.25],
];

/// The stage times c_i = Σ_j 𝔄_ij as fractions of the step.
pub const NODES: [f64; STAGES] = [0.25, 0.75, 11.0 / 20.0, 0.5, 1.0];

/// 𝔄² (the positions' weights of the stage accelerations).
fn a_squared() -> [[f64; STAGES]; STAGES] {
    let mut a2 = [[0.0; STAGES]; STAGES];
    for (i, row) in a2.iter_mut().enumerate() {
        for (k, x) in row.iter_mut().enumerate() {
            *x = (0..STAGES).map(|j| A[i][j] * A[j][k]).sum();
        }
    }
    a2
}

/// The integrator with its work arrays and Jacobian policy.
#[derive(Debug, Clone)]
pub struct Sdirk {
    a2: [[f64; STAGES]; STAGES],
    /// The Newton loop with its held matrix (tolerance and iteration limit per stage) and the
    /// work counters (an accepted step counts once, its Newton iterations over all stages).
    newton: Newton,
    eta: f64,
    /// Stage accelerations A_j (n each).
    stage_acc: Vec<Vec<f64>>,
    trial: State,
}

impl Sdirk {
    /// New integrator for `n` coordinates and `m` constraints, with the Newton tolerance and
    /// iteration limit of `params`.
    pub fn new(params: &IntegrationParameters, n: usize, m: usize) -> Self {
        Self {
            a2: a_squared(),
            newton: Newton::new(
                (params.tolerance * STAGE_TOLERANCE_FACTOR).max(MIN_TOLERANCE),
                params.max_iterations,
                n + m,
            ),
            eta: 1.0,
            stage_acc: vec![vec![0.0; n]; STAGES],
            trial: State::at_rest(0.0, vec![0.0; n], m),
        }
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
        self.newton.restore(model, mem, |h| request(h, true))
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
    /// they are the next step's first guess).
    pub fn change_inputs<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        change: impl FnOnce(&mut M),
    ) -> Result<(), StepFailure> {
        self.newton.jump(model, s, change)
    }

    /// One step of size `h` from `s`; `at(model, dt)` sets the model's time-dependent inputs
    /// (a mount's motion, varying loads) at t_n + dt before each stage, the last one at
    /// t_n + h. On success `s` holds the new state (q̈ and the algorithmic acceleration those of
    /// the last stage); on failure `s` is untouched (the model holds the inputs of the stage
    /// that failed).
    pub fn step<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        s: &mut State,
        h: f64,
        mut at: impl FnMut(&mut M, f64),
    ) -> Result<usize, StepFailure> {
        let n = s.q.len();
        let m = s.lambda.len();
        let g = GAMMA * h;
        let g2 = g * g;
        let mut iterations = 0;
        // the rate estimate of earlier steps is trusted less as steps go by (Hairer & Wanner)
        let mut eta = math::pow(self.eta.max(f64::EPSILON), 0.8);
        for j in 0..m {
            self.trial.lambda[j] = g2 * s.lambda[j];
        }
        for i in 0..STAGES {
            at(model, NODES[i] * h);
            // the stage's predictors without its own acceleration, then with the guess: the
            // accelerations known in this step (q̈_n at 0, the stages before) interpolated at c_i
            let guess = guess_weights(i);
            let t = &mut self.trial;
            for k in 0..n {
                let (mut dq, mut dv) = (0.0, 0.0);
                for j in 0..i {
                    dq += self.a2[i][j] * self.stage_acc[j][k];
                    dv += A[i][j] * self.stage_acc[j][k];
                }
                let mut a = guess.0 * s.acc[k];
                for (j, w) in guess.1.iter().enumerate().take(i) {
                    a += w * self.stage_acc[j][k];
                }
                t.acc[k] = a;
                t.q[k] = s.q[k] + NODES[i] * h * s.v[k] + h * h * dq + g2 * a;
                t.v[k] = s.v[k] + h * dv + g * a;
            }
            let (its, rate) = self.stage(model, h, eta)?;
            iterations += its;
            eta = rate;
            self.stage_acc[i].copy_from_slice(&self.trial.acc);
        }
        self.eta = eta;
        let t = &mut self.trial;
        t.t = s.t + h;
        t.aux.copy_from_slice(&t.acc);
        for j in 0..m {
            t.lambda[j] /= g2;
        }
        std::mem::swap(s, t);
        // the next step's first guess of the scaled multipliers
        self.newton.counters.steps += 1;
        Ok(iterations)
    }

    /// Newton on one stage from the trial state's guess; returns its iterations and the
    /// contraction estimate.
    fn stage<M: Integrable + ?Sized>(
        &mut self,
        model: &mut M,
        h: f64,
        eta: f64,
    ) -> Result<(usize, f64), StepFailure> {
        let g = GAMMA * h;
        let rates = Rates {
            dv: 1.0 / g,
            da: 1.0 / (g * g),
            aux_div: None,
        };
        let done = self.newton.iterate(
            model,
            &mut self.trial,
            h,
            |matrix| request(h, matrix),
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
/// to c_i, evaluated there.
fn guess_weights(i: usize) -> (f64, [f64; STAGES]) {
    // the points: index 0 is q̈_n, index j + 1 stage j
    let mut pts: Vec<(usize, f64)> = std::iter::once((0, 0.0))
        .chain((0..i).map(|j| (j + 1, NODES[j])))
        .collect();
    let c = NODES[i];
    pts.sort_by(|a, b| (a.1 - c).abs().total_cmp(&(b.1 - c).abs()));
    pts.truncate(3);
    let mut w = (0.0, [0.0; STAGES]);
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

/// The evaluation request of a stage at step `h`: rows scaled by (γh)², the matrix
/// M + γh C + (γh)² K if `matrix`.
fn request(h: f64, matrix: bool) -> EvalRequest {
    let g = GAMMA * h;
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
            tolerance: 1e-14,
            max_iterations: 20,
            ..Default::default()
        }
    }

    /// θ every 10 ms over 0.4 s from rest at 0.5 rad, `k` steps per 10 ms, with SDIRK (the
    /// force set at every stage time) or generalized-α (at every step's end).
    fn swing(k: usize, sdirk: bool) -> Vec<f64> {
        let mut model = Swing {
            force: force(0.0),
            k: 0.0,
        };
        let mut s = State::at_rest(0.0, vec![0.5], 0);
        let mut integ = if sdirk {
            Integrator::Sdirk(Sdirk::new(&params(), 1, 0))
        } else {
            Integrator::Alpha(GeneralizedAlpha::new(&params(), 1, 0))
        };
        integ.initialize(&mut model, &mut s).unwrap();
        let h = 0.01 / k as f64;
        let mut out = Vec::new();
        for _ in 0..40 {
            for _ in 0..k {
                let t0 = s.t;
                integ
                    .step(&mut model, &mut s, h, |m, dt| m.force = force(t0 + dt))
                    .unwrap();
            }
            out.push(s.q[0]);
        }
        out
    }

    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// The SDIRK's error against its own converged run (128 steps per 10 ms) falls at about
    /// fourth order as the step halves; that run meets generalized-α converged (4096 steps, second
    /// order: its error is ~4e-11 rad from its 2.4e-6 at 16 steps), an independent integrator,
    /// to 1e-10 rad; and 2 SDIRK steps per 10 ms beat generalized-α at 16.
    #[test]
    fn converges_at_fourth_order_to_generalized_alpha() {
        let fine = swing(128, true);
        let errors: Vec<f64> = [1, 2, 4, 8]
            .into_iter()
            .map(|k| max_diff(&swing(k, true), &fine))
            .collect();
        let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        let reference = swing(4096, false);
        let (ga16, agree) = (
            max_diff(&swing(16, false), &reference),
            max_diff(&fine, &reference),
        );
        println!(
            "SDIRK errors {errors:?} rad, orders {orders:.2?}; generalized-α at 16: {ga16:e}; \
             SDIRK 128 vs generalized-α 4096: {agree:e}"
        );
        // 3.88, 3.00, 3.93 here: fourth order, one pre-asymptotic halving; 3.6 on average
        let mean = (errors[0] / errors[3]).log2() / 3.0;
        assert!(mean > 3.5 && orders.iter().all(|p| *p > 2.8), "{orders:?}");
        assert!(agree < 1e-10, "{agree}");
        assert!(errors[1] < ga16, "{} vs {ga16}", errors[1]);
    }

    #[test]
    fn tableau_is_stiffly_accurate_and_of_order_four() {
        // order conditions up to 4 on b = last row, c = row sums (Hairer & Wanner Table 6.5)
        let b = A[STAGES - 1];
        for (i, row) in A.iter().enumerate() {
            let c: f64 = row.iter().sum();
            assert!((c - NODES[i]).abs() < 1e-15, "c_{i}");
        }
        let c = NODES;
        let dot = |f: &dyn Fn(usize) -> f64| (0..STAGES).map(|i| b[i] * f(i)).sum::<f64>();
        let ac = |i: usize| (0..STAGES).map(|j| A[i][j] * c[j]).sum::<f64>();
        let ac2 = |i: usize| (0..STAGES).map(|j| A[i][j] * c[j] * c[j]).sum::<f64>();
        let aac = |i: usize| (0..STAGES).map(|j| A[i][j] * ac(j)).sum::<f64>();
        let checks = [
            (dot(&|_| 1.0), 1.0),
            (dot(&|i| c[i]), 0.5),
            (dot(&|i| c[i] * c[i]), 1.0 / 3.0),
            (dot(&ac), 1.0 / 6.0),
            (dot(&|i| c[i].powi(3)), 0.25),
            (dot(&|i| c[i] * ac(i)), 0.125),
            (dot(&ac2), 1.0 / 12.0),
            (dot(&aac), 1.0 / 24.0),
        ];
        for (k, (got, want)) in checks.iter().enumerate() {
            assert!((got - want).abs() < 1e-14, "condition {k}: {got} vs {want}");
        }
    }
}
