//! Sparse Newton matrix: a pattern built once, values refilled through slot tables, and faer's
//! sparse LU with the symbolic analysis (COLAMD ordering, elimination structure) done once per
//! model and the numeric factorization reusing its storage.

use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

/// Marker for "no slot" (a fixed coordinate).
pub const NO_SLOT: u32 = u32::MAX;

/// Square sparse matrix in compressed sparse column form with a fixed pattern.
#[derive(Debug, Clone)]
pub struct SparsePattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl SparsePattern {
    /// Pattern of an `n × n` matrix from (row, col) entries (duplicates allowed).
    pub fn new(n: usize, mut entries: Vec<(usize, usize)>) -> Self {
        // every diagonal entry is present so that the pattern is structurally non-singular
        // wherever the matrix is
        entries.extend((0..n).map(|i| (i, i)));
        entries.sort_unstable_by_key(|&(r, c)| (c, r));
        entries.dedup();
        let mut col_ptr = vec![0usize; n + 1];
        let mut row_idx = Vec::with_capacity(entries.len());
        for &(r, c) in &entries {
            col_ptr[c + 1] += 1;
            row_idx.push(r);
        }
        for c in 0..n {
            col_ptr[c + 1] += col_ptr[c];
        }
        Self {
            n,
            col_ptr,
            row_idx,
        }
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Row indices of column `col`.
    pub fn column(&self, col: usize) -> impl Iterator<Item = usize> + '_ {
        self.row_idx[self.col_ptr[col]..self.col_ptr[col + 1]]
            .iter()
            .copied()
    }

    /// Position of entry (row, col) in the value array. Panics if it is not in the pattern
    /// (a bug in the assembly, never a consequence of input).
    pub fn slot(&self, row: usize, col: usize) -> u32 {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        let k = self.row_idx[a..b]
            .binary_search(&row)
            .expect("entry belongs to the Newton matrix pattern");
        (a + k) as u32
    }
}

/// Failure of the factorization.
#[derive(Debug, Clone, PartialEq)]
pub struct SingularMatrix;

/// Sparse LU solver bound to one pattern.
pub struct SparseLu {
    pattern: SparsePattern,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    mem: MemBuffer,
    factored: bool,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLu")
            .field("n", &self.pattern.n)
            .field("nnz", &self.pattern.nnz())
            .finish()
    }
}

impl SparseLu {
    /// Symbolic analysis of the pattern (done once).
    pub fn new(pattern: SparsePattern) -> Self {
        let sym = SymbolicSparseColMatRef::new_checked(
            pattern.n,
            pattern.n,
            &pattern.col_ptr,
            None,
            &pattern.row_idx,
        );
        let symbolic =
            factorize_symbolic_lu(sym, Default::default()).expect("symbolic LU of a valid pattern");
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        Self {
            pattern,
            symbolic,
            numeric: NumericLu::new(),
            mem: MemBuffer::new(req),
            factored: false,
        }
    }

    /// The pattern.
    pub fn pattern(&self) -> &SparsePattern {
        &self.pattern
    }

    /// Numeric factorization of the matrix with the given values (in pattern order).
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), SingularMatrix> {
        self.factored = false;
        if values.iter().any(|v| !v.is_finite()) {
            return Err(SingularMatrix);
        }
        let p = &self.pattern;
        let sym = SymbolicSparseColMatRef::new_checked(p.n, p.n, &p.col_ptr, None, &p.row_idx);
        let a = SparseColMatRef::new(sym, values);
        let stack = MemStack::new(&mut self.mem);
        self.symbolic
            .factorize_numeric_lu(&mut self.numeric, a, Par::Seq, stack, Default::default())
            .map_err(|_| SingularMatrix)?;
        self.factored = true;
        Ok(())
    }

    /// Whether a valid factorization is held.
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Solves A x = b in place; returns false if the result is not finite.
    pub fn solve(&mut self, rhs: &mut [f64]) -> bool {
        debug_assert!(self.factored);
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let n = rhs.len();
        let stack = MemStack::new(&mut self.mem);
        let mat = MatMut::from_column_major_slice_mut(rhs, n, 1);
        lu.solve_in_place_with_conj(Conj::No, mat, Par::Seq, stack);
        rhs.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_saddle_point_system() {
        // [2 1 1; 1 3 0; 1 0 0] x = b  (zero diagonal in the constraint row)
        let entries = vec![(0, 0), (0, 1), (1, 0), (1, 1), (0, 2), (2, 0)];
        let p = SparsePattern::new(3, entries);
        let mut v = vec![0.0; p.nnz()];
        for (r, c, x) in [
            (0, 0, 2.0),
            (0, 1, 1.0),
            (1, 0, 1.0),
            (1, 1, 3.0),
            (0, 2, 1.0),
            (2, 0, 1.0),
        ] {
            v[p.slot(r, c) as usize] += x;
        }
        let mut lu = SparseLu::new(p);
        lu.factorize(&v).unwrap();
        let mut b = vec![4.0, 4.0, 1.0];
        assert!(lu.solve(&mut b));
        // x0 = 1, x1 = 1, x2 = 4 - 2 - 1 = 1
        for (x, want) in b.iter().zip([1.0, 1.0, 1.0]) {
            assert!((x - want).abs() < 1e-14);
        }
    }
}
