//! The planar elements as components: the ANCF cable element (8 coordinates) and the
//! floating-frame modal body (3 + n coordinates), wrapping their kernels.

use super::Planar;
use crate::math;
use crate::model::ancf::{
    gauss5_interpolate, AncfProps, Mat8, QuadTables, SectionMass, Shape, Vec8, GAUSS5,
};
use crate::model::assembly::Model;
use crate::model::component::{Element, ElementOut, Energies, Env, LocalState, Validity};
use crate::model::modal::{BodyGravity, BodyOut, ModalBody};
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
    /// ∫ρA Sᵀ g dx at the current gravity (and the point masses' weight).
    gravity_force: Vec8,
    /// Σ m S(ξ_m)ᵀ over the point masses on the element (scalar pattern) [kg, kg m]; `None`
    /// without masses.
    points: Option<[f64; 4]>,
    /// Rigid bodies on the element's section (offset or rotary inertia) with S(ξ), S′(ξ).
    bodies: Vec<(SectionMass, [f64; 4], [f64; 4])>,
    /// The current gravity [m/s²].
    g: [f64; 2],
    /// The segment's line load over ρA, q/(ρA) [m/s²] on a uniform element; on a tapered one
    /// ([`AncfProps::taper`]) the load q itself [N/m]; `None` without one.
    line: Option<[f64; 2]>,
    /// The point masses (ξ, m [kg]) on the element, for [`Element::partial_load`].
    point_list: Vec<(f64, f64)>,
}

/// The Newton coefficients (c_a, c_v, c_x) and the 8 × 8 block the section bodies add to.
type BodyBlock<'a> = ((f64, f64, f64), &'a mut [[f64; 8]; 8]);

/// Σ_k w_k e_{2k + c} for c = 0, 1.
#[inline]
fn comb2(w: &[f64; 4], e: &[f64; 8]) -> [f64; 2] {
    let mut o = [0.0; 2];
    for k in 0..4 {
        o[0] += w[k] * e[2 * k];
        o[1] += w[k] * e[2 * k + 1];
    }
    o
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
            points: None,
            bodies: Vec::new(),
            g: [0.0; 2],
            line: None,
            point_list: Vec::new(),
        }
    }

    /// The element under the uniform dead line load `q` [N/m] (world axes; `None`: none): a
    /// load of density q beside the weight ρA g, so ∫Sᵀ(ρA g + q) dx is the distributed force
    /// (and −∫qᵀr dx joins the potential); the point masses and section bodies keep g.
    pub fn with_line_load(mut self, q: Option<[f64; 2]>) -> Self {
        self.line = q.map(|q| self.line_of(q));
        self
    }

    /// The stored form of the line load `q` [N/m] ([`AncfElement::line`]).
    fn line_of(&self, q: [f64; 2]) -> [f64; 2] {
        let tapered = self.props.taper.is_some();
        q.map(|c| if tapered { c } else { c / self.props.rho_a })
    }

    /// The element carrying rigid bodies on its section ([`SectionMass`]: an offset or a
    /// rotary inertia).
    pub fn with_bodies(mut self, bodies: &[SectionMass]) -> Self {
        let l = self.props.length;
        self.bodies = bodies
            .iter()
            .map(|b| {
                let sh = Shape::at(b.xi, l);
                (*b, sh.s, sh.ds)
            })
            .collect();
        self
    }

    /// Adds the section bodies' forces at (e, ė, ë) under gravity `g` to `res`, and with
    /// `matrix` = (c_a, c_v, c_x) their Newton block (8 × 8, row-major) to `block`.
    fn add_bodies(
        &self,
        (e, ed, ea): (&[f64; 8], &[f64; 8], &[f64; 8]),
        g: [f64; 2],
        res: &mut [f64; 8],
        mut block: Option<BodyBlock<'_>>,
    ) {
        use num_dual::Dual64;
        for (b, sv, dv) in &self.bodies {
            let x = [comb2(sv, ea), comb2(dv, e), comb2(dv, ed), comb2(dv, ea)];
            let f = b.forces(x[0], x[1], x[2], x[3], g);
            for k in 0..4 {
                for c in 0..2 {
                    res[2 * k + c] += sv[k] * f[c] + dv[k] * f[2 + c];
                }
            }
            let Some(((ca, cv, cx), blk)) = block.as_mut() else {
                continue;
            };
            // ∂f/∂(r̈, d, ḋ, d̈) column by column, then through S (r̈ = Së) and S′ (d = S′e)
            let lift = |v: [f64; 2]| v.map(Dual64::from_re);
            for input in 0..4 {
                let (coef, w) = match input {
                    0 => (*ca, sv),
                    1 => (*cx, dv),
                    2 => (*cv, dv),
                    _ => (*ca, dv),
                };
                if coef == 0.0 {
                    continue;
                }
                for cc in 0..2 {
                    let mut xd = x.map(lift);
                    xd[input][cc].eps = 1.0;
                    let fd = b.forces(xd[0], xd[1], xd[2], xd[3], g);
                    for k in 0..4 {
                        for c in 0..2 {
                            let row = sv[k] * fd[c].eps + dv[k] * fd[2 + c].eps;
                            for l in 0..4 {
                                blk[2 * k + c][2 * l + cc] += coef * row * w[l];
                            }
                        }
                    }
                }
            }
        }
    }

    /// M ë with M = M4 ⊗ I₂ (row by row, left to right).
    #[inline]
    fn inertia(&self, ea: &[f64; 8]) -> [f64; 8] {
        let mut m = [0.0; 8];
        for k in 0..4 {
            let (mut mx, mut my) = (0.0, 0.0);
            for j in 0..4 {
                mx += self.mass4[k][j] * ea[2 * j];
                my += self.mass4[k][j] * ea[2 * j + 1];
            }
            (m[2 * k], m[2 * k + 1]) = (mx, my);
        }
        m
    }

    /// The element carrying point masses `points` (ξ ∈ [0, 1], mass [kg]): a point at ξ is at
    /// r = S(ξ)e, so it adds m S(ξ)ᵀS(ξ) to the constant mass matrix and m S(ξ)ᵀg to the
    /// gravity force.
    pub fn with_points(mut self, points: &[(f64, f64)]) -> Self {
        if points.is_empty() {
            return self;
        }
        let mut w = [0.0; 4];
        for &(xi, m) in points {
            let s = Shape::at(xi, self.props.length).s;
            for k in 0..4 {
                w[k] += m * s[k];
                for j in 0..4 {
                    let mkj = m * s[k] * s[j];
                    self.mass4[k][j] += mkj;
                    self.mass[(2 * k, 2 * j)] += mkj;
                    self.mass[(2 * k + 1, 2 * j + 1)] += mkj;
                }
            }
        }
        self.points = Some(w);
        self.point_list = points.to_vec();
        self
    }
}

impl Element<Planar> for AncfElement {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
        let (e, ed, ea) = x.arrays::<8>();
        // r = M ë + f_int − load·f_g, M = M4 ⊗ I₂
        let mut res = self.inertia(&ea);
        let gf = &self.gravity_force;
        let Some((ca, cv, cx)) = out.matrix else {
            let force = self.props.internal_force_with(&self.tables, &e, &ed);
            for i in 0..8 {
                res[i] = res[i] + force[i] - env.load * gf[i];
            }
            if !self.bodies.is_empty() {
                let g = [env.load * self.g[0], env.load * self.g[1]];
                self.add_bodies((&e, &ed, &ea), g, &mut res, None);
            }
            out.add_residual(&res);
            return;
        };
        let (mut force, mut k, mut d) = ([0.0; 8], [[0.0; 8]; 8], [[0.0; 8]; 8]);
        let matrices = Some((&mut k, &mut d));
        self.props
            .elastic_into(&self.tables, &e, &ed, &mut force, matrices);
        for i in 0..8 {
            res[i] = res[i] + force[i] - env.load * gf[i];
        }
        // c_a M + c_x K (+ c_v C) (+ the section bodies' block), entry by entry in that order
        for (r, row) in k.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = ca * self.mass[(r, c)] + cx * *v;
            }
        }
        if cv != 0.0 && self.props.damping_time > 0.0 {
            for (row, drow) in k.iter_mut().zip(&d) {
                for (v, dv) in row.iter_mut().zip(drow) {
                    *v += cv * dv;
                }
            }
        }
        if !self.bodies.is_empty() {
            let mut blk = [[0.0; 8]; 8];
            let g = [env.load * self.g[0], env.load * self.g[1]];
            self.add_bodies((&e, &ed, &ea), g, &mut res, Some(((ca, cv, cx), &mut blk)));
            for (row, brow) in k.iter_mut().zip(&blk) {
                for (v, bv) in row.iter_mut().zip(brow) {
                    *v += bv;
                }
            }
        }
        out.add_residual(&res);
        out.add_block(|r, c| k[r][c]);
    }

    fn residual(&self, x: &LocalState<'_>, _env: &Env<Planar>, res: &mut [f64]) {
        let (e, ed, ea) = x.arrays::<8>();
        let (ev, edv, eav) = (Vec8::from(e), Vec8::from(ed), Vec8::from(ea));
        let f = self.mass * eav + self.props.elastic(&ev, &edv, false).force - self.gravity_force;
        res.copy_from_slice(f.as_slice());
        if !self.bodies.is_empty() {
            let mut r = [0.0; 8];
            self.add_bodies((&e, &ed, &ea), self.g, &mut r, None);
            for (o, x) in res.iter_mut().zip(r) {
                *o += x;
            }
        }
    }

    fn energies(&self, x: &LocalState<'_>, _gravity: &[f64; 2]) -> Energies {
        let (e, ed, _) = x.arrays::<8>();
        let (ev, edv) = (Vec8::from(e), Vec8::from(ed));
        let mut out = Energies {
            kinetic: 0.5 * edv.dot(&(self.mass * edv)),
            strain: self.props.strain_energy(&ev),
            potential: -self.gravity_force.dot(&ev),
        };
        for (b, sv, dv) in &self.bodies {
            let (r, rd) = (comb2(sv, &e), comb2(sv, &ed));
            let (t, u) = b.energies(r, rd, comb2(dv, &e), comb2(dv, &ed), self.g);
            out.kinetic += t;
            out.potential += u;
        }
        out
    }

    fn length(&self) -> f64 {
        self.props.length
    }

    fn sample(&self, x: &LocalState<'_>, xi: &[f64], out: &mut Vec<ShapePoint>) {
        let (e, ed, _) = x.arrays::<8>();
        let (e, ed) = (Vec8::from(e), Vec8::from(ed));
        out.extend(xi.iter().map(|&s| self.props.sample(&e, &ed, s)));
    }

    fn set_line_load(&mut self, q: &[f64; 2]) {
        self.line = Some(self.line_of(*q));
    }

    /// Gauss 5 on [0, ξ]: exact for ρA(g − S ë) and (r − p) × ρA(g − S ë), of degree 6 on a
    /// uniform element and 8 on a tapered one (ρA(x), at most quadratic, from its 5 quadrature
    /// values, [`gauss5_interpolate`]); the point masses at ξ_m < ξ and the section bodies at
    /// ξ_b < ξ with their own d'Alembert force −f_r and moment −((r − p) × f_r + d × f_d)
    /// ([`SectionMass::forces`]: the rigid projection of their generalized force).
    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 2],
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let (e8, ed8, ea8) = x.arrays::<8>();
        let (e, ea) = (Vec8::from(e8), Vec8::from(ea8));
        let l = self.props.length;
        let line = self.line.unwrap_or([0.0; 2]);
        let (mut f, mut m) = ([0.0; 3], 0.0);
        let mut add = |s: f64, w: f64, mass: f64, field: [f64; 2]| {
            let sh = Shape::at(s, l);
            let (r, a) = (sh.r(&e), sh.r(&ea));
            let load = [w * mass * (field[0] - a[0]), w * mass * (field[1] - a[1])];
            f[0] += load[0];
            f[1] += load[1];
            m += (r[0] - about[0]) * load[1] - (r[1] - about[1]) * load[0];
        };
        match &self.props.taper {
            None => {
                let distributed = [gravity[0] + line[0], gravity[1] + line[1]];
                for (xg, wg) in GAUSS5 {
                    add(
                        0.5 * xi * (xg + 1.0),
                        0.5 * xi * l * wg,
                        self.props.rho_a,
                        distributed,
                    );
                }
            }
            Some(t) => {
                // the line load q [N/m] as a field over the local ρA(x)
                for (xg, wg) in GAUSS5 {
                    let s = 0.5 * xi * (xg + 1.0);
                    let ra = gauss5_interpolate(&t.rho_a, s);
                    let field = [gravity[0] + line[0] / ra, gravity[1] + line[1] / ra];
                    add(s, 0.5 * xi * l * wg, ra, field);
                }
            }
        }
        for &(xm, mass) in self.point_list.iter().filter(|(xm, _)| *xm < xi) {
            add(xm, 1.0, mass, *gravity);
        }
        for (b, sv, dv) in self.bodies.iter().filter(|(b, _, _)| b.xi < xi) {
            let d = comb2(dv, &e8);
            let fb = b.forces(
                comb2(sv, &ea8),
                d,
                comb2(dv, &ed8),
                comb2(dv, &ea8),
                *gravity,
            );
            let r = comb2(sv, &e8);
            f[0] -= fb[0];
            f[1] -= fb[1];
            m -= (r[0] - about[0]) * fb[1] - (r[1] - about[1]) * fb[0];
            m -= d[0] * fb[3] - d[1] * fb[2];
        }
        Some((f, [0.0, 0.0, m]))
    }

    fn set_gravity(&mut self, g: &[f64; 2]) {
        self.gravity_force = match self.line {
            Some(q) if self.props.taper.is_some() => {
                self.props.gravity_force(*g) + self.props.line_force(q)
            }
            Some(b) => self.props.gravity_force([g[0] + b[0], g[1] + b[1]]),
            None => self.props.gravity_force(*g),
        };
        self.g = *g;
        if let Some(w) = &self.points {
            for k in 0..4 {
                self.gravity_force[2 * k] += w[k] * g[0];
                self.gravity_force[2 * k + 1] += w[k] * g[1];
            }
        }
    }

    fn is_damped(&self) -> bool {
        self.props.damping_time > 0.0
    }

    fn validity(&self, q: &[f64]) -> Validity {
        let mut worst: f64 = 0.0;
        for (i, (_, ds)) in self.tables.axial.iter().enumerate() {
            let (mut x, mut y) = (0.0, 0.0);
            for k in 0..4 {
                x += ds[k][0] * q[2 * k];
                y += ds[k][1] * q[2 * k + 1];
            }
            // from the curved reference's ε₀ (the strain the element's stress counts)
            let e0 = self.props.reference.map_or(0.0, |r| r.axial[i]);
            worst = worst.max(((x * x + y * y).sqrt() - 1.0 - e0).abs());
        }
        Validity {
            axial_strain: worst,
            modal_deflection: None,
            section: None,
            chart_margin: None,
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A planar floating-frame modal body, local coordinates `[R_x, R_y, θ, a_1 … a_n]`. The
/// nonlinear body's kinematics carry the foreshortening of every point, so the axial force of
/// the centrifugal, axial inertia and gravity fields stiffens the modes of held and free frames
/// alike; a linear body ([`ModalBody::linear`]) of a held frame adds instead its leading term,
/// the geometric stiffness K_G = ρAL θ̇² G2 − ρA ā_x G1 (docs/spatial.md).
#[derive(Debug, Clone)]
pub struct ModalElement {
    /// The body (shared with its ports).
    pub body: Arc<ModalBody>,
    /// (G1, G2) of the basis when a linear body's frame is held by a support (a clamped or
    /// mounted root segment): the bending rows then carry K_G = ρAL θ̇² G2 − ρA ā_x G1,
    /// ā = Aᵀ(R̈ − g), the axial force of the segment's centrifugal and axial inertia field.
    stiffening: Option<(Vec<f64>, Vec<f64>)>,
    out: BodyOut,
    /// The body's output for [`Element::residual`] (through `&self`).
    residual_out: crate::model::scratch::Scratch<BodyOut>,
    /// Local (q, q̇, q̈) of the last evaluation.
    x: [Vec<f64>; 3],
    /// The segment's line load over ρA, q/(ρA) [m/s²] (the body's at build, then
    /// [`Element::set_line_load`]'s); `None` without one.
    line: Option<[f64; 2]>,
}

impl ModalElement {
    /// Component of `body`.
    pub fn new(body: Arc<ModalBody>) -> Self {
        let d = body.dim();
        let out = BodyOut::new(d);
        Self {
            line: body.line,
            body,
            stiffening: None,
            residual_out: crate::model::scratch::Scratch::new(out.clone()),
            out,
            x: [vec![0.0; d], vec![0.0; d], vec![0.0; d]],
        }
    }

    /// The element of a held frame: with the geometric stiffening K_G if the body is linear
    /// (the nonlinear body has it in its own forces).
    pub fn held(body: Arc<ModalBody>) -> Self {
        let stiffening = (!body.nonlinear).then(|| body.stiffening_grams());
        Self {
            stiffening,
            ..Self::new(body)
        }
    }
}

/// Adds K_G a to the bending rows of `res` (and K_G to the a×a block of `k`) for a held frame
/// at (q, q̇, q̈) under gravity `g`; derivatives by the held frame's coordinates are not needed
/// (they have no columns). A tapered body ([`ModalBody::is_tapered`]): its ρA-weighted grams,
/// gravity on its mass and its line load's axial part (Aᵀq)_x G1 apart.
fn add_stiffening(
    body: &ModalBody,
    (g1, g2): &(Vec<f64>, Vec<f64>),
    (q, v, a): (&[f64], &[f64], &[f64]),
    grav: &BodyGravity<2>,
    res: &mut [f64],
    k: Option<&mut nalgebra::DMatrix<f64>>,
) {
    let n = body.modes();
    let (s, c) = math::sin_cos(q[2]);
    let g = if body.is_tapered() {
        grav.points
    } else {
        grav.distributed
    };
    let ax = c * (a[0] - g[0]) + s * (a[1] - g[1]);
    let (kw, ka) = (body.rho_a * body.length * v[2] * v[2], body.rho_a * ax);
    let line = body
        .taper_line(grav)
        .map(|(qw, g1l)| (c * qw[0] + s * qw[1], g1l));
    if kw == 0.0 && ka == 0.0 && line.is_none() {
        // a frame at rest with no axial field (a clamped root across gravity): K_G = 0
        return;
    }
    let kg = |i: usize, j: usize| {
        let k = kw * g2[i * n + j] - ka * g1[i * n + j];
        match line {
            Some((qx, g1l)) => k + qx * g1l[i * n + j],
            None => k,
        }
    };
    for i in 0..n {
        res[3 + i] += (0..n).map(|j| kg(i, j) * q[3 + j]).sum::<f64>();
    }
    if let Some(k) = k {
        for i in 0..n {
            for j in 0..n {
                k[(3 + i, 3 + j)] += kg(i, j);
            }
        }
    }
}

impl Element<Planar> for ModalElement {
    fn eval(&mut self, x: &LocalState<'_>, env: &Env<Planar>, mut out: ElementOut<'_>) {
        let g = BodyGravity::of(env.gravity, env.load, self.line);
        let [q, v, a] = &mut self.x;
        x.gather(q, v, a);
        let body = &mut self.out;
        self.body.eval(q, v, a, g, out.matrix.is_some(), body);
        if let Some(grams) = &self.stiffening {
            let k = out.matrix.is_some().then_some(&mut body.k);
            add_stiffening(&self.body, grams, (q, v, a), &g, body.res.as_mut_slice(), k);
        }
        out.add_residual(body.res.as_slice());
        if let Some((ca, cv, cx)) = out.matrix {
            out.add_block(|r, c| ca * body.m[(r, c)] + cv * body.c[(r, c)] + cx * body.k[(r, c)]);
        }
    }

    fn residual(&self, x: &LocalState<'_>, env: &Env<Planar>, res: &mut [f64]) {
        let (q, v, a) = x.vectors();
        self.residual_out.with(|out| {
            let g = BodyGravity::of(env.gravity, 1.0, self.line);
            self.body.eval(&q, &v, &a, g, false, out);
            if let Some(grams) = &self.stiffening {
                let r = out.res.as_mut_slice();
                add_stiffening(&self.body, grams, (&q, &v, &a), &g, r, None);
            }
            res.copy_from_slice(out.res.as_slice());
        });
    }

    fn energies(&self, x: &LocalState<'_>, gravity: &[f64; 2]) -> Energies {
        let (q, v, _) = x.vectors();
        Energies {
            kinetic: self.body.kinetic_energy(&q, &v),
            strain: self.body.strain_energy(&q),
            potential: self
                .body
                .potential_energy(&q, BodyGravity::of(*gravity, 1.0, self.line)),
        }
    }

    fn set_line_load(&mut self, q: &[f64; 2]) {
        self.line = Some(q.map(|c| c / self.body.rho_a));
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

    /// [`ModalBody::partial_load`] with the element's line load.
    fn partial_load(
        &self,
        x: &LocalState<'_>,
        gravity: &[f64; 2],
        xi: f64,
        about: [f64; 3],
    ) -> Option<([f64; 3], [f64; 3])> {
        let (q, v, a) = x.vectors();
        let g = BodyGravity::of(*gravity, 1.0, self.line);
        self.body.partial_load((&q, &v, &a), g, xi, about)
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
            chart_margin: None,
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
