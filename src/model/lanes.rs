//! Quadrature points as lanes: an element's shape weights laid out by function then point (and
//! by point then function), so that its residual runs the point-wise arithmetic on all points
//! together while every sum keeps the per-point path's order (the same bits).

/// A cable element's quadrature points as lanes: shape weights by function then point, for S
/// shapes and room for A axial and B bending points (the unused ones zero), for the residuals
/// computed on all points at once (the 3D cable's `Lanes::force` in
/// [`super::ancf3d`], cubic and of degree p; the planar element of degree p,
/// [`super::ancf_p`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lanes<const S: usize, const A: usize, const B: usize> {
    /// dS_j/dx at the axial points.
    pub(crate) axial_ds: [[f64; A]; S],
    /// Weight × l/2 × EA at the axial points [N m].
    pub(crate) axial_w: [f64; A],
    /// dS_j/dx at the bending points.
    pub(crate) ds: [[f64; B]; S],
    /// d²S_j/dx² at the bending points.
    pub(crate) dds: [[f64; B]; S],
    /// Weight × l/2 × EI at the bending points [N m³].
    pub(crate) bend_w: [f64; B],
    /// The same shape weights by point then function (the sums into the coordinates, the
    /// functions as lanes): dS_j/dx at the axial points,
    pub(crate) axial_t: [[f64; S]; A],
    /// dS_j/dx at the bending points,
    pub(crate) ds_t: [[f64; S]; B],
    /// d²S_j/dx² at the bending points.
    pub(crate) dds_t: [[f64; S]; B],
}

impl<const S: usize, const A: usize, const B: usize> Default for Lanes<S, A, B> {
    fn default() -> Self {
        Self {
            axial_ds: [[0.0; A]; S],
            axial_w: [0.0; A],
            ds: [[0.0; B]; S],
            dds: [[0.0; B]; S],
            bend_w: [0.0; B],
            axial_t: [[0.0; S]; A],
            ds_t: [[0.0; S]; B],
            dds_t: [[0.0; S]; B],
        }
    }
}

impl<const S: usize, const A: usize, const B: usize> Lanes<S, A, B> {
    /// The lanes of the axial points (weight × EA, dS/dx) and the bending points (weight ×
    /// EI, dS/dx, d²S/dx²), each given by its first S shapes.
    pub(crate) fn new<'a>(
        axial: impl IntoIterator<Item = (f64, &'a [f64])>,
        bending: impl IntoIterator<Item = (f64, &'a [f64], &'a [f64])>,
    ) -> Self {
        let mut l = Self::default();
        for (q, (w, ds)) in axial.into_iter().enumerate() {
            l.axial_w[q] = w;
            for j in 0..S {
                l.axial_ds[j][q] = ds[j];
                l.axial_t[q][j] = ds[j];
            }
        }
        for (q, (w, ds, dds)) in bending.into_iter().enumerate() {
            l.bend_w[q] = w;
            for j in 0..S {
                l.ds[j][q] = ds[j];
                l.dds[j][q] = dds[j];
                l.ds_t[q][j] = ds[j];
                l.dds_t[q][j] = dds[j];
            }
        }
        l
    }
}

/// Σ_{j<M} w_j e[C·j + c] at the first Q points, for each of the C components (`combine`'s
/// operations per lane: each sum from 0 in j order).
#[inline(always)]
pub(crate) fn lane_comb<
    const C: usize,
    const M: usize,
    const Q: usize,
    const S: usize,
    const W: usize,
    const D: usize,
>(
    w: &[[f64; W]; S],
    e: &[f64; D],
) -> [[f64; Q]; C] {
    let mut r = [[0.0; Q]; C];
    for (c, rc) in r.iter_mut().enumerate() {
        for (j, wj) in w.iter().enumerate().take(M) {
            let x = e[C * j + c];
            for q in 0..Q {
                rc[q] += x * wj[q];
            }
        }
    }
    r
}
