//! Scene → spatial model: the spatial parts of the segment walk ([`crate::model::walk`]; each
//! free frame's Euler-parameter normalization before the joint to its upstream neighbour).
//!
//! Geometry: the root frame → world rotation A₀ is `scene.root_orientation()`; the beam starts
//! straight at the origin along A₀x̄ with its section axes A₀ȳ, A₀z̄, every segment in that
//! frame, each segment after a curved one on that one's end frame. ANCF nodes are
//! `[r, r_x, r_y]` (the director element), `[r, r_x, θ]` (the angle element) or `[r, r_x]`
//! (the 3D cable); modal bodies `[R, p, a_y, a_z, a_t]` with p = A₀'s
//! Euler parameters. A joint's DOT1 rows are scaled by the length of its upstream segment.

use super::joint::RigidJoint3;
use super::{
    AncfElement3, AngleElement3, AnglePort3, EulerNormalization, FrameSupport3, ModalElement3,
    ModalRootPort3, ModalTipPort3, NodePort3, NodeSupport3, Spatial,
};
use crate::model::ancf::SectionMass;
use crate::model::ancf3d::angle::Angle3;
use crate::model::ancf3d::cable_p::Cable3P;
use crate::model::ancf3d::{arc_frame, Ancf3Props, Reference3};
use crate::model::assembly::Model;
use crate::model::component::{Constraint, Element, Port, Support};
use crate::model::direction::SlopeDirection;
use crate::model::dofs::{LocalDofs, Numbering, Rigid};
use crate::model::element_p::ElementP;
use crate::model::modal::{ModalBasis, ModalBody3, ModalProps3};
use crate::model::section3::SectionBody3;
use crate::model::walk::{walk, Coords, End, Hold, ModalSegment, SegmentMasses, SegmentParts};
use crate::scene::{Scene, SceneError, Segment, SegmentKind, SpaceKind, TorsionElement};
use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};
use std::sync::Arc;

/// The spatial parts of a scene: the root frame and the element family.
struct SpatialParts {
    /// Root frame → world, unit Euler parameters.
    e0: [f64; 4],
    /// Its axes x̄, ȳ in world axes.
    ax: Vector3<f64>,
    /// See [`SpatialParts::ax`].
    ay: Vector3<f64>,
    /// The root frame as a matrix (the node ports' reference).
    reference: Matrix3<f64>,
    /// Whether ANCF nodes carry the section director r_y.
    torsion: bool,
    /// Whether they carry a twist angle θ instead (`torsion_element = "angle"`).
    angle: bool,
    /// Newton scale of positions and bending amplitudes: the total length [m].
    lref: f64,
    /// The current segment's root frame (position [m], section frame → world, columns t, d2,
    /// d3) once a curved segment came before it; `None` while every segment so far is
    /// straight (positions s·x̄ in the root frame, exactly as a straight beam's).
    start: Option<(Vector3<f64>, Matrix3<f64>)>,
    /// Arc length of the current segment's root [m].
    s0: f64,
    /// The current segment's initial curvature [κ_y, κ_z] [1/m] (zero: straight).
    curvature: [f64; 2],
    /// The last node placed (position, frame): an ANCF segment's end.
    last: (Vector3<f64>, Matrix3<f64>),
}

impl SpatialParts {
    /// The current segment's root (position, frame).
    fn root(&self) -> (Vector3<f64>, Matrix3<f64>) {
        self.start.unwrap_or((self.s0 * self.ax, self.reference))
    }

    /// Whether the current segment is laid out as the straight beam's.
    fn straight_layout(&self) -> bool {
        self.start.is_none() && self.curvature == [0.0, 0.0]
    }

    /// The frame (position, frame) at arc length `s` along the current segment.
    fn frame_at(&self, s: f64) -> (Vector3<f64>, Matrix3<f64>) {
        let (p0, r0) = self.root();
        let (p, f) = arc_frame(self.curvature, s - self.s0);
        let col = |v: [f64; 3]| r0 * Vector3::from(v);
        (
            p0 + col(p),
            Matrix3::from_columns(&[col(f[0]), col(f[1]), col(f[2])]),
        )
    }
}

impl SegmentParts<Spatial> for SpatialParts {
    type AncfProps = Ancf3Props;

    fn begin_segment(&mut self, seg: &Segment, s: f64) {
        self.s0 = s;
        self.curvature = seg.curvature().unwrap_or([0.0, 0.0]);
    }

    fn end_segment(&mut self, seg: &Segment) {
        if self.straight_layout() {
            return;
        }
        self.start = Some(match seg.kind {
            SegmentKind::Ancf => self.last,
            SegmentKind::Modal => {
                let (p0, r0) = self.root();
                (p0 + seg.length * r0.column(0), r0)
            }
        });
    }

    fn modal(
        &mut self,
        num: &mut Numbering,
        si: usize,
        seg: &Segment,
        s: f64,
        held: bool,
        masses: &SegmentMasses,
    ) -> Result<ModalSegment<Spatial>, SceneError> {
        let first = si == 0;
        let (root_pt, e0) = match self.start {
            None => (s * self.ax, self.e0),
            Some((p, r)) => {
                let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r));
                (p, [q.w, q.i, q.j, q.k])
            }
        };
        let basis = ModalBasis::new(seg.modes.unwrap_or(1), seg.interface_modes);
        let mut body = ModalBody3::new(basis, ModalProps3::of_segment(seg));
        if seg.is_tapered() {
            body = body.tapered(seg).map_err(SceneError)?;
        }
        if seg.linear {
            body = body.linear();
            if held {
                // a held linear frame: its motion is the support's, so the axial inertia and
                // centrifugal forces of the segment stiffen its bending (K_G); the nonlinear
                // body's foreshortening carries the axial force field, held or free
                body = body.with_stiffening();
            }
        }
        let body = body
            .with_points(&masses.points)
            .with_bodies(&masses.bodies3);
        let body = Arc::new(body.with_line_load(seg.line_load_vec()));
        let free_p = !held;
        let mut c = Coords::default();
        for k in 0..3 {
            c.push(num, !first, root_pt[k], self.lref);
        }
        for k in 0..4 {
            c.push(num, free_p, e0[k], 1.0);
        }
        num.rigid(Rigid::Point, &c.dofs[..3]);
        num.rigid(Rigid::Euler, &c.dofs[3..7]);
        let nb = body.modes();
        for _ in 0..2 * nb {
            c.push(num, true, 0.0, self.lref);
        }
        while c.dofs.len() < body.dim() {
            c.push(num, true, 0.0, 1.0); // twist amplitudes [rad]
        }
        let support: Option<Box<dyn Support<Spatial>>> = first.then(|| {
            Box::new(FrameSupport3 {
                position: c.held(0),
                attitude: (!free_p).then(|| c.held(3)),
            }) as Box<dyn Support<Spatial>>
        });
        let mut constraints: Vec<(LocalDofs, Box<dyn Constraint>)> = Vec::new();
        if free_p {
            let p = LocalDofs::new(c.dofs[3..7].to_vec());
            constraints.push((p, Box::new(EulerNormalization)));
        }
        Ok(ModalSegment {
            coords: c,
            root: Box::new(ModalRootPort3(body.clone())),
            tip: Box::new(ModalTipPort3(body.clone())),
            element: Box::new(ModalElement3::new(body)),
            support,
            constraints,
        })
    }

    fn ancf_props(&self, si: usize, seg: &Segment, _le: f64) -> Result<Ancf3Props, SceneError> {
        let err = |m: String| SceneError(format!("segments[{si}]: {m}"));
        let mut props = Ancf3Props::of_segment(seg, self.torsion).map_err(err)?;
        // a curved segment (the director element only: `Scene::validate`)
        if let Some(k) = seg.curvature().filter(|_| props.director) {
            props.reference = Some(Reference3::arc(&props, k));
        }
        if self.angle {
            // the angle element bends as the cable: one bending stiffness
            Angle3::new(props, self.ax.into(), self.ay.into())
                .map_err(|m| err(format!("segment {:?}: {m}", seg.name)))?;
        }
        Ok(props)
    }

    fn ancf_element(
        &self,
        props: &Ancf3Props,
        x0: f64,
        points: &[(f64, f64)],
        _bodies: &[SectionMass],
        bodies3: &[SectionBody3],
        seg: &Segment,
    ) -> Box<dyn Element<Spatial>> {
        let line = seg.line_load_vec();
        if seg.degree > 3 {
            // the 3D cable, uniform and straight, point masses only (the scene's validation)
            let kernel = Cable3P::new(*props, seg.degree);
            return Box::new(ElementP::new(kernel, points, line.as_ref().map(|q| &q[..])));
        }
        let tapered = seg.is_tapered().then(|| props.tapered(seg, x0));
        let props = tapered.as_ref().unwrap_or(props);
        if self.angle {
            // the axes of the root frame: unit and perpendicular (checked in `ancf_props`)
            Box::new(
                AngleElement3::new(Angle3 {
                    cable: Ancf3Props {
                        director: false,
                        ..*props
                    },
                    t0: self.ax.into(),
                    d0: self.ay.into(),
                })
                .with_points(points)
                .with_bodies(bodies3)
                .with_line_load(line),
            )
        } else {
            Box::new(
                AncfElement3::new(*props)
                    .with_points(points)
                    .with_bodies(bodies3)
                    .with_line_load(line),
            )
        }
    }

    /// Node coordinates r, r_x (, r_y) at arc length `s`, held as the root asks.
    fn node(&mut self, num: &mut Numbering, s: f64, hold: Hold) -> Coords {
        let mut c = Coords::default();
        let (r, ax, ay) = if self.straight_layout() {
            (s * self.ax, self.ax, self.ay)
        } else {
            let (p, f) = self.frame_at(s);
            self.last = (p, f);
            (p, f.column(0).into_owned(), f.column(1).into_owned())
        };
        let free_r = hold == Hold::Free;
        for k in 0..3 {
            c.push(num, free_r, r[k], self.lref);
        }
        for k in 0..3 {
            c.push(num, true, ax[k], 1.0);
        }
        if self.angle {
            // a clamp holds the twist angle [rad]; not a rigid group (a mount would turn the
            // reference axis: mounted roots refuse the angle element)
            c.push(num, hold != Hold::Clamp, 0.0, 1.0);
        } else if self.torsion {
            // a clamp holds the section director r_y
            for k in 0..3 {
                c.push(num, hold != Hold::Clamp, ay[k], 1.0);
            }
        }
        num.rigid(Rigid::Point, &c.dofs[..3]);
        for d in c.dofs[3..].chunks_exact(3) {
            num.rigid(Rigid::Direction, d);
        }
        c
    }

    /// The section axes e_y, e_z (normals of the clamped axis e_x), held; the rows
    /// e_y · r_x = 0, e_z · r_x = 0.
    fn slope_direction(
        &self,
        num: &mut Numbering,
        node: &Coords,
    ) -> (Coords, (LocalDofs, Box<dyn Constraint>)) {
        let az = self.ax.cross(&self.ay);
        let mut n = Coords::default();
        for axis in [self.ay, az] {
            for k in 0..3 {
                n.push(num, false, axis[k], 1.0);
            }
        }
        for d in n.dofs.chunks(3) {
            num.rigid(Rigid::Direction, d);
        }
        let dofs = LocalDofs::new(node.dofs[3..6].iter().chain(&n.dofs).copied().collect());
        let rows = SlopeDirection { dim: 3, normals: 2 };
        (n, (dofs, Box::new(rows)))
    }

    fn node_support(&self, c: &Coords, normals: Option<&Coords>) -> Box<dyn Support<Spatial>> {
        Box::new(NodeSupport3 {
            position: c.held(0),
            slope: normals.map(|n| n.held(0)),
            normal: normals.map(|n| n.held(3)),
            section: (self.torsion && !self.angle && c.is_held(6)).then(|| c.held(6)),
            twist: (self.angle && c.is_held(6)).then(|| (c.held::<1>(6)[0], self.ax.into())),
        })
    }

    fn node_port(&self) -> Box<dyn Port<Spatial>> {
        if self.angle {
            Box::new(AnglePort3 {
                t0: self.ax.into(),
                d0: self.ay.into(),
            })
        } else {
            Box::new(NodePort3::new(self.torsion, self.reference))
        }
    }

    /// The rigid joint between `up` and `down`, DOT1 rows scaled by `length` [m].
    fn join(
        &self,
        up: End<Spatial>,
        down: End<Spatial>,
        length: f64,
    ) -> Result<(LocalDofs, Box<dyn Constraint>), SceneError> {
        let dofs = LocalDofs::concat(&[&up.dofs, &down.dofs]);
        let q0: Vec<f64> = up.q0.iter().chain(&down.q0).copied().collect();
        let joint =
            RigidJoint3::new(up.port, down.port, up.dofs.len(), length, &q0).ok_or_else(|| {
                SceneError(
                    "internal: a rigid joint between two ANCF ends (they share a node)".into(),
                )
            })?;
        Ok((dofs, Box::new(joint)))
    }
}

/// Unit Euler parameters `[e0, e1, e2, e3]` → rotation columns (x̄, ȳ, z̄ in world axes).
fn frame_of(e: [f64; 4]) -> [Vector3<f64>; 3] {
    let r = UnitQuaternion::from_quaternion(Quaternion::new(e[0], e[1], e[2], e[3]))
        .to_rotation_matrix();
    let m = r.matrix();
    [0, 1, 2].map(|c| m.column(c).into_owned())
}

impl Model<Spatial> {
    /// Builds the model of a validated spatial scene (`space = "spatial"`) from the origin
    /// along the root frame's x axis: straight, each segment after a curved one
    /// (`initial_curvature`, [`arc_frame`]) on that one's end position and section frame. Scales for Newton norms: the total length for
    /// positions and bending amplitudes, 1 for slopes, directors, Euler parameters and twist
    /// amplitudes [rad].
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        scene.validate()?;
        if scene.space != SpaceKind::Spatial {
            return Err(SceneError(
                "space = \"planar\": this scene builds a planar model (Model::<Planar>), not a spatial one".into(),
            ));
        }
        if !scene.torsion {
            let after_ancf = scene
                .segments
                .windows(2)
                .position(|w| w[0].kind == SegmentKind::Ancf && w[1].kind == SegmentKind::Modal);
            if let Some(i) = after_ancf {
                return Err(SceneError(format!(
                    "torsion = false with segments[{}] (modal) after segments[{i}] (ancf): the cable has no section director, so nothing would hold the modal segment's spin about its axis; use torsion = true or put the modal segment first",
                    i + 1
                )));
            }
        }
        let e0 = scene.root_orientation();
        let [ax, ay, az] = frame_of(e0);
        let mut parts = SpatialParts {
            e0,
            ax,
            ay,
            reference: Matrix3::from_columns(&[ax, ay, az]),
            torsion: scene.torsion,
            angle: scene.torsion && scene.torsion_element == TorsionElement::Angle,
            lref: scene.total_length(),
            start: None,
            s0: 0.0,
            curvature: [0.0, 0.0],
            last: (Vector3::zeros(), Matrix3::from_columns(&[ax, ay, az])),
        };
        walk(scene, &mut parts)
    }
}
