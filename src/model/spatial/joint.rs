//! The spatial rigid joint between the tip of one segment and the root of the next
//! (`docs/spatial.md` §3): a spherical joint plus DOT1 rows.
//!
//! Rows over the local coordinates `[up ; down]`:
//! * `p_up − p_down` [m] (3 rows);
//! * with n1, n2, n3 the normals of the end that carries them (the up end if both do) and t, s
//!   the tangent and section director of the other end: `ℓ·n1·t`, `ℓ·n2·t` and, when the other
//!   end has a section director, `ℓ·n3·s` [m], with ℓ a length (the joint's segment length
//!   scale) so that their multipliers carry moments.
//!
//! Every row is a sum of products of two [`Field3`]s; Φ_q and Σλ∂²Φ are exact from the fields'
//! first and second derivatives, cross terms ∂u/∂q_i·∂w/∂q_j included. Two ANCF segments share
//! their node instead (no joint).

use super::kin::{EndKin3, EndValues3, Field3};
use super::Spatial;
use crate::model::component::{Constraint, ConstraintOut, Port};
use crate::model::space::Space;

/// Σλ∂²Φ triplets (local i, local j, value), as in [`ConstraintOut::hess`].
type Hessian = Vec<(usize, usize, f64)>;

/// A rigid joint over the local coordinates `[up ; down]` of its two ends.
#[derive(Debug)]
pub struct RigidJoint3 {
    up: Box<dyn Port<Spatial>>,
    down: Box<dyn Port<Spatial>>,
    up_len: usize,
    length: f64,
    /// Whether the normals are the up end's (else the down end's).
    normals_up: bool,
    /// Whether the twist row n3·s is present.
    twist: bool,
}

impl RigidJoint3 {
    /// The joint between `up` (with `up_len` local coordinates) and `down`, DOT1 rows scaled
    /// by `length` [m]. `q` (the joint's local coordinates, e.g. initial ones) is used once to
    /// find which end carries the normals and whether the other one has a section director.
    /// `None` if neither end has normals (two ANCF ends share a node instead).
    pub fn new(
        up: Box<dyn Port<Spatial>>,
        down: Box<dyn Port<Spatial>>,
        up_len: usize,
        length: f64,
        q: &[f64],
    ) -> Option<Self> {
        let ku = up.kinematics(&q[..up_len]);
        let kd = down.kinematics(&q[up_len..]);
        let (normals_up, other) = if ku.normals.is_some() {
            (true, &kd)
        } else if kd.normals.is_some() {
            (false, &ku)
        } else {
            return None;
        };
        Some(Self {
            twist: other.section.is_some(),
            up,
            down,
            up_len,
            length,
            normals_up,
        })
    }

    /// Whether the joint fixes the relative twist (row n3·s present).
    pub fn fixes_twist(&self) -> bool {
        self.twist
    }
}

impl Constraint for RigidJoint3 {
    fn rows(&self) -> usize {
        if self.twist {
            6
        } else {
            5
        }
    }

    fn eval(&self, q: &[f64], lambda: Option<&[f64]>, out: &mut ConstraintOut) {
        let (qu, qd) = q.split_at(self.up_len);
        // each written in place (no tuple: the kinematics are large values, kept on the stack)
        let (ku, kd);
        if lambda.is_some() {
            ku = self.up.kinematics(qu);
            kd = self.down.kinematics(qd);
        } else {
            ku = self.up.kinematics_first(qu);
            kd = self.down.kinematics_first(qd);
        }
        let d = q.len();
        let (ou, od) = (0, self.up_len);
        // position rows
        for c in 0..3 {
            let row = &mut out.jac[c * d..(c + 1) * d];
            for (k, v) in ku.p.d.iter().enumerate() {
                row[ou + k] += v[c];
            }
            for (k, v) in kd.p.d.iter().enumerate() {
                row[od + k] -= v[c];
            }
        }
        if let Some(l) = lambda {
            let mu = nalgebra::Vector3::new(l[0], l[1], l[2]);
            let hess = &mut out.hess;
            ku.p.add_hessian(&mu, |i, j, v| hess.push((ou + i, ou + j, v)));
            kd.p.add_hessian(&-mu, |i, j, v| hess.push((od + i, od + j, v)));
        }
        // DOT1 rows
        let (kn, on, ko, oo) = if self.normals_up {
            (&ku, ou, &kd, od)
        } else {
            (&kd, od, &ku, ou)
        };
        let normals = kn
            .normals
            .as_ref()
            .expect("the end found with normals at construction keeps them");
        let mut pairs: [(&Field3, &Field3); 3] = [
            (&normals[0], &ko.tangent),
            (&normals[1], &ko.tangent),
            (&normals[2], &ko.tangent),
        ];
        if self.twist {
            pairs[2].1 = section(ko);
        }
        for (r, (a, b)) in pairs.iter().take(self.rows() - 3).enumerate() {
            let row = 3 + r;
            let w = lambda.map(|l| l[row] * self.length);
            let jac = &mut out.jac[row * d..(row + 1) * d];
            product(
                (a, on),
                (b, oo),
                self.length,
                jac,
                w.map(|w| (w, &mut out.hess)),
            );
        }
        // Φ from the ends' values, as `values` gives it
        let (vu, vd) = (Spatial::port_values(&ku), Spatial::port_values(&kd));
        self.phi_of(&vu, &vd, &mut out.phi);
    }

    fn values(&self, q: &[f64], out: &mut ConstraintOut) {
        let (qu, qd) = q.split_at(self.up_len);
        let (vu, vd) = (self.up.values(qu), self.down.values(qd));
        self.phi_of(&vu, &vd, &mut out.phi);
    }
}

impl RigidJoint3 {
    /// Φ from the ends' values (no derivatives): the same products as [`Constraint::eval`]'s.
    fn phi_of(&self, vu: &EndValues3, vd: &EndValues3, phi: &mut [f64]) {
        for c in 0..3 {
            phi[c] = vu.p[c] - vd.p[c];
        }
        let (vn, vo) = if self.normals_up { (vu, vd) } else { (vd, vu) };
        let normals = vn
            .normals
            .as_ref()
            .expect("the end found with normals at construction keeps them");
        let section = || {
            vo.section
                .as_ref()
                .expect("the end found with a section director at construction keeps it")
        };
        for r in 0..self.rows() - 3 {
            let other = if r == 2 { section() } else { &vo.tangent };
            phi[3 + r] = self.length * normals[r].dot(other);
        }
    }
}

/// The section director of an end found to have one at construction.
fn section(k: &EndKin3) -> &Field3 {
    k.section
        .as_ref()
        .expect("the end found with a section director at construction keeps it")
}

/// The derivatives of a·b for fields `a`, `b` on the local coordinates starting at the given
/// offsets (disjoint blocks): adds `scale·∂(a·b)/∂q` to `jac` and, with `(w, hess)`,
/// `w·∂²(a·b)/∂q∂q` to `hess` (both orders of every off-diagonal pair, cross terms
/// ∂a/∂q_i·∂b/∂q_j included).
fn product(
    (a, oa): (&Field3, usize),
    (b, ob): (&Field3, usize),
    scale: f64,
    jac: &mut [f64],
    hess: Option<(f64, &mut Hessian)>,
) {
    for (k, v) in a.d.iter().enumerate() {
        jac[oa + k] += scale * v.dot(&b.v);
    }
    for (k, v) in b.d.iter().enumerate() {
        jac[ob + k] += scale * v.dot(&a.v);
    }
    if let Some((w, hess)) = hess {
        a.add_hessian(&(w * b.v), |i, j, v| hess.push((oa + i, oa + j, v)));
        b.add_hessian(&(w * a.v), |i, j, v| hess.push((ob + i, ob + j, v)));
        for (i, da) in a.d.iter().enumerate() {
            if *da == nalgebra::Vector3::zeros() {
                continue;
            }
            for (j, db) in b.d.iter().enumerate() {
                let h = w * da.dot(db);
                if h != 0.0 {
                    hess.push((oa + i, ob + j, h));
                    hess.push((ob + j, oa + i, h));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::spatial::kin::{Grad3, Second3};
    use nalgebra::{Matrix3, Vector3};

    /// A deterministic pseudo-random number in (−1, 1) from integers.
    fn coef(seed: usize, c: usize, i: usize, j: usize) -> f64 {
        let x = (seed * 7919 + c * 104_729 + i * 1_299_709 + j * 15_485_863) as f64;
        (x * 0.618_033_988_75).sin()
    }

    /// v_c(q) = v0_c + Σ_i A_ci q_i + ½ Σ_ij B_cij q_i q_j + 0.3 sin(Σ_i w_ci q_i): a nonlinear
    /// field with exact first and second derivatives.
    fn field(seed: usize, q: &[f64]) -> Field3 {
        let n = q.len();
        let mut f = Field3 {
            v: Vector3::zeros(),
            d: Grad3::from_elem(Vector3::zeros(), n),
            dd: Second3::default(),
        };
        let mut dd = vec![Vector3::zeros(); n * n];
        for c in 0..3 {
            let w: Vec<f64> = (0..n).map(|i| coef(seed + 1, c, i, 0)).collect();
            let arg: f64 = w.iter().zip(q).map(|(w, q)| w * q).sum();
            let (s, co) = arg.sin_cos();
            f.v[c] = coef(seed, c, 99, 99) + 0.3 * s;
            for i in 0..n {
                f.v[c] += coef(seed, c, i, 0) * q[i];
                f.d[i][c] += coef(seed, c, i, 0) + 0.3 * co * w[i];
                for j in 0..n {
                    let b = coef(seed + 2, c, i.min(j), i.max(j));
                    f.v[c] += 0.5 * b * q[i] * q[j];
                    f.d[i][c] += b * q[j];
                    dd[i * n + j][c] = b - 0.3 * s * w[i] * w[j];
                }
            }
        }
        for i in 0..n {
            for j in i..n {
                f.dd.list.push((i, j, dd[i * n + j]));
            }
        }
        f
    }

    /// A port with `n` local coordinates whose position and directors are nonlinear fields.
    #[derive(Debug)]
    struct TestPort {
        n: usize,
        seed: usize,
        normals: bool,
        section: bool,
    }

    impl Port<Spatial> for TestPort {
        fn kinematics(&self, q: &[f64]) -> EndKin3 {
            assert_eq!(q.len(), self.n);
            let s = self.seed;
            EndKin3 {
                p: field(s, q),
                frame: Matrix3::identity(),
                rotation: Grad3::from_elem(Vector3::zeros(), self.n),
                tangent: field(s + 10, q),
                section: self.section.then(|| field(s + 20, q)),
                normals: self
                    .normals
                    .then(|| [field(s + 30, q), field(s + 40, q), field(s + 50, q)]),
            }
        }

        fn add_moment_stiffness(
            &self,
            _q: &[f64],
            _m: &[f64; 3],
            _add: &mut dyn FnMut(usize, usize, f64),
        ) {
        }
    }

    fn port(n: usize, seed: usize, normals: bool, section: bool) -> Box<dyn Port<Spatial>> {
        Box::new(TestPort {
            n,
            seed,
            normals,
            section,
        })
    }

    fn eval(j: &RigidJoint3, q: &[f64], lam: Option<&[f64]>) -> ConstraintOut {
        let mut out = ConstraintOut::default();
        out.reset(j.rows(), q.len());
        j.eval(q, lam, &mut out);
        out
    }

    /// Φ_q against central differences of Φ, Σλ∂²Φ against central differences of λᵀΦ_q.
    fn check(j: &RigidJoint3, d: usize) {
        let m = j.rows();
        let q: Vec<f64> = (0..d).map(|i| 0.4 * coef(3, 0, i, 7)).collect();
        let lam: Vec<f64> = (0..m).map(|r| coef(4, 0, r, 5)).collect();
        let out = eval(j, &q, Some(&lam));
        // Φ alone (constraint values) is eval's Φ, to the bit
        let mut only = ConstraintOut::default();
        only.reset(m, d);
        j.values(&q, &mut only);
        assert_eq!(only.phi, out.phi);
        let mut hess = vec![0.0; d * d];
        for (a, b, v) in &out.hess {
            hess[a * d + b] += v;
        }
        let h = 1e-6;
        let mut worst = (0.0f64, 0.0f64);
        for k in 0..d {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += h;
            qm[k] -= h;
            let (p, mm) = (eval(j, &qp, None), eval(j, &qm, None));
            for r in 0..m {
                let fd = (p.phi[r] - mm.phi[r]) / (2.0 * h);
                let err = (fd - out.jac[r * d + k]).abs();
                worst.0 = worst.0.max(err);
                assert!(err < 1e-7 * (1.0 + fd.abs()), "Φ_q[{r},{k}]: {fd} vs fd");
            }
            for i in 0..d {
                let lj = |o: &ConstraintOut| (0..m).map(|r| lam[r] * o.jac[r * d + i]).sum::<f64>();
                let fd = (lj(&p) - lj(&mm)) / (2.0 * h);
                let err = (fd - hess[i * d + k]).abs();
                worst.1 = worst.1.max(err);
                assert!(
                    err < 1e-6 * (1.0 + fd.abs()),
                    "Σλ∂²Φ[{i},{k}]: {} vs fd {fd}",
                    hess[i * d + k]
                );
            }
        }
        assert!(worst.0 < 1e-7 && worst.1 < 1e-6, "{worst:?}");
    }

    #[test]
    fn jacobian_and_hessian_match_central_differences() {
        // normals on the up end (modal tip → ANCF node with r_y)
        let j = RigidJoint3::new(
            port(5, 1, true, true),
            port(4, 2, false, true),
            5,
            0.7,
            &[0.1; 9],
        )
        .unwrap();
        assert_eq!(j.rows(), 6);
        check(&j, 9);
        // normals on the down end (ANCF node → modal root), cable node: no twist row
        let j = RigidJoint3::new(
            port(3, 3, false, false),
            port(6, 4, true, true),
            3,
            1.3,
            &[0.1; 9],
        )
        .unwrap();
        assert_eq!(j.rows(), 5);
        check(&j, 9);
        // both ends with normals (modal ↔ modal): the up end's are used
        let j = RigidJoint3::new(
            port(4, 5, true, true),
            port(4, 6, true, true),
            4,
            0.2,
            &[0.1; 8],
        )
        .unwrap();
        assert!(j.fixes_twist());
        check(&j, 8);
    }

    #[test]
    fn rows_are_position_then_scaled_dot1_of_the_normals_end() {
        let q = [0.2, -0.1, 0.3, 0.05, 0.4, -0.3, 0.1];
        let (pu, pd) = (port(3, 7, false, true), port(4, 8, true, true));
        let (ku, kd) = (pu.kinematics(&q[..3]), pd.kinematics(&q[3..]));
        let j = RigidJoint3::new(pu, pd, 3, 2.5, &q).unwrap();
        let out = eval(&j, &q, None);
        let n = kd.normals.as_ref().unwrap();
        let s = ku.section.as_ref().unwrap();
        let want = [
            ku.p.v[0] - kd.p.v[0],
            ku.p.v[1] - kd.p.v[1],
            ku.p.v[2] - kd.p.v[2],
            2.5 * n[0].v.dot(&ku.tangent.v),
            2.5 * n[1].v.dot(&ku.tangent.v),
            2.5 * n[2].v.dot(&s.v),
        ];
        for (a, b) in out.phi.iter().zip(want) {
            assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        }
        assert!(RigidJoint3::new(
            port(2, 1, false, true),
            port(2, 2, false, true),
            2,
            1.0,
            &[0.0; 4]
        )
        .is_none());
    }
}
