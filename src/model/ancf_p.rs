//! Planar ANCF cable element of degree p = 4 … [`MAX_DEGREE`] (a segment's `degree`): the cubic
//! element's nodes [r, r′] and hierarchic C¹ bubbles ([`super::hierarchic`]), coordinates
//! `e = [r0, r0′, r1, r1′, a_4, …, a_p]` (x, y each; 2(p + 1)).
//!
//! The strain measures, damping and energies are the cubic element's ([`super::ancf`]):
//! U = ½∫EA ε² dx + ½∫EI K² dx, for [`StrainModel::Exact`] ε = |r′| − 1 and K =
//! e₃·(r′×r″)/|r′|², for [`StrainModel::Paper`] ε = ½(r′ᵀr′ − 1) and r″ for the curvature;
//! Kelvin–Voigt damping EAτ ε̇ δε + EIτ K̇ δK. Quadrature: p + 1 Gauss points axial, p for
//! bending ([`PTables`]). Each point's local forces on (r′, r″) and their Jacobians are
//! scattered onto the element by [`add_point_jacobian`]. Uniform straight elements only
//! (no taper, no initial curvature: the scene refuses those with degree > 3).

use super::ancf::{cross, AncfProps};
use super::hierarchic::{
    add_point_jacobian, combine, scatter, PKernel, PMat, PShape, PTables, PVec, MAX_DEGREE,
    MAX_DOFS, MAX_SHAPES,
};
use super::lanes::{lane_comb, Lanes};
use super::sample::ShapePoint;
use crate::scene::StrainModel;

type B2 = [[f64; 2]; 2];

/// The planar element of degree p: the cubic element's properties (uniform, straight) and the
/// degree's tables.
#[derive(Debug, Clone, PartialEq)]
pub struct CableP {
    /// Length, ρA, EA, EI, damping, strain measures (`reference` and `taper` unused: `None`).
    pub props: AncfProps,
    /// Shapes at the quadrature points, mass pattern, load weights.
    pub tables: PTables,
    /// The same points laid out for the residual path ([`CableP::internal_force_of`]).
    pub lanes: Lanes<MAX_SHAPES, MAX_SHAPES, MAX_DEGREE>,
}

/// (ε, dε/dr′) of the axial strain measure at slope `r1`.
#[inline(always)]
fn axial_measure(strain: StrainModel, r1: [f64; 2]) -> (f64, [f64; 2]) {
    match strain {
        StrainModel::Exact => {
            let n = (r1[0] * r1[0] + r1[1] * r1[1]).sqrt();
            let inv = 1.0 / n;
            (n - 1.0, [r1[0] * inv, r1[1] * inv])
        }
        StrainModel::Paper => (0.5 * (r1[0] * r1[0] + r1[1] * r1[1] - 1.0), r1),
    }
}

/// d²ε/dr′² of the axial strain measure at slope `r1` (unit tangent `t` of the exact one).
fn axial_hessian(strain: StrainModel, r1: [f64; 2], t: [f64; 2]) -> B2 {
    match strain {
        StrainModel::Exact => {
            let inv = 1.0 / (r1[0] * r1[0] + r1[1] * r1[1]).sqrt();
            [
                [(1.0 - t[0] * t[0]) * inv, -t[0] * t[1] * inv],
                [-t[1] * t[0] * inv, (1.0 - t[1] * t[1]) * inv],
            ]
        }
        StrainModel::Paper => [[1.0, 0.0], [0.0, 1.0]],
    }
}

/// The exact material curvature K = e₃·(r′×r″)/|r′|² at (r′, r″) = (`a`, `b`) with ∂K/∂r′ and
/// ∂K/∂r″.
#[inline(always)]
fn curvature(a: [f64; 2], b: [f64; 2]) -> (f64, [f64; 2], [f64; 2]) {
    let inv = 1.0 / (a[0] * a[0] + a[1] * a[1]);
    let k = (a[0] * b[1] - a[1] * b[0]) * inv;
    let dk1 = [
        (b[1] - 2.0 * k * a[0]) * inv,
        (-b[0] - 2.0 * k * a[1]) * inv,
    ];
    let dk2 = [-a[1] * inv, a[0] * inv];
    (k, dk1, dk2)
}

/// (∂²K/∂r′², ∂²K/∂r′∂r″) of [`curvature`] (∂²K/∂r″² = 0).
fn curvature_hessian(a: [f64; 2], b: [f64; 2]) -> (B2, B2) {
    let gg = a[0] * a[0] + a[1] * a[1];
    let c = a[0] * b[1] - a[1] * b[0];
    let c1 = [b[1], -b[0]];
    let c2 = [-a[1], a[0]];
    let dg = [2.0 * a[0], 2.0 * a[1]];
    let (g2, g3) = (gg * gg, gg * gg * gg);
    let mut h11 = [[0.0; 2]; 2];
    let mut h12 = [[0.0; 2]; 2];
    let jt = [[0.0, 1.0], [-1.0, 0.0]];
    for i in 0..2 {
        for j in 0..2 {
            let id = if i == j { 1.0 } else { 0.0 };
            h11[i][j] = -(c1[i] * dg[j] + dg[i] * c1[j]) / g2 - 2.0 * c / g2 * id
                + 2.0 * c / g3 * dg[i] * dg[j];
            h12[i][j] = jt[i][j] / gg - dg[i] * c2[j] / g2;
        }
    }
    (h11, h12)
}

fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn mul2(m: &B2, v: [f64; 2]) -> [f64; 2] {
    [dot2(m[0], v), dot2(m[1], v)]
}

fn transpose(m: &B2) -> B2 {
    [[m[0][0], m[1][0]], [m[0][1], m[1][1]]]
}

/// s·(a bᵀ) + t·m.
fn outer_plus(s: f64, a: [f64; 2], b: [f64; 2], t: f64, m: &B2) -> B2 {
    std::array::from_fn(|i| std::array::from_fn(|j| s * a[i] * b[j] + t * m[i][j]))
}

/// Where [`CableP::forces`] writes the element's stiffness ∂f/∂e and damping ∂f/∂ė.
pub type Matrices<'a> = (&'a mut PMat, &'a mut PMat);

impl CableP {
    /// The element of `props` (uniform and straight) and degree `degree` (3 … [`MAX_DEGREE`]).
    pub fn new(props: AncfProps, degree: usize) -> Self {
        assert!(props.reference.is_none() && props.taper.is_none());
        let tables = PTables::new(degree, props.length);
        let lanes = Lanes::new(
            (tables.axial.iter()).map(|q| (q.w * props.ea, &q.ds[..])),
            (tables.bending.iter()).map(|q| (q.w * props.ei, &q.ds[..], &q.dds[..])),
        );
        Self {
            lanes,
            tables,
            props,
        }
    }
}

impl CableP {
    /// The residual path of [`PKernel::forces_of`] (no matrices) of an element of N shapes,
    /// NB = N − 1 bending points: the same operations in the same order (the same bits)
    /// arranged by point ([`Lanes`]): r′ (and r″) at every point at once, the points' measures
    /// side by side (their square roots and divisions independent), then the forces added up
    /// point by point in the order of [`PKernel::forces_of`].
    #[inline(always)]
    fn internal_force_of<const N: usize, const NB: usize>(&self, e: &PVec, ed: &PVec) -> PVec {
        let p = &self.props;
        let (tau, damped) = (p.damping_time, p.damping_time > 0.0);
        let l = &self.lanes;
        let axial =
            |x: &PVec| lane_comb::<2, N, N, MAX_SHAPES, MAX_SHAPES, MAX_DOFS>(&l.axial_ds, x);
        let bend = |w: &[[f64; MAX_DEGREE]; MAX_SHAPES], x: &PVec| {
            lane_comb::<2, N, NB, MAX_SHAPES, MAX_DEGREE, MAX_DOFS>(w, x)
        };
        // the axial points: w·EA·(ε + τ ε̇) and dε/dr′
        let r1 = axial(e);
        let r1d = if damped { axial(ed) } else { [[0.0; N]; 2] };
        let mut sa = [0.0; N];
        let mut ga = [[0.0; 2]; N];
        for q in 0..N {
            let (eps, g) = axial_measure(p.strain, [r1[0][q], r1[1][q]]);
            let stress = eps + tau * dot2(g, [r1d[0][q], r1d[1][q]]);
            sa[q] = l.axial_w[q] * stress;
            ga[q] = g;
        }
        let mut f = [[0.0; 2]; N];
        // f_j += (s w_j) v (as `scatter`)
        let scat = |f: &mut [[f64; 2]; N], s: f64, w: &[f64; MAX_SHAPES], v: [f64; 2]| {
            for j in 0..N {
                let c = s * w[j];
                f[j][0] += c * v[0];
                f[j][1] += c * v[1];
            }
        };
        for q in 0..N {
            scat(&mut f, sa[q], &l.axial_t[q], ga[q]);
        }
        // the bending points
        let zero = [[0.0; NB]; 2];
        let r2 = bend(&l.dds, e);
        let r2d = if damped { bend(&l.dds, ed) } else { zero };
        match p.strain {
            StrainModel::Paper => {
                for q in 0..NB {
                    let m = [r2[0][q] + tau * r2d[0][q], r2[1][q] + tau * r2d[1][q]];
                    scat(&mut f, l.bend_w[q], &l.dds_t[q], m);
                }
            }
            StrainModel::Exact => {
                let r1 = bend(&l.ds, e);
                let r1d = if damped { bend(&l.ds, ed) } else { zero };
                let mut m = [0.0; NB];
                let mut d1 = [[0.0; 2]; NB];
                let mut d2 = [[0.0; 2]; NB];
                for q in 0..NB {
                    let (a, b) = ([r1[0][q], r1[1][q]], [r2[0][q], r2[1][q]]);
                    let (kappa, dk1, dk2) = curvature(a, b);
                    let rates =
                        dot2(dk1, [r1d[0][q], r1d[1][q]]) + dot2(dk2, [r2d[0][q], r2d[1][q]]);
                    m[q] = l.bend_w[q] * (kappa + tau * rates);
                    (d1[q], d2[q]) = (dk1, dk2);
                }
                for q in 0..NB {
                    scat(&mut f, m[q], &l.ds_t[q], d1[q]);
                    scat(&mut f, m[q], &l.dds_t[q], d2[q]);
                }
            }
        }
        let mut out = [0.0; MAX_DOFS];
        for j in 0..N {
            out[2 * j] = f[j][0];
            out[2 * j + 1] = f[j][1];
        }
        out
    }
}

impl PKernel for CableP {
    const DIM: usize = 2;

    fn tables(&self) -> &PTables {
        &self.tables
    }

    fn rho_a(&self) -> f64 {
        self.props.rho_a
    }

    fn damping_time(&self) -> f64 {
        self.props.damping_time
    }

    /// [`CableP::forces`] of an element of `N` shapes.
    #[inline(always)]
    fn forces_of<const N: usize>(
        &self,
        e: &PVec,
        ed: &PVec,
        mut mats: Option<Matrices<'_>>,
    ) -> PVec {
        let n = N;
        debug_assert_eq!(n, self.tables.n);
        if mats.is_none() {
            return match N {
                4 => self.internal_force_of::<4, 3>(e, ed),
                5 => self.internal_force_of::<5, 4>(e, ed),
                6 => self.internal_force_of::<6, 5>(e, ed),
                7 => self.internal_force_of::<7, 6>(e, ed),
                8 => self.internal_force_of::<8, 7>(e, ed),
                n => unreachable!("{n} shapes"),
            };
        }
        let p = &self.props;
        let tau = p.damping_time;
        let mut f = [0.0; MAX_DOFS];
        for q in &self.tables.axial {
            let w = q.w * p.ea;
            let r1 = combine::<2>(n, &q.ds, e);
            let (eps, g) = axial_measure(p.strain, r1);
            let r1d = if tau > 0.0 {
                combine::<2>(n, &q.ds, ed)
            } else {
                [0.0; 2]
            };
            let stress = eps + tau * dot2(g, r1d);
            scatter::<2>(n, &q.ds, w * stress, &g, &mut f);
            if let Some((k, c)) = mats.as_mut() {
                let h = axial_hessian(p.strain, r1, g);
                let hd = mul2(&h, r1d);
                let mut j = outer_plus(w, g, g, w * stress, &h);
                if tau > 0.0 {
                    j = outer_plus(w * tau, g, hd, 1.0, &j);
                    let cj = outer_plus(w * tau, g, g, 0.0, &h);
                    add_point_jacobian::<2, 1, MAX_DOFS>(n, [&q.ds], &[[cj]], c);
                }
                add_point_jacobian::<2, 1, MAX_DOFS>(n, [&q.ds], &[[j]], k);
            }
        }
        for q in &self.tables.bending {
            let w = q.w * p.ei;
            let r2 = combine::<2>(n, &q.dds, e);
            let rate = |w: &[f64; MAX_SHAPES]| {
                if tau > 0.0 {
                    combine::<2>(n, w, ed)
                } else {
                    [0.0; 2]
                }
            };
            let r2d = rate(&q.dds);
            match p.strain {
                StrainModel::Paper => {
                    let m = [r2[0] + tau * r2d[0], r2[1] + tau * r2d[1]];
                    scatter::<2>(n, &q.dds, w, &m, &mut f);
                    if let Some((k, c)) = mats.as_mut() {
                        let id = [[w, 0.0], [0.0, w]];
                        add_point_jacobian::<2, 1, MAX_DOFS>(n, [&q.dds], &[[id]], k);
                        if tau > 0.0 {
                            let cd = [[w * tau, 0.0], [0.0, w * tau]];
                            add_point_jacobian::<2, 1, MAX_DOFS>(n, [&q.dds], &[[cd]], c);
                        }
                    }
                }
                StrainModel::Exact => {
                    let r1 = combine::<2>(n, &q.ds, e);
                    let r1d = rate(&q.ds);
                    let (kappa, dk1, dk2) = curvature(r1, r2);
                    let moment = kappa + tau * (dot2(dk1, r1d) + dot2(dk2, r2d));
                    scatter::<2>(n, &q.ds, w * moment, &dk1, &mut f);
                    scatter::<2>(n, &q.dds, w * moment, &dk2, &mut f);
                    if let Some((k, c)) = mats.as_mut() {
                        let (h11, h12) = curvature_hessian(r1, r2);
                        let h21 = transpose(&h12);
                        let zero = [[0.0; 2]; 2];
                        let wm = w * moment;
                        let mut jac = [
                            [
                                outer_plus(w, dk1, dk1, wm, &h11),
                                outer_plus(w, dk1, dk2, wm, &h12),
                            ],
                            [
                                outer_plus(w, dk2, dk1, wm, &h21),
                                outer_plus(w, dk2, dk2, 0.0, &zero),
                            ],
                        ];
                        if tau > 0.0 {
                            // ∂K̇/∂(r′, r″) = (H11 ṙ′ + H12 ṙ″, H21 ṙ′)
                            let (a, b) = (mul2(&h11, r1d), mul2(&h12, r2d));
                            let u = [[a[0] + b[0], a[1] + b[1]], mul2(&h21, r1d)];
                            let d = [dk1, dk2];
                            let mut cj = [[zero; 2]; 2];
                            for x in 0..2 {
                                for y in 0..2 {
                                    jac[x][y] = outer_plus(w * tau, d[x], u[y], 1.0, &jac[x][y]);
                                    cj[x][y] = outer_plus(w * tau, d[x], d[y], 0.0, &zero);
                                }
                            }
                            add_point_jacobian::<2, 2, MAX_DOFS>(n, [&q.ds, &q.dds], &cj, c);
                        }
                        add_point_jacobian::<2, 2, MAX_DOFS>(n, [&q.ds, &q.dds], &jac, k);
                    }
                }
            }
        }
        f
    }

    /// Strain energy [J] (2(p + 1) coordinates).
    fn strain_energy(&self, e: &[f64]) -> f64 {
        let n = self.tables.n;
        let p = &self.props;
        let mut u = 0.0;
        for q in &self.tables.axial {
            let eps = axial_measure(p.strain, combine::<2>(n, &q.ds, e)).0;
            u += 0.5 * q.w * p.ea * eps * eps;
        }
        for q in &self.tables.bending {
            let r2 = combine::<2>(n, &q.dds, e);
            let k2 = match p.strain {
                StrainModel::Exact => {
                    let r1 = combine::<2>(n, &q.ds, e);
                    let k = (r1[0] * r2[1] - r1[1] * r2[0]) / dot2(r1, r1);
                    k * k
                }
                StrainModel::Paper => dot2(r2, r2),
            };
            u += 0.5 * q.w * p.ei * k2;
        }
        u
    }

    /// The centreline at ξ ∈ [0, 1] ([`super::ancf::AncfProps::sample`]'s measures).
    fn sample(&self, e: &[f64], ed: &[f64], xi: f64) -> ShapePoint {
        let sh = PShape::at(self.tables.degree, xi, self.props.length);
        let r: [f64; 2] = sh.combine(&sh.s, e);
        let v: [f64; 2] = sh.combine(&sh.s, ed);
        let r1 = nalgebra::Vector2::from(sh.combine::<2>(&sh.ds, e));
        let r2 = nalgebra::Vector2::from(sh.combine::<2>(&sh.dds, e));
        let (eps, k) = match self.props.strain {
            StrainModel::Exact => (r1.norm() - 1.0, cross(&r1, &r2) / r1.norm_squared()),
            StrainModel::Paper => (
                0.5 * (r1.norm_squared() - 1.0),
                r2.norm().copysign(cross(&r1, &r2)),
            ),
        };
        let t = r1.normalize();
        ShapePoint {
            position: [r[0], r[1], 0.0],
            velocity: [v[0], v[1], 0.0],
            frame: [[t.x, t.y, 0.0], [-t.y, t.x, 0.0], [0.0, 0.0, 1.0]],
            axial_strain: eps,
            curvature: [0.0, k],
            ..ShapePoint::default()
        }
    }
}

/// The coordinates of a straight unstretched element of degree `degree` from `p0` along the
/// unit direction `d`, length `l` (bubble amplitudes zero).
pub fn straight(p0: [f64; 2], d: [f64; 2], l: f64, degree: usize) -> PVec {
    debug_assert!(degree <= MAX_DEGREE);
    let mut e = [0.0; MAX_DOFS];
    e[..8].copy_from_slice(&[
        p0[0],
        p0[1],
        d[0],
        d[1],
        p0[0] + l * d[0],
        p0[1] + l * d[1],
        d[0],
        d[1],
    ]);
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ancf::tests::props;
    use crate::model::ancf::Vec8;

    /// A bent, stretched, moving state of an element of degree p.
    fn state(p: usize) -> (PVec, PVec) {
        let mut e = [0.0; MAX_DOFS];
        let mut ed = [0.0; MAX_DOFS];
        e[..8].copy_from_slice(&[0.01, -0.02, 0.9, 0.3, 0.055, 0.01, 0.7, 0.75]);
        ed[..8].copy_from_slice(&[0.1, -0.3, 0.5, 0.2, -0.4, 0.6, 0.3, -0.2]);
        for k in 8..2 * (p + 1) {
            e[k] = 0.002 * ((k as f64) * 1.3).sin();
            ed[k] = 0.05 * ((k as f64) * 0.7).cos();
        }
        (e, ed)
    }

    /// With the bubble amplitudes zero, the element of degree p is the cubic element on other
    /// quadrature rules: its nodal forces agree with the cubic's on a state both integrate
    /// nearly exactly (a slightly bent, stretched element).
    /// The residual path (by point, [`PLanes`]) is the matrix path's force to the bit, for every
    /// degree, both strain measures, damped and undamped.
    #[test]
    fn residual_path_is_the_matrix_paths_force_bit_for_bit() {
        for p in 3..=MAX_DEGREE {
            for strain in [StrainModel::Exact, StrainModel::Paper] {
                for tau in [0.0, 2e-3] {
                    let k = CableP::new(props(strain, tau), p);
                    let (e, ed) = state(p);
                    let fast = k.forces(&e, &ed, None);
                    let (mut km, mut cm) =
                        ([[0.0; MAX_DOFS]; MAX_DOFS], [[0.0; MAX_DOFS]; MAX_DOFS]);
                    let full = k.forces(&e, &ed, Some((&mut km, &mut cm)));
                    let bits = |f: &PVec| f.map(f64::to_bits);
                    assert_eq!(bits(&fast), bits(&full), "degree {p} {strain:?} tau {tau}");
                }
            }
        }
    }

    #[test]
    fn zero_bubbles_give_the_cubic_element() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            let p3 = props(strain, 0.0);
            let e8 = [0.0, 0.0, 1.001, 0.002, 0.05005, 0.0001, 1.001, 0.003];
            let cubic = p3.elastic(&Vec8::from(e8), &Vec8::zeros(), false).force;
            for degree in 3..=MAX_DEGREE {
                let el = CableP::new(p3, degree);
                let mut e = [0.0; MAX_DOFS];
                e[..8].copy_from_slice(&e8);
                let f = el.forces(&e, &[0.0; MAX_DOFS], None);
                let scale = cubic.amax();
                for k in 0..8 {
                    assert!(
                        (f[k] - cubic[k]).abs() < 1e-6 * scale,
                        "{strain:?} p {degree} {k}: {} vs {}",
                        f[k],
                        cubic[k]
                    );
                }
            }
        }
    }

    /// The exact tangent and damping matrices and the energy's gradient
    /// ([`crate::model::hierarchic::checks::jacobians`]).
    #[test]
    fn tangent_and_damping_match_central_differences() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            for tau in [0.0, 1e-3] {
                for degree in [4, 5, MAX_DEGREE] {
                    let el = CableP::new(props(strain, tau), degree);
                    let (e, ed) = state(degree);
                    let label = format!("{strain:?} tau {tau} p {degree}");
                    crate::model::hierarchic::checks::jacobians(&el, &e, &ed, tau, &label);
                }
            }
        }
    }

    #[test]
    fn rigid_motion_is_free() {
        for strain in [StrainModel::Exact, StrainModel::Paper] {
            let el = CableP::new(props(strain, 1e-3), 5);
            for angle in [0.0f64, 0.7, -2.5] {
                let (s, c) = (angle.sin(), angle.cos());
                let e = straight([0.3, -0.1], [c, s], 0.05, 5);
                let w = 2.0;
                let mut ed = [0.0; MAX_DOFS];
                ed[..8].copy_from_slice(&[
                    0.0,
                    0.0,
                    -w * s,
                    w * c,
                    -w * 0.05 * s,
                    w * 0.05 * c,
                    -w * s,
                    w * c,
                ]);
                let f = el.forces(&e, &ed, None);
                assert!(f.iter().all(|x| x.abs() < 1e-14 * 6.6e5), "{f:?}");
                assert!(el.strain_energy(&e) < 1e-20);
            }
        }
    }
}
