//! The seam between the integrators and a model: what the integrators may ask.

use crate::linalg::SingularMatrix;

/// A state at which a model is evaluated: coordinates, their rates, multipliers, and the
/// load factor of statics.
#[derive(Debug, Clone, Copy)]
pub struct StateRef<'a> {
    /// Coordinates q (n).
    pub q: &'a [f64],
    /// Velocities q̇ (n).
    pub v: &'a [f64],
    /// Accelerations q̈ (n).
    pub a: &'a [f64],
    /// Multipliers λ̃ (m), scaled as the constraint rows of the request are.
    pub lambda: &'a [f64],
    /// Factor on the external loads (gravity, tip force): 1 in dynamics, raised from 0 to 1 by
    /// the load stepping of statics.
    pub load: f64,
}

impl<'a> StateRef<'a> {
    /// The state (q, q̇, q̈, λ̃) under the full loads.
    pub fn new(q: &'a [f64], v: &'a [f64], a: &'a [f64], lambda: &'a [f64]) -> Self {
        Self {
            q,
            v,
            a,
            lambda,
            load: 1.0,
        }
    }

    /// The same state with the external loads scaled by `load` (statics).
    pub fn with_load(self, load: f64) -> Self {
        Self { load, ..self }
    }
}

/// What [`Integrable::eval`] should produce.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EvalRequest {
    /// Row scale s_d of the dynamic equations [s²]: βh² in generalized-α (so that the
    /// multipliers come out as λ̃ = βh²λ and the matrix is O(1) in h), 1 in statics.
    pub sd: f64,
    /// Matrix coefficients (c_a, c_v, c_x) if the Newton matrix
    /// `c_a·M + c_v·C + c_x·K (+ Σλ̃_i ∂²Φ_i)` is wanted.
    pub matrix: Option<(f64, f64, f64)>,
    /// Include Σλ̃_i ∂²Φ_i in the matrix.
    pub lambda_hessian: bool,
}

/// A second-order system with holonomic constraints, as the integrators see it:
/// `s_d·(M(q) q̈ + f(q, q̇) − load·f_ext(q)) + Φ_qᵀ λ̃ = 0` (n rows), `Φ(q) = 0` (m rows).
pub trait Integrable {
    /// Number of coordinates n.
    fn coordinates(&self) -> usize;

    /// Number of constraint rows m.
    fn constraints(&self) -> usize;

    /// Characteristic magnitude of each coordinate (n), for scaled Newton norms.
    fn scales(&self) -> &[f64];

    /// Residuals at `x` into `res` (n + m) and, if `req.matrix` asks for it, the Newton matrix
    /// (held for [`Integrable::factorize`]).
    fn eval(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]);

    /// Factorizes the matrix of the last [`Integrable::eval`] with a matrix request.
    fn factorize(&mut self) -> Result<(), SingularMatrix>;

    /// Solves with the held factorization in place; false if the result is not finite.
    fn solve(&mut self, rhs: &mut [f64]) -> bool;

    /// Φ at `q` (m rows into `out`) with the held (eliminated) coordinates moved `dt` [s] along
    /// their prescribed motion (value + ḣ dt + ½ ḧ dt²): the second difference along (q̇, ḣ)
    /// gives the acceleration-level constraint of a moving support. Default: Φ(q) through
    /// [`Integrable::eval`] (held coordinates that do not move).
    fn constraint_values(&mut self, q: &[f64], _dt: f64, out: &mut [f64]) {
        constraint_rows(self, q, out);
    }

    /// Whether held coordinates follow a prescribed motion (a driven support; default: no).
    fn is_driven(&self) -> bool {
        false
    }

    /// How fast the held coordinates move: max |ḣ| + √max |ḧ| (held values in m or unit
    /// directions) [1/s]; 0 when they are fixed (the default).
    fn held_rate(&self) -> f64 {
        0.0
    }

    /// The matrix assembled by the last [`Integrable::eval`] with a matrix request, as dense
    /// rows, where the model can give it (dense analyses of small models); `None` by default.
    fn dense_matrix(&self) -> Option<Vec<Vec<f64>>> {
        None
    }

    /// Applies a Newton increment `dq` (n) to the coordinates `q` (Chrono's
    /// `StateIncrementX`). Additive by default; a model whose coordinates live on a manifold
    /// (Euler parameters) may override it. Rates and accelerations stay additive.
    fn increment(&self, q: &mut [f64], dq: &[f64]) {
        for (q, d) in q.iter_mut().zip(dq) {
            *q += d;
        }
    }
}

/// Φ(q) (m rows into `out`) through [`Integrable::eval`] at rest under no load (allocates its
/// working memory: the default of [`Integrable::constraint_values`]; a model that evaluates
/// its constraints in a step overrides that, as `Model` does).
pub fn constraint_rows<M: Integrable + ?Sized>(model: &mut M, q: &[f64], out: &mut [f64]) {
    let (n, m) = (model.coordinates(), model.constraints());
    let zeros = vec![0.0; n.max(m)];
    let mut r = vec![0.0; n + m];
    let req = EvalRequest {
        sd: 0.0,
        matrix: None,
        lambda_hessian: false,
    };
    let x = StateRef::new(q, &zeros[..n], &zeros[..n], &zeros[..m]).with_load(0.0);
    model.eval(x, req, &mut r);
    out.copy_from_slice(&r[n..]);
}
