//! Stations (`[[stations]]`): the section loads at a cut of the beam — the force and moment that
//! the part beyond the cut (outboard) exerts on the part before it (inboard), in the section
//! frame at the cut — and the largest von Mises stress over the section's boundary.
//!
//! The loads come from the equilibrium of a part of the beam, not from the local strain of an
//! element: with r_e the residual of an element at full load (M q̈ + internal − external forces,
//! on its local coordinates) and δq its coordinates' virtual displacement under a rigid virtual
//! motion of the part before the cut (inboard, with the support) — a translation δu, a rotation
//! δθ about the cut point p ([`Rigid`] says how each coordinate group moves) — the internal and
//! joint forces within the part do no virtual work, so the loads F, M that the part beyond the
//! cut (outboard) exerts on the inboard part at p (world axes) are
//!
//! F·δu + M·δθ = Σ_{inboard e} r_e·δq_e − R·δu − (M_R + (o − p) × R)·δθ,
//!
//! R, M_R the support's force and moment on the beam about the root point o (`root.force`,
//! `root.moment`), then turned into the section frame at the cut (x along the tangent; planar:
//! force x, y and moment z). This is the discrete model's own equilibrium: a cut at the root
//! gives exactly minus the support reaction, a cut at the free end the tip loads (to the Newton
//! tolerance of the state: the outboard part's equilibrium, F_tip − Σ_{outboard} r_e·δq_e, gives
//! the same loads to that tolerance), and the loads converge with the mesh as the reaction does.
//! A cut is anywhere along a segment: at a segment's end or a node between ANCF elements the
//! outboard part is a set of whole elements; inside an element (ANCF element, modal body) the
//! element integrates its own part before the cut ([`super::component::Element::partial_load`])
//! and the loads at its start are carried across that part (see [`Model::station_loads`]).

use super::assembly::Model;
use super::component::{Env, LocalState};
use super::cut::{Cut, GroupMap, StressPoint};
use super::dofs::{Dof, Rigid};
pub use super::section_stress::{SectionShape, StressSection};
use super::space::Space;
use crate::scene::{Scene, SceneError, Segment, MAX_STATIONS};

/// The loads at one station, section frame at the cut.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StationLoads {
    /// Force of the outboard part on the inboard part [N]: axial x (tension positive), shear
    /// y, z (planar: x, y).
    pub force: [f64; 3],
    /// Moment of the outboard part on the inboard part about the cut [N m]: torsion x,
    /// bending y, z (planar: z).
    pub moment: [f64; 3],
    /// Largest von Mises stress over the section's boundary [Pa] ([`SectionShape::stress`]).
    pub stress: f64,
}

/// Where the beam's stress is sampled along an element: its ends and its 3 Gauss points
/// (those of the elements' bending terms), ξ ∈ [0, 1].
const STRESS_POINTS: [f64; 5] = [
    0.0,
    0.112_701_665_379_258_31,
    0.5,
    0.887_298_334_620_741_7,
    1.0,
];

impl<S: Space> Model<S> {
    /// Sets the stations of `scene` (validated): for each, the outboard elements, the sample
    /// of its cut, its section.
    pub fn set_stations(&mut self, scene: &Scene) -> Result<(), SceneError> {
        let mut map = GroupMap {
            free: vec![None; self.initial_coordinates().len()],
            held: vec![None; self.held.len()],
            root: (0, 0.0),
            stress: None,
        };
        for (g, group) in self.groups.iter().enumerate() {
            for (c, dof) in group.dofs.iter().enumerate() {
                let slot = match *dof {
                    Dof::Free(i) => map.free.get_mut(i as usize),
                    Dof::Held(j) => map.held.get_mut(j as usize),
                };
                if let Some(s) = slot {
                    *s = Some((g as u32, c as u8));
                }
            }
        }
        // each element's start along its segment [m]: elements of a segment in build order
        let mut start = vec![0.0; self.elements.len()];
        let mut along = vec![0.0; scene.segments.len()];
        for (i, e) in self.elements.iter().enumerate() {
            if let Some(a) = along.get_mut(e.segment) {
                start[i] = *a;
                *a += e.at.part.length();
            }
        }
        // root to tip: by segment, then along it
        let order = |a: &usize, b: &usize| {
            let (ea, eb) = (&self.elements[*a], &self.elements[*b]);
            (ea.segment, start[*a])
                .partial_cmp(&(eb.segment, start[*b]))
                .unwrap_or(std::cmp::Ordering::Equal)
        };
        // the tip end of the last element: the sample of a cut with nothing beyond it
        let last = (0..self.elements.len()).max_by(order).map(|i| (i, 1.0));
        let mut cuts = Vec::with_capacity(scene.stations.len().min(MAX_STATIONS));
        for st in scene.stations.iter().take(MAX_STATIONS) {
            let Some(si) = scene.segments.iter().position(|s| s.name == st.segment) else {
                return Err(SceneError(format!(
                    "stations: {:?} names no segment",
                    st.segment
                )));
            };
            let seg = &scene.segments[si];
            let tol = 1e-9 * seg.length;
            let beyond = |i: usize| {
                let e = &self.elements[i];
                e.segment > si || (e.segment == si && start[i] >= st.at - tol)
            };
            let outboard: Vec<usize> = (0..self.elements.len()).filter(|&i| beyond(i)).collect();
            // the cut's sample: the first outboard element's root (the lowest segment, then the
            // lowest start), else the tip end of the last element
            let first = outboard.iter().copied().min_by(order).map(|i| (i, 0.0));
            let at = first
                .or(last)
                .ok_or_else(|| SceneError("stations: a beam without elements".into()))?;
            // a cut inside an element of the segment: the element holding it (its part before
            // the cut is integrated by the element; inboard are the elements before it)
            let inside = (0..self.elements.len()).find(|&i| {
                let e = &self.elements[i];
                e.segment == si
                    && start[i] < st.at - tol
                    && st.at < start[i] + e.at.part.length() - tol
            });
            let (outboard, at, partial) = match inside {
                Some(i) => {
                    let xi = (st.at - start[i]) / self.elements[i].at.part.length();
                    let mut out = outboard;
                    out.push(i);
                    (out, (i, xi), Some((i, xi)))
                }
                None => (outboard, at, None),
            };
            let inboard: Vec<usize> = (0..self.elements.len())
                .filter(|i| !outboard.contains(i))
                .collect();
            let t = if seg.length > 0.0 {
                (st.at / seg.length).clamp(0.0, 1.0)
            } else {
                0.0
            };
            cuts.push(Cut {
                inboard,
                at,
                partial,
                section: StressSection::of(seg, t),
            });
        }
        // the root section: the first element of the first segment at ξ = 0
        map.root = (0..self.elements.len())
            .min_by(order)
            .map_or((0, 0.0), |i| (i, 0.0));
        if scene.outputs.stress {
            let mut seg_start = vec![0.0; scene.segments.len()];
            for i in 1..scene.segments.len() {
                seg_start[i] = seg_start[i - 1] + scene.segments[i - 1].length;
            }
            let points = self
                .elements
                .iter()
                .enumerate()
                .map(|(i, e)| {
                    let Some(seg) = scene.segments.get(e.segment) else {
                        return Vec::new();
                    };
                    let l = e.at.part.length();
                    STRESS_POINTS
                        .iter()
                        .map(|xi| {
                            let s = start[i] + xi * l;
                            let t = if seg.length > 0.0 {
                                (s / seg.length).clamp(0.0, 1.0)
                            } else {
                                0.0
                            };
                            StressPoint::of(seg, t, seg_start[e.segment] + s)
                        })
                        .collect()
                })
                .collect();
            map.stress = Some(points);
        }
        // the elements holding a cut inside prepare it now (a modal body keeps its shapes at
        // the cut's quadrature points): no allocation when a step asks for the loads
        let q0 = self.initial_coordinates();
        let rest = vec![0.0; q0.len()];
        for (ei, xi) in cuts.iter().filter_map(|c| c.partial) {
            let e = &self.elements[ei];
            let x = LocalState::moving(&e.at.dofs, self.held_state(), (q0, &rest, &rest));
            let _ = e.at.part.partial_load(&x, &self.gravity, xi, [0.0; 3]);
        }
        self.stations = cuts;
        self.group_map = map;
        // the working memory at its size: every element's residual, the samples of a cut or
        // an element's stress points
        let mut offset = Vec::with_capacity(self.elements.len());
        let mut total = 0;
        for e in &self.elements {
            offset.push(total);
            total += e.at.dofs.len();
        }
        let work = super::cut::StationWork {
            residual: vec![0.0; total],
            done: vec![false; self.elements.len()],
            offset,
            samples: Vec::with_capacity(STRESS_POINTS.len()),
        };
        self.station_work = super::scratch::Scratch::new(work);
        Ok(())
    }

    /// With `outputs.stress`: the largest von Mises stress along the beam [Pa] and its arc
    /// length from the root [m], from the local strains of the elements' samples at their ends
    /// and Gauss points (N = EAε, T = GJτ, M_y = EI_y κ_y, M_z = EI_z κ_z; no transverse shear:
    /// a strain field does not give it) by [`StressSection::stress`].
    pub fn beam_stress(&self, (q, v, acc): (&[f64], &[f64], &[f64])) -> Option<(f64, f64)> {
        let points = self.group_map.stress.as_ref()?;
        let held = self.held_state();
        let (mut worst, mut at) = (0.0f64, 0.0);
        self.station_work.with(|work| {
            let samples = &mut work.samples;
            for (e, points) in self.elements.iter().zip(points) {
                if points.is_empty() {
                    continue;
                }
                let x = LocalState::moving(&e.at.dofs, held, (q, v, acc));
                samples.clear();
                e.at.part.sample(&x, &STRESS_POINTS, samples);
                for (p, point) in samples.iter().zip(points) {
                    let sigma = point.stress(p);
                    if sigma > worst {
                        (worst, at) = (sigma, point.at);
                    }
                }
            }
        });
        Some((worst, at))
    }

    /// The number of stations.
    pub fn station_count(&self) -> usize {
        self.stations.len()
    }

    /// The loads at each station at the state (q, q̇, q̈) whose support reaction is
    /// `reaction` (force [N], moment about the root point [N m], world axes) (see the module
    /// doc).
    pub fn station_loads(
        &self,
        (q, v, acc): (&[f64], &[f64], &[f64]),
        reaction: (&S::Vec, &S::Moment),
    ) -> [StationLoads; MAX_STATIONS] {
        let mut out = [StationLoads::default(); MAX_STATIONS];
        if self.stations.is_empty() {
            return out;
        }
        self.station_work.with(|work| {
            let env = Env {
                gravity: self.gravity,
                load: 1.0,
            };
            let held = self.held_state();
            let value = |d: Dof| match d {
                Dof::Free(i) => q[i as usize],
                Dof::Held(j) => self.held[j as usize],
            };
            let sample = |(ei, xi): (usize, f64), out: &mut Vec<super::sample::ShapePoint>| {
                let e = &self.elements[ei];
                let x = LocalState::moving(&e.at.dofs, held, (q, v, acc));
                out.clear();
                e.at.part.sample(&x, &[xi], out);
                out.first().map(|p| (p.position, p.frame))
            };
            let work = &mut *work;
            let samples = &mut work.samples;
            let Some((root, _)) = sample(self.group_map.root, samples) else {
                return;
            };
            let r_s = embed::<S>(reaction.0.as_ref());
            let m_s = moment3::<S>(S::moment_components(reaction.1));
            // each inboard element's residual once per output, evaluated on first need
            work.done.iter_mut().for_each(|d| *d = false);
            for (slot, cut) in out.iter_mut().zip(&self.stations) {
                let Some((p, frame)) = sample(cut.at, samples) else {
                    continue;
                };
                // −R·δu − (M_R + (o − p) × R)·δθ, then the inboard residuals' virtual work
                let mut f = r_s.map(|x| -x);
                let mut m = sub([0.0; 3], add(m_s, cross(sub(root, p), r_s)));
                for &i in &cut.inboard {
                    let e = &self.elements[i];
                    let (o, d) = (work.offset[i], e.at.dofs.len());
                    let local = &mut work.residual[o..o + d];
                    if !work.done[i] {
                        let x = LocalState::moving(&e.at.dofs, held, (q, v, acc));
                        local.fill(0.0);
                        e.at.part.residual(&x, &env, local);
                        work.done[i] = true;
                    }
                    for (k, dof) in e.at.dofs.dofs().iter().enumerate() {
                        let r = local[k];
                        let found = match *dof {
                            Dof::Free(i) => self.group_map.free.get(i as usize),
                            Dof::Held(j) => self.group_map.held.get(j as usize),
                        };
                        let Some(&Some((g, c))) = found else { continue };
                        let group = &self.groups[g as usize];
                        let c = c as usize;
                        // the group's values (at most 4: a point, a direction, Euler parameters)
                        let mut gv = [0.0; 4];
                        for (o, d) in gv.iter_mut().zip(&group.dofs) {
                            *o = value(*d);
                        }
                        let n = group.dofs.len().min(4);
                        match group.kind {
                            Rigid::Point => {
                                let r_pt = embed::<S>(&gv[..n]);
                                f[c] += r;
                                // δq_c under δθ about axis j: (e_j × (r − p))_c
                                let d = sub(r_pt, p);
                                for j in 0..3 {
                                    m[j] += r * cross(unit(j), d)[c];
                                }
                            }
                            Rigid::Direction => {
                                let dv = embed::<S>(&gv[..n]);
                                for j in 0..3 {
                                    m[j] += r * cross(unit(j), dv)[c];
                                }
                            }
                            Rigid::Angle => m[2] += r,
                            Rigid::Euler => {
                                let e4 = gv;
                                // δp = ½ (0, e_j) ⊗ p
                                for j in 0..3 {
                                    let w = unit(j);
                                    let pv = [e4[1], e4[2], e4[3]];
                                    let wxp = cross(w, pv);
                                    let dp = [
                                        -0.5 * (w[0] * pv[0] + w[1] * pv[1] + w[2] * pv[2]),
                                        0.5 * (e4[0] * w[0] + wxp[0]),
                                        0.5 * (e4[0] * w[1] + wxp[1]),
                                        0.5 * (e4[0] * w[2] + wxp[2]),
                                    ];
                                    m[j] += r * dp[c];
                                }
                            }
                        }
                    }
                }
                // inside an element: the loads at its start node p₀ (about p the projection above
                // already gives M₀ + (p₀ − p) × F₀) carried across its part [0, ξ]:
                // F = F₀ − ∫(f − ρA r̈), M = M₀ + (p₀ − p) × F₀ − ∫(r − p) × (f − ρA r̈)
                if let Some((ei, xi)) = cut.partial {
                    let e = &self.elements[ei];
                    let x = LocalState::moving(&e.at.dofs, held, (q, v, acc));
                    let Some((pf, pm)) = e.at.part.partial_load(&x, &self.gravity, xi, p) else {
                        continue;
                    };
                    for k in 0..3 {
                        f[k] -= pf[k];
                        m[k] -= pm[k];
                    }
                }
                let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                let force = [dot(f, frame[0]), dot(f, frame[1]), dot(f, frame[2])];
                let moment = [dot(m, frame[0]), dot(m, frame[1]), dot(m, frame[2])];
                *slot = StationLoads {
                    force,
                    moment,
                    stress: cut.section.stress(force, moment),
                };
            }
        });
        out
    }
}

/// The largest von Mises stress [Pa] over the section of `seg` at the fraction `t` of its length
/// from the local strains of the sample `p` ([`StressPoint::stress`]).
pub fn strain_stress(seg: &Segment, t: f64, p: &super::sample::ShapePoint) -> f64 {
    StressPoint::of(seg, t, 0.0).stress(p)
}

fn embed<S: Space>(v: &[f64]) -> [f64; 3] {
    let _ = S::DIM;
    std::array::from_fn(|k| v.get(k).copied().unwrap_or(0.0))
}

/// A moment's components as a 3-vector (the plane's z alone).
fn moment3<S: Space>(m: &[f64]) -> [f64; 3] {
    if m.len() == 1 {
        [0.0, 0.0, m[0]]
    } else {
        embed::<S>(m)
    }
}

fn unit(j: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[j] = 1.0;
    e
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
