//! Scene → planar model: the planar parts of the segment walk ([`crate::model::walk`]): a
//! modal segment as a floating frame [R, θ, a], ANCF nodes [r, r′], the rigid joint (position
//! + angle–slope row) and the root support.

use super::elements::{AncfElement, ModalElement};
use super::ends::{ModalRootPort, ModalTipPort, NodePort, RootSupport};
use super::joint::RigidJoint;
use super::Planar;
use crate::math;
use crate::model::ancf::{arc_end, AncfProps, AncfReference, SectionMass, SectionTable};
use crate::model::ancf_p::CableP;
use crate::model::assembly::Model;
use crate::model::component::{Constraint, Element, Port, Support};
use crate::model::direction::SlopeDirection;
use crate::model::dofs::{LocalDofs, Numbering, Rigid};
use crate::model::element_p::ElementP;
use crate::model::modal::{ModalBasis, ModalBody};
use crate::model::section3::SectionBody3;
use crate::model::walk::{walk, Coords, End, Hold, ModalSegment, SegmentMasses, SegmentParts};
use crate::scene::{Scene, SceneError, Segment, SegmentKind, SpaceKind};
use std::sync::Arc;

/// The planar parts of a scene: the beam's direction and reference length, and the layout of
/// the current segment.
struct PlanarParts {
    /// Unit direction of the straight beam at `initial.angle`.
    dir: [f64; 2],
    /// `initial.angle` [rad].
    angle: f64,
    /// Newton scale of positions and modal amplitudes: the total length [m].
    lref: f64,
    /// The current segment's root (position [m], tangent angle [rad]) once a curved segment
    /// came before it; `None` while every segment so far is straight (positions s·dir from
    /// the origin, exactly as a straight beam's).
    start: Option<([f64; 2], f64)>,
    /// Arc length of the current segment's root [m].
    s0: f64,
    /// The current segment's initial curvature κ [1/m] (0: straight).
    kappa: f64,
    /// The last node placed (position, tangent angle): an ANCF segment's end.
    last: ([f64; 2], f64),
}

impl PlanarParts {
    /// The current segment's root (position, tangent angle).
    fn root(&self) -> ([f64; 2], f64) {
        self.start
            .unwrap_or(([self.s0 * self.dir[0], self.s0 * self.dir[1]], self.angle))
    }
}

impl SegmentParts<Planar> for PlanarParts {
    type AncfProps = AncfProps;

    fn begin_segment(&mut self, seg: &Segment, s: f64) {
        self.s0 = s;
        self.kappa = seg.curvature().map_or(0.0, |k| k[1]);
    }

    fn end_segment(&mut self, seg: &Segment) {
        if self.start.is_none() && self.kappa == 0.0 {
            return; // still the straight layout
        }
        self.start = Some(match seg.kind {
            SegmentKind::Ancf => self.last,
            SegmentKind::Modal => {
                let (p0, a0) = self.root();
                arc_end(p0, a0, seg.length, 0.0)
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
    ) -> Result<ModalSegment<Planar>, SceneError> {
        let (area, inertia) = seg.area_inertia();
        let basis = ModalBasis::new(seg.modes.unwrap_or(1), seg.interface_modes);
        let body = ModalBody::new(
            basis,
            seg.length,
            seg.density * area,
            seg.youngs_modulus * inertia,
            seg.damping_ratio,
            seg.damping_time,
        );
        let body = if seg.is_tapered() {
            body.tapered(seg).map_err(SceneError)?
        } else {
            body
        };
        let body = if seg.linear { body.linear() } else { body };
        let body = body.with_points(&masses.points).with_bodies(&masses.bodies);
        let body = body.with_line_load(seg.line_load_vec());
        let body = Arc::new(body);
        let first = si == 0;
        let (root_pt, angle) = match self.start {
            None => ([s * self.dir[0], s * self.dir[1]], self.angle),
            Some(r) => r,
        };
        let mut c = Coords::default();
        c.push(num, !first, root_pt[0], self.lref);
        c.push(num, !first, root_pt[1], self.lref);
        c.push(num, !held, angle, 1.0);
        num.rigid(Rigid::Point, &c.dofs[..2]);
        num.rigid(Rigid::Angle, &c.dofs[2..3]);
        for _ in 0..body.modes() {
            c.push(num, true, 0.0, self.lref);
        }
        let support: Option<Box<dyn Support<Planar>>> = first.then(|| {
            Box::new(RootSupport::Frame {
                position: c.held(0),
                angle: c.is_held(2).then(|| c.held::<1>(2)[0]),
            }) as Box<dyn Support<Planar>>
        });
        // the nonlinear body's foreshortening stiffens it by its axial force field, held or
        // free; a linear body of a held frame gets the leading term
        let element = if held {
            ModalElement::held(body.clone())
        } else {
            ModalElement::new(body.clone())
        };
        Ok(ModalSegment {
            coords: c,
            root: Box::new(ModalRootPort(body.clone())),
            tip: Box::new(ModalTipPort(body)),
            element: Box::new(element),
            support,
            constraints: Vec::new(),
        })
    }

    fn ancf_props(&self, _si: usize, seg: &Segment, le: f64) -> Result<AncfProps, SceneError> {
        let (area, inertia) = seg.area_inertia();
        Ok(AncfProps {
            length: le,
            rho_a: seg.density * area,
            ea: seg.youngs_modulus * area,
            ei: seg.youngs_modulus * inertia,
            damping_time: seg.damping_time,
            strain: seg.strain,
            reference: seg.curvature().map(|k| AncfReference::arc(le, k[1])),
            taper: None,
        })
    }

    fn ancf_element(
        &self,
        props: &AncfProps,
        x0: f64,
        points: &[(f64, f64)],
        bodies: &[SectionMass],
        _bodies3: &[SectionBody3],
        seg: &Segment,
    ) -> Box<dyn Element<Planar>> {
        if seg.degree > 3 {
            // uniform, straight, point masses only (the scene's validation)
            let line = seg.line_load_vec::<2>();
            let kernel = CableP::new(*props, seg.degree);
            return Box::new(ElementP::new(kernel, points, line.as_ref().map(|q| &q[..])));
        }
        let mut props = *props;
        if seg.is_tapered() {
            let (e, rho) = (seg.youngs_modulus, seg.density);
            let at = |x: f64| {
                let p = seg.section_props_at(x / seg.length);
                (e * p.area, e * p.i_z, rho * p.area)
            };
            let l = props.length;
            (props.ea, props.ei, props.rho_a) = at(x0 + 0.5 * l);
            props.taper = Some(SectionTable::of(x0, l, at));
        }
        Box::new(
            AncfElement::new(props)
                .with_points(points)
                .with_bodies(bodies)
                .with_line_load(seg.line_load_vec()),
        )
    }

    fn node(&mut self, num: &mut Numbering, s: f64, hold: Hold) -> Coords {
        let d = self.dir;
        let v = if self.start.is_none() && self.kappa == 0.0 {
            self.last = ([s * d[0], s * d[1]], self.angle);
            [s * d[0], s * d[1], d[0], d[1]]
        } else {
            let (p0, a0) = self.root();
            let (p, a) = arc_end(p0, a0, s - self.s0, self.kappa);
            self.last = (p, a);
            let (sa, ca) = math::sin_cos(a);
            [p[0], p[1], ca, sa]
        };
        let free_r = hold == Hold::Free;
        let free = [free_r, free_r, true, true];
        let scale = [self.lref, self.lref, 1.0, 1.0];
        let mut c = Coords::default();
        for k in 0..4 {
            c.push(num, free[k], v[k], scale[k]);
        }
        num.rigid(Rigid::Point, &c.dofs[..2]);
        num.rigid(Rigid::Direction, &c.dofs[2..]);
        c
    }

    /// The normal n = (−d_y, d_x) of the clamped direction d, held; the row n · r_x = 0.
    fn slope_direction(
        &self,
        num: &mut Numbering,
        node: &Coords,
    ) -> (Coords, (LocalDofs, Box<dyn Constraint>)) {
        let d = self.dir;
        let mut n = Coords::default();
        for v in [-d[1], d[0]] {
            n.push(num, false, v, 1.0);
        }
        num.rigid(Rigid::Direction, &n.dofs);
        let dofs = LocalDofs::new(node.dofs[2..4].iter().chain(&n.dofs).copied().collect());
        let rows = SlopeDirection { dim: 2, normals: 1 };
        (n, (dofs, Box::new(rows)))
    }

    fn node_support(&self, node: &Coords, normals: Option<&Coords>) -> Box<dyn Support<Planar>> {
        Box::new(RootSupport::Node {
            position: node.held::<2>(0),
            slope: normals.map(|n| n.held::<2>(0)),
        })
    }

    fn node_port(&self) -> Box<dyn Port<Planar>> {
        Box::new(NodePort)
    }

    fn join(
        &self,
        up: End<Planar>,
        down: End<Planar>,
        _length: f64,
    ) -> Result<(LocalDofs, Box<dyn Constraint>), SceneError> {
        let dofs = LocalDofs::concat(&[&up.dofs, &down.dofs]);
        let joint = RigidJoint::new(up.port, down.port, up.dofs.len());
        Ok((dofs, Box::new(joint)))
    }
}

impl Model<Planar> {
    /// Builds the model of a validated scene from the origin at `initial.angle`: straight, each
    /// segment after a curved one (`initial_curvature`) on that one's end position and tangent.
    /// Scales for Newton norms: the total length for positions and modal amplitudes, 1 for
    /// slopes and angles.
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        scene.validate()?;
        if scene.space != SpaceKind::Planar {
            return Err(SceneError(
                "space = \"spatial\": this scene builds a spatial model, not a planar one".into(),
            ));
        }
        let (sa, ca) = math::sin_cos(scene.initial.angle);
        let mut parts = PlanarParts {
            dir: [ca, sa],
            angle: scene.initial.angle,
            lref: scene.total_length(),
            start: None,
            s0: 0.0,
            kappa: 0.0,
            last: ([0.0; 2], scene.initial.angle),
        };
        walk(scene, &mut parts)
    }
}
