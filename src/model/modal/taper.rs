//! Section-property integrals of a tapered modal segment (a section dimension `[at_start,
//! at_end]`, [`crate::scene::Dim`]): the Ritz functions stay the uniform beam's (the clamped–free
//! modes and interface shapes of [`ModalBasis`], the torsion shapes of the spatial body), and
//! every integral of the body that carries ρA, EI, GJ or ρI_p takes the property at its point.
//! The modal mass and stiffness are then full matrices (∫ρA φ_iφ_j dx, ∫EI φ_i″φ_j″ dx), not
//! the uniform body's ρAL·I and diag(EIΛ_k/L³). All tables are built once; the uniform body
//! does not use this module.

use super::basis::{quadrature, torsion_shapes, ModalBasis};
use super::nonlinear::Nonlinear;
use crate::scene::Segment;
use nalgebra::DMatrix;

/// Properties per unit length at a point of the segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LineProps {
    /// ρA [kg/m].
    pub(super) rho_a: f64,
    /// E·i_z [N m²] (bending in the x–y plane: the planar EI).
    pub(super) ei_z: f64,
    /// E·i_y [N m²] (bending in the x–z plane).
    pub(super) ei_y: f64,
    /// G·J [N m²].
    pub(super) gj: f64,
    /// ρI_p [kg m].
    pub(super) rho_ip: f64,
}

/// The segment's properties per unit length at ξ = x/L ∈ [0, 1] ([`Segment::section_props_at`]).
pub(super) fn line_props(seg: &Segment, xi: f64) -> LineProps {
    let s = seg.section_props_at(xi);
    LineProps {
        rho_a: seg.density * s.area,
        ei_z: seg.youngs_modulus * s.i_z,
        ei_y: seg.youngs_modulus * s.i_y,
        gj: seg.shear_modulus() * s.torsion,
        rho_ip: seg.density * s.polar,
    }
}

/// The integrals of a tapered body that replace the uniform body's closed forms (x = ξL,
/// φ the basis's shapes of ξ, ′ = d/dξ unless stated).
#[derive(Debug, Clone)]
pub(super) struct Taper {
    /// The segment (its dimensions give the properties at any point).
    pub(super) segment: Segment,
    /// ρA at the start [kg/m]: the reference of the line load's stored form q/ρA_ref and of the
    /// stiffening grams.
    pub(super) rho_ref: f64,
    /// m = ∫ρA dx [kg].
    pub(super) mu: f64,
    /// ∫ρA x dx [kg m].
    pub(super) s0: f64,
    /// ∫ρA x² dx [kg m²].
    pub(super) j0: f64,
    /// ∫ρI_p dx [kg m²].
    pub(super) jp: f64,
    /// ∫ρA φ_k dx [kg].
    pub(super) s_f: Vec<f64>,
    /// ∫ρA x φ_k dx [kg m].
    pub(super) s_x: Vec<f64>,
    /// Modal mass ∫ρA φ_iφ_j dx [kg] (row-major n × n).
    pub(super) mass: Vec<f64>,
    /// Modal stiffness ∫E i_z φ_i″φ_j″ dx (x-derivatives) [N/m] (row-major n × n): the planar
    /// body's and the spatial a_y modes'.
    pub(super) k_z: Vec<f64>,
    /// The same with E i_y (the spatial a_z modes) [N/m].
    pub(super) k_y: Vec<f64>,
    /// ∫φ_k dξ · L [m]: the line load's generalized force per unit load (q per unit length).
    pub(super) line_f: Vec<f64>,
    /// Geometric stiffness grams of a held linear frame normalized by `rho_ref`:
    /// G1 = ∫(∫_ξ¹ρA ds/ρA_ref) φ_i′φ_j′ dξ (axial inertia) and G2 = ∫(∫_ξ¹ρA s ds/ρA_ref)
    /// φ_i′φ_j′ dξ (centrifugal), so that K_G = ρA_ref L ω² G2 − ρA_ref ā_x G1 as the uniform
    /// body's; and the basis's unweighted G1 for the line load's axial part q_x G1.
    pub(super) g1: Vec<f64>,
    /// See [`Taper::g1`].
    pub(super) g2: Vec<f64>,
    /// See [`Taper::g1`].
    pub(super) g1_line: Vec<f64>,
    /// Per point of the nonlinear rule: ρA(ξ_p) L W_p [kg].
    pub(super) m_p: Vec<f64>,
    /// Per point of the nonlinear rule: E i_z(ξ_p) [N m²].
    pub(super) ei_z_p: Vec<f64>,
    /// Per point of the nonlinear rule: E i_y(ξ_p) [N m²].
    pub(super) ei_y_p: Vec<f64>,
    /// Per point of the nonlinear rule: 1/ρA(ξ_p) [m/kg] (the line load as a field q/ρA).
    pub(super) inv_rho_p: Vec<f64>,
    /// Modal damping of the planar (or spatial a_y) modes, row-major n × n [N s/m]
    /// ([`modal_damping`] on (M, K_z)); empty if undamped.
    pub(super) damp_z: Vec<f64>,
    /// The same of the spatial a_z modes on (M, K_y).
    pub(super) damp_y: Vec<f64>,
    /// Natural frequencies of the clamped segment on (M, K_z) [rad/s], ascending.
    pub(super) omega_z: Vec<f64>,
}

impl Taper {
    /// The integrals of the tapered `seg` on the shapes of `basis`, and the point tables of
    /// the nonlinear rule `nl` (composite 5-point Gauss, 64 panels for the integrals: the
    /// properties are polynomials of ξ of degree ≤ 4, the shapes smooth).
    pub(super) fn new(seg: &Segment, basis: &ModalBasis, nl: &Nonlinear) -> Self {
        let n = basis.len();
        let l = seg.length;
        let rho_ref = line_props(seg, 0.0).rho_a;
        let mut t = Self {
            segment: seg.clone(),
            rho_ref,
            mu: 0.0,
            s0: 0.0,
            j0: 0.0,
            jp: 0.0,
            s_f: vec![0.0; n],
            s_x: vec![0.0; n],
            mass: vec![0.0; n * n],
            k_z: vec![0.0; n * n],
            k_y: vec![0.0; n * n],
            line_f: basis.i1.iter().map(|v| v * l).collect(),
            g1: vec![0.0; n * n],
            g2: vec![0.0; n * n],
            g1_line: basis.stiffening_grams().0,
            m_p: Vec::new(),
            ei_z_p: Vec::new(),
            ei_y_p: Vec::new(),
            inv_rho_p: Vec::new(),
            damp_z: Vec::new(),
            damp_y: Vec::new(),
            omega_z: Vec::new(),
        };
        let mut phi = Vec::new();
        for (xi, w) in quadrature(64) {
            let p = line_props(seg, xi);
            basis.eval_all(xi, &mut phi);
            let x = xi * l;
            let wl = w * l;
            t.mu += wl * p.rho_a;
            t.s0 += wl * p.rho_a * x;
            t.j0 += wl * p.rho_a * x * x;
            t.jp += wl * p.rho_ip;
            // the mass beyond ξ, ∫_ξ¹ ρA ds and ∫_ξ¹ ρA s ds (ρA of degree ≤ 2 in s: the
            // 5-point rule on [ξ, 1] is exact)
            let (mut beyond, mut beyond_s) = (0.0, 0.0);
            for (gx, gw) in crate::model::ancf::GAUSS5 {
                let s = xi + 0.5 * (1.0 - xi) * (gx + 1.0);
                let r = line_props(seg, s).rho_a / rho_ref * 0.5 * (1.0 - xi) * gw;
                beyond += r;
                beyond_s += r * s;
            }
            let (ez, ey) = (w * p.ei_z / l.powi(3), w * p.ei_y / l.powi(3));
            for i in 0..n {
                t.s_f[i] += wl * p.rho_a * phi[i][0];
                t.s_x[i] += wl * p.rho_a * x * phi[i][0];
                for j in 0..n {
                    t.mass[i * n + j] += wl * p.rho_a * phi[i][0] * phi[j][0];
                    let kk = phi[i][2] * phi[j][2];
                    t.k_z[i * n + j] += ez * kk;
                    t.k_y[i * n + j] += ey * kk;
                    let gg = w * phi[i][1] * phi[j][1];
                    t.g1[i * n + j] += beyond * gg;
                    t.g2[i * n + j] += beyond_s * gg;
                }
            }
        }
        t.points(nl, l);
        t
    }

    /// The point tables of the nonlinear rule `nl` for a body of length `l`.
    pub(super) fn points(&mut self, nl: &Nonlinear, l: f64) {
        let props: Vec<LineProps> = nl
            .xi
            .iter()
            .map(|&x| line_props(&self.segment, x))
            .collect();
        self.m_p = props
            .iter()
            .zip(&nl.w)
            .map(|(p, w)| p.rho_a * l * w)
            .collect();
        self.ei_z_p = props.iter().map(|p| p.ei_z).collect();
        self.ei_y_p = props.iter().map(|p| p.ei_y).collect();
        self.inv_rho_p = props.iter().map(|p| 1.0 / p.rho_a).collect();
    }

    /// The torsion integrals on χ₁ = ξ, χ₂ = √2 sin πξ: (M_t = ∫ρI_p χ_iχ_j dx [kg m²],
    /// K_t = ∫GJ χ_i′χ_j′ dx (x-derivatives) [N m], c_t = ∫ρI_p χ_m dx [kg m²]).
    pub(super) fn torsion(&self) -> ([[f64; 2]; 2], [[f64; 2]; 2], [f64; 2]) {
        let l = self.segment.length;
        let (mut m, mut k, mut c) = ([[0.0; 2]; 2], [[0.0; 2]; 2], [0.0; 2]);
        for (xi, w) in quadrature(64) {
            let p = line_props(&self.segment, xi);
            let (chi, dchi) = torsion_shapes(xi);
            for i in 0..2 {
                c[i] += w * l * p.rho_ip * chi[i];
                for j in 0..2 {
                    m[i][j] += w * l * p.rho_ip * chi[i] * chi[j];
                    k[i][j] += w * p.gj / l * dchi[i] * dchi[j];
                }
            }
        }
        (m, k, c)
    }

    /// (M a)_k for the modal mass and amplitudes `a` (n of them).
    #[inline]
    pub(super) fn mass_times<T: crate::model::vector::Real>(&self, a: &[T], k: usize) -> T {
        let n = self.s_f.len();
        let mut s = T::zero();
        for (m, &x) in self.mass[k * n..(k + 1) * n].iter().zip(a) {
            s += x * *m;
        }
        s
    }
}

/// (row-major n × n) `x` times the vector `a`, entry `k`.
#[inline]
pub(super) fn row_times<T: crate::model::vector::Real>(x: &[f64], a: &[T], k: usize) -> T {
    let n = a.len();
    let mut s = T::zero();
    for (m, &y) in x[k * n..(k + 1) * n].iter().zip(a) {
        s += y * *m;
    }
    s
}

/// The natural frequencies ω [rad/s] (ascending) of K φ = ω² M φ for the symmetric positive
/// definite n × n `mass` and the symmetric `stiff` (row-major), with the modal damping
/// D = 2ζ M Φ diag(ω) Φᵀ M (Φ the M-orthonormal eigenvectors: every mode of (M, K) gets the
/// damping ratio ζ, the uniform body's 2ζω_k m when M = m I and K diagonal) plus τK. `None`
/// if `mass` is not positive definite.
pub(super) fn modal_damping(
    mass: &[f64],
    stiff: &[f64],
    zeta: f64,
    tau: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let n = (mass.len() as f64).sqrt().round() as usize;
    let m = DMatrix::from_row_slice(n, n, mass);
    let k = DMatrix::from_row_slice(n, n, stiff);
    let lo = m.clone().cholesky()?.l();
    let li = lo.clone().try_inverse()?;
    let c = &li * &k * li.transpose();
    let eig = (0.5 * (&c + c.transpose())).symmetric_eigen();
    let mut om: Vec<f64> = eig.eigenvalues.iter().map(|x| x.max(0.0).sqrt()).collect();
    // D = 2ζ L √(L⁻¹KL⁻ᵀ) Lᵀ: with L⁻¹KL⁻ᵀ = V Ω² Vᵀ and Φ = L⁻ᵀV, M Φ Ω Φᵀ M = L V Ω Vᵀ Lᵀ
    let sq = &eig.eigenvectors
        * DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&om))
        * eig.eigenvectors.transpose();
    let d = 2.0 * zeta * &lo * sq * lo.transpose() + tau * &k;
    om.sort_by(f64::total_cmp);
    let mut out = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            out[i * n + j] = 0.5 * (d[(i, j)] + d[(j, i)]);
        }
    }
    Some((om, out))
}

#[cfg(test)]
mod tests {
    use super::super::{ModalBasis, ModalBody, ModalBody3, ModalProps3};
    use crate::scene::Scene;

    /// A tapered rectangle (both dimensions tapered: ρA quadratic, EI quartic in x, the two
    /// planes' EI different).
    fn segment() -> crate::scene::Segment {
        let text = "name = \"t\"\n[[segments]]\nname = \"a\"\nkind = \"modal\"\nlength = 0.4\n\
                    section = \"rectangle\"\nwidth = [0.012, 0.006]\nheight = [0.008, 0.005]\n\
                    youngs_modulus = 7e10\ndensity = 2700.0\nmodes = 3\ninterface_modes = true\n";
        Scene::from_toml(text).unwrap().segments[0].clone()
    }

    /// The static residual (q̇ = q̈ = 0) of a tapered body under gravity and a line load is the
    /// gradient of its strain and potential energies (central differences), and its kinetic
    /// energy is ½q̇ᵀM q̇ with the residual's M: the tapered energies and forces are the same
    /// integrals (the nonlinear and the linear body, planar and spatial; spatial: the R, a rows).
    #[test]
    fn tapered_forces_are_the_gradients_of_the_energies() {
        let seg = segment();
        let (ra, ei) = {
            let p = seg.section_props();
            (seg.density * p.area, seg.youngs_modulus * p.i_z)
        };
        let g = [1.5, -9.81];
        for linear in [false, true] {
            let b = ModalBody::new(ModalBasis::new(3, true), 0.4, ra, ei, 0.0, 0.0)
                .tapered(&seg)
                .unwrap();
            let b = if linear { b.linear() } else { b };
            let b = b.with_line_load(Some([2.0, -3.0]));
            let d = b.dim();
            let q: Vec<f64> = (0..d)
                .map(|i| 0.3 + 0.002 * (1.7 * i as f64).sin())
                .collect();
            let z = vec![0.0; d];
            let mut o = super::super::BodyOut::new(d);
            let gr = b.gravity(g, 1.0);
            b.eval(&q, &z, &z, gr, true, &mut o);
            let e = |q: &[f64]| b.strain_energy(q) + b.potential_energy(q, gr);
            let h = 1e-6;
            for i in 0..d {
                let (mut p, mut m) = (q.clone(), q.clone());
                p[i] += h;
                m[i] -= h;
                let fd = (e(&p) - e(&m)) / (2.0 * h);
                let err = (fd - o.res[i]).abs();
                assert!(
                    err < 1e-7 * (1.0 + o.res.amax()),
                    "planar {linear} {i}: {fd} vs {}",
                    o.res[i]
                );
            }
            let v: Vec<f64> = (0..d).map(|i| 0.4 * (0.9 * i as f64).cos()).collect();
            let vv = nalgebra::DVector::from_column_slice(&v);
            let t = 0.5 * vv.dot(&(&o.m * &vv));
            let te = b.kinetic_energy(&q, &v);
            assert!(
                (t - te).abs() < 1e-12 * t.abs(),
                "planar {linear}: {t} vs {te}"
            );
        }
        let g = [1.5, 0.7, -9.81];
        for linear in [false, true] {
            let b = ModalBody3::new(ModalBasis::new(3, true), ModalProps3::of_segment(&seg))
                .tapered(&seg)
                .unwrap();
            let b = if linear { b.linear() } else { b };
            let b = b.with_line_load(Some([2.0, -3.0, 1.0]));
            let d = b.dim();
            let mut q: Vec<f64> = (0..d).map(|i| 0.002 * (1.7 * i as f64).sin()).collect();
            let pn = [0.9, 0.2, -0.3, 0.25];
            let nrm = pn.iter().map(|x| x * x).sum::<f64>().sqrt();
            for k in 0..4 {
                q[3 + k] = pn[k] / nrm;
            }
            let z = vec![0.0; d];
            let mut r = vec![0.0; d];
            let gr = b.gravity(g, 1.0);
            b.residual(&q, &z, &z, gr, &mut r);
            let e = |q: &[f64]| b.strain_energy(q) + b.potential_energy(q, gr);
            let scale = r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let h = 1e-6;
            for i in (0..3).chain(7..d) {
                let (mut p, mut m) = (q.clone(), q.clone());
                p[i] += h;
                m[i] -= h;
                let fd = (e(&p) - e(&m)) / (2.0 * h);
                // 1e-6: the uniform spatial body shows the same 1.6e-7·scale at this state
                assert!(
                    (fd - r[i]).abs() < 1e-6 * (1.0 + scale),
                    "spatial {linear} {i}: {fd} vs {}",
                    r[i]
                );
            }
            // ½q̇ᵀMq̇ with M from the Newton block (c_a = 1)
            let mut block = vec![0.0; d * d];
            b.newton_block((&q, &z, &z), gr, (1.0, 0.0, 0.0), &mut block);
            let v: Vec<f64> = (0..d).map(|i| 0.4 * (0.9 * i as f64).cos()).collect();
            let t: f64 = 0.5
                * (0..d)
                    .map(|i| v[i] * (0..d).map(|j| block[i * d + j] * v[j]).sum::<f64>())
                    .sum::<f64>();
            let te = b.kinetic_energy(&q, &v);
            assert!(
                (t - te).abs() < 1e-10 * t.abs(),
                "spatial {linear}: {t} vs {te}"
            );
        }
    }

    /// The modal damping of a tapered body gives each mode of (M, K) the ratio ζ: ΦᵀDΦ =
    /// diag(2ζω) for the M-orthonormal modes Φ (an independent eigen-solve here).
    #[test]
    fn tapered_modal_damping_gives_every_mode_its_ratio() {
        let seg = segment();
        let b = ModalBasis::new(4, true);
        let nl = super::super::nonlinear::Nonlinear::new(&b, 2);
        let t = super::Taper::new(&seg, &b, &nl);
        let zeta = 0.04;
        let (om, d) = super::modal_damping(&t.mass, &t.k_z, zeta, 0.0).unwrap();
        let n = b.len();
        let m = nalgebra::DMatrix::from_row_slice(n, n, &t.mass);
        let k = nalgebra::DMatrix::from_row_slice(n, n, &t.k_z);
        let dd = nalgebra::DMatrix::from_row_slice(n, n, &d);
        // M⁻¹K eigenvectors, M-normalized
        let e = (m.clone().try_inverse().unwrap() * &k).eigen_qr_or_symmetric(&m);
        for (j, (w2, phi)) in e.iter().enumerate() {
            let c = (phi.transpose() * &dd * phi)[(0, 0)];
            let w = w2.sqrt();
            assert!((w / om[j] - 1.0).abs() < 1e-9, "{j}: {w} vs {}", om[j]);
            assert!((c / (2.0 * zeta * w) - 1.0).abs() < 1e-9, "{j}: {c}");
        }
    }

    /// Eigenpairs of A = M⁻¹K (`self`) through M^{-1/2} from M's symmetric eigen-decomposition
    /// (not the Cholesky route of [`super::modal_damping`]): (ω², M-normalized φ), ascending.
    trait Eig {
        fn eigen_qr_or_symmetric(
            self,
            m: &nalgebra::DMatrix<f64>,
        ) -> Vec<(f64, nalgebra::DVector<f64>)>;
    }
    impl Eig for nalgebra::DMatrix<f64> {
        fn eigen_qr_or_symmetric(
            self,
            m: &nalgebra::DMatrix<f64>,
        ) -> Vec<(f64, nalgebra::DVector<f64>)> {
            // M^{-1/2} from M's own symmetric eigen-decomposition (not a Cholesky factor)
            let em = m.clone().symmetric_eigen();
            let ih = &em.eigenvectors
                * nalgebra::DMatrix::from_diagonal(&em.eigenvalues.map(|x| 1.0 / x.sqrt()))
                * em.eigenvectors.transpose();
            let k = m * &self;
            let s = &ih * k * &ih;
            let es = (0.5 * (&s + s.transpose())).symmetric_eigen();
            let mut out: Vec<_> = (0..s.nrows())
                .map(|j| (es.eigenvalues[j], &ih * es.eigenvectors.column(j)))
                .collect();
            out.sort_by(|a, b| a.0.total_cmp(&b.0));
            out
        }
    }
}
