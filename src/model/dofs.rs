//! Coordinate numbering: which global coordinate each local coordinate of a component is, and
//! the gather/scatter between the two. Dimension-free.
//!
//! Held coordinates (those a support fixes, e.g. the root of a clamped beam) are eliminated,
//! not constrained: they take their value from a table of held values and have no unknown, no
//! row and no column. Their residual is what the support carries (the reaction).

use crate::linalg::{SparsePattern, NO_SLOT};

/// One local coordinate of a component.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    /// A free coordinate: index into q (and row/column of the Newton matrix).
    Free(u32),
    /// A held (eliminated) coordinate: index into the held values.
    Held(u32),
}

/// Numbers the coordinates of a model as a build creates them.
#[derive(Debug, Clone, Default)]
pub struct Numbering {
    q0: Vec<f64>,
    scale: Vec<f64>,
    held: Vec<f64>,
    groups: Vec<RigidGroup>,
}

/// How a group of coordinates moves when the whole beam moves rigidly (a mount carrying it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rigid {
    /// A point [m] (DIM coordinates): r ↦ R + A r.
    Point,
    /// A direction or gradient (DIM coordinates): d ↦ A d.
    Direction,
    /// A planar frame angle [rad] (1 coordinate): θ ↦ θ_b + θ.
    Angle,
    /// Euler parameters of a frame (4 coordinates, scalar first): p ↦ p_b ⊗ p.
    Euler,
}

/// Coordinates that move together under a rigid motion of the beam (all free or all held).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidGroup {
    /// What they are.
    pub kind: Rigid,
    /// The coordinates.
    pub dofs: Vec<Dof>,
}

impl Numbering {
    /// A new free coordinate with initial value `value` and characteristic magnitude `scale`.
    pub fn free(&mut self, value: f64, scale: f64) -> Dof {
        self.q0.push(value);
        self.scale.push(scale);
        Dof::Free((self.q0.len() - 1) as u32)
    }

    /// A new held coordinate fixed at `value`.
    pub fn held(&mut self, value: f64) -> Dof {
        self.held.push(value);
        Dof::Held((self.held.len() - 1) as u32)
    }

    /// [`Numbering::free`] if `free`, else [`Numbering::held`].
    pub fn coordinate(&mut self, free: bool, value: f64, scale: f64) -> Dof {
        if free {
            self.free(value, scale)
        } else {
            self.held(value)
        }
    }

    /// Declares how `dofs` (all free or all held) move under a rigid motion of the beam; the
    /// coordinates not in any group (modal amplitudes) are invariant.
    pub fn rigid(&mut self, kind: Rigid, dofs: &[Dof]) {
        debug_assert!(
            dofs.iter().all(|d| matches!(d, Dof::Free(_)))
                || dofs.iter().all(|d| matches!(d, Dof::Held(_)))
        );
        self.groups.push(RigidGroup {
            kind,
            dofs: dofs.to_vec(),
        });
    }

    /// The rigid groups declared so far (moved out).
    pub fn take_groups(&mut self) -> Vec<RigidGroup> {
        std::mem::take(&mut self.groups)
    }

    /// (initial free coordinates, their scales, held values).
    pub fn finish(self) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        (self.q0, self.scale, self.held)
    }
}

/// The local coordinates of one component (element, port, constraint) and, once the sparse
/// pattern is known, the value slots of its local block.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LocalDofs {
    dofs: Vec<Dof>,
    /// Row-major d × d slots of (local i, local j) in the matrix values ([`NO_SLOT`] if held).
    slots: Vec<u32>,
}

impl LocalDofs {
    /// Local coordinates in order.
    pub fn new(dofs: Vec<Dof>) -> Self {
        Self {
            dofs,
            slots: Vec::new(),
        }
    }

    /// The local coordinates of `parts` one after the other.
    pub fn concat(parts: &[&LocalDofs]) -> Self {
        Self::new(parts.iter().flat_map(|p| p.dofs.iter().copied()).collect())
    }

    /// Number of local coordinates d.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// The local coordinates.
    pub fn dofs(&self) -> &[Dof] {
        &self.dofs
    }

    /// Global index of local coordinate `k` if it is free.
    pub fn free(&self, k: usize) -> Option<usize> {
        match self.dofs[k] {
            Dof::Free(i) => Some(i as usize),
            Dof::Held(_) => None,
        }
    }

    /// Whether any local coordinate is held.
    pub fn has_held(&self) -> bool {
        self.dofs.iter().any(|d| matches!(d, Dof::Held(_)))
    }

    /// Local coordinates from the global `q` and the held values.
    pub fn gather(&self, q: &[f64], held: &[f64], out: &mut [f64]) {
        for (o, d) in out.iter_mut().zip(&self.dofs) {
            *o = match *d {
                Dof::Free(i) => q[i as usize],
                Dof::Held(j) => held[j as usize],
            };
        }
    }

    /// Local (q, q̇, q̈) from the global vectors in one pass: held coordinates at their held
    /// values, with the held rates and accelerations `held_motion` (empty: not moving).
    #[inline]
    pub fn gather_state(
        &self,
        (q, v, a): (&[f64], &[f64], &[f64]),
        (held, held_v, held_a): (&[f64], &[f64], &[f64]),
        (ql, vl, al): (&mut [f64], &mut [f64], &mut [f64]),
    ) {
        // equal lengths let one bounds check on q cover q̇ and q̈
        let (v, a) = (&v[..q.len()], &a[..q.len()]);
        let out = ql.iter_mut().zip(vl.iter_mut()).zip(al.iter_mut());
        for (((qk, vk), ak), d) in out.zip(&self.dofs) {
            (*qk, *vk, *ak) = state_of(*d, (q, v, a), (held, held_v, held_a));
        }
    }

    /// [`LocalDofs::gather_state`] of a component with `D` local coordinates into arrays: a
    /// fixed trip count, unrolled, so that the values reach the arrays in registers (the
    /// kernels' paired loads then forward from whole stores).
    #[inline(always)]
    pub fn gather_arrays<const D: usize>(
        &self,
        (q, v, a): (&[f64], &[f64], &[f64]),
        held: (&[f64], &[f64], &[f64]),
    ) -> ([f64; D], [f64; D], [f64; D]) {
        let dofs: &[Dof; D] = self
            .dofs
            .as_slice()
            .try_into()
            .expect("D local coordinates");
        let (v, a) = (&v[..q.len()], &a[..q.len()]);
        let mut out = ([0.0; D], [0.0; D], [0.0; D]);
        for (k, d) in dofs.iter().enumerate() {
            (out.0[k], out.1[k], out.2[k]) = state_of(*d, (q, v, a), held);
        }
        out
    }

    /// `global[i] += s·local[k]` for every free local coordinate k at global index i.
    #[inline]
    pub fn scatter_add(&self, s: f64, local: &[f64], global: &mut [f64]) {
        for (x, d) in local.iter().zip(&self.dofs) {
            if let Dof::Free(i) = *d {
                global[i as usize] += s * x;
            }
        }
    }

    /// `held[j] += local[k]` for every held local coordinate k at held index j.
    pub fn scatter_held(&self, local: &[f64], held: &mut [f64]) {
        for (x, d) in local.iter().zip(&self.dofs) {
            if let Dof::Held(j) = *d {
                held[j as usize] += x;
            }
        }
    }

    /// Entries of the local block (free × free) for the sparsity pattern.
    pub fn block_entries(&self, entries: &mut Vec<(usize, usize)>) {
        for i in self.dofs.iter().filter_map(free_index) {
            for j in self.dofs.iter().filter_map(free_index) {
                entries.push((i, j));
            }
        }
    }

    /// Looks up the slots of the local block in `pattern` (once, after the pattern is built).
    pub fn bind(&mut self, pattern: &SparsePattern) {
        let d = self.dofs.len();
        self.slots = Vec::with_capacity(d * d);
        for a in &self.dofs {
            for b in &self.dofs {
                self.slots.push(match (free_index(a), free_index(b)) {
                    (Some(i), Some(j)) => pattern.slot(i, j),
                    _ => NO_SLOT,
                });
            }
        }
    }

    /// Slot of the local entry (i, j), if both coordinates are free.
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let s = self.slots[i * self.dofs.len() + j];
        (s != NO_SLOT).then_some(s as usize)
    }

    /// `values[slot(i, j)] += h(i, j)` over the free × free local pairs, row by row.
    #[inline]
    pub fn add_block_with(&self, values: &mut [f64], mut h: impl FnMut(usize, usize) -> f64) {
        let d = self.dofs.len();
        for (i, row) in self.slots.chunks_exact(d.max(1)).enumerate() {
            for (j, &s) in row.iter().enumerate() {
                if s != NO_SLOT {
                    values[s as usize] += h(i, j);
                }
            }
        }
    }
}

/// (q, q̇, q̈) of local coordinate `d` (`v`, `a` as long as `q`): a held one at its held value
/// with its held rate and acceleration (0 where `held_v`, `held_a` are empty).
#[inline(always)]
fn state_of(
    d: Dof,
    (q, v, a): (&[f64], &[f64], &[f64]),
    (held, held_v, held_a): (&[f64], &[f64], &[f64]),
) -> (f64, f64, f64) {
    match d {
        Dof::Free(i) => {
            let i = i as usize;
            (q[i], v[i], a[i])
        }
        Dof::Held(j) => {
            let j = j as usize;
            let rate = |x: &[f64]| x.get(j).copied().unwrap_or(0.0);
            (held[j], rate(held_v), rate(held_a))
        }
    }
}

fn free_index(d: &Dof) -> Option<usize> {
    match *d {
        Dof::Free(i) => Some(i as usize),
        Dof::Held(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gather_scatter_and_slots_follow_the_numbering() {
        let mut num = Numbering::default();
        let a = num.held(0.5);
        let b = num.free(2.0, 1.0);
        let c = num.free(3.0, 1.0);
        let mut dofs = LocalDofs::new(vec![b, a, c]);
        let (q0, _, held) = num.finish();
        let mut x = [0.0; 3];
        dofs.gather(&q0, &held, &mut x);
        assert_eq!(x, [2.0, 0.5, 3.0]);
        let (mut v, mut a) = ([0.0; 3], [0.0; 3]);
        dofs.gather_state(
            (&q0, &[7.0, 8.0], &[5.0, 6.0]),
            (&held, &[], &[]),
            (&mut x, &mut v, &mut a),
        );
        assert_eq!(
            (x, v, a),
            ([2.0, 0.5, 3.0], [7.0, 0.0, 8.0], [5.0, 0.0, 6.0])
        );
        let mut g = [1.0, 1.0];
        dofs.scatter_add(2.0, &[1.0, 10.0, 3.0], &mut g);
        assert_eq!(g, [3.0, 7.0]);
        let mut h = [0.0];
        dofs.scatter_held(&[1.0, 10.0, 3.0], &mut h);
        assert_eq!(h, [10.0]);
        let mut entries = Vec::new();
        dofs.block_entries(&mut entries);
        assert_eq!(entries, [(0, 0), (0, 1), (1, 0), (1, 1)]);
        let p = SparsePattern::new(2, entries);
        dofs.bind(&p);
        assert_eq!(dofs.slot(0, 2), Some(p.slot(0, 1) as usize));
        assert_eq!(dofs.slot(1, 0), None);
        let mut vals = vec![0.0; p.nnz()];
        let block = [1.0, 9.0, 2.0, 9.0, 9.0, 9.0, 3.0, 9.0, 4.0];
        dofs.add_block_with(&mut vals, |i, j| block[3 * i + j]);
        assert_eq!(vals[p.slot(1, 0) as usize], 3.0);
        assert_eq!(vals[p.slot(1, 1) as usize], 4.0);
    }
}
