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
//! A cut is at a segment's end or, on an ANCF
//! segment, at a node between elements (where the outboard part is a set of whole elements).

use super::assembly::Model;
use super::component::{Env, LocalState};
use super::dofs::{Dof, Rigid};
use super::space::Space;
use crate::scene::{Scene, SceneError, Section, Segment, MAX_STATIONS};

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

/// A cross-section's shape and properties for the stress at a station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SectionShape {
    /// Solid round, radius [m].
    Round(f64),
    /// Round tube, outer and inner radius [m].
    Tube(f64, f64),
    /// Rectangle: width b along the section z axis, height h along y [m].
    Rectangle(f64, f64),
}

/// A station's section: its shape and the properties (A, I_y, I_z, J) of the segment at the cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressSection {
    /// The shape.
    pub shape: SectionShape,
    /// Area [m²].
    pub area: f64,
    /// Second moments about the section's y and z axes [m⁴].
    pub i_y: f64,
    /// Second moment about z [m⁴].
    pub i_z: f64,
}

impl StressSection {
    /// The section of `seg` at the fraction `t` of its length from its start.
    pub fn of(seg: &Segment, t: f64) -> Self {
        let d = |x: &Option<crate::scene::Dim>| x.as_ref().map_or(0.0, |d| d.at(t));
        let shape = match seg.section {
            Section::Round => SectionShape::Round(0.5 * d(&seg.diameter)),
            Section::Tube => {
                SectionShape::Tube(0.5 * d(&seg.diameter), 0.5 * d(&seg.inner_diameter))
            }
            Section::Rectangle => SectionShape::Rectangle(d(&seg.width), d(&seg.height)),
        };
        let p = seg.section_props_at(t);
        Self {
            shape,
            area: p.area,
            i_y: p.i_y,
            i_z: p.i_z,
        }
    }

    /// The largest von Mises stress σ_v = √(σ² + 3τ²) [Pa] over the boundary points of the
    /// section under the loads `force` (N, V_y, V_z) [N] and `moment` (T, M_y, M_z) [N m],
    /// section frame. At a boundary point (y, z): σ = N/A + M_y z/I_y − M_z y/I_z (beam
    /// theory); τ = |τ_T| + |τ_V| (the two added as magnitudes: exact where they are parallel,
    /// on the safe side elsewhere) with, for a solid round section of radius r, τ_T = T r/J
    /// (J = πr⁴/2) and τ_V = (4V/3A)(1 − η²/r²), η the point's coordinate along the shear
    /// force V (Jourawski on the chord); for a tube (r_o, r_i), τ_T = T r_o/J
    /// (J = π(r_o⁴ − r_i⁴)/2) and τ_V = (2V/A)|sin β|, β the angle of the point from V's
    /// direction (thin-walled shear flow); for a rectangle (long side a, short side b),
    /// τ_T = T/(k₂ a b²) at the middle of the long sides and k₃ times that at the middle of the
    /// short sides, zero at the corners, parabolic along each side (Saint-Venant; k₂, k₃ by
    /// Roark's fits, docs/stations.md), and τ_V = 1.5 (V_s/A)(1 − (2η/d)²) for the shear V_s
    /// parallel to a side of depth d (η from the side's middle). 72 points around a circle,
    /// 4 × 17 along a rectangle's sides.
    pub fn stress(&self, force: [f64; 3], moment: [f64; 3]) -> f64 {
        let [n, vy, vz] = force;
        let [t, my, mz] = moment;
        let sigma = |y: f64, z: f64| {
            n / self.area
                + if self.i_y > 0.0 {
                    my * z / self.i_y
                } else {
                    0.0
                }
                - if self.i_z > 0.0 {
                    mz * y / self.i_z
                } else {
                    0.0
                }
        };
        let vm = |s: f64, tau: f64| (s * s + 3.0 * tau * tau).sqrt();
        let v = (vy * vy + vz * vz).sqrt();
        let mut worst: f64 = 0.0;
        match self.shape {
            SectionShape::Round(r) | SectionShape::Tube(r, _) => {
                let ri = match self.shape {
                    SectionShape::Tube(_, ri) => ri,
                    _ => 0.0,
                };
                let j = 0.5 * std::f64::consts::PI * (r.powi(4) - ri.powi(4));
                let tau_t = if j > 0.0 { (t * r / j).abs() } else { 0.0 };
                for k in 0..72 {
                    let phi = 2.0 * std::f64::consts::PI * k as f64 / 72.0;
                    let (y, z) = (r * phi.cos(), r * phi.sin());
                    // the point's coordinate along V and the angle from it
                    let eta = if v > 0.0 { (y * vy + z * vz) / v } else { 0.0 };
                    let tau_v = if v == 0.0 {
                        0.0
                    } else if ri > 0.0 {
                        2.0 * v / self.area * (1.0 - (eta / r).powi(2)).max(0.0).sqrt()
                    } else {
                        4.0 * v / (3.0 * self.area) * (1.0 - (eta / r).powi(2)).max(0.0)
                    };
                    worst = worst.max(vm(sigma(y, z), tau_t + tau_v));
                }
            }
            SectionShape::Rectangle(b, h) => {
                let (long, short) = (h.max(b), h.min(b));
                let beta = short / long;
                // Roark (Table 10.7 case 4): τ_max = 3T/(8 a b²)[1 + 0.6095β + 0.8865β² −
                // 1.8023β³ + 0.9100β⁴] with half sides a ≥ b; mid short side ≈ τ_max (0.7425
                // for a square's equal sides is 1, β → 0: 0.742)
                let (a2, b2) = (0.5 * long, 0.5 * short);
                let tau_max = 3.0 * t.abs() / (8.0 * a2 * b2 * b2)
                    * (1.0 + 0.6095 * beta + 0.8865 * beta * beta - 1.8023 * beta.powi(3)
                        + 0.9100 * beta.powi(4));
                let short_factor = 1.0 - 0.258 * (1.0 - beta);
                // sides: (fixed coordinate on y or z, half length, τ_T at the middle)
                for side in 0..4 {
                    let along_z = side < 2; // the sides y = ±h/2 run along z (length b)
                    let half = if along_z { 0.5 * b } else { 0.5 * h };
                    let is_long = (along_z && b >= h) || (!along_z && h > b);
                    let tau_mid = if is_long {
                        tau_max
                    } else {
                        tau_max * short_factor
                    };
                    for k in 0..=16 {
                        let u = -1.0 + 2.0 * k as f64 / 16.0; // −1 … 1 along the side
                        let (y, z) = if along_z {
                            (if side == 0 { 0.5 * h } else { -0.5 * h }, u * half)
                        } else {
                            (u * half, if side == 2 { 0.5 * b } else { -0.5 * b })
                        };
                        let tau_t = tau_mid * (1.0 - u * u);
                        // V_y along h (depth h, η = y), V_z along b (depth b, η = z)
                        let tau_v = 1.5 * vy.abs() / self.area
                            * (1.0 - (2.0 * y / h).powi(2)).max(0.0)
                            + 1.5 * vz.abs() / self.area * (1.0 - (2.0 * z / b).powi(2)).max(0.0);
                        worst = worst.max(vm(sigma(y, z), tau_t + tau_v));
                    }
                }
            }
        }
        worst
    }
}

/// A station of a model: the elements before its cut, where its point and frame are sampled,
/// its section.
#[derive(Debug, Clone)]
pub(crate) struct Cut {
    /// Indices of the elements of the inboard part.
    inboard: Vec<usize>,
    /// (element, ξ) whose sample is the cut's point and section frame.
    at: (usize, f64),
    section: StressSection,
}

/// Where each coordinate's rigid group is: (group index, component), for free and held ones;
/// and the root section's sample (element, ξ).
#[derive(Debug, Clone, Default)]
pub(crate) struct GroupMap {
    free: Vec<Option<(u32, u8)>>,
    held: Vec<Option<(u32, u8)>>,
    root: (usize, f64),
}

impl<S: Space> Model<S> {
    /// Sets the stations of `scene` (validated): for each, the outboard elements, the sample
    /// of its cut, its section.
    pub fn set_stations(&mut self, scene: &Scene) -> Result<(), SceneError> {
        let mut map = GroupMap {
            free: vec![None; self.initial_coordinates().len()],
            held: vec![None; self.held.len()],
            root: (0, 0.0),
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
            let first = outboard
                .iter()
                .copied()
                .min_by(|&a, &b| {
                    let (ea, eb) = (&self.elements[a], &self.elements[b]);
                    (ea.segment, start[a])
                        .partial_cmp(&(eb.segment, start[b]))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .map(|i| (i, 0.0));
            let last = (0..self.elements.len())
                .max_by(|&a, &b| {
                    let (ea, eb) = (&self.elements[a], &self.elements[b]);
                    (ea.segment, start[a])
                        .partial_cmp(&(eb.segment, start[b]))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .map(|i| (i, 1.0));
            let at = first
                .or(last)
                .ok_or_else(|| SceneError("stations: a beam without elements".into()))?;
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
                section: StressSection::of(seg, t),
            });
        }
        // the root section: the first element of the first segment at ξ = 0
        map.root = (0..self.elements.len())
            .min_by(order)
            .map_or((0, 0.0), |i| (i, 0.0));
        self.stations = cuts;
        self.group_map = map;
        Ok(())
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
        let mut samples = Vec::with_capacity(1);
        let Some((root, _)) = sample(self.group_map.root, &mut samples) else {
            return out;
        };
        let r_s = embed::<S>(reaction.0.as_ref());
        let m_s = moment3::<S>(S::moment_components(reaction.1));
        let mut local = Vec::new();
        for (slot, cut) in out.iter_mut().zip(&self.stations) {
            let Some((p, frame)) = sample(cut.at, &mut samples) else {
                continue;
            };
            // −R·δu − (M_R + (o − p) × R)·δθ, then the inboard residuals' virtual work
            let mut f = r_s.map(|x| -x);
            let mut m = sub([0.0; 3], add(m_s, cross(sub(root, p), r_s)));
            for &i in &cut.inboard {
                let e = &self.elements[i];
                let x = LocalState::moving(&e.at.dofs, held, (q, v, acc));
                local.clear();
                local.resize(x.len(), 0.0);
                e.at.part.residual(&x, &env, &mut local);
                for (k, dof) in e.at.dofs.dofs().iter().enumerate() {
                    let r = local[k];
                    let found = match *dof {
                        Dof::Free(i) => self.group_map.free.get(i as usize),
                        Dof::Held(j) => self.group_map.held.get(j as usize),
                    };
                    let Some(&Some((g, c))) = found else { continue };
                    let group = &self.groups[g as usize];
                    let c = c as usize;
                    match group.kind {
                        Rigid::Point => {
                            let r_pt = embed::<S>(
                                &group.dofs.iter().map(|d| value(*d)).collect::<Vec<_>>(),
                            );
                            f[c] += r;
                            // δq_c under δθ about axis j: (e_j × (r − p))_c
                            let d = sub(r_pt, p);
                            for j in 0..3 {
                                m[j] += r * cross(unit(j), d)[c];
                            }
                        }
                        Rigid::Direction => {
                            let dv = embed::<S>(
                                &group.dofs.iter().map(|d| value(*d)).collect::<Vec<_>>(),
                            );
                            for j in 0..3 {
                                m[j] += r * cross(unit(j), dv)[c];
                            }
                        }
                        Rigid::Angle => m[2] += r,
                        Rigid::Euler => {
                            let e4: Vec<f64> = group.dofs.iter().map(|d| value(*d)).collect();
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
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let force = [dot(f, frame[0]), dot(f, frame[1]), dot(f, frame[2])];
            let moment = [dot(m, frame[0]), dot(m, frame[1]), dot(m, frame[2])];
            *slot = StationLoads {
                force,
                moment,
                stress: cut.section.stress(force, moment),
            };
        }
        out
    }
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
