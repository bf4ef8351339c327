//! The beam's shape at one state, for viewers: the centreline sampled along every element by the
//! element's own interpolation (ANCF: the cubic Hermite field; modal: the mode shapes with the
//! second-order foreshortening), the section frame along it, the strains, the joints between
//! segments and the root (mount) frame. Dimension-free; every vector is in world axes and has
//! three components (a planar beam lies in z = 0, its section z axis is the world z axis).

use super::assembly::Model;
use super::component::LocalState;
use super::sample::{embed, ShapePoint};
use super::space::Space;

/// A frame: origin [m] and axes (unit vectors, world axes; `[x, y, z]`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Frame {
    /// Origin [m].
    pub origin: [f64; 3],
    /// The frame's x, y, z axes in world axes.
    pub axes: [[f64; 3]; 3],
}

/// The sampled beam: polylines root to tip, one per segment.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Shape {
    /// Samples, segment by segment root to tip; within an ANCF segment the node shared by two
    /// elements appears once (with the upstream element's strains).
    pub points: Vec<ShapePoint>,
    /// The point range of each segment's polyline, in scene order.
    pub segments: Vec<std::ops::Range<usize>>,
    /// Position of each joint between consecutive segments [m] (the downstream segment's root).
    pub joints: Vec<[f64; 3]>,
    /// The root frame: the mount frame of a mounted root, else the section frame of the root.
    pub root: Frame,
}

impl<S: Space> Model<S> {
    /// The centreline at state (q, q̇, q̈), `per_element` ≥ 1 intervals per element (so
    /// `per_element + 1` samples each, the shared node once).
    pub fn shape(&self, (q, v, a): (&[f64], &[f64], &[f64]), per_element: usize) -> Shape {
        let n = per_element.max(1);
        let xi: Vec<f64> = (0..=n).map(|k| k as f64 / n as f64).collect();
        // elements root to tip: by segment, in build order within a segment (stable sort)
        let mut order: Vec<usize> = (0..self.elements.len()).collect();
        order.sort_by_key(|&i| self.elements[i].segment);
        let mut shape = Shape::default();
        let mut buf = Vec::with_capacity(n + 1);
        let mut arc = 0.0;
        for i in order {
            let e = &self.elements[i];
            let x = LocalState::moving(&e.at.dofs, self.held_state(), (q, v, a));
            buf.clear();
            e.at.part.sample(&x, &xi, &mut buf);
            let new_segment = shape.points.last().map(|p| p.segment) != Some(e.segment);
            if new_segment {
                if !shape.points.is_empty() {
                    shape.joints.push(buf[0].position);
                }
                shape.segments.push(shape.points.len()..shape.points.len());
            }
            let skip = usize::from(!new_segment);
            for (k, mut p) in buf.drain(..).enumerate().skip(skip) {
                p.segment = e.segment;
                p.arc = arc + xi[k] * e.at.part.length();
                shape.points.push(p);
            }
            arc += e.at.part.length();
            let len = shape.points.len();
            shape.segments.last_mut().expect("pushed above").end = len;
        }
        shape.root = match &self.mount {
            Some(m) => Frame {
                origin: embed(m.position.as_ref()),
                axes: std::array::from_fn(|k| {
                    let mut e = S::Vec::default();
                    if k < S::DIM {
                        e[k] = 1.0;
                        embed(S::from_frame(&m.attitude, &e).as_ref())
                    } else {
                        [0.0, 0.0, 1.0]
                    }
                }),
            },
            None => shape
                .points
                .first()
                .map(|p| Frame {
                    origin: p.position,
                    axes: p.frame,
                })
                .unwrap_or_default(),
        };
        shape
    }
}
