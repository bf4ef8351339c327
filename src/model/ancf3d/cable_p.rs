//! The 3D cable of degree p = 4 … [`crate::model::hierarchic::MAX_DEGREE`] (`torsion = false`, a segment's `degree`): the
//! 3D cable's nodes [r, r_x] and hierarchic C¹ bubbles ([`crate::model::hierarchic`]),
//! coordinates `[r0, r0_x, r1, r1_x, a_4, …, a_p]` (3 each; 3(p + 1)).
//!
//! The strain measures and damping are the 3D cable's ([`super::cable`]): stretching ε = |r_x| − 1
//! (`Ancf3Props::axial_point`), bending ½EI|r_x × r_xx|²/|r_x|⁴ with the rate of the curvature
//! vector relative to the tangent's rotation (`Ancf3Props::cable_point`), on p + 1 axial and
//! p bending Gauss points ([`PTables`]). The tangent and damping matrices are the exact
//! Jacobians of the same point functions by forward-mode AD on each point's local vectors
//! (`local_jacobian`), mapped onto the element ([`add_point_jacobian`]). Uniform straight
//! cables only (no taper, no initial curvature; the scene refuses those with degree > 3).

use super::cable::Lanes;
use super::kernel::{local_jacobian, Blocks};
use super::Ancf3Props;
use crate::model::hierarchic::{
    add_point_jacobian, combine, scatter, PKernel, PMat, PShape, PTables, PVec, MAX_DEGREE,
    MAX_DOFS, MAX_SHAPES,
};
use crate::model::sample::{minimal_frame, ShapePoint};
use crate::model::vector::{cross, dot};

/// The 3D cable of degree p: the cable's properties (uniform, straight, no torsion) and the
/// degree's tables.
#[derive(Debug, Clone, PartialEq)]
pub struct Cable3P {
    /// Length, ρA, EA, E·I (the cable's mean, [`Ancf3Props::cable_ei`]), damping.
    pub props: Ancf3Props,
    /// Shapes at the quadrature points, mass pattern, load weights.
    pub tables: PTables,
    /// The same points laid out for the residual ([`Lanes::force`]).
    lanes: Lanes<MAX_SHAPES, MAX_SHAPES, MAX_DEGREE>,
}

/// Adds the local Jacobians `jac` (and the rate Jacobians `rate` to `c`) of a point whose local
/// vectors are Σ_j maps[a][j] e_j.
fn add_blocks<const K: usize>(
    n: usize,
    maps: [&[f64; MAX_SHAPES]; K],
    (jac, rate): (Blocks<K>, Option<Blocks<K>>),
    (k, c): (&mut PMat, &mut PMat),
) {
    add_point_jacobian::<3, K, MAX_DOFS>(n, maps, &jac, k);
    if let Some(r) = rate {
        add_point_jacobian::<3, K, MAX_DOFS>(n, maps, &r, c);
    }
}

impl Cable3P {
    /// The cable of `props` (the 3D cable: `director` false; uniform, straight) and degree
    /// `degree` (3 … [`crate::model::hierarchic::MAX_DEGREE`]).
    pub fn new(props: Ancf3Props, degree: usize) -> Self {
        assert!(!props.director && props.reference.is_none() && props.taper.is_none());
        let tables = PTables::new(degree, props.length);
        let lanes = Lanes::new(
            (tables.axial.iter()).map(|q| (q.w * props.ea, &q.ds[..])),
            (tables.bending.iter()).map(|q| {
                (
                    q.w * (0.5 * (props.ei_y + props.ei_z)),
                    &q.ds[..],
                    &q.dds[..],
                )
            }),
        );
        Self {
            tables,
            lanes,
            props,
        }
    }
}

impl Cable3P {
    /// The force of [`PKernel::forces_of`] without matrices: [`Lanes::force`] on the element's
    /// p + 1 axial and p bending points (the same bits as the per-point path).
    #[inline(always)]
    fn residual<const N: usize>(&self, e: &PVec, ed: &PVec) -> PVec {
        let (l, tau) = (&self.lanes, self.props.damping_time);
        match N {
            4 => l.force::<4, 4, 3, MAX_DOFS>(tau, None, e, ed),
            5 => l.force::<5, 5, 4, MAX_DOFS>(tau, None, e, ed),
            6 => l.force::<6, 6, 5, MAX_DOFS>(tau, None, e, ed),
            7 => l.force::<7, 7, 6, MAX_DOFS>(tau, None, e, ed),
            8 => l.force::<8, 8, 7, MAX_DOFS>(tau, None, e, ed),
            n => unreachable!("{n} shapes"),
        }
    }
}

impl PKernel for Cable3P {
    const DIM: usize = 3;

    fn tables(&self) -> &PTables {
        &self.tables
    }

    fn rho_a(&self) -> f64 {
        self.props.rho_a
    }

    fn damping_time(&self) -> f64 {
        self.props.damping_time
    }

    #[inline(always)]
    fn forces_of<const N: usize>(
        &self,
        e: &PVec,
        ed: &PVec,
        mut mats: Option<(&mut PMat, &mut PMat)>,
    ) -> PVec {
        if mats.is_none() {
            return self.residual::<N>(e, ed);
        }
        let n = N;
        let p = &self.props;
        let damped = p.damping_time > 0.0;
        let ei = [p.ei_y, p.ei_z];
        let mut f = [0.0; MAX_DOFS];
        let rate = |w: &[f64; MAX_SHAPES]| {
            if damped {
                combine::<3>(n, w, ed)
            } else {
                [0.0; 3]
            }
        };
        for q in &self.tables.axial {
            let w = q.w * p.ea;
            let u = [combine::<3>(n, &q.ds, e)];
            let ud = [rate(&q.ds)];
            let [g] = p.axial_point(w, 0, &u, damped.then_some(&ud));
            scatter::<3>(n, &q.ds, 1.0, &g, &mut f);
            if let Some((k, c)) = mats.as_mut() {
                let maps = [&q.ds];
                let jac = if damped {
                    local_jacobian::<1, 6>(&u, &ud, |u, ud| p.axial_point(w, 0, u, Some(ud)))
                } else {
                    local_jacobian::<1, 3>(&u, &ud, |u, _| p.axial_point(w, 0, u, None))
                };
                add_blocks(n, maps, jac, (k, c));
            }
        }
        for q in &self.tables.bending {
            let u = [combine::<3>(n, &q.ds, e), combine::<3>(n, &q.dds, e)];
            let ud = [rate(&q.ds), rate(&q.dds)];
            let [ga, gb] = p.cable_point(q.w, ei, &u, damped.then_some(&ud));
            scatter::<3>(n, &q.ds, 1.0, &ga, &mut f);
            scatter::<3>(n, &q.dds, 1.0, &gb, &mut f);
            if let Some((k, c)) = mats.as_mut() {
                let maps = [&q.ds, &q.dds];
                let jac = if damped {
                    local_jacobian::<2, 12>(&u, &ud, |u, ud| p.cable_point(q.w, ei, u, Some(ud)))
                } else {
                    local_jacobian::<2, 6>(&u, &ud, |u, _| p.cable_point(q.w, ei, u, None))
                };
                add_blocks(n, maps, jac, (k, c));
            }
        }
        f
    }

    /// Strain energy [J] (3(p + 1) coordinates).
    fn strain_energy(&self, e: &[f64]) -> f64 {
        let (n, p) = (self.tables.n, &self.props);
        let mut u = 0.0;
        for q in &self.tables.axial {
            let a = combine::<3>(n, &q.ds, e);
            let eps = dot(a, a).sqrt() - 1.0;
            u += 0.5 * q.w * p.ea * eps * eps;
        }
        for q in &self.tables.bending {
            let (a, b) = (combine::<3>(n, &q.ds, e), combine::<3>(n, &q.dds, e));
            let (bv, n2) = (cross(a, b), dot(a, a));
            u += 0.5 * q.w * p.cable_ei() * dot(bv, bv) / (n2 * n2);
        }
        u
    }

    /// The centreline at ξ ∈ [0, 1] ([`Ancf3Props::sample`]'s measures of the 3D cable: the
    /// smallest rotation's section frame, the curvature vector on it, no twist).
    fn sample(&self, e: &[f64], ed: &[f64], xi: f64) -> ShapePoint {
        let sh = PShape::at(self.tables.degree, xi, self.props.length);
        let (a, b): ([f64; 3], [f64; 3]) = (sh.combine(&sh.ds, e), sh.combine(&sh.dds, e));
        let frame = minimal_frame(a);
        let k = cross(a, b).map(|c| c / dot(a, a));
        ShapePoint {
            position: sh.combine(&sh.s, e),
            velocity: sh.combine(&sh.s, ed),
            axial_strain: dot(a, a).sqrt() - 1.0,
            curvature: [dot(k, frame[1]), dot(k, frame[2])],
            frame,
            ..ShapePoint::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ancf3d::CABLE_DOFS;
    use crate::model::hierarchic::MAX_DEGREE;

    fn props(tau: f64) -> Ancf3Props {
        Ancf3Props {
            length: 0.05,
            rho_a: 0.0247,
            rho_ip: 1e-6,
            ea: 6.6e5,
            ei_y: 0.165,
            ei_z: 0.165,
            gj: 0.127,
            damping_time: tau,
            director: false,
            reference: None,
            taper: None,
        }
    }

    /// A bent, stretched, twisted-in-space, moving state of a cable of degree p.
    fn state(p: usize) -> (PVec, PVec) {
        let mut e = [0.0; MAX_DOFS];
        let mut ed = [0.0; MAX_DOFS];
        e[..12].copy_from_slice(&[
            0.01, -0.02, 0.005, 0.9, 0.3, 0.1, 0.055, 0.01, -0.004, 0.7, 0.75, -0.2,
        ]);
        ed[..12].copy_from_slice(&[
            0.1, -0.3, 0.2, 0.5, 0.2, -0.1, -0.4, 0.6, 0.3, 0.3, -0.2, 0.4,
        ]);
        for k in 12..3 * (p + 1) {
            e[k] = 0.002 * ((k as f64) * 1.3).sin();
            ed[k] = 0.05 * ((k as f64) * 0.7).cos();
        }
        (e, ed)
    }

    /// The exact Jacobians (AD per point) against central differences of the forces, with and
    /// without damping; the force is the energy's gradient.
    #[test]
    fn tangent_damping_and_energy_agree_with_the_forces() {
        for tau in [0.0, 1e-3] {
            for degree in [4, 5, MAX_DEGREE] {
                let el = Cable3P::new(props(tau), degree);
                let (e, ed) = state(degree);
                let label = format!("tau {tau} p {degree}");
                crate::model::hierarchic::checks::jacobians(&el, &e, &ed, tau, &label);
            }
        }
    }

    /// The residual on lanes ([`Lanes::force`]) is the per-point path of the matrices bit for
    /// bit, undamped and damped, every degree, several states.
    #[test]
    fn residual_is_the_per_point_path_bit_for_bit() {
        for tau in [0.0, 1e-3] {
            for degree in 3..=MAX_DEGREE {
                let el = Cable3P::new(props(tau), degree);
                for seed in 0..4 {
                    let (mut e, mut ed) = state(degree);
                    for k in 0..3 * (degree + 1) {
                        let x = (seed * 7 + k) as f64;
                        e[k] += 0.01 * seed as f64 * (x * 0.9).sin();
                        ed[k] += 0.2 * seed as f64 * (x * 1.7).cos();
                    }
                    let (mut k, mut c) = ([[0.0; MAX_DOFS]; MAX_DOFS], [[0.0; MAX_DOFS]; MAX_DOFS]);
                    let per_point = el.forces(&e, &ed, Some((&mut k, &mut c)));
                    let lanes = el.forces(&e, &ed, None);
                    let label = format!("tau {tau} p {degree} seed {seed}");
                    assert_eq!(
                        lanes.map(f64::to_bits),
                        per_point.map(f64::to_bits),
                        "{label}"
                    );
                }
            }
        }
    }

    /// With the bubbles zero the cable of degree p is the cubic 3D cable on other rules: the
    /// same nodal forces on a state both integrate nearly exactly; and the planar element of
    /// degree p in the x–y plane.
    #[test]
    fn zero_bubbles_give_the_cubic_cable_and_the_plane_gives_the_planar_element() {
        let p = props(0.0);
        let e12 = [
            0.0, 0.0, 0.0, 1.001, 0.002, 0.001, 0.05005, 0.0001, 0.00005, 1.001, 0.003, 0.002,
        ];
        let tab = p.tables();
        let cubic = p.internal_force::<CABLE_DOFS>(&tab, &e12, &[0.0; CABLE_DOFS]);
        let scale = cubic.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for degree in 3..=MAX_DEGREE {
            let mut e = [0.0; MAX_DOFS];
            e[..12].copy_from_slice(&e12);
            let f = Cable3P::new(p, degree).forces(&e, &[0.0; MAX_DOFS], None);
            for k in 0..12 {
                assert!((f[k] - cubic[k]).abs() < 1e-6 * scale, "p {degree} {k}");
            }
        }
        // the plane: the same forces as the planar element of that degree (exact measures)
        let planar = crate::model::ancf::AncfProps {
            length: p.length,
            rho_a: p.rho_a,
            ea: p.ea,
            ei: p.ei_z,
            damping_time: 0.0,
            strain: crate::scene::StrainModel::Exact,
            reference: None,
            taper: None,
        };
        let (e3, _) = state(5);
        let (mut e2, mut e3p) = ([0.0; MAX_DOFS], [0.0; MAX_DOFS]);
        for j in 0..6 {
            e2[2 * j] = e3[3 * j];
            e2[2 * j + 1] = e3[3 * j + 1];
            e3p[3 * j] = e3[3 * j];
            e3p[3 * j + 1] = e3[3 * j + 1];
        }
        let f2 = crate::model::ancf_p::CableP::new(planar, 5).forces(&e2, &[0.0; MAX_DOFS], None);
        let f3 = Cable3P::new(p, 5).forces(&e3p, &[0.0; MAX_DOFS], None);
        let scale = f2.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for j in 0..6 {
            assert!((f3[3 * j] - f2[2 * j]).abs() < 1e-9 * scale);
            assert!((f3[3 * j + 1] - f2[2 * j + 1]).abs() < 1e-9 * scale);
            assert!(f3[3 * j + 2].abs() < 1e-12 * scale);
        }
    }
}
