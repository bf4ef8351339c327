//! Planar floating-frame body with transverse modal coordinates (docs/references.md §3): the
//! kernel of [`crate::model::planar::ModalElement`].
//!
//! Local coordinates `q = [Rx, Ry, θ, a_1 … a_n]`: frame origin R [m] (the segment root),
//! frame angle θ [rad] (counter-clockwise from global x), modal amplitudes a [m]. A material
//! point at x ∈ [0, L] is at r = R + A(θ)[x; Σ φ_k(x/L) a_k]. The shapes are mass-orthonormal
//! (∫ρA φ_iφ_j dx = ρAL δ_ij) and stiffness-diagonal, so M_ff = ρAL·I and K_ff = diag(EIΛ_k/L³).
//! Linear FFRF inside the segment (no distributed geometric stiffening); the tip position used
//! by joints and tip loads includes the second-order foreshortening ½aᵀGa/L
//! ([`ModalBody::tip_local`]), through which axial tip loads stiffen the modes.
//!
//! [`ModalBody::eval`] returns the residual of the equations of motion
//! `F = M(q) q̈ − Q_v(q, q̇) − Q_g(q) + K a + D ȧ` and its exact partial derivatives
//! ∂F/∂q̈ (mass matrix), ∂F/∂q̇ and ∂F/∂q.

use super::basis::ModalBasis;
use crate::math;
use crate::model::sample::ShapePoint;
use nalgebra::{DMatrix, DVector, Matrix2, Vector2};

/// Rotation matrix A(θ).
pub fn rot(theta: f64) -> Matrix2<f64> {
    let (s, c) = math::sin_cos(theta);
    Matrix2::new(c, -s, s, c)
}

/// J = A(π/2): Jv rotates v by +90°.
fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v[1], v[0])
}

/// Constant properties and invariants of a modal segment.
#[derive(Debug, Clone)]
pub struct ModalBody {
    /// Shape basis.
    pub basis: ModalBasis,
    /// Length L [m].
    pub length: f64,
    /// Mass per length ρA [kg/m].
    pub rho_a: f64,
    /// Bending stiffness EI [N m²].
    pub ei: f64,
    /// Modal stiffness K_k = EIΛ_k/L³ [N/m].
    pub k: Vec<f64>,
    /// Modal damping D_k = 2ζω_k·ρAL + τK_k [N s/m]; empty if undamped.
    pub d: Vec<f64>,
    /// ρA L ∫φ_k dξ [kg].
    pub s_f: Vec<f64>,
    /// ρA L² ∫ξφ_k dξ [kg m].
    pub s_x: Vec<f64>,
}

/// Residual and derivatives of one body at one state (local coordinates).
#[derive(Debug, Clone)]
pub struct BodyOut {
    /// F (3 + n) [N, N m, N].
    pub res: DVector<f64>,
    /// ∂F/∂q̈ = M(q).
    pub m: DMatrix<f64>,
    /// ∂F/∂q̇.
    pub c: DMatrix<f64>,
    /// ∂F/∂q.
    pub k: DMatrix<f64>,
}

impl BodyOut {
    /// Zeroed output for `dim` local coordinates.
    pub fn new(dim: usize) -> Self {
        Self {
            res: DVector::zeros(dim),
            m: DMatrix::zeros(dim, dim),
            c: DMatrix::zeros(dim, dim),
            k: DMatrix::zeros(dim, dim),
        }
    }
}

impl ModalBody {
    /// Builds the body from geometry, material and damping.
    pub fn new(
        basis: ModalBasis,
        length: f64,
        rho_a: f64,
        ei: f64,
        damping_ratio: f64,
        damping_time: f64,
    ) -> Self {
        let mu = rho_a * length;
        let k: Vec<f64> = basis
            .lambda4
            .iter()
            .map(|l4| ei * l4 / length.powi(3))
            .collect();
        let d = if damping_ratio > 0.0 || damping_time > 0.0 {
            k.iter()
                .map(|kk| 2.0 * damping_ratio * (kk / mu).sqrt() * mu + damping_time * kk)
                .collect()
        } else {
            Vec::new()
        };
        let s_f = basis.i1.iter().map(|v| mu * v).collect();
        let s_x = basis.ix.iter().map(|v| mu * length * v).collect();
        Self {
            basis,
            length,
            rho_a,
            ei,
            k,
            d,
            s_f,
            s_x,
        }
    }

    /// Number of modal coordinates.
    pub fn modes(&self) -> usize {
        self.k.len()
    }

    /// Local coordinate count 3 + n.
    pub fn dim(&self) -> usize {
        3 + self.modes()
    }

    /// Mass ρAL [kg].
    pub fn mass(&self) -> f64 {
        self.rho_a * self.length
    }

    /// Natural frequencies of the clamped segment ω_k [rad/s].
    pub fn omegas(&self) -> Vec<f64> {
        self.k.iter().map(|k| (k / self.mass()).sqrt()).collect()
    }

    fn dot_sf(&self, x: &[f64]) -> f64 {
        self.s_f.iter().zip(x).map(|(a, b)| a * b).sum()
    }

    /// Residual and its derivatives at (q, q̇, q̈) for gravity g. With `matrices` false only
    /// `res` is filled.
    pub fn eval(
        &self,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        g: [f64; 2],
        matrices: bool,
        out: &mut BodyOut,
    ) {
        let n = self.modes();
        let mu = self.mass();
        let s0 = 0.5 * self.rho_a * self.length * self.length;
        let j0 = self.rho_a * self.length.powi(3) / 3.0;
        let (th, thd, thdd) = (q[2], v[2], a[2]);
        let am = &q[3..];
        let vm = &v[3..];
        let acc = &a[3..];
        let rot_a = rot(th);
        let sfa = self.dot_sf(am);
        let sfv = self.dot_sf(vm);
        let sfacc = self.dot_sf(acc);
        let a2: f64 = am.iter().map(|x| x * x).sum();
        let av: f64 = am.iter().zip(vm).map(|(x, y)| x * y).sum();
        let z = Vector2::new(a[0] - g[0], a[1] - g[1]);
        let zl = rot_a.transpose() * z;
        // local part w of F_R = m(R̈ − g) + A w
        let w = Vector2::new(
            -thdd * sfa - 2.0 * thd * sfv - thd * thd * s0,
            thdd * s0 + sfacc - thd * thd * sfa,
        );
        let fr = mu * z + rot_a * w;
        out.res[0] = fr[0];
        out.res[1] = fr[1];
        out.res[2] = thdd * (j0 + mu * a2)
            + (s0 * zl[1] - sfa * zl[0])
            + self.s_x.iter().zip(acc).map(|(s, x)| s * x).sum::<f64>()
            + 2.0 * mu * thd * av;
        for kk in 0..n {
            let mut f = self.s_f[kk] * zl[1]
                + self.s_x[kk] * thdd
                + mu * (acc[kk] - thd * thd * am[kk])
                + self.k[kk] * am[kk];
            if !self.d.is_empty() {
                f += self.d[kk] * vm[kk];
            }
            out.res[3 + kk] = f;
        }
        if !matrices {
            return;
        }
        out.m.fill(0.0);
        out.c.fill(0.0);
        out.k.fill(0.0);
        let ey = rot_a.column(1).into_owned(); // A e_y
        let ajsv = rot_a * Vector2::new(-sfa, s0); // A J Sv
                                                   // mass matrix
        out.m[(0, 0)] = mu;
        out.m[(1, 1)] = mu;
        for i in 0..2 {
            out.m[(i, 2)] = ajsv[i];
            out.m[(2, i)] = ajsv[i];
        }
        out.m[(2, 2)] = j0 + mu * a2;
        for kk in 0..n {
            for i in 0..2 {
                out.m[(i, 3 + kk)] = ey[i] * self.s_f[kk];
                out.m[(3 + kk, i)] = ey[i] * self.s_f[kk];
            }
            out.m[(2, 3 + kk)] = self.s_x[kk];
            out.m[(3 + kk, 2)] = self.s_x[kk];
            out.m[(3 + kk, 3 + kk)] = mu;
        }
        // ∂F/∂q̇
        let dw_dthd = Vector2::new(-2.0 * sfv - 2.0 * thd * s0, -2.0 * thd * sfa);
        let c_r = rot_a * dw_dthd;
        out.c[(0, 2)] = c_r[0];
        out.c[(1, 2)] = c_r[1];
        out.c[(2, 2)] = 2.0 * mu * av;
        for kk in 0..n {
            let c_rk = rot_a * Vector2::new(-2.0 * thd * self.s_f[kk], 0.0);
            out.c[(0, 3 + kk)] = c_rk[0];
            out.c[(1, 3 + kk)] = c_rk[1];
            out.c[(2, 3 + kk)] = 2.0 * mu * thd * am[kk];
            out.c[(3 + kk, 2)] = -2.0 * thd * mu * am[kk];
            out.c[(3 + kk, 3 + kk)] = if self.d.is_empty() { 0.0 } else { self.d[kk] };
        }
        // ∂F/∂q (R does not appear)
        let dfr_dth = rot_a * perp(w);
        out.k[(0, 2)] = dfr_dth[0];
        out.k[(1, 2)] = dfr_dth[1];
        out.k[(2, 2)] = -s0 * zl[0] - sfa * zl[1];
        for kk in 0..n {
            let sk = self.s_f[kk];
            let dfr_da = rot_a * Vector2::new(-thdd * sk, -thd * thd * sk);
            out.k[(0, 3 + kk)] = dfr_da[0];
            out.k[(1, 3 + kk)] = dfr_da[1];
            out.k[(2, 3 + kk)] = 2.0 * thdd * mu * am[kk] - sk * zl[0] + 2.0 * mu * thd * vm[kk];
            out.k[(3 + kk, 2)] = -sk * zl[0];
            out.k[(3 + kk, 3 + kk)] = -thd * thd * mu + self.k[kk];
        }
    }

    /// Kinetic energy ½ q̇ᵀ M(q) q̇ [J].
    pub fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let n = self.modes();
        let mu = self.mass();
        let s0 = 0.5 * self.rho_a * self.length * self.length;
        let j0 = self.rho_a * self.length.powi(3) / 3.0;
        let rot_a = rot(q[2]);
        let am = &q[3..];
        let vm = &v[3..];
        let sfa = self.dot_sf(am);
        let a2: f64 = am.iter().map(|x| x * x).sum();
        let rd = Vector2::new(v[0], v[1]);
        let ajsv = rot_a * Vector2::new(-sfa, s0);
        let ey = rot_a.column(1).into_owned();
        let mut t =
            mu * rd.norm_squared() + v[2] * v[2] * (j0 + mu * a2) + 2.0 * v[2] * ajsv.dot(&rd);
        for kk in 0..n {
            t += 2.0 * vm[kk] * (self.s_f[kk] * ey.dot(&rd) + self.s_x[kk] * v[2]);
            t += mu * vm[kk] * vm[kk];
        }
        0.5 * t
    }

    /// Strain energy ½ aᵀ K a [J].
    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        0.5 * self
            .k
            .iter()
            .zip(&q[3..])
            .map(|(k, a)| k * a * a)
            .sum::<f64>()
    }

    /// Gravity potential −gᵀ∫ρA r dx [J].
    pub fn potential_energy(&self, q: &[f64], g: [f64; 2]) -> f64 {
        let s0 = 0.5 * self.rho_a * self.length * self.length;
        let first = self.mass() * Vector2::new(q[0], q[1])
            + rot(q[2]) * Vector2::new(s0, self.dot_sf(&q[3..]));
        -(g[0] * first[0] + g[1] * first[1])
    }

    /// (G a)_k / L: gradient of the tip foreshortening ½ aᵀ G a / L with respect to a_k [-].
    pub fn foreshortening_gradient(&self, q: &[f64]) -> Vec<f64> {
        let n = self.modes();
        let a = &q[3..];
        (0..n)
            .map(|k| {
                (0..n)
                    .map(|j| self.basis.slope_gram[k * n + j] * a[j])
                    .sum::<f64>()
                    / self.length
            })
            .collect()
    }

    /// Local position of the tip in the body frame: [L − ½ aᵀ G a / L; Σ φ_k(1) a_k], with
    /// the second-order foreshortening of the deflected segment (G = ∫φ′φ′ dξ), so that the
    /// tip moves inward as the segment bends and an axial tip load stiffens the modes.
    pub fn tip_local(&self, q: &[f64]) -> Vector2<f64> {
        self.tip_local_and_gradient(q).0
    }

    /// [`ModalBody::tip_local`] and [`ModalBody::foreshortening_gradient`] in one pass.
    pub fn tip_local_and_gradient(&self, q: &[f64]) -> (Vector2<f64>, Vec<f64>) {
        let w: f64 = self.basis.tip.iter().zip(&q[3..]).map(|(p, a)| p * a).sum();
        let g = self.foreshortening_gradient(q);
        let short: f64 = 0.5 * g.iter().zip(&q[3..]).map(|(g, a)| g * a).sum::<f64>();
        (Vector2::new(self.length - short, w), g)
    }

    /// Elastic slope angle at the tip θ_J = Σ φ_k′(1) a_k / L [rad].
    pub fn tip_slope(&self, q: &[f64]) -> f64 {
        self.basis
            .tip_slope
            .iter()
            .zip(&q[3..])
            .map(|(p, a)| p * a)
            .sum::<f64>()
            / self.length
    }

    /// The centreline at each ξ ∈ [0, 1] of the ascending `xi` at (q, q̇) onto `out`: r = R +
    /// A(θ)ū, ū = (ξL − ½∫₀^ξ w′²dξ/L, w) (the tip's [`ModalBody::tip_local`] at ξ = 1, so the
    /// last sample is the tip port's point), ṙ = Ṙ + θ̇ J A ū + A u̇̄, the section frame of the
    /// tangent, curvature w″/L² (the linear field's: the body's strain energy is ½EI∫w″²dx); no
    /// axial strain, no twist.
    pub fn sample(&self, q: &[f64], v: &[f64], xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (a, ad) = (&q[3..], &v[3..]);
        let l = self.length;
        let f = self.basis.fields(&[a, ad], xi);
        let short = self.basis.slope_integrals(&[(a, a), (a, ad)], xi);
        let r = rot(q[2]);
        for (k, &x) in xi.iter().enumerate() {
            let [w, w1, w2] = f[0][k];
            let (u, short_rate) = if x == 1.0 {
                let (u, g) = self.tip_local_and_gradient(q);
                (u, g.iter().zip(ad).map(|(g, v)| g * v).sum::<f64>())
            } else {
                let u = Vector2::new(x * l - 0.5 * short[0][k] / l, w);
                (u, short[1][k] / l)
            };
            let ud = Vector2::new(-short_rate, f[1][k][0]);
            let p = Vector2::new(q[0], q[1]) + r * u;
            let vel = Vector2::new(v[0], v[1]) + v[2] * perp(r * u) + r * ud;
            let t = r * Vector2::new(1.0, w1 / l).normalize();
            out.push(ShapePoint {
                position: [p.x, p.y, 0.0],
                velocity: [vel.x, vel.y, 0.0],
                frame: [[t.x, t.y, 0.0], [-t.y, t.x, 0.0], [0.0, 0.0, 1.0]],
                curvature: [0.0, w2 / (l * l)],
                ..ShapePoint::default()
            });
        }
    }

    /// Global position of the material point at x = ξL.
    pub fn point(&self, q: &[f64], xi: f64) -> Vector2<f64> {
        let n = self.modes();
        let w: f64 = (0..n)
            .map(|k| self.basis.eval_one(k, xi)[0] * q[3 + k])
            .sum();
        Vector2::new(q[0], q[1]) + rot(q[2]) * Vector2::new(xi * self.length, w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> ModalBody {
        ModalBody::new(ModalBasis::new(3, true), 0.2, 0.0247, 0.165, 0.02, 1e-4)
    }

    #[test]
    fn derivatives_match_central_differences() {
        let b = body();
        let d = b.dim();
        let q: Vec<f64> = (0..d).map(|i| 0.1 + 0.37 * (i as f64).sin()).collect();
        let v: Vec<f64> = (0..d).map(|i| 0.5 * (1.3 * i as f64).cos()).collect();
        let a: Vec<f64> = (0..d).map(|i| 2.0 * (0.7 * i as f64 + 0.2).sin()).collect();
        let g = [0.3, -9.81];
        let mut o = BodyOut::new(d);
        b.eval(&q, &v, &a, g, true, &mut o);
        let h = 1e-6;
        let mut tmp = BodyOut::new(d);
        let mut col = |which: usize, j: usize| {
            let (mut qp, mut vp, mut ap) = (q.clone(), v.clone(), a.clone());
            let (mut qm, mut vm, mut am) = (q.clone(), v.clone(), a.clone());
            match which {
                0 => {
                    qp[j] += h;
                    qm[j] -= h
                }
                1 => {
                    vp[j] += h;
                    vm[j] -= h
                }
                _ => {
                    ap[j] += h;
                    am[j] -= h
                }
            }
            b.eval(&qp, &vp, &ap, g, false, &mut tmp);
            let fp = tmp.res.clone();
            b.eval(&qm, &vm, &am, g, false, &mut tmp);
            (fp - &tmp.res) / (2.0 * h)
        };
        for j in 0..d {
            for (which, mat) in [(0, &o.k), (1, &o.c), (2, &o.m)] {
                let fd = col(which, j);
                for i in 0..d {
                    // FD round-off is ~ 1e-16·|F|/h
                    let err = (fd[i] - mat[(i, j)]).abs();
                    assert!(
                        err < 1e-7 * (1.0 + mat[(i, j)].abs()) + 1e-9 * o.res.amax(),
                        "{which} [{i},{j}] {} vs {}",
                        fd[i],
                        mat[(i, j)]
                    );
                }
            }
        }
    }

    #[test]
    fn kinetic_energy_is_half_vmv() {
        let b = body();
        let d = b.dim();
        let q: Vec<f64> = (0..d).map(|i| 0.05 * (i as f64 + 1.0)).collect();
        let v: Vec<f64> = (0..d).map(|i| 0.3 - 0.1 * i as f64).collect();
        let mut o = BodyOut::new(d);
        b.eval(&q, &v, &vec![0.0; d], [0.0, 0.0], true, &mut o);
        let vv = DVector::from_column_slice(&v);
        let t = 0.5 * vv.dot(&(&o.m * &vv));
        assert!((t - b.kinetic_energy(&q, &v)).abs() < 1e-14 * (1.0 + t.abs()));
    }

    #[test]
    fn frequencies_of_the_clamped_segment_match_euler_bernoulli() {
        // docs/references.md §4c: d = 2 mm steel, L = 0.4 m: f1..f3 = 9.045, 56.68, 158.71 Hz.
        let d: f64 = 0.002;
        let area = std::f64::consts::PI * d * d / 4.0;
        let ei = 2.1e11 * area * d * d / 16.0;
        let b = ModalBody::new(ModalBasis::new(3, false), 0.4, 7850.0 * area, ei, 0.0, 0.0);
        let f: Vec<f64> = b
            .omegas()
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect();
        for (fi, want) in f.iter().zip([9.045, 56.68, 158.71]) {
            assert!((fi / want - 1.0).abs() < 5e-4, "{fi} vs {want}");
        }
    }
}
