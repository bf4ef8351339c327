//! A written ParaView series read back (vtkio) into shapes: what `hybeam animate RESULT_DIR`
//! turns into the animation page.

use crate::vtk::{read_collection, ViewError};
use hybeam::model::{Frame, Shape, ShapePoint};
use std::path::Path;
use vtkio::model::{Attribute, DataSet, Piece, Vtk};

/// One piece of a series: its time [s], the shape and the section radius per point [m].
#[derive(Debug, Clone)]
pub struct Piece3 {
    /// Time [s].
    pub time: f64,
    /// The shape (position, velocity, section frame, strains, arc length, segment per point).
    pub shape: Shape,
    /// Outer section radius per point [m].
    pub radius: Vec<f64>,
    /// The attached masses: centre [m] and sphere radius [m] ([`crate::look`]).
    pub masses: Vec<([f64; 3], f64)>,
}

/// The pieces of the `.pvd` collection `pvd`, in order.
pub fn read_series(pvd: &Path) -> Result<Vec<Piece3>, ViewError> {
    read_collection(pvd)?
        .into_iter()
        .map(|(t, path)| {
            read_dressed(&path).map(|(shape, radius, masses)| Piece3 {
                time: t,
                shape,
                radius,
                masses,
            })
        })
        .collect()
}

/// The shape and radii of one `.vtu` piece written by [`crate::vtk::piece`].
pub fn read_piece(path: &Path) -> Result<(Shape, Vec<f64>), ViewError> {
    read_dressed(path).map(|(shape, radius, _)| (shape, radius))
}

/// The shape of one `.vtu` piece, the radius at each point and the attached masses (centre and
/// sphere radius [m]).
#[allow(clippy::type_complexity)]
pub fn read_dressed(path: &Path) -> Result<(Shape, Vec<f64>, Vec<([f64; 3], f64)>), ViewError> {
    let bad = |message: String| ViewError::Format {
        path: path.to_path_buf(),
        message,
    };
    let vtk = Vtk::import(path).map_err(|e| ViewError::Vtk {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(bad("not an unstructured grid".into()));
    };
    let Some(Piece::Inline(p)) = pieces.into_iter().next() else {
        return Err(bad("no inline piece".into()));
    };
    let points: Vec<f64> = p
        .points
        .cast_into()
        .ok_or_else(|| bad("points not numeric".into()))?;
    let array = |name: &str| -> Result<Vec<f64>, ViewError> {
        p.data
            .point
            .iter()
            .find_map(|a| match a {
                Attribute::DataArray(d) if d.name == name => d.data.cast_into::<f64>(),
                _ => None,
            })
            .ok_or_else(|| bad(format!("no point array {name}")))
    };
    let (conn, offsets) = p.cells.cell_verts.clone().into_xml();
    let kinds: Vec<f64> = p
        .data
        .cell
        .iter()
        .find_map(|a| match a {
            Attribute::DataArray(d) if d.name == "kind" => d.data.cast_into::<f64>(),
            _ => None,
        })
        .ok_or_else(|| bad("no cell array kind".into()))?;
    let [velocity, tangent, sy, sz] = ["velocity", "tangent", "section_y", "section_z"].map(array);
    let [axial, cy, cz, twist, arc, radius] = [
        "axial_strain",
        "curvature_y",
        "curvature_z",
        "twist",
        "arc",
        "radius",
    ]
    .map(array);
    let (velocity, tangent, sy, sz) = (velocity?, tangent?, sy?, sz?);
    let (axial, cy, cz, twist, arc, radius) = (axial?, cy?, cz?, twist?, arc?, radius?);
    let v3 = |a: &[f64], i: usize| [a[3 * i], a[3 * i + 1], a[3 * i + 2]];
    let mut shape = Shape::default();
    let mut per_point = Vec::new();
    let mut start = 0u64;
    let mut root = None;
    let mut masses = Vec::new();
    for (c, &end) in offsets.iter().enumerate() {
        let cell = &conn[start as usize..end as usize];
        start = end;
        match kinds.get(c).copied() {
            Some(0.0) => {
                let first = shape.points.len();
                let segment = shape.segments.len();
                for &i in cell {
                    let i = i as usize;
                    per_point.push(radius[i]);
                    shape.points.push(ShapePoint {
                        segment,
                        arc: arc[i],
                        position: v3(&points, i),
                        velocity: v3(&velocity, i),
                        frame: [v3(&tangent, i), v3(&sy, i), v3(&sz, i)],
                        axial_strain: axial[i],
                        curvature: [cy[i], cz[i]],
                        twist: twist[i],
                    });
                }
                shape.segments.push(first..shape.points.len());
            }
            Some(1.0) => shape.joints.push(v3(&points, cell[0] as usize)),
            Some(2.0) => {
                let i = cell[0] as usize;
                root = Some(Frame {
                    origin: v3(&points, i),
                    axes: [v3(&tangent, i), v3(&sy, i), v3(&sz, i)],
                });
            }
            Some(3.0) => {
                let i = cell[0] as usize;
                masses.push((v3(&points, i), radius[i]));
            }
            _ => return Err(bad(format!("cell {c} of unknown kind"))),
        }
    }
    shape.root = root.ok_or_else(|| bad("no root frame vertex".into()))?;
    Ok((shape, per_point, masses))
}
