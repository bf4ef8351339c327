//! The segment walk of a build, written once: segments root to tip, a modal segment as a
//! floating frame joined to its neighbours, an ANCF segment as a chain of elements whose first
//! node is shared with an ANCF segment before it; root coordinates held by the support are
//! eliminated. Each space supplies its parts through [`SegmentParts`] (`planar/build.rs`,
//! `spatial/build.rs`). The order is the recordings': ANCF elements first, then modal bodies;
//! constraints from root to tip, a segment's own rows before the joint to its upstream
//! neighbour (this order is the summation order of the assembly).

use super::ancf::SectionMass;
use super::assembly::{Model, Parts};
use super::component::{Constraint, Element, Port, Support};
use super::dofs::{Dof, LocalDofs, Numbering, Rigid};
use super::section3::SectionBody3;
use super::space::{moment_from, vec_from, Space};
use crate::scene::{Root, Scene, SceneError, Segment, SegmentKind, SpaceKind};

/// An end of a segment being built: its local coordinates with their initial values, and its
/// port.
pub struct End<S: Space> {
    /// Local coordinates.
    pub dofs: LocalDofs,
    /// Their initial values.
    pub q0: Vec<f64>,
    /// The end's port.
    pub port: Box<dyn Port<S>>,
    /// An ANCF node (shared with a following ANCF segment instead of joined).
    pub node: bool,
}

/// Coordinates being numbered for one component: their dofs and initial values.
#[derive(Debug, Clone, Default)]
pub struct Coords {
    /// The numbered coordinates.
    pub dofs: Vec<Dof>,
    /// Their initial values.
    pub q0: Vec<f64>,
}

impl Coords {
    /// Numbers one coordinate (free or held) of initial `value` and Newton `scale`.
    pub fn push(&mut self, num: &mut Numbering, free: bool, value: f64, scale: f64) {
        self.dofs.push(num.coordinate(free, value, scale));
        self.q0.push(value);
    }

    /// Indices into the held values of the `N` coordinates from `first` (all held).
    pub fn held<const N: usize>(&self, first: usize) -> [usize; N] {
        std::array::from_fn(|k| match self.dofs[first + k] {
            Dof::Held(j) => j as usize,
            Dof::Free(_) => unreachable!("a root coordinate held by the support"),
        })
    }

    /// Whether coordinate `k` is held.
    pub fn is_held(&self, k: usize) -> bool {
        matches!(self.dofs[k], Dof::Held(_))
    }
}

/// What the support holds of an ANCF node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hold {
    /// Nothing: every coordinate free.
    Free,
    /// The position (a pinned root).
    Position,
    /// The position, the slope's direction (not its length: the rows of
    /// [`SegmentParts::slope_direction`]) and a section director (a clamped or mounted root).
    Clamp,
}

/// A modal segment as its space builds it.
pub struct ModalSegment<S: Space> {
    /// The body's coordinates.
    pub coords: Coords,
    /// Its root and tip ports.
    pub root: Box<dyn Port<S>>,
    /// See [`ModalSegment::root`].
    pub tip: Box<dyn Port<S>>,
    /// The element.
    pub element: Box<dyn Element<S>>,
    /// The support, for the first segment.
    pub support: Option<Box<dyn Support<S>>>,
    /// Its own rows (e.g. an Euler-parameter normalization), before its joint.
    pub constraints: Vec<(LocalDofs, Box<dyn Constraint>)>,
}

/// What a space builds of each segment kind.
pub trait SegmentParts<S: Space> {
    /// The properties shared by the elements of an ANCF segment.
    type AncfProps;

    /// Segment `seg` begins, its root at arc length `s` [m] from the beam's root: the space
    /// lays it out on the end frame of the segment before (an arc for an
    /// [`Segment::initial_curvature`]); [`SegmentParts::modal`] and [`SegmentParts::node`]
    /// then place on it.
    fn begin_segment(&mut self, seg: &Segment, s: f64);
    /// Segment `seg` ends: the next one starts on its end position, tangent and section frame.
    fn end_segment(&mut self, seg: &Segment);

    /// A modal segment `si` whose root is at arc length `s` [m]; `held` when its frame is the
    /// support's (the first segment of a clamped or mounted root); carrying the attached
    /// masses `masses`.
    fn modal(
        &mut self,
        num: &mut Numbering,
        si: usize,
        seg: &Segment,
        s: f64,
        held: bool,
        masses: &SegmentMasses,
    ) -> Result<ModalSegment<S>, SceneError>;
    /// The element properties of ANCF segment `si` (elements of length `le` [m]).
    fn ancf_props(&self, si: usize, seg: &Segment, le: f64) -> Result<Self::AncfProps, SceneError>;
    /// One ANCF element carrying the point masses `points`: (ξ ∈ [0, 1] along the element,
    /// mass [kg]) (empty: the element alone), and the rigid bodies on its section (offset or
    /// rotary inertia): `bodies` in a planar scene, `bodies3` in a spatial one, under the
    /// line load of its segment `seg` ([`Segment::line_load`]); the element starts at arc length
    /// `x0` [m] from the segment's start (a tapered segment's section there).
    fn ancf_element(
        &self,
        props: &Self::AncfProps,
        x0: f64,
        points: &[(f64, f64)],
        bodies: &[SectionMass],
        bodies3: &[SectionBody3],
        seg: &Segment,
    ) -> Box<dyn Element<S>>;
    /// An ANCF node at arc length `s` [m] (on the current segment's layout), held as `hold`
    /// says, with the rigid groups it forms.
    fn node(&mut self, num: &mut Numbering, s: f64, hold: Hold) -> Coords;
    /// The held normals of a clamped root node's slope direction (rigid directions, turning
    /// with a mount) and the rows holding the slope `node`'s r_x to that direction
    /// ([`super::direction::SlopeDirection`]) on their local coordinates.
    fn slope_direction(
        &self,
        num: &mut Numbering,
        node: &Coords,
    ) -> (Coords, (LocalDofs, Box<dyn Constraint>));
    /// The support of a first ANCF node, with the normals of a clamped slope direction.
    fn node_support(&self, node: &Coords, normals: Option<&Coords>) -> Box<dyn Support<S>>;
    /// An ANCF node's port.
    fn node_port(&self) -> Box<dyn Port<S>>;
    /// The rigid joint between `up` and `down`, its angle rows scaled by the upstream segment's
    /// length `length` [m].
    fn join(
        &self,
        up: End<S>,
        down: End<S>,
        length: f64,
    ) -> Result<(LocalDofs, Box<dyn Constraint>), SceneError>;
}

/// The attached masses of a modal segment: point masses (x from the segment's start [m], mass
/// [kg]) and rigid bodies on the section (offset or rotary inertia; `xi` = x/L).
#[derive(Debug, Clone, Default)]
pub struct SegmentMasses {
    /// Point masses (x [m], mass [kg]).
    pub points: Vec<(f64, f64)>,
    /// Bodies with an offset or a rotary inertia (planar scenes).
    pub bodies: Vec<SectionMass>,
    /// Bodies with an offset or a rotary inertia (spatial scenes).
    pub bodies3: Vec<SectionBody3>,
}

/// The element of an ANCF segment of length `length` cut into `ne` equal elements that carries
/// a point at arc length `at` [m] from the segment's start, and the point's ξ ∈ [0, 1] on it (a
/// point on a node between two elements goes to the earlier one: the node moves both alike).
pub fn element_of(at: f64, length: f64, ne: usize) -> (usize, f64) {
    let le = length / ne as f64;
    let k = ((at / le).ceil() as usize).clamp(1, ne) - 1;
    (k, ((at - k as f64 * le) / le).clamp(0.0, 1.0))
}

/// Refuses attached masses with what the model does not carry: an offset or a rotary inertia
/// (non-zero) on an ANCF segment of a spatial scene without torsion (the 3D cable has no
/// section frame about its axis), naming the field, its value and the fix.
fn point_masses_are_points<S: Space>(scene: &Scene) -> Result<(), SceneError> {
    if S::KIND == SpaceKind::Planar || scene.torsion {
        return Ok(());
    }
    for (i, m) in scene.masses.iter().enumerate() {
        let on_cable =
            (scene.segments.iter()).any(|s| s.name == m.segment && s.kind == SegmentKind::Ancf);
        if !on_cable {
            continue;
        }
        for (field, v) in [("inertia", &m.inertia), ("offset", &m.offset)] {
            if let Some(v) = v.as_ref().filter(|v| v.iter().any(|x| *x != 0.0)) {
                return Err(SceneError(format!(
                    "masses[{i}].{field} = {v:?}: segment {:?} is a 3D cable (torsion = false), whose section has no frame about its axis to carry a mass's {field}; set `torsion = true` (the director or angle element carries the section frame), put the mass on a modal segment, or remove `{field}` (a point mass)",
                    m.segment
                )));
            }
        }
    }
    Ok(())
}

/// Bodies with the index of the element carrying them.
type Placed<B> = Vec<(usize, B)>;

/// The section bodies (non-point masses) on segment `si` of length `length`, split onto `ne`
/// equal elements (`None`: one modal body, ξ = at/L): (element, body) in scene order, in the
/// space's form.
fn section_bodies<S: Space>(
    scene: &Scene,
    si: usize,
    length: f64,
    ne: Option<usize>,
) -> (Placed<SectionMass>, Placed<SectionBody3>) {
    let (mut planar, mut spatial) = (Vec::new(), Vec::new());
    for m in scene.masses_on(si).filter(|m| !m.is_point()) {
        let (k, xi) = match ne {
            Some(ne) => element_of(m.at, length, ne),
            None => (0, m.at / length),
        };
        if S::KIND == SpaceKind::Planar {
            let (inertia, offset) = m.planar_body();
            planar.push((
                k,
                SectionMass {
                    xi,
                    mass: m.mass,
                    inertia,
                    offset,
                },
            ));
        } else {
            let (inertia, offset) = m.spatial_body();
            spatial.push((
                k,
                SectionBody3 {
                    xi,
                    mass: m.mass,
                    inertia,
                    offset,
                },
            ));
        }
    }
    (planar, spatial)
}

/// The element-internal coordinates of an ANCF element of degree `degree` and length `le`
/// [m] (none for the cubic element, 3): one vector amplitude per hierarchic bubble
/// ([`super::hierarchic`]), free, 0 on a straight segment, Newton scale `le`, each a rigid
/// direction (a moving mount turns it, a translation leaves it).
fn bubbles<S: Space>(num: &mut Numbering, degree: usize, le: f64) -> Vec<Dof> {
    let mut out = Vec::new();
    for _ in 4..=degree {
        let a: Vec<Dof> = (0..S::DIM).map(|_| num.free(0.0, le)).collect();
        num.rigid(Rigid::Direction, &a);
        out.extend(a);
    }
    out
}

/// The bodies of `bodies` on element `k`.
fn on_element<B: Copy>(bodies: &[(usize, B)], k: usize) -> Vec<B> {
    bodies.iter().filter(|b| b.0 == k).map(|b| b.1).collect()
}

/// The model of a validated scene, its segments built by `parts`.
pub fn walk<S: Space, P: SegmentParts<S>>(
    scene: &Scene,
    parts: &mut P,
) -> Result<Model<S>, SceneError> {
    let clamped = matches!(scene.root, Root::Clamped | Root::Mounted);
    let mut num = Numbering::default();
    let mut ancf: Vec<(LocalDofs, Box<dyn Element<S>>, usize)> = Vec::new();
    let mut bodies: Vec<(LocalDofs, Box<dyn Element<S>>, usize)> = Vec::new();
    let mut constraints: Vec<(LocalDofs, Box<dyn Constraint>)> = Vec::new();
    let mut support: Option<Box<dyn Support<S>>> = None;
    let mut prev: Option<End<S>> = None;
    let mut s_pos = 0.0; // arc length at the segment root
    let mut prev_len = 0.0; // length of the previous segment (joint row scale)
    point_masses_are_points::<S>(scene)?;
    for (si, seg) in scene.segments.iter().enumerate() {
        let first = si == 0;
        let points = scene.point_masses(si);
        parts.begin_segment(seg, s_pos);
        match seg.kind {
            SegmentKind::Modal => {
                let (planar, spatial) = section_bodies::<S>(scene, si, seg.length, None);
                let masses = SegmentMasses {
                    points: points.clone(),
                    bodies: planar.into_iter().map(|b| b.1).collect(),
                    bodies3: spatial.into_iter().map(|b| b.1).collect(),
                };
                let m = parts.modal(&mut num, si, seg, s_pos, first && clamped, &masses)?;
                if first {
                    support = m.support;
                }
                constraints.extend(m.constraints);
                let dofs = LocalDofs::new(m.coords.dofs.clone());
                if let Some(up) = prev.take() {
                    let down = End {
                        dofs: dofs.clone(),
                        q0: m.coords.q0.clone(),
                        port: m.root,
                        node: false,
                    };
                    constraints.push(parts.join(up, down, prev_len)?);
                }
                prev = Some(End {
                    dofs: dofs.clone(),
                    q0: m.coords.q0,
                    port: m.tip,
                    node: false,
                });
                bodies.push((dofs, m.element, si));
            }
            SegmentKind::Ancf => {
                let ne = seg.elements.unwrap_or(1);
                let le = seg.length / ne as f64;
                let props = parts.ancf_props(si, seg, le)?;
                let (planar, spatial) = section_bodies::<S>(scene, si, seg.length, Some(ne));
                // first node: shared with a previous ANCF segment, else new (held at the root)
                let mut last = match prev.take() {
                    Some(up) if up.node => Coords {
                        dofs: up.dofs.dofs().to_vec(),
                        q0: up.q0,
                    },
                    up => {
                        let hold = match (first, clamped) {
                            (false, _) => Hold::Free,
                            (true, false) => Hold::Position,
                            (true, true) => Hold::Clamp,
                        };
                        let c = parts.node(&mut num, s_pos, hold);
                        if first {
                            let normals = (hold == Hold::Clamp).then(|| {
                                let (n, rows) = parts.slope_direction(&mut num, &c);
                                constraints.push(rows);
                                n
                            });
                            support = Some(parts.node_support(&c, normals.as_ref()));
                        }
                        if let Some(up) = up {
                            let down = End {
                                dofs: LocalDofs::new(c.dofs.clone()),
                                q0: c.q0.clone(),
                                port: parts.node_port(),
                                node: true,
                            };
                            constraints.push(parts.join(up, down, prev_len)?);
                        }
                        c
                    }
                };
                for k in 0..ne {
                    let next = parts.node(&mut num, s_pos + (k + 1) as f64 * le, Hold::Free);
                    let inner = bubbles::<S>(&mut num, seg.degree, le);
                    let dofs = LocalDofs::new(
                        (last.dofs.iter().chain(&next.dofs).chain(&inner))
                            .copied()
                            .collect(),
                    );
                    let on: Vec<(f64, f64)> = points
                        .iter()
                        .filter_map(|&(at, m)| {
                            let (j, xi) = element_of(at, seg.length, ne);
                            (j == k).then_some((xi, m))
                        })
                        .collect();
                    let held = on_element(&planar, k);
                    let held3 = on_element(&spatial, k);
                    ancf.push((
                        dofs,
                        parts.ancf_element(&props, k as f64 * le, &on, &held, &held3, seg),
                        si,
                    ));
                    last = next;
                }
                prev = Some(End {
                    dofs: LocalDofs::new(last.dofs),
                    q0: last.q0,
                    port: parts.node_port(),
                    node: true,
                });
            }
        }
        parts.end_segment(seg);
        s_pos += seg.length;
        prev_len = seg.length;
    }
    let tip = prev.expect("a validated scene has at least one segment");
    let mut elements = ancf;
    elements.append(&mut bodies);
    Ok(Model::assemble(Parts {
        numbering: num,
        elements,
        constraints,
        tip: (tip.dofs, tip.port),
        support: support.expect("the first segment is held at the root"),
        gravity: vec_from::<S>(&scene.gravity),
        tip_force: vec_from::<S>(&scene.tip.force),
        tip_moment: moment_from::<S>(&scene.tip.moment),
        line_loads: scene
            .line_load_segments()
            .into_iter()
            .map(|i| {
                (
                    i,
                    vec_from::<S>(scene.segments[i].line_load.as_deref().unwrap_or(&[])),
                )
            })
            .collect(),
        mounted: scene.root == Root::Mounted,
    }))
}
