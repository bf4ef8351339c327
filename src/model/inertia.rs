//! The rigid inertia of a beam at its mount, [`MountInertia`]: what a host adds to the body the
//! beam is mounted on, and the reaction that inertia alone would give (a beam's reaction minus
//! it is the elastic part).

use super::space::{Motion, Space};
use super::vector::cross;

/// The rigid inertia of the beam at the mount: what a host adds to its mount body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MountInertia<S: Space> {
    /// Mass [kg].
    pub mass: f64,
    /// Centre of mass relative to the mount point [m], mount frame axes.
    pub center_of_mass: S::Vec,
    /// Inertia tensor about the mount point [kg m²], mount frame axes, row-major DIM×DIM in
    /// space (xx, xy, xz, yx, …); in the plane the single entry zz.
    pub inertia: [f64; 9],
}

/// A vector of a space as three components (the plane's z = 0).
fn vec3<S: Space>(v: &S::Vec) -> [f64; 3] {
    let mut out = [0.0; 3];
    out[..S::DIM].copy_from_slice(&v.as_ref()[..S::DIM]);
    out
}

/// A moment of a space as three components (the plane's about z).
fn moment3<S: Space>(m: &S::Moment) -> [f64; 3] {
    let c = S::moment_components(m);
    if c.len() == 1 {
        [0.0, 0.0, c[0]]
    } else {
        [c[0], c[1], c[2]]
    }
}

impl<S: Space> MountInertia<S> {
    /// Centre of mass c [m] and inertia about the mount point I [kg m²] in world axes, for a
    /// mount frame at orientation `attitude` (3 components; the plane: z = 0, only I_zz).
    fn world(&self, attitude: &S::Attitude) -> ([f64; 3], [[f64; 3]; 3]) {
        let c = vec3::<S>(&S::from_frame(attitude, &self.center_of_mass));
        let iw = S::inertia_to_world(attitude, &self.inertia);
        (c, iw)
    }

    /// The reaction of a rigid body with this inertia moving with the mount `m` under
    /// `gravity` (support on the body, world axes; moment about the mount point):
    /// F = m (a + α × c + ω × (ω × c) − g), M = I α + ω × I ω + m c × (a − g), with c and I in
    /// world axes. A beam's reaction minus this is its elastic part.
    pub fn rigid_reaction(&self, m: &Motion<S>, gravity: &S::Vec) -> (S::Vec, S::Moment) {
        let (c, iw) = self.world(&m.attitude);
        let (w, al) = (
            moment3::<S>(&m.angular_velocity),
            moment3::<S>(&m.angular_acceleration),
        );
        let (a, g) = (vec3::<S>(&m.acceleration), vec3::<S>(gravity));
        let (ac, wwc) = (cross(al, c), cross(w, cross(w, c)));
        let mut f = S::Vec::default();
        for k in 0..S::DIM {
            f[k] = self.mass * (a[k] + ac[k] + wwc[k] - g[k]);
        }
        let iv = |v: [f64; 3]| {
            std::array::from_fn::<f64, 3, _>(|r| (0..3).map(|k| iw[r][k] * v[k]).sum())
        };
        let (ia, gyro) = (iv(al), cross(w, iv(w)));
        let ag = std::array::from_fn(|k| a[k] - g[k]);
        let cm = cross(c, ag);
        let mut mo = S::Moment::default();
        for (x, &k) in S::moment_components_mut(&mut mo)
            .iter_mut()
            .zip(S::MOMENT_INDICES)
        {
            *x = ia[k] + gyro[k] + self.mass * cm[k];
        }
        (f, mo)
    }

    /// ∂[`MountInertia::rigid_reaction`]/∂(a, α) for a mount frame at orientation `attitude`:
    /// the rigid body's mass matrix at the mount point, rows force then moment components,
    /// columns acceleration then angular acceleration components (world axes):
    /// [m 1, −m [c]×; m [c]×, I].
    pub fn mass_matrix(&self, attitude: &S::Attitude) -> Vec<Vec<f64>> {
        let (full, n) = self.mass_matrix_array(attitude);
        full[..n].iter().map(|row| row[..n].to_vec()).collect()
    }

    /// [`MountInertia::mass_matrix`] without allocating: the matrix in the upper left n × n of
    /// a 6 × 6 array (n = 3 in the plane, 6 in space), and n.
    pub fn mass_matrix_array(&self, attitude: &S::Attitude) -> ([[f64; 6]; 6], usize) {
        let (c, iw) = self.world(attitude);
        let skew = [[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]];
        let m = self.mass;
        // the 6×6 matrix, then the space's rows and columns
        let full = |r: usize, k: usize| match (r < 3, k < 3) {
            (true, true) => {
                if r == k {
                    m
                } else {
                    0.0
                }
            }
            (true, false) => -m * skew[r][k - 3],
            (false, true) => m * skew[r - 3][k],
            (false, false) => iw[r - 3][k - 3],
        };
        let n = S::DIM + S::MOMENT_INDICES.len();
        let idx = |i: usize| {
            if i < S::DIM {
                i
            } else {
                S::MOMENT_INDICES[i - S::DIM] + 3
            }
        };
        let mut out = [[0.0; 6]; 6];
        for (r, row) in out.iter_mut().enumerate().take(n) {
            for (k, x) in row.iter_mut().enumerate().take(n) {
                *x = full(idx(r), idx(k));
            }
        }
        (out, n)
    }
}

/// The most rigid fields of a mount (3 translations, 3 rotations).
pub(crate) const MAX_FIELDS: usize = 6;

/// The working memory of `Model::mount_inertia` (a mounted model's own, sized at build: no
/// allocation in a step).
#[derive(Debug, Clone, Default)]
pub(crate) struct MountWork {
    /// The rigid fields over the free coordinates, field by field (n each).
    pub(crate) free: Vec<f64>,
    /// The rigid fields over the held coordinates, field by field.
    pub(crate) held: Vec<f64>,
    /// Zeros: the rates and accelerations (only ever zero).
    pub(crate) zeros: Vec<f64>,
    /// An element's residual at rest, and moving with a field; a field's local values.
    pub(crate) r0: Vec<f64>,
    pub(crate) r1: Vec<f64>,
    pub(crate) ul: Vec<f64>,
}

impl MountWork {
    /// Sized for `n` free and `nh` held coordinates and elements of up to `local`
    /// coordinates.
    pub(crate) fn sized(n: usize, nh: usize, local: usize) -> Self {
        let mut w = Self::default();
        w.size(n, nh);
        for v in [&mut w.r0, &mut w.r1, &mut w.ul] {
            v.reserve(local);
        }
        w
    }

    /// Sizes the fields and zeros (no allocation once sized).
    pub(crate) fn size(&mut self, n: usize, nh: usize) {
        self.free.resize(MAX_FIELDS * n, 0.0);
        self.held.resize(MAX_FIELDS * nh, 0.0);
        self.zeros.resize(n.max(nh), 0.0);
    }
}
