//! Scene → spatial model: numbering (root coordinates held by the support are eliminated),
//! components, joints, tip port and support, in the order of the planar build (ANCF elements
//! first, then modal bodies; constraints from root to tip, each free frame's Euler-parameter
//! normalization before the joint to its upstream neighbour).
//!
//! Geometry: the root frame → world rotation A₀ is `scene.root_orientation()`; the beam starts
//! straight at the origin along A₀x̄ with its section axes A₀ȳ, A₀z̄, every segment in that
//! frame. ANCF nodes are `[r, r_x, r_y]` (with torsion) or `[r, r_x]` (the cable); modal bodies
//! `[R, p, a_y, a_z, a_t]` with p = A₀'s Euler parameters. A joint's DOT1 rows are scaled by
//! the length of its upstream segment.

use super::joint::RigidJoint3;
use super::{
    AncfElement3, EulerNormalization, FrameSupport3, ModalElement3, ModalRootPort3, ModalTipPort3,
    NodePort3, NodeSupport3, Spatial,
};
use crate::model::ancf3d::Ancf3Props;
use crate::model::assembly::{Model, Parts};
use crate::model::component::{Constraint, Element, Port, Support};
use crate::model::dofs::{Dof, LocalDofs, Numbering, Rigid};
use crate::model::modal::{ModalBasis, ModalBody3, ModalProps3};
use crate::scene::{Root, Scene, SceneError, SegmentKind, SpaceKind};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use std::sync::Arc;

/// An end of a segment being built: its local coordinates with their initial values, and its
/// port.
struct End {
    dofs: LocalDofs,
    q0: Vec<f64>,
    port: Box<dyn Port<Spatial>>,
    /// An ANCF node (shared with a following ANCF segment instead of joined).
    node: bool,
}

/// Coordinates being numbered for one component: their dofs and initial values.
#[derive(Default)]
struct Coords {
    dofs: Vec<Dof>,
    q0: Vec<f64>,
}

impl Coords {
    fn push(&mut self, num: &mut Numbering, free: bool, value: f64, scale: f64) {
        self.dofs.push(num.coordinate(free, value, scale));
        self.q0.push(value);
    }

    /// Indices into the held values of the `N` coordinates from `first` (all held).
    fn held<const N: usize>(&self, first: usize) -> [usize; N] {
        std::array::from_fn(|k| match self.dofs[first + k] {
            Dof::Held(j) => j as usize,
            Dof::Free(_) => unreachable!("a root coordinate held by the support"),
        })
    }

    fn is_held(&self, k: usize) -> bool {
        matches!(self.dofs[k], Dof::Held(_))
    }
}

/// Adds the rigid joint between `up` and `down`, DOT1 rows scaled by `length` [m].
fn join(
    constraints: &mut Vec<(LocalDofs, Box<dyn Constraint>)>,
    up: End,
    down: End,
    length: f64,
) -> Result<(), SceneError> {
    let dofs = LocalDofs::concat(&[&up.dofs, &down.dofs]);
    let q0: Vec<f64> = up.q0.iter().chain(&down.q0).copied().collect();
    let joint =
        RigidJoint3::new(up.port, down.port, up.dofs.len(), length, &q0).ok_or_else(|| {
            SceneError("internal: a rigid joint between two ANCF ends (they share a node)".into())
        })?;
    constraints.push((dofs, Box::new(joint)));
    Ok(())
}

/// Unit Euler parameters `[e0, e1, e2, e3]` → rotation columns (x̄, ȳ, z̄ in world axes).
fn frame_of(e: [f64; 4]) -> [Vector3<f64>; 3] {
    let r = UnitQuaternion::from_quaternion(Quaternion::new(e[0], e[1], e[2], e[3]))
        .to_rotation_matrix();
    let m = r.matrix();
    [0, 1, 2].map(|c| m.column(c).into_owned())
}

impl Model<Spatial> {
    /// Builds the model of a validated spatial scene (`space = "spatial"`), straight from the
    /// origin along the root frame's x axis. Scales for Newton norms: the total length for
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
        let reference = Matrix3::from_columns(&[ax, ay, az]);
        let clamped = matches!(scene.root, Root::Clamped | Root::Mounted);
        let torsion = scene.torsion;
        let lref = scene.total_length();
        let mut num = Numbering::default();
        let mut ancf: Vec<(LocalDofs, Box<dyn Element<Spatial>>, usize)> = Vec::new();
        let mut bodies: Vec<(LocalDofs, Box<dyn Element<Spatial>>, usize)> = Vec::new();
        let mut constraints: Vec<(LocalDofs, Box<dyn Constraint>)> = Vec::new();
        let mut support: Option<Box<dyn Support<Spatial>>> = None;
        let mut prev: Option<End> = None;
        let mut s_pos = 0.0; // arc length at the segment root
        let mut prev_len = 0.0; // length of the previous segment (DOT1 row scale)
        for (si, seg) in scene.segments.iter().enumerate() {
            let first = si == 0;
            let root_pt = s_pos * ax;
            match seg.kind {
                SegmentKind::Modal => {
                    let basis = ModalBasis::new(seg.modes.unwrap_or(1), seg.interface_modes);
                    let mut body = ModalBody3::new(basis, ModalProps3::of_segment(seg));
                    if first && clamped {
                        // a held frame: its motion is the support's, so the axial inertia and
                        // centrifugal forces of the segment stiffen its bending (K_G)
                        body = body.with_stiffening();
                    }
                    let body = Arc::new(body);
                    let free_p = !(first && clamped);
                    let mut c = Coords::default();
                    for k in 0..3 {
                        c.push(&mut num, !first, root_pt[k], lref);
                    }
                    for k in 0..4 {
                        c.push(&mut num, free_p, e0[k], 1.0);
                    }
                    num.rigid(Rigid::Point, &c.dofs[..3]);
                    num.rigid(Rigid::Euler, &c.dofs[3..7]);
                    let nb = body.modes();
                    for _ in 0..2 * nb {
                        c.push(&mut num, true, 0.0, lref);
                    }
                    while c.dofs.len() < body.dim() {
                        c.push(&mut num, true, 0.0, 1.0); // twist amplitudes [rad]
                    }
                    if first {
                        support = Some(Box::new(FrameSupport3 {
                            position: c.held(0),
                            attitude: (!free_p).then(|| c.held(3)),
                        }));
                    }
                    let dofs = LocalDofs::new(c.dofs.clone());
                    if free_p {
                        let p = LocalDofs::new(c.dofs[3..7].to_vec());
                        constraints.push((p, Box::new(EulerNormalization)));
                    }
                    if let Some(up) = prev.take() {
                        let down = End {
                            dofs: dofs.clone(),
                            q0: c.q0.clone(),
                            port: Box::new(ModalRootPort3(body.clone())),
                            node: false,
                        };
                        join(&mut constraints, up, down, prev_len)?;
                    }
                    prev = Some(End {
                        dofs: dofs.clone(),
                        q0: c.q0,
                        port: Box::new(ModalTipPort3(body.clone())),
                        node: false,
                    });
                    bodies.push((dofs, Box::new(ModalElement3::new(body)), si));
                }
                SegmentKind::Ancf => {
                    let ne = seg.elements.unwrap_or(1);
                    let le = seg.length / ne as f64;
                    let props = Ancf3Props::of_segment(seg, torsion)
                        .map_err(|m| SceneError(format!("segments[{si}]: {m}")))?;
                    // node coordinates r, r_x (, r_y) at arc length s; held as the root asks
                    let node = |num: &mut Numbering, s: f64, free_r: bool, free_d: bool| {
                        let mut c = Coords::default();
                        let r = s * ax;
                        for k in 0..3 {
                            c.push(num, free_r, r[k], lref);
                        }
                        for k in 0..3 {
                            c.push(num, free_d, ax[k], 1.0);
                        }
                        if torsion {
                            for k in 0..3 {
                                c.push(num, free_d, ay[k], 1.0);
                            }
                        }
                        num.rigid(Rigid::Point, &c.dofs[..3]);
                        for d in c.dofs[3..].chunks(3) {
                            num.rigid(Rigid::Direction, d);
                        }
                        c
                    };
                    // first node: shared with a previous ANCF segment, else new (held at the root)
                    let mut last = match prev.take() {
                        Some(up) if up.node => Coords {
                            dofs: up.dofs.dofs().to_vec(),
                            q0: up.q0,
                        },
                        up => {
                            let c = node(&mut num, s_pos, !first, !(first && clamped));
                            if first {
                                support = Some(Box::new(NodeSupport3 {
                                    position: c.held(0),
                                    slope: c.is_held(3).then(|| c.held(3)),
                                    section: (torsion && c.is_held(6)).then(|| c.held(6)),
                                }));
                            }
                            if let Some(up) = up {
                                let down = End {
                                    dofs: LocalDofs::new(c.dofs.clone()),
                                    q0: c.q0.clone(),
                                    port: Box::new(NodePort3::new(torsion, reference)),
                                    node: true,
                                };
                                join(&mut constraints, up, down, prev_len)?;
                            }
                            c
                        }
                    };
                    for k in 0..ne {
                        let next = node(&mut num, s_pos + (k + 1) as f64 * le, true, true);
                        let dofs =
                            LocalDofs::new(last.dofs.iter().chain(&next.dofs).copied().collect());
                        ancf.push((dofs, Box::new(AncfElement3::new(props)), si));
                        last = next;
                    }
                    prev = Some(End {
                        dofs: LocalDofs::new(last.dofs),
                        q0: last.q0,
                        port: Box::new(NodePort3::new(torsion, reference)),
                        node: true,
                    });
                }
            }
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
            gravity: scene.gravity_vec(),
            tip_force: scene.tip_force_vec(),
            tip_moment: scene.tip_moment_vec(),
            mounted: scene.root == Root::Mounted,
        }))
    }
}
