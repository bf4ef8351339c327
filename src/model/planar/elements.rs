//! The planar elements as components: the ANCF cable element (8 coordinates) and the
//! floating-frame modal body (3 + n coordinates), wrapping their kernels.

use super::Planar;
use crate::model::ancf::{AncfProps, Mat8, QuadTables, Vec8};
use crate::model::assembly::Model;
use crate::model::component::{Element, ElementOut, Energies, Env, LocalState, Validity};
use crate::model::modal::{BodyOut, ModalBody};
use crate::model::sample::ShapePoint;
use std::any::Any;
use std::sync::Arc;

/// A planar ANCF cable element, local coordinates `e = [r0, r0′, r1, r1′]` (x, y each).
#[derive(Debug, Clone)]
pub struct AncfElement {
    /// Element properties.
    pub props: AncfProps,
    mass: Mat8,
    /// 4×4 scalar pattern of the mass matrix (M = M4 ⊗ I₂).
    mass4: [[f64; 4]; 4],
    tables: QuadTables,
    /// ∫ρA Sᵀ g dx at the current gravity.
    gravity_force: Vec8,
}

impl AncfElement {
    /// Element of the given properties (gravity zero until set).
    pub fn new(props: AncfProps) -> Self {
        let mass = props.mass_matrix();
        let mut mass4 = [[0.0; 4]; 4];
        for k in 0..4 {
            for j in 0..4 {
                mass4[k][j] = mass[(2 * k, 2 * j)];
            }
        }
        Self {
            props,
            mass,
            mass4,
            tables: props.tables(),
            gravity_force: Vec8::zeros(),
        }
    }
}

impl Element<Planar> for AncfElement {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
        let (e, ed, ea) = x.arrays::<8>();
        let (force, matrices) = if out.matrix.is_some() {
            let out = self.props.elastic(&Vec8::from(e), &Vec8::from(ed), true);
            (out.force.into(), Some(out))
        } else {
            (self.props.internal_force_with(&self.tables, &e, &ed), None)
        };
        let gf = &self.gravity_force;
        // r = M ë + f_int − load·f_g, M = M4 ⊗ I₂
        let mut res = [0.0; 8];
        for k in 0..4 {
            let (mut mx, mut my) = (0.0, 0.0);
            for j in 0..4 {
                mx += self.mass4[k][j] * ea[2 * j];
                my += self.mass4[k][j] * ea[2 * j + 1];
            }
            let (x, y) = (2 * k, 2 * k + 1);
            res[x] = mx + force[x] - env.load * gf[x];
            res[y] = my + force[y] - env.load * gf[y];
        }
        out.add_residual(&res);
        if let (Some((ca, cv, cx)), Some(m)) = (out.matrix, matrices) {
            let damped = cv != 0.0 && self.props.damping_time > 0.0;
            out.add_block(|r, c| {
                let mut val = ca * self.mass[(r, c)] + cx * m.stiffness[(r, c)];
                if damped {
                    val += cv * m.damping[(r, c)];
                }
                val
            });
        }
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<Planar>, res: &mut [f64]) {
        let (e, ed, ea) = x.arrays::<8>();
        let (e, ed, ea) = (Vec8::from(e), Vec8::from(ed), Vec8::from(ea));
        let f = self.mass * ea + self.props.elastic(&e, &ed, false).force - self.gravity_force;
        res.copy_from_slice(f.as_slice());
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &[f64; 2]) -> Energies {
        let (e, ed, _) = x.arrays::<8>();
        let (e, ed) = (Vec8::from(e), Vec8::from(ed));
        Energies {
            kinetic: 0.5 * ed.dot(&(self.mass * ed)),
            strain: self.props.strain_energy(&e),
            potential: -self.gravity_force.dot(&e),
        }
    }

    fn length(&self) -> f64 {
        self.props.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = x.arrays::<8>();
        let (e, ed) = (Vec8::from(e), Vec8::from(ed));
        out.extend(xi.iter().map(|&s| self.props.sample(&e, &ed, s)));
    }

    fn set_gravity(&mut self, g: &[f64; 2]) {
        self.gravity_force = self.props.gravity_force(*g);
    }

    fn is_damped(&self) -> bool {
        self.props.damping_time > 0.0
    }

    fn validity(&self, q: &[f64]) -> Validity {
        let mut worst: f64 = 0.0;
        for (_, ds) in &self.tables.axial {
            let (mut x, mut y) = (0.0, 0.0);
            for k in 0..4 {
                x += ds[k] * q[2 * k];
                y += ds[k] * q[2 * k + 1];
            }
            worst = worst.max(((x * x + y * y).sqrt() - 1.0).abs());
        }
        Validity {
            axial_strain: worst,
            modal_deflection: None,
            section: None,
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A planar floating-frame modal body, local coordinates `[R_x, R_y, θ, a_1 … a_n]`. The
/// body's kinematics carry the foreshortening of every point, so the axial force of the
/// centrifugal, axial inertia and gravity fields stiffens the modes of held and free frames
/// alike (it replaces the geometric stiffness K_G = ρAL θ̇² G2 − ρA ā_x G1 that held frames
/// used to add, docs/spatial.md, of which it is the leading term).
#[derive(Debug, Clone)]
pub struct ModalElement {
    /// The body (shared with its ports).
    pub body: Arc<ModalBody>,
    out: BodyOut,
    /// Local (q, q̇, q̈) of the last evaluation.
    x: [Vec<f64>; 3],
}

impl ModalElement {
    /// Component of `body`.
    pub fn new(body: Arc<ModalBody>) -> Self {
        let d = body.dim();
        let out = BodyOut::new(d);
        Self {
            body,
            out,
            x: [vec![0.0; d], vec![0.0; d], vec![0.0; d]],
        }
    }
}

impl Element<Planar> for ModalElement {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
        let g = [env.load * env.gravity[0], env.load * env.gravity[1]];
        let [q, v, a] = &mut self.x;
        x.gather(q, v, a);
        let body = &mut self.out;
        self.body.eval(q, v, a, g, out.matrix.is_some(), body);
        out.add_residual(body.res.as_slice());
        if let Some((ca, cv, cx)) = out.matrix {
            out.add_block(|r, c| ca * body.m[(r, c)] + cv * body.c[(r, c)] + cx * body.k[(r, c)]);
        }
    }

    fn residual(&self, x: &LocalState<'_>, env: &Env<Planar>, res: &mut [f64]) {
        let (q, v, a) = x.vectors();
        let mut out = BodyOut::new(self.body.dim());
        self.body.eval(&q, &v, &a, env.gravity, false, &mut out);
        res.copy_from_slice(out.res.as_slice());
    }

    fn energies(&self, x: &LocalState<'_>, gravity: &[f64; 2]) -> Energies {
        let (q, v, _) = x.vectors();
        Energies {
            kinetic: self.body.kinetic_energy(&q, &v),
            strain: self.body.strain_energy(&q),
            potential: self.body.potential_energy(&q, *gravity),
        }
    }

    fn length(&self) -> f64 {
        self.body.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (q, v, _) = x.vectors();
        self.body.sample(&q, &v, xi, out);
    }

    fn is_damped(&self) -> bool {
        !self.body.d.is_empty()
    }

    /// Modal deflection max(|w(L)|/L, |θ_J|): the tip deflection over the length or the tip
    /// slope [rad].
    fn validity(&self, q: &[f64]) -> Validity {
        let b = &self.body;
        let w = b.tip_local(q)[1].abs() / b.length;
        Validity {
            axial_strain: 0.0,
            modal_deflection: Some(w.max(b.tip_slope(q).abs())),
            section: None,
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

impl Model<Planar> {
    /// The `i`-th modal body in summation order (for tests and analyses).
    pub fn modal_body(&self, i: usize) -> &ModalBody {
        &self
            .elements_of::<ModalElement>()
            .nth(i)
            .expect("modal body index in range")
            .body
    }
}
