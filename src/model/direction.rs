//! The clamp of an ANCF root node's slope direction: the rows `n_i · r_x = 0` for the held
//! normals n_i of the clamped direction (one in the plane, two in space), so the clamp holds
//! the slope's direction and leaves its length, the root's axial stretch, free
//! (docs/engine-findings.md). The normals are held coordinates that turn with a mount; the
//! support's moment is Σ n_i × r_{n_i} (their residual is λ_i r_x).

use super::component::{Constraint, ConstraintOut};

/// Rows `n_i · r_x = 0` on local coordinates `[r_x (dim), n_1 (dim), …, n_k (dim)]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopeDirection {
    /// Components of a vector (2 or 3).
    pub dim: usize,
    /// Number of normals (rows): dim − 1.
    pub normals: usize,
}

impl Constraint for SlopeDirection {
    fn rows(&self) -> usize {
        self.normals
    }

    fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut) {
        let (m, d) = (self.dim, q.len());
        for i in 0..self.normals {
            let n = (1 + i) * m;
            let mut phi = 0.0;
            for c in 0..m {
                phi += q[n + c] * q[c];
                out.jac[i * d + c] = q[n + c];
                out.jac[i * d + n + c] = q[c];
            }
            out.phi[i] = phi;
            if let Some(l) = lambda {
                for c in 0..m {
                    out.hess.push((c, n + c, l[i]));
                    out.hess.push((n + c, c, l[i]));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ, Φ_q and Σλ∂²Φ against central differences of Φ.
    #[test]
    fn rows_and_derivatives_match_differences() {
        let c = SlopeDirection { dim: 3, normals: 2 };
        let q = [1.02, 0.1, -0.05, 0.0, 0.8, 0.6, 0.1, -0.6, 0.8];
        let lam = [0.7, -1.3];
        let mut out = ConstraintOut::default();
        out.reset(2, 9);
        c.eval(&q, Some(&lam), &mut out);
        let phi = |q: &[f64]| {
            let mut o = ConstraintOut::default();
            o.reset(2, 9);
            c.eval(q, None, &mut o);
            o.phi
        };
        let h = 1e-6;
        for k in 0..9 {
            let (mut a, mut b) = (q, q);
            a[k] += h;
            b[k] -= h;
            let (pa, pb) = (phi(&a), phi(&b));
            for r in 0..2 {
                let fd = (pa[r] - pb[r]) / (2.0 * h);
                assert!((fd - out.jac[r * 9 + k]).abs() < 1e-9, "row {r} col {k}");
            }
        }
        // Σλ ∂²Φ: ∂²Φ_i/∂r_x,c ∂n_i,c = 1
        let mut hess = [[0.0; 9]; 9];
        for &(i, j, v) in &out.hess {
            hess[i][j] += v;
        }
        assert_eq!(hess[0][3], 0.7);
        assert_eq!(hess[6][0], -1.3);
        assert_eq!(hess[0][0], 0.0);
    }
}
