//! Scene → planar model: numbering (root coordinates held by the support are eliminated),
//! components, joints, tip port and support, in the order of the recordings (ANCF elements
//! first, then modal bodies; joints from root to tip).

use super::elements::{AncfElement, ModalElement};
use super::ends::{ModalRootPort, ModalTipPort, NodePort, RootSupport};
use super::joint::RigidJoint;
use super::Planar;
use crate::math;
use crate::model::ancf::AncfProps;
use crate::model::assembly::{Model, Parts};
use crate::model::component::{Constraint, Element, Port};
use crate::model::dofs::{Dof, LocalDofs, Numbering, Rigid};
use crate::model::modal::{ModalBasis, ModalBody};
use crate::scene::{Root, Scene, SceneError, SegmentKind, SpaceKind};
use std::sync::Arc;

/// An end of a segment being built: its local coordinates and port.
struct End {
    dofs: LocalDofs,
    port: Box<dyn Port<Planar>>,
    /// An ANCF node (shared with a following ANCF segment instead of joined).
    node: bool,
}

fn held_index(d: Dof) -> Option<usize> {
    match d {
        Dof::Held(j) => Some(j as usize),
        Dof::Free(_) => None,
    }
}

impl Model<Planar> {
    /// Builds the model of a validated scene, straight at `initial.angle` from the origin.
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
        let dir = [ca, sa];
        let clamped = matches!(scene.root, Root::Clamped | Root::Mounted);
        let lref = scene.total_length();
        let mut num = Numbering::default();
        let mut ancf: Vec<(LocalDofs, Box<dyn Element<Planar>>, usize)> = Vec::new();
        let mut bodies: Vec<(LocalDofs, Box<dyn Element<Planar>>, usize)> = Vec::new();
        let mut joints: Vec<(LocalDofs, Box<dyn Constraint>)> = Vec::new();
        let mut support = None;
        let mut prev: Option<End> = None;
        let mut s_pos = 0.0; // arc length at the segment root
        let mut join = |up: End, down: End| {
            let dofs = LocalDofs::concat(&[&up.dofs, &down.dofs]);
            let joint = RigidJoint {
                up: up.port,
                down: down.port,
                up_len: up.dofs.len(),
            };
            joints.push((dofs, Box::new(joint)));
        };
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
                    let body = Arc::new(ModalBody::new(
                        basis,
                        seg.length,
                        rho_a,
                        ei,
                        seg.damping_ratio,
                        seg.damping_time,
                    ));
                    let free_th = !(first && clamped);
                    let mut dofs = vec![
                        num.coordinate(!first, root_pt[0], lref),
                        num.coordinate(!first, root_pt[1], lref),
                        num.coordinate(free_th, scene.initial.angle, 1.0),
                    ];
                    num.rigid(Rigid::Point, &dofs[..2]);
                    num.rigid(Rigid::Angle, &dofs[2..3]);
                    dofs.extend((0..body.modes()).map(|_| num.free(0.0, lref)));
                    if first {
                        support = Some(RootSupport::Frame {
                            position: [0, 1].map(|k| held_index(dofs[k]).expect("held root")),
                            angle: held_index(dofs[2]),
                        });
                    }
                    let dofs = LocalDofs::new(dofs);
                    if let Some(up) = prev.take() {
                        let root = Box::new(ModalRootPort(body.clone()));
                        join(
                            up,
                            End {
                                dofs: dofs.clone(),
                                port: root,
                                node: false,
                            },
                        );
                    }
                    prev = Some(End {
                        dofs: dofs.clone(),
                        port: Box::new(ModalTipPort(body.clone())),
                        node: false,
                    });
                    // a held frame's segment is stiffened by its centrifugal and axial inertia
                    let element = if first && clamped {
                        ModalElement::stiffened(body)
                    } else {
                        ModalElement::new(body)
                    };
                    bodies.push((dofs, Box::new(element), si));
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
                    let node_vals = |s: f64| [s * dir[0], s * dir[1], dir[0], dir[1]];
                    let node = |num: &mut Numbering, s: f64, free_r: bool, free_s: bool| {
                        let v = node_vals(s);
                        let free = [free_r, free_r, free_s, free_s];
                        let scale = [lref, lref, 1.0, 1.0];
                        let dofs: Vec<Dof> = (0..4)
                            .map(|c| num.coordinate(free[c], v[c], scale[c]))
                            .collect();
                        num.rigid(Rigid::Point, &dofs[..2]);
                        num.rigid(Rigid::Direction, &dofs[2..]);
                        LocalDofs::new(dofs)
                    };
                    // first node: shared with a previous ANCF segment, else new (held at the root)
                    let mut last = match prev.take() {
                        Some(up) if up.node => up.dofs,
                        up => {
                            let dofs = node(&mut num, s_pos, !first, !(first && clamped));
                            if first {
                                let held = |k: usize| held_index(dofs.dofs()[k]);
                                support = Some(RootSupport::Node {
                                    position: [0, 1].map(|k| held(k).expect("held root")),
                                    slope: held(2).zip(held(3)).map(|(x, y)| [x, y]),
                                });
                            }
                            if let Some(up) = up {
                                join(
                                    up,
                                    End {
                                        dofs: dofs.clone(),
                                        port: Box::new(NodePort),
                                        node: true,
                                    },
                                );
                            }
                            dofs
                        }
                    };
                    for k in 0..ne {
                        let next = node(&mut num, s_pos + (k + 1) as f64 * le, true, true);
                        let dofs = LocalDofs::concat(&[&last, &next]);
                        ancf.push((dofs, Box::new(AncfElement::new(props)), si));
                        last = next;
                    }
                    prev = Some(End {
                        dofs: last,
                        port: Box::new(NodePort),
                        node: true,
                    });
                }
            }
            s_pos += seg.length;
        }
        let tip = prev.expect("a validated scene has at least one segment");
        let mut elements = ancf;
        elements.append(&mut bodies);
        Ok(Model::assemble(Parts {
            numbering: num,
            elements,
            constraints: joints,
            tip: (tip.dofs, tip.port),
            support: Box::new(support.expect("the first segment is held at the root")),
            gravity: scene.gravity_vec(),
            tip_force: scene.tip_force_vec(),
            tip_moment: scene.tip_moment_vec::<1>()[0],
            mounted: scene.root == Root::Mounted,
        }))
    }
}
