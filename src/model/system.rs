//! The assembled beam: coordinates, components, and the one seam the integrators use.
//!
//! Unknowns: `q` (n free coordinates, fixed ones eliminated), `λ` (m joint multipliers).
//! Equations: `s_d·(M(q) q̈ + f(q, q̇) − f_ext(q)) + Φ_qᵀ λ̃ = 0` and `Φ(q) = 0`, where `s_d` is a
//! row scale chosen by the integrator (βh² for generalized-α, 1 for statics) and λ̃ the
//! correspondingly scaled multiplier. [`Model::eval`] returns these residuals and, on request,
//! the Newton matrix `c_a·M + c_v·C + c_x·K + Σλ̃_i ∂²Φ_i` in a sparse pattern fixed at build.

use super::ancf::{AncfProps, Mat8, QuadTables, Vec8};
use super::joint::{end_kin, gather, joint_eval, End, Joint, FIXED};
use super::modal::{BodyOut, ModalBasis, ModalBody};
use crate::integrator::{EvalRequest, Integrable, StateRef};
use crate::linalg::{SingularMatrix, SparseLu, SparsePattern, NO_SLOT};
use crate::scene::{Root, Scene, SceneError, SegmentKind};
use nalgebra::Vector2;

#[derive(Debug, Clone)]
struct Element {
    props: AncfProps,
    mass: Mat8,
    /// 4×4 scalar pattern of the mass matrix (M = M4 ⊗ I₂).
    mass4: [[f64; 4]; 4],
    tables: QuadTables,
    idx: [u32; 8],
    fixed: [f64; 8],
    slots: Vec<u32>,
}

#[derive(Debug, Clone)]
struct JointSlot {
    joint: Joint,
    /// slots of (local q, row) for Φ_qᵀ, (row, local q) for Φ_q, Hessian computed on the fly.
    idx: Vec<u32>,
}

/// Largest local coordinate count of a modal body: 3 frame + modes + 2 interface shapes.
const MAX_BODY_DIM: usize = 3 + crate::scene::MAX_MODES + 2;

/// Which coordinates a segment owns (for outputs and tests).
#[derive(Debug, Clone, PartialEq)]
pub enum SegmentCoords {
    /// Modal body index.
    Modal(usize),
    /// Range of element indices.
    Ancf(std::ops::Range<usize>),
}

/// Scalar results of one state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Outputs {
    /// Tip position [m], global.
    pub tip_position: [f64; 2],
    /// Tip velocity [m/s], global.
    pub tip_velocity: [f64; 2],
    /// Angle of the tip tangent from global x [rad], in (−π, π].
    pub tip_angle: f64,
    /// Kinetic energy [J].
    pub kinetic: f64,
    /// Strain energy [J].
    pub strain: f64,
    /// Gravity potential energy −∫ρA gᵀr dx [J] (zero at the origin).
    pub potential: f64,
    /// Force of the support on the beam at the root [N], global axes.
    pub root_force: [f64; 2],
    /// Moment of the support on the beam about the root point [N m], counter-clockwise
    /// positive (zero for a pinned root).
    pub root_moment: f64,
}

/// The assembled beam model.
pub struct Model {
    n: usize,
    m: usize,
    elements: Vec<Element>,
    bodies: Vec<(ModalBody, Vec<u32>, Vec<f64>)>,
    body_slots: Vec<Vec<u32>>,
    body_out: Vec<BodyOut>,
    joints: Vec<JointSlot>,
    segments: Vec<SegmentCoords>,
    tip: End,
    tip_slots: Vec<u32>,
    gravity: [f64; 2],
    gravity_forces: Vec<Vec8>,
    /// Tip force applied on top of the scene's [N], global axes.
    pub tip_force: [f64; 2],
    scene_tip_force: [f64; 2],
    scale: Vec<f64>,
    q0: Vec<f64>,
    lu: SparseLu,
    values: Vec<f64>,
    damped: bool,
}

impl std::fmt::Debug for Model {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Model")
            .field("coordinates", &self.n)
            .field("constraints", &self.m)
            .field("elements", &self.elements.len())
            .field("modal_bodies", &self.bodies.len())
            .finish()
    }
}

fn idx_of(next: &mut usize, free: bool) -> u32 {
    if free {
        let i = *next as u32;
        *next += 1;
        i
    } else {
        FIXED
    }
}

impl Model {
    /// Builds the model of a validated scene, straight at `initial.angle` from the origin.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        scene.validate()?;
        let (sa, ca) = scene.initial.angle.sin_cos();
        let dir = [ca, sa];
        let clamped = scene.root == Root::Clamped;
        let mut next = 0usize;
        let mut q0: Vec<f64> = Vec::new();
        let mut scale: Vec<f64> = Vec::new();
        let lref = scene.total_length();
        let push = |next: &mut usize,
                    q0: &mut Vec<f64>,
                    scale: &mut Vec<f64>,
                    free: bool,
                    val: f64,
                    sc: f64| {
            let i = idx_of(next, free);
            if free {
                q0.push(val);
                scale.push(sc);
            }
            i
        };
        let mut elements = Vec::new();
        let mut bodies: Vec<(ModalBody, Vec<u32>, Vec<f64>)> = Vec::new();
        let mut joints = Vec::new();
        let mut segments = Vec::new();
        let mut prev_end: Option<End> = None;
        let mut s_pos = 0.0; // arc length at the segment root
        let mut damped = false;
        for (si, seg) in scene.segments.iter().enumerate() {
            let (area, inertia) = seg.area_inertia();
            let rho_a = seg.density * area;
            let ea = seg.youngs_modulus * area;
            let ei = seg.youngs_modulus * inertia;
            let root_pt = [s_pos * dir[0], s_pos * dir[1]];
            let first = si == 0;
            match seg.kind {
                SegmentKind::Modal => {
                    let basis = ModalBasis::new(seg.modes.unwrap_or(1), seg.interface_modes);
                    let body = ModalBody::new(
                        basis,
                        seg.length,
                        rho_a,
                        ei,
                        seg.damping_ratio,
                        seg.damping_time,
                    );
                    damped |= !body.d.is_empty();
                    let free_r = !first;
                    let free_th = !(first && clamped);
                    let mut idx = Vec::new();
                    let mut fixed = Vec::new();
                    for (v, free, sc) in [
                        (root_pt[0], free_r, lref),
                        (root_pt[1], free_r, lref),
                        (scene.initial.angle, free_th, 1.0),
                    ] {
                        idx.push(push(&mut next, &mut q0, &mut scale, free, v, sc));
                        fixed.push(v);
                    }
                    for _ in 0..body.modes() {
                        idx.push(push(&mut next, &mut q0, &mut scale, true, 0.0, lref));
                        fixed.push(0.0);
                    }
                    let bi = bodies.len();
                    bodies.push((body, idx, fixed));
                    if let Some(up) = prev_end.take() {
                        joints.push(Joint {
                            up,
                            down: End::ModalRoot { body: bi },
                            row: 3 * joints.len(),
                        });
                    }
                    segments.push(SegmentCoords::Modal(bi));
                    prev_end = Some(End::ModalTip { body: bi });
                }
                SegmentKind::Ancf => {
                    let ne = seg.elements.unwrap_or(1);
                    let le = seg.length / ne as f64;
                    let props = AncfProps {
                        length: le,
                        rho_a,
                        ea,
                        ei,
                        damping_time: seg.damping_time,
                        strain: seg.strain,
                    };
                    damped |= seg.damping_time > 0.0;
                    let node_vals = |s: f64| [s * dir[0], s * dir[1], dir[0], dir[1]];
                    // first node: shared with a previous ANCF segment, else new (fixed at the root)
                    let mut node: ([u32; 4], [f64; 4]) = match &prev_end {
                        Some(End::Node { idx, fixed }) => (*idx, *fixed),
                        _ => {
                            let v = node_vals(s_pos);
                            let free_r = !first;
                            let free_s = !(first && clamped);
                            let mut idx = [FIXED; 4];
                            for c in 0..4 {
                                let free = if c < 2 { free_r } else { free_s };
                                idx[c] = push(
                                    &mut next,
                                    &mut q0,
                                    &mut scale,
                                    free,
                                    v[c],
                                    if c < 2 { lref } else { 1.0 },
                                );
                            }
                            (idx, v)
                        }
                    };
                    if let Some(up) = prev_end.take() {
                        if !matches!(up, End::Node { .. }) {
                            joints.push(Joint {
                                up,
                                down: End::Node {
                                    idx: node.0,
                                    fixed: node.1,
                                },
                                row: 3 * joints.len(),
                            });
                        }
                    }
                    let e0 = elements.len();
                    for k in 0..ne {
                        let v = node_vals(s_pos + (k + 1) as f64 * le);
                        let mut idx2 = [FIXED; 4];
                        for c in 0..4 {
                            idx2[c] = push(
                                &mut next,
                                &mut q0,
                                &mut scale,
                                true,
                                v[c],
                                if c < 2 { lref } else { 1.0 },
                            );
                        }
                        let mut idx = [FIXED; 8];
                        let mut fixed = [0.0; 8];
                        idx[..4].copy_from_slice(&node.0);
                        idx[4..].copy_from_slice(&idx2);
                        fixed[..4].copy_from_slice(&node.1);
                        fixed[4..].copy_from_slice(&v);
                        elements.push(Element {
                            props,
                            mass: props.mass_matrix(),
                            tables: props.tables(),
                            mass4: {
                                let m = props.mass_matrix();
                                let mut m4 = [[0.0; 4]; 4];
                                for k in 0..4 {
                                    for j in 0..4 {
                                        m4[k][j] = m[(2 * k, 2 * j)];
                                    }
                                }
                                m4
                            },
                            idx,
                            fixed,
                            slots: Vec::new(),
                        });
                        node = (idx2, v);
                    }
                    segments.push(SegmentCoords::Ancf(e0..elements.len()));
                    prev_end = Some(End::Node {
                        idx: node.0,
                        fixed: node.1,
                    });
                }
            }
            s_pos += seg.length;
        }
        let tip = prev_end.expect("a validated scene has at least one segment");
        let n = next;
        let m = 3 * joints.len();
        // sparsity pattern
        let mut entries = Vec::new();
        let push_block = |entries: &mut Vec<(usize, usize)>, idx: &[u32]| {
            for &i in idx.iter().filter(|&&i| i != FIXED) {
                for &j in idx.iter().filter(|&&j| j != FIXED) {
                    entries.push((i as usize, j as usize));
                }
            }
        };
        for e in &elements {
            push_block(&mut entries, &e.idx);
        }
        for (_, idx, _) in &bodies {
            push_block(&mut entries, idx);
        }
        let joint_slots: Vec<JointSlot> = joints
            .into_iter()
            .map(|j| {
                let ku = end_kin(&j.up, &q0, &bodies);
                let kd = end_kin(&j.down, &q0, &bodies);
                let mut idx = ku.idx.clone();
                idx.extend_from_slice(&kd.idx);
                JointSlot { joint: j, idx }
            })
            .collect();
        for js in &joint_slots {
            push_block(&mut entries, &js.idx);
            for r in 0..3 {
                let row = n + js.joint.row + r;
                for &i in js.idx.iter().filter(|&&i| i != FIXED) {
                    entries.push((row, i as usize));
                    entries.push((i as usize, row));
                }
            }
        }
        let tip_kin = end_kin(&tip, &q0, &bodies);
        push_block(&mut entries, &tip_kin.idx);
        let pattern = SparsePattern::new(n + m, entries);
        let slots_of = |idx: &[u32]| -> Vec<u32> {
            let mut s = Vec::with_capacity(idx.len() * idx.len());
            for &i in idx {
                for &j in idx {
                    s.push(if i == FIXED || j == FIXED {
                        NO_SLOT
                    } else {
                        pattern.slot(i as usize, j as usize)
                    });
                }
            }
            s
        };
        for e in &mut elements {
            e.slots = slots_of(&e.idx);
        }
        let body_slots: Vec<Vec<u32>> = bodies.iter().map(|(_, idx, _)| slots_of(idx)).collect();
        let tip_slots = slots_of(&tip_kin.idx);
        let body_out = bodies
            .iter()
            .map(|(b, _, _)| BodyOut::new(b.dim()))
            .collect();
        let gravity_forces = elements
            .iter()
            .map(|e| e.props.gravity_force(scene.gravity))
            .collect();
        let nnz = pattern.nnz();
        Ok(Self {
            n,
            m,
            elements,
            bodies,
            body_slots,
            body_out,
            joints: joint_slots,
            segments,
            tip,
            tip_slots,
            gravity: scene.gravity,
            gravity_forces,
            tip_force: [0.0; 2],
            scene_tip_force: scene.tip.force,
            scale,
            q0,
            lu: SparseLu::new(pattern),
            values: vec![0.0; nnz],
            damped,
        })
    }

    /// Number of ANCF elements.
    pub fn element_count(&self) -> usize {
        self.elements.len()
    }

    /// Whether any damping term is present.
    pub fn is_damped(&self) -> bool {
        self.damped
    }

    /// Coordinates of the straight initial configuration.
    pub fn initial_coordinates(&self) -> &[f64] {
        &self.q0
    }

    /// Gravity [m/s²].
    pub fn gravity(&self) -> [f64; 2] {
        self.gravity
    }

    /// Sets gravity [m/s²].
    pub fn set_gravity(&mut self, g: [f64; 2]) {
        self.gravity = g;
        for (f, e) in self.gravity_forces.iter_mut().zip(&self.elements) {
            *f = e.props.gravity_force(g);
        }
    }

    /// Total tip force: scene constant + [`Model::tip_force`] [N].
    pub fn total_tip_force(&self) -> [f64; 2] {
        [
            self.scene_tip_force[0] + self.tip_force[0],
            self.scene_tip_force[1] + self.tip_force[1],
        ]
    }

    /// Segments and their coordinates.
    pub fn segments(&self) -> &[SegmentCoords] {
        &self.segments
    }

    /// Modal bodies (for tests and outputs).
    pub fn modal_body(&self, i: usize) -> &ModalBody {
        &self.bodies[i].0
    }

    /// Evaluates residuals into `res` (length n + m) and, if requested, the Newton matrix.
    /// `x.load` scales gravity and the tip force (1 = full load; load stepping in statics).
    fn eval_impl(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]) {
        let StateRef {
            q,
            v,
            a,
            lambda: lam,
            load,
        } = x;
        let n = self.n;
        res.fill(0.0);
        let want = req.matrix;
        if want.is_some() {
            self.values.fill(0.0);
        }
        let sd = req.sd;
        let f = self.total_tip_force();
        let values = &mut self.values;
        // ANCF elements
        for (el, gf) in self.elements.iter().zip(&self.gravity_forces) {
            let mut e = [0.0; 8];
            let mut ed = [0.0; 8];
            let mut ea = [0.0; 8];
            for k in 0..8 {
                let i = el.idx[k];
                if i == FIXED {
                    e[k] = el.fixed[k];
                } else {
                    let i = i as usize;
                    e[k] = q[i];
                    ed[k] = v[i];
                    ea[k] = a[i];
                }
            }
            let (force, matrices) = if want.is_some() {
                let out = el.props.elastic(&Vec8::from(e), &Vec8::from(ed), true);
                (out.force.into(), Some(out))
            } else {
                (el.props.internal_force_with(&el.tables, &e, &ed), None)
            };
            // f = M ë + f_int − f_g, M = M4 ⊗ I₂
            for k in 0..4 {
                for c in 0..2 {
                    let mut mk = 0.0;
                    for j in 0..4 {
                        mk += el.mass4[k][j] * ea[2 * j + c];
                    }
                    let r = 2 * k + c;
                    let i = el.idx[r];
                    if i != FIXED {
                        res[i as usize] += sd * (mk + force[r] - load * gf[r]);
                    }
                }
            }
            if let (Some((ca, cv, cx)), Some(out)) = (want, matrices) {
                for r in 0..8 {
                    for c in 0..8 {
                        let s = el.slots[r * 8 + c];
                        if s != NO_SLOT {
                            let mut val = ca * el.mass[(r, c)] + cx * out.stiffness[(r, c)];
                            if cv != 0.0 && el.props.damping_time > 0.0 {
                                val += cv * out.damping[(r, c)];
                            }
                            values[s as usize] += val;
                        }
                    }
                }
            }
        }
        // modal bodies
        for (bi, (body, idx, fixed)) in self.bodies.iter().enumerate() {
            let d = idx.len();
            let mut ql = [0.0; MAX_BODY_DIM];
            let mut vl = [0.0; MAX_BODY_DIM];
            let mut al = [0.0; MAX_BODY_DIM];
            for k in 0..d {
                if idx[k] == FIXED {
                    ql[k] = fixed[k];
                } else {
                    let i = idx[k] as usize;
                    ql[k] = q[i];
                    vl[k] = v[i];
                    al[k] = a[i];
                }
            }
            let out = &mut self.body_out[bi];
            let g = [load * self.gravity[0], load * self.gravity[1]];
            body.eval(&ql[..d], &vl[..d], &al[..d], g, want.is_some(), out);
            for k in 0..d {
                if idx[k] != FIXED {
                    res[idx[k] as usize] += sd * out.res[k];
                }
            }
            if let Some((ca, cv, cx)) = want {
                let slots = &self.body_slots[bi];
                for r in 0..d {
                    for c in 0..d {
                        let s = slots[r * d + c];
                        if s != NO_SLOT {
                            values[s as usize] +=
                                ca * out.m[(r, c)] + cv * out.c[(r, c)] + cx * out.k[(r, c)];
                        }
                    }
                }
            }
        }
        // tip force: residual −Jᵀ F, stiffness −F·∂²p
        if f != [0.0, 0.0] {
            let fv = load * Vector2::new(f[0], f[1]);
            let kin = end_kin(&self.tip, q, &self.bodies);
            for (k, &i) in kin.idx.iter().enumerate() {
                if i != FIXED {
                    res[i as usize] -= sd * kin.dp[k].dot(&fv);
                }
            }
            if let Some((_, _, cx)) = want {
                let d = kin.idx.len();
                let slots = &self.tip_slots;
                kin.add_point_hessian(-fv, |i, j, h| {
                    let s = slots[i * d + j];
                    if s != NO_SLOT {
                        values[s as usize] += cx * h;
                    }
                });
            }
        }
        // joints
        for js in &self.joints {
            let ku = end_kin(&js.joint.up, q, &self.bodies);
            let kd = end_kin(&js.joint.down, q, &self.bodies);
            let row = n + js.joint.row;
            let l = [
                lam[js.joint.row],
                lam[js.joint.row + 1],
                lam[js.joint.row + 2],
            ];
            let je = joint_eval(
                &ku,
                &kd,
                if req.lambda_hessian && want.is_some() {
                    Some(l)
                } else {
                    None
                },
            );
            for r in 0..3 {
                res[row + r] = je.phi[r];
                for (k, &i) in je.idx.iter().enumerate() {
                    if i != FIXED {
                        res[i as usize] += je.jac[r][k] * l[r];
                    }
                }
            }
            if want.is_some() {
                let pat = self.lu.pattern();
                for r in 0..3 {
                    for (k, &i) in je.idx.iter().enumerate() {
                        if i != FIXED && je.jac[r][k] != 0.0 {
                            values[pat.slot(row + r, i as usize) as usize] += je.jac[r][k];
                            values[pat.slot(i as usize, row + r) as usize] += je.jac[r][k];
                        }
                    }
                }
                for &(i, j, h) in &je.hess {
                    let (gi, gj) = (je.idx[i], je.idx[j]);
                    if gi != FIXED && gj != FIXED {
                        values[pat.slot(gi as usize, gj as usize) as usize] += h;
                    }
                }
            }
        }
    }

    /// The matrix assembled by the last [`Model::eval`] with a matrix request, as dense rows
    /// (for linearized analyses and tests; O((n + m)²) memory).
    pub fn assembled_dense(&self) -> Vec<Vec<f64>> {
        let p = self.lu.pattern();
        let d = p.dim();
        let mut out = vec![vec![0.0; d]; d];
        for (c, row) in (0..d).flat_map(|c| p.column(c).map(move |r| (c, r))) {
            out[row][c] = self.values[p.slot(row, c) as usize];
        }
        out
    }

    /// Reaction of the support on the beam: the residual `M q̈ + f − f_ext + Φ_qᵀλ` of the
    /// eliminated root coordinates (force on the root position, moment from the root slope or
    /// frame angle).
    fn root_reaction(&self, q: &[f64], v: &[f64], acc: &[f64], lam: &[f64]) -> ([f64; 2], f64) {
        match &self.segments[0] {
            SegmentCoords::Ancf(range) => {
                let el = &self.elements[range.start];
                let e = Vec8::from_column_slice(&gather(&el.idx, Some(&el.fixed), q));
                let ed = Vec8::from_column_slice(&gather(&el.idx, None, v));
                let ea = Vec8::from_column_slice(&gather(&el.idx, None, acc));
                let f = el.mass * ea + el.props.elastic(&e, &ed, false).force
                    - self.gravity_forces[range.start];
                let moment = if el.idx[2] == FIXED {
                    e[2] * f[3] - e[3] * f[2]
                } else {
                    0.0
                };
                ([f[0], f[1]], moment)
            }
            SegmentCoords::Modal(bi) => {
                let (body, idx, fixed) = &self.bodies[*bi];
                let ql = gather(idx, Some(fixed), q);
                let vl = gather(idx, None, v);
                let al = gather(idx, None, acc);
                let mut out = BodyOut::new(body.dim());
                body.eval(&ql, &vl, &al, self.gravity, false, &mut out);
                let mut r = [out.res[0], out.res[1], out.res[2]];
                let tip_here = End::ModalTip { body: *bi };
                if self.tip == tip_here {
                    let f = self.total_tip_force();
                    let kin = end_kin(&self.tip, q, &self.bodies);
                    for k in 0..3 {
                        r[k] -= kin.dp[k][0] * f[0] + kin.dp[k][1] * f[1];
                    }
                }
                for js in self.joints.iter().filter(|j| j.joint.up == tip_here) {
                    let ku = end_kin(&js.joint.up, q, &self.bodies);
                    let kd = end_kin(&js.joint.down, q, &self.bodies);
                    let je = joint_eval(&ku, &kd, None);
                    for row in 0..3 {
                        for k in 0..3 {
                            r[k] += je.jac[row][k] * lam[js.joint.row + row];
                        }
                    }
                }
                let moment = if idx[2] == FIXED { r[2] } else { 0.0 };
                ([r[0], r[1]], moment)
            }
        }
    }

    /// Largest elastic deflection of a modal segment: (segment index in the scene,
    /// max(|w(L)|/L, |θ_J|)), the tip deflection over the length or the tip slope [rad].
    pub fn max_modal_deflection(&self, q: &[f64]) -> Option<(usize, f64)> {
        let mut worst: Option<(usize, f64)> = None;
        for (si, seg) in self.segments.iter().enumerate() {
            if let SegmentCoords::Modal(bi) = seg {
                let (body, idx, fixed) = &self.bodies[*bi];
                let ql = gather(idx, Some(fixed), q);
                let w = body.tip_local(&ql)[1].abs() / body.length;
                let d = w.max(body.tip_slope(&ql).abs());
                if worst.is_none_or(|(_, x)| d > x) {
                    worst = Some((si, d));
                }
            }
        }
        worst
    }

    /// Largest |axial strain| over the ANCF quadrature points (0 without ANCF segments).
    pub fn max_axial_strain(&self, q: &[f64]) -> f64 {
        let mut worst: f64 = 0.0;
        for el in &self.elements {
            let mut e = [0.0; 8];
            for k in 0..8 {
                e[k] = if el.idx[k] == FIXED {
                    el.fixed[k]
                } else {
                    q[el.idx[k] as usize]
                };
            }
            for (_, ds) in &el.tables.axial {
                let (mut x, mut y) = (0.0, 0.0);
                for k in 0..4 {
                    x += ds[k] * e[2 * k];
                    y += ds[k] * e[2 * k + 1];
                }
                worst = worst.max(((x * x + y * y).sqrt() - 1.0).abs());
            }
        }
        worst
    }

    /// Outputs at a state (q, q̇, q̈, λ).
    pub fn outputs(&self, q: &[f64], v: &[f64], acc: &[f64], lam: &[f64]) -> Outputs {
        let kin = end_kin(&self.tip, q, &self.bodies);
        let mut vel = Vector2::zeros();
        for (k, &i) in kin.idx.iter().enumerate() {
            if i != FIXED {
                vel += kin.dp[k] * v[i as usize];
            }
        }
        let mut o = Outputs {
            tip_position: [kin.p[0], kin.p[1]],
            tip_velocity: [vel[0], vel[1]],
            tip_angle: kin.angle(),
            ..Default::default()
        };
        for (el, gf) in self.elements.iter().zip(&self.gravity_forces) {
            let mut e = Vec8::zeros();
            let mut ed = Vec8::zeros();
            for k in 0..8 {
                let i = el.idx[k];
                if i == FIXED {
                    e[k] = el.fixed[k];
                } else {
                    e[k] = q[i as usize];
                    ed[k] = v[i as usize];
                }
            }
            o.kinetic += 0.5 * ed.dot(&(el.mass * ed));
            o.strain += el.props.strain_energy(&e);
            o.potential -= gf.dot(&e);
        }
        for (body, idx, fixed) in &self.bodies {
            let ql = gather(idx, Some(fixed), q);
            let vl = gather(idx, None, v);
            o.kinetic += body.kinetic_energy(&ql, &vl);
            o.strain += body.strain_energy(&ql);
            o.potential += body.potential_energy(&ql, self.gravity);
        }
        (o.root_force, o.root_moment) = self.root_reaction(q, v, acc, lam);
        o
    }
}

impl Integrable for Model {
    fn coordinates(&self) -> usize {
        self.n
    }
    fn constraints(&self) -> usize {
        self.m
    }
    fn scales(&self) -> &[f64] {
        &self.scale
    }
    fn eval(&mut self, x: StateRef<'_>, req: EvalRequest, res: &mut [f64]) {
        self.eval_impl(x, req, res)
    }
    fn factorize(&mut self) -> Result<(), SingularMatrix> {
        self.lu.factorize(&self.values)
    }
    fn solve(&mut self, rhs: &mut [f64]) -> bool {
        self.lu.solve(rhs)
    }
}
