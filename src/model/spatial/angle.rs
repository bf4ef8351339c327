//! The spatial ANCF element with nodal twist angles as a component ([`AngleElement3`]) and its
//! node as a port ([`AnglePort3`]), `torsion_element = "angle"`. Kernel:
//! [`crate::model::ancf3d::angle`].

use super::kin::{EndKin3, Field3, Grad3, Second3};
use super::node::{
    add_point_weight, add_points, frame_duals, gravity_potential, moment_stiffness, rotation_of,
    rotation_second_along, NodeFrame,
};
use super::Spatial;
use crate::model::ancf3d::angle::{section_frame, Angle3, ANGLE_DOFS};
use crate::model::ancf3d::{MassPatterns, Tables3};
use crate::model::component::{Element, ElementOut, Energies, Env, LocalState, Port, Validity};
use crate::model::sample::ShapePoint;
use crate::model::section3::{
    add_bodies, add_body_energies, gram_schmidt, SectionBody3, SectionPose,
};
use crate::model::vector::{Real, V3};
use nalgebra::{Const, Vector3};
use num_dual::Dual2Vec;
use std::any::Any;

/// A spatial ANCF element with nodal twist angles, local coordinates node 0 then node 1, each
/// `[r, r_x, θ]` (global axes; [m], [-], [rad]).
#[derive(Debug, Clone)]
pub struct AngleElement3 {
    /// Element properties.
    pub props: Angle3,
    /// Dense constant mass matrix, row-major 14 × 14 (for the Newton block).
    mass: Vec<f64>,
    /// The cable part's mass patterns (the residual's M ë without the dense matrix).
    patterns: MassPatterns,
    tables: Tables3,
    /// ∫ρA S_rᵀ g dx at the current gravity, and the point masses' weight.
    gravity_force: [f64; ANGLE_DOFS],
    /// Σ m S(ξ_m) over the point masses on the element; `None` without.
    points: Option<[f64; 4]>,
    /// The segment's line load q [N/m] ([`Ancf3Props::load_force`]); `None` without one.
    line: Option<[f64; 3]>,
    /// Rigid bodies on the section (offset or rotary inertia) with their poses
    /// ([`AnglePose`]).
    bodies: Vec<(SectionBody3, AnglePose)>,
    /// The current gravity [m/s²] (the bodies' weight).
    g: [f64; 3],
}

/// The centreline point r = S(ξ)e and the section frame of the angle element at ξ: r_x =
/// S′(ξ)e and the nodal section axes d2 of [`section_frame`] interpolated linearly, made ⟂ r_x
/// (Gram–Schmidt), the frame of the element's samples ([`Angle3::sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnglePose {
    sh: [f64; 4],
    ds: [f64; 4],
    xi: f64,
    t0: [f64; 3],
    d0: [f64; 3],
}

impl SectionPose for AnglePose {
    fn pose<S: Real>(&self, q: impl Fn(usize) -> S) -> (V3<S>, [V3<S>; 3]) {
        let comb = |w: &[f64; 4]| -> V3<S> {
            std::array::from_fn(|c| (0..4).fold(S::zero(), |s, j| s + q(R_SLOTS[j] + c) * w[j]))
        };
        let (r, a) = (comb(&self.sh), comb(&self.ds));
        let node = |k: usize| {
            let s = R_SLOTS[2 * k + 1];
            section_frame(&self.t0, &self.d0, &[q(s), q(s + 1), q(s + 2)], q(s + 3))[1]
        };
        let (d0, d1) = (node(0), node(1));
        let d: V3<S> = std::array::from_fn(|c| d0[c] * (1.0 - self.xi) + d1[c] * self.xi);
        (r, gram_schmidt(a, d))
    }
}

/// Starts of the r-blocks of S1..S4 (r0, r0_x, r1, r1_x) in the element's coordinates
/// `[r, r_x, θ]` per node.
const R_SLOTS: [usize; 4] = [0, 3, 7, 10];

impl AngleElement3 {
    /// Element of the given properties (gravity zero until set).
    pub fn new(props: Angle3) -> Self {
        Self {
            props,
            mass: props.mass_matrix(),
            patterns: props.cable.mass_patterns(),
            tables: props.tables(),
            gravity_force: [0.0; ANGLE_DOFS],
            points: None,
            line: None,
            bodies: Vec::new(),
            g: [0.0; 3],
        }
    }

    /// The element carrying rigid bodies `bodies` on its section ([`SectionBody3`], ξ along
    /// the element).
    pub fn with_bodies(mut self, bodies: &[SectionBody3]) -> Self {
        let l = self.props.cable.length;
        let (t0, d0) = (self.props.t0, self.props.d0);
        self.bodies = bodies
            .iter()
            .map(|b| {
                let sh = crate::model::ancf::Shape::at(b.xi, l);
                let pose = AnglePose {
                    sh: sh.s,
                    ds: sh.ds,
                    xi: b.xi,
                    t0,
                    d0,
                };
                (*b, pose)
            })
            .collect();
        self
    }

    /// The element under the uniform dead line load `q` [N/m] (world axes; `None`: none), as
    /// [`super::node::AncfElement3::with_line_load`].
    pub fn with_line_load(mut self, q: Option<[f64; 3]>) -> Self {
        self.line = q;
        self
    }

    /// The element carrying point masses `points` (ξ ∈ [0, 1], mass [kg]): m S(ξ)ᵀS(ξ) on the
    /// cable's mass pattern and the dense matrix's r-blocks.
    pub fn with_points(mut self, points: &[(f64, f64)]) -> Self {
        let l = self.props.cable.length;
        let (pat, dense) = (&mut self.patterns, &mut self.mass);
        self.points = add_points(points, l, pat, dense, ANGLE_DOFS, R_SLOTS);
        self
    }

    /// `res += M ë` with the constant mass matrix.
    fn add_mass_product(&self, ea: &[f64; 14], res: &mut [f64; 14]) {
        self.props.add_mass_product(&self.patterns, ea, res);
    }
}

impl Element<Spatial> for AngleElement3 {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Spatial>, mut out: ElementOut<'_>) {
        let (e, ed, ea) = x.arrays::<14>();
        let p = &self.props;
        let tab = &self.tables;
        let (force, matrices) = if out.matrix.is_some() {
            let (mut f, mut k, mut c) = p.tangent(tab, &e, &ed);
            let (fi, mi) = p.twist_inertia_tangent((&e, &ed, &ea), &mut k, &mut c);
            for (f, fi) in f.iter_mut().zip(&fi) {
                *f += fi;
            }
            (f, Some((k, c, mi)))
        } else {
            let mut f = p.internal_force(tab, &e, &ed);
            let fi = p.twist_inertia(&e, &ed, &ea);
            for (f, fi) in f.iter_mut().zip(&fi) {
                *f += fi;
            }
            (f, None)
        };
        // r = M(e) ë + (twist inertia's velocity terms) + f_int − load·f_g
        let mut res = force;
        for (r, g) in res.iter_mut().zip(&self.gravity_force) {
            *r -= env.load * g;
        }
        self.add_mass_product(&ea, &mut res);
        let mut blk = [[0.0; 14]; 14];
        if !self.bodies.is_empty() {
            let g = self.g.map(|x| env.load * x);
            add_bodies(
                &self.bodies,
                (&e, &ed, &ea),
                g,
                out.matrix,
                &mut res,
                &mut blk,
            );
        }
        out.add_residual(&res);
        if let (Some((ca, cv, cx)), Some((k, c, mi))) = (out.matrix, matrices) {
            let m = &self.mass;
            let bodies = !self.bodies.is_empty();
            out.add_block(|r, col| {
                let v = ca * (m[r * 14 + col] + mi[r][col]) + cx * k[r][col] + cv * c[r][col];
                if bodies {
                    v + blk[r][col]
                } else {
                    v
                }
            });
        }
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<Spatial>, res: &mut [f64]) {
        let (e, ed, ea) = x.arrays::<14>();
        let mut r = self.props.internal_force(&self.tables, &e, &ed);
        let fi = self.props.twist_inertia(&e, &ed, &ea);
        for ((r, g), fi) in r.iter_mut().zip(&self.gravity_force).zip(&fi) {
            *r += fi - g;
        }
        self.add_mass_product(&ea, &mut r);
        for (b, pose) in &self.bodies {
            b.add_forces(pose, 14, (&e[..], &ed[..], &ea[..]), self.g, &mut r);
        }
        res.copy_from_slice(&r);
    }

    fn length(&self) -> f64 {
        self.props.cable.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = x.vectors();
        out.extend(
            xi.iter()
                .map(|&s| self.props.sample(&self.tables, &e, &ed, s)),
        );
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &[f64; 3]) -> Energies {
        let (e, ed, _) = x.arrays::<14>();
        let mut out = Energies {
            kinetic: self.props.kinetic_energy(&self.patterns, &e, &ed),
            strain: self.props.strain_energy(&self.tables, &e),
            potential: gravity_potential(&e, &self.gravity_force),
        };
        add_body_energies(&self.bodies, (&e[..], &ed[..]), self.g, &mut out);
        out
    }

    fn set_line_load(&mut self, q: &[f64; 3]) {
        self.line = Some(*q);
    }

    fn set_gravity(&mut self, g: &[f64; 3]) {
        self.gravity_force = self.props.load_force(*g, self.line);
        add_point_weight(&self.points, g, R_SLOTS, &mut self.gravity_force);
        self.g = *g;
    }

    fn is_damped(&self) -> bool {
        self.props.cable.damping_time > 0.0
    }

    fn validity(&self, q: &[f64]) -> Validity {
        Validity {
            axial_strain: self.props.max_axial_strain(&self.tables, q),
            modal_deflection: None,
            section: None,
            chart_margin: Some(self.props.chart_margin(q)),
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A node of the angle element as a port, local coordinates `[r, r_x, θ]`: frame [t, d2, d3]
/// of [`section_frame`] (reference axes of the straight initial beam), rotations and the
/// section axis d2 as a field of (r_x, θ) with its exact first and second derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnglePort3 {
    /// Reference axis t⁰ (unit, global axes).
    pub t0: [f64; 3],
    /// Reference section axis d⁰ (unit, ⟂ t⁰).
    pub d0: [f64; 3],
}

impl NodeFrame for AnglePort3 {
    fn frame<T: Real, const N: usize>(&self, x: &[T; N]) -> [[T; 3]; 3] {
        section_frame(&self.t0, &self.d0, &[x[0], x[1], x[2]], x[3])
    }
}

impl AnglePort3 {
    /// The kinematics; the section axis's second derivatives only if `second`.
    fn end(&self, q: &[f64], second: bool) -> EndKin3 {
        let d = q.len();
        let duals = frame_duals::<_, 4>(self, q);
        let (frame, r) = rotation_of(&duals);
        let mut rotation = Grad3::from_elem(Vector3::zeros(), d);
        rotation[3..7].copy_from_slice(&r);
        // the section axis d2(r_x, θ): its gradient from the same duals, its Hessian from
        // second-order duals (joint rows' matrices only)
        let d2 = &duals[1];
        let mut section = Field3 {
            v: Vector3::from_fn(|c, _| d2[c].re),
            d: Grad3::from_elem(Vector3::zeros(), d),
            dd: Second3::default(),
        };
        for k in 0..4 {
            section.d[3 + k] = Vector3::from_fn(|c, _| d2[c].eps.0.map_or(0.0, |g| g[k]));
        }
        if second {
            let x: [Dual2Vec<f64, Const<4>>; 4] =
                std::array::from_fn(|k| Dual2Vec::<f64, Const<4>>::from_re(q[3 + k]).derivative(k));
            let d2 = self.frame(&x)[1];
            for k in 0..4 {
                for j in k..4 {
                    let h = Vector3::from_fn(|c, _| d2[c].v2.0.map_or(0.0, |h| h[(k, j)]));
                    if h != Vector3::zeros() {
                        section.dd.list.push((3 + k, 3 + j, h));
                    }
                }
            }
        }
        EndKin3 {
            p: Field3::coordinates(q, 0, d),
            frame,
            rotation,
            tangent: Field3::coordinates(q, 3, d),
            section: Some(section),
            normals: None,
        }
    }
}

impl Port<Spatial> for AnglePort3 {
    fn kinematics(&self, q: &[f64]) -> EndKin3 {
        self.end(q, true)
    }

    fn kinematics_first(&self, q: &[f64]) -> EndKin3 {
        self.end(q, false)
    }

    /// p = r, the node's first three coordinates.
    fn point_force_residual(&self, _q: &[f64], force: &[f64; 3], r: &mut [f64]) {
        Field3::selection_force_residual(force, r)
    }

    fn add_moment_stiffness(
        &self,
        q: &[f64],
        m: &[f64; 3],
        add: &mut dyn FnMut(usize, usize, f64),
    ) {
        moment_stiffness::<_, 4>(self, q, m, add)
    }

    fn rotation_second_derivative_along(&self, q: &[f64], dir: &[f64]) -> [f64; 3] {
        rotation_second_along::<_, 4>(self, q, dir)
    }
}

#[cfg(test)]
mod tests;
