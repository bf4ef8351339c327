//! Newton matrix: a pattern built once, values refilled through slot tables, and its LU: in band
//! storage after a reverse Cuthill–McKee ordering when the band is narrow (every chain of
//! elements; [`band`]), otherwise faer's sparse LU with the symbolic analysis (COLAMD ordering,
//! elimination structure) done once per model and the numeric factorization reusing its storage.

use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

pub mod band;

pub use band::{BandLu, BandOrder, DenseInverse};

/// Largest kl + ku (sub- plus super-diagonals in reverse Cuthill–McKee order) factorized in band
/// storage; a wider band goes to the general sparse LU. A chain of ANCF elements has
/// kl + ku ≈ 4 × a node's coordinates (16 planar, 24–36 spatial) whatever its length; a modal
/// body adds its coordinates to the band once. At 64 a band solve costs at most about
/// 128 multiply-adds per unknown, below the general LU's per-entry overhead at these sizes
/// (`cargo bench --bench engine -- lu`).
pub const BAND_MAX_WIDTH: usize = 64;

/// Systems of at most this many unknowns (coordinates and multipliers) are solved with the
/// explicit inverse ([`DenseInverse`]).
pub const INVERSE_MAX_DIM: usize = 48;

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

/// How the Newton matrix is factorized.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LuMethod {
    /// Band storage in reverse Cuthill–McKee order ([`BandLu`]).
    Band,
    /// faer's general sparse LU ([`SparseLu`]).
    General,
    /// [`BandLu`]'s factors turned into the explicit inverse ([`DenseInverse`]): the solve is
    /// one matrix-vector product.
    Inverse,
}

/// The Newton matrix's LU: [`BandLu`] when the reordered band is at most [`BAND_MAX_WIDTH`]
/// wide, [`SparseLu`] otherwise. Both solve the same system; their results differ by round-off.
#[derive(Debug)]
pub struct NewtonLu {
    pattern: SparsePattern,
    solver: Solver,
    factored: bool,
}

// one per model, built once and never moved in a step: the variants' sizes do not matter
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
enum Solver {
    Band(BandLu),
    General(SparseLu),
    Inverse(BandLu, DenseInverse),
}

impl NewtonLu {
    /// The LU for `pattern`, its method chosen by the band width.
    pub fn new(pattern: SparsePattern) -> Self {
        let order = BandOrder::reverse_cuthill_mckee(&pattern);

        let method = if pattern.dim() <= INVERSE_MAX_DIM {
            LuMethod::Inverse
        } else if order.kl + order.ku <= BAND_MAX_WIDTH {
            LuMethod::Band
        } else {
            LuMethod::General
        };
        Self::build(pattern, method, order)
    }

    /// The LU for `pattern` by `method` (tests and benchmarks compare the two).
    pub fn with_method(pattern: SparsePattern, method: LuMethod) -> Self {
        let order = BandOrder::reverse_cuthill_mckee(&pattern);
        Self::build(pattern, method, order)
    }

    fn build(pattern: SparsePattern, method: LuMethod, order: BandOrder) -> Self {
        let solver = match method {
            LuMethod::Band => Solver::Band(BandLu::new(&pattern, order)),
            LuMethod::General => Solver::General(SparseLu::new(pattern.clone())),
            LuMethod::Inverse => Solver::Inverse(
                BandLu::new(&pattern, order),
                DenseInverse::new(pattern.dim()),
            ),
        };
        Self {
            pattern,
            solver,
            factored: false,
        }
    }

    /// The method in use.
    pub fn method(&self) -> LuMethod {
        match self.solver {
            Solver::Band(_) => LuMethod::Band,
            Solver::General(_) => LuMethod::General,
            Solver::Inverse(..) => LuMethod::Inverse,
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
        match &mut self.solver {
            Solver::Band(b) => b.factorize(values)?,
            Solver::General(g) => g.factorize(values)?,
            Solver::Inverse(b, inv) => {
                b.factorize(values)?;
                inv.invert(b);
            }
        }
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
        match &mut self.solver {
            Solver::Band(b) => b.solve(rhs),
            Solver::General(g) => g.solve(rhs),
            Solver::Inverse(_, inv) => inv.solve(rhs),
        }
        rhs.iter().all(|v| v.is_finite())
    }
}

/// faer's sparse LU bound to one pattern.
pub struct SparseLu {
    pattern: SparsePattern,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    mem: MemBuffer,
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
        }
    }

    /// The pattern.
    pub fn pattern(&self) -> &SparsePattern {
        &self.pattern
    }

    /// Numeric factorization of the matrix with the given finite values (in pattern order).
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), SingularMatrix> {
        let p = &self.pattern;
        let sym = SymbolicSparseColMatRef::new_checked(p.n, p.n, &p.col_ptr, None, &p.row_idx);
        let a = SparseColMatRef::new(sym, values);
        let stack = MemStack::new(&mut self.mem);
        self.symbolic
            .factorize_numeric_lu(&mut self.numeric, a, Par::Seq, stack, Default::default())
            .map(|_| ())
            .map_err(|_| SingularMatrix)
    }

    /// Solves A x = b in place with the factors of the last successful [`Self::factorize`].
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let n = rhs.len();
        let stack = MemStack::new(&mut self.mem);
        let mat = MatMut::from_column_major_slice_mut(rhs, n, 1);
        lu.solve_in_place_with_conj(Conj::No, mat, Par::Seq, stack);
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
        lu.solve(&mut b);
        // x0 = 1, x1 = 1, x2 = 4 - 2 - 1 = 1
        for (x, want) in b.iter().zip([1.0, 1.0, 1.0]) {
            assert!((x - want).abs() < 1e-14);
        }
    }
}
