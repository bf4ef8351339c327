//! The planar ANCF cable element of degree p > 3 as a component ([`CableP`]: the cubic element's
//! nodes and hierarchic bubbles): local coordinates `[r0, r0′, r1, r1′, a_4, …, a_p]`, the last
//! element-internal. Mass, gravity, line load and point masses as the cubic element's
//! ([`super::AncfElement`]) with the degree's shapes; no section bodies (refused by the build).

use super::Planar;
use crate::model::ancf::AncfProps;
use crate::model::ancf_p::{CableP, PMat, PVec, PD};
use crate::model::component::{Element, ElementOut, Energies, Env, LocalState, Validity};
use crate::model::hierarchic::{partial_load, PShape, MAX_SHAPES};
use crate::model::sample::ShapePoint;
use std::any::Any;

/// A planar ANCF cable element of degree p > 3.
#[derive(Debug, Clone)]
pub struct AncfElementP {
    /// The kernel.
    pub cable: CableP,
    /// The scalar mass pattern ρA∫S_j S_k dx + Σ m S_j(ξ_m) S_k(ξ_m) (M = pattern ⊗ I₂).
    mass: [[f64; MAX_SHAPES]; MAX_SHAPES],
    /// Σ m S(ξ_m) over the point masses [kg, kg m].
    points: [f64; MAX_SHAPES],
    /// The point masses (ξ, m [kg]).
    point_list: Vec<(f64, f64)>,
    /// ∫ρA Sᵀ(g + q/ρA) dx + Σ m S(ξ_m)ᵀ g at the current gravity and line load.
    gravity_force: PVec,
    /// The current gravity [m/s²].
    g: [f64; 2],
    /// The segment's line load q [N/m] (zero without one).
    line: [f64; 2],
}

impl AncfElementP {
    /// The element of degree `degree` with the properties `props` (uniform, straight), carrying
    /// the point masses `points` (ξ ∈ [0, 1], mass [kg]) under the line load `line` [N/m].
    pub fn new(
        props: AncfProps,
        degree: usize,
        points: &[(f64, f64)],
        line: Option<[f64; 2]>,
    ) -> Self {
        let cable = CableP::new(props, degree);
        let n = cable.tables.n;
        let mut mass = cable.tables.mass;
        for row in mass.iter_mut() {
            for x in row.iter_mut() {
                *x *= props.rho_a;
            }
        }
        let mut w = [0.0; MAX_SHAPES];
        for &(xi, m) in points {
            let s = PShape::at(degree, xi, props.length).s;
            for j in 0..n {
                w[j] += m * s[j];
                for k in 0..n {
                    mass[j][k] += m * s[j] * s[k];
                }
            }
        }
        Self {
            cable,
            mass,
            points: w,
            point_list: points.to_vec(),
            gravity_force: [0.0; PD],
            g: [0.0; 2],
            line: line.unwrap_or([0.0; 2]),
        }
    }

    fn n(&self) -> usize {
        self.cable.tables.n
    }

    /// (e, ė, ë) of the element.
    fn state(&self, x: &LocalState<'_>) -> (PVec, PVec, PVec) {
        let d = self.cable.dofs();
        let (mut e, mut ed, mut ea) = ([0.0; PD], [0.0; PD], [0.0; PD]);
        x.gather(&mut e[..d], &mut ed[..d], &mut ea[..d]);
        (e, ed, ea)
    }

    /// M ë + f − load·f_ext.
    fn residual_at(&self, ea: &PVec, force: &PVec, load: f64, res: &mut [f64]) {
        let n = self.n();
        for j in 0..n {
            let (mut mx, mut my) = (0.0, 0.0);
            for k in 0..n {
                mx += self.mass[j][k] * ea[2 * k];
                my += self.mass[j][k] * ea[2 * k + 1];
            }
            let (x, y) = (2 * j, 2 * j + 1);
            res[x] = mx + force[x] - load * self.gravity_force[x];
            res[y] = my + force[y] - load * self.gravity_force[y];
        }
    }
}

impl Element<Planar> for AncfElementP {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
        let (e, ed, ea) = self.state(x);
        let d = self.cable.dofs();
        let mut res = [0.0; PD];
        match out.matrix {
            None => {
                let f = self.cable.forces(&e, &ed, None);
                self.residual_at(&ea, &f, env.load, &mut res);
                out.add_residual(&res[..d]);
            }
            Some((ca, cv, cx)) => {
                let (mut k, mut c): (PMat, PMat) = ([[0.0; PD]; PD], [[0.0; PD]; PD]);
                let f = self.cable.forces(&e, &ed, Some((&mut k, &mut c)));
                self.residual_at(&ea, &f, env.load, &mut res);
                out.add_residual(&res[..d]);
                let mass = &self.mass;
                out.add_block(|r, col| {
                    let m = if r % 2 == col % 2 {
                        mass[r / 2][col / 2]
                    } else {
                        0.0
                    };
                    ca * m + cv * c[r][col] + cx * k[r][col]
                });
            }
        }
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<Planar>, res: &mut [f64]) {
        let (e, ed, ea) = self.state(x);
        let f = self.cable.forces(&e, &ed, None);
        self.residual_at(&ea, &f, 1.0, res);
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &[f64; 2]) -> Energies {
        let (e, ed, _) = self.state(x);
        let n = self.n();
        let mut kinetic = 0.0;
        for j in 0..n {
            for k in 0..n {
                let v = ed[2 * j] * ed[2 * k] + ed[2 * j + 1] * ed[2 * k + 1];
                kinetic += 0.5 * self.mass[j][k] * v;
            }
        }
        let d = self.cable.dofs();
        Energies {
            kinetic,
            strain: self.cable.strain_energy(&e),
            potential: -(0..d).map(|i| self.gravity_force[i] * e[i]).sum::<f64>(),
        }
    }

    fn set_gravity(&mut self, g: &[f64; 2]) {
        let t = &self.cable.tables;
        let ra = self.cable.props.rho_a;
        self.gravity_force = [0.0; PD];
        for j in 0..t.n {
            for c in 0..2 {
                self.gravity_force[2 * j + c] =
                    t.load[j] * (ra * g[c] + self.line[c]) + self.points[j] * g[c];
            }
        }
        self.g = *g;
    }

    fn set_line_load(&mut self, q: &[f64; 2]) {
        self.line = *q;
    }

    fn is_damped(&self) -> bool {
        self.cable.props.damping_time > 0.0
    }

    fn length(&self) -> f64 {
        self.cable.props.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = self.state(x);
        out.extend(xi.iter().map(|&s| self.cable.sample(&e, &ed, s)));
    }

    /// [`partial_load`] on the element's (p + 1)-point rule over [0, ξ], with the point masses
    /// before ξ.
    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 2],
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let (e, _, ea) = self.state(x);
        let ra = self.cable.props.rho_a;
        let field = [0, 1].map(|c| gravity[c] + self.line[c] / ra);
        let t = &self.cable.tables;
        Some(partial_load::<2>(
            t,
            (&e, &ea),
            ra,
            field,
            *gravity,
            &self.point_list,
            xi,
            about,
        ))
    }

    fn validity(&self, q: &[f64]) -> Validity {
        Validity {
            axial_strain: self.cable.max_axial_strain(q),
            ..Validity::default()
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
