//! Banded LU with partial pivoting for the Newton matrix of a chain, in a bandwidth-reducing
//! order (reverse Cuthill–McKee).
//!
//! A beam is a chain: a node's coordinates couple only to its neighbours' and to a few joint
//! rows, so in a reverse Cuthill–McKee order the Newton matrix (multiplier rows included) is
//! banded with kl, ku of about two nodes' coordinates, independent of the number of elements.
//! Gaussian elimination with row interchanges inside the band (LAPACK's `dgbtf2`/`dgbtrs`,
//! Golub & Van Loan, *Matrix Computations*, 4th ed., §4.3.5) keeps the fill inside
//! kl + ku superdiagonals; the solve then costs about n·(2kl + ku) multiply-adds and touches
//! contiguous columns, where a general sparse LU walks index lists (`docs/performance.md`).
//!
//! Written here rather than taken from a library: the LAPACK routines would need a system LAPACK
//! in the win64 cross build, and no maintained pure-Rust crate has a pivoting banded LU;
//! the ordering is the textbook algorithm (George & Liu, *Computer Solution of Large Sparse
//! Positive Definite Systems*, 1981, §4.3), about forty lines.

use super::{SingularMatrix, SparsePattern};

/// Symmetric permutation of a pattern and the band it leaves.
#[derive(Debug, Clone, PartialEq)]
pub struct BandOrder {
    /// `perm[new] = old`.
    pub perm: Vec<usize>,
    /// Sub-diagonals kl of the permuted matrix.
    pub kl: usize,
    /// Super-diagonals ku of the permuted matrix (before pivoting).
    pub ku: usize,
}

impl BandOrder {
    /// Reverse Cuthill–McKee order of the symmetrized pattern (A + Aᵀ), started in each
    /// connected component from a pseudo-peripheral vertex, and the resulting band.
    pub fn reverse_cuthill_mckee(p: &SparsePattern) -> Self {
        let n = p.dim();
        let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n];
        for c in 0..n {
            for r in p.column(c) {
                if r != c {
                    adj[r].push(c);
                    adj[c].push(r);
                }
            }
        }
        for a in &mut adj {
            a.sort_unstable();
            a.dedup();
        }
        let mut order = Vec::with_capacity(n);
        let mut placed = vec![false; n];
        while order.len() < n {
            // lowest-degree unplaced vertex, then a pseudo-peripheral vertex of its component
            let seed = (0..n)
                .filter(|&v| !placed[v])
                .min_by_key(|&v| (adj[v].len(), v))
                .expect("an unplaced vertex remains");
            let start = pseudo_peripheral(&adj, &placed, seed);
            let first = order.len();
            order.push(start);
            placed[start] = true;
            let mut head = first;
            while head < order.len() {
                let v = order[head];
                head += 1;
                let mut next: Vec<usize> = adj[v].iter().copied().filter(|&w| !placed[w]).collect();
                next.sort_unstable_by_key(|&w| (adj[w].len(), w));
                for w in next {
                    placed[w] = true;
                    order.push(w);
                }
            }
        }
        order.reverse();
        Self::of(p, order)
    }

    /// The band of `p` in the order `perm` (`perm[new] = old`).
    pub fn of(p: &SparsePattern, perm: Vec<usize>) -> Self {
        let n = p.dim();
        let inv = inverse(&perm);
        let (mut kl, mut ku) = (0, 0);
        for c in 0..n {
            for r in p.column(c) {
                let (i, j) = (inv[r], inv[c]);
                kl = kl.max(i.saturating_sub(j));
                ku = ku.max(j.saturating_sub(i));
            }
        }
        Self { perm, kl, ku }
    }
}

/// The inverse of a permutation: `inverse(perm)[old] = new` for `perm[new] = old`.
fn inverse(perm: &[usize]) -> Vec<usize> {
    let mut inv = vec![0usize; perm.len()];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    inv
}

/// The end of a breadth-first search from `v` that goes deepest, repeated while that deepens
/// the level structure (Gibbs–Poole–Stockmeyer's pseudo-peripheral vertex, simplified).
fn pseudo_peripheral(adj: &[Vec<usize>], placed: &[bool], mut v: usize) -> usize {
    let mut depth = 0;
    let mut level = vec![usize::MAX; adj.len()];
    loop {
        level.iter_mut().for_each(|l| *l = usize::MAX);
        level[v] = 0;
        let mut queue = vec![v];
        let mut head = 0;
        while head < queue.len() {
            let u = queue[head];
            head += 1;
            for &w in &adj[u] {
                if !placed[w] && level[w] == usize::MAX {
                    level[w] = level[u] + 1;
                    queue.push(w);
                }
            }
        }
        let last = level[*queue.last().expect("v is queued")];
        if last <= depth {
            return v;
        }
        depth = last;
        // the lowest-degree vertex of the last level
        v = queue
            .iter()
            .copied()
            .filter(|&w| level[w] == last)
            .min_by_key(|&w| (adj[w].len(), w))
            .expect("the last level is not empty");
    }
}

/// LU factors of a banded matrix with row interchanges, in LAPACK band storage: column j holds
/// rows j − kl − ku ..= j + kl at offsets 0 ..= 2kl + ku (U with kl + ku superdiagonals, the
/// multipliers of L below the diagonal).
#[derive(Debug, Clone)]
pub struct BandLu {
    n: usize,
    kl: usize,
    ku: usize,
    /// Column stride 2kl + ku + 1.
    ld: usize,
    ab: Vec<f64>,
    /// Row interchanged with row j at step j.
    ipiv: Vec<usize>,
    /// `perm[new] = old`.
    perm: Vec<usize>,
    /// Band position of each pattern slot.
    pos: Vec<usize>,
    /// Permuted right-hand side.
    work: Vec<f64>,
    /// 1 / U(j, j).
    inv_diag: Vec<f64>,
    /// Rows j + 1 ..= j + l_len[j] hold column j's nonzero multipliers (the rest are zero).
    l_len: Vec<usize>,
    /// Column j of U is zero above row u_top[j].
    u_top: Vec<usize>,
}

impl BandLu {
    /// Storage for `p` in the order and band `order`.
    pub fn new(p: &SparsePattern, order: BandOrder) -> Self {
        let n = p.dim();
        let BandOrder { perm, kl, ku } = order;
        let ld = 2 * kl + ku + 1;
        let inv = inverse(&perm);
        let mut pos = Vec::with_capacity(p.nnz());
        for c in 0..n {
            for r in p.column(c) {
                let (i, j) = (inv[r], inv[c]);
                pos.push(j * ld + kl + ku + i - j);
            }
        }
        Self {
            n,
            kl,
            ku,
            ld,
            ab: vec![0.0; ld * n],
            ipiv: vec![0; n],
            perm,
            pos,
            work: vec![0.0; n],
            inv_diag: vec![0.0; n],
            l_len: vec![0; n],
            u_top: vec![0; n],
        }
    }

    /// Sub- and super-diagonals (kl, ku) of the permuted matrix.
    pub fn band(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }

    /// Factorizes the matrix with `values` in pattern order (`dgbtf2`: pivot = the largest
    /// magnitude in the column below the diagonal; the first of equals).
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), SingularMatrix> {
        let (n, kl, ld) = (self.n, self.kl, self.ld);
        let kv = self.kl + self.ku;
        self.ab.iter_mut().for_each(|x| *x = 0.0);
        for (&p, &v) in self.pos.iter().zip(values) {
            self.ab[p] = v;
        }
        let mut ju = 0usize;
        for j in 0..n {
            let km = kl.min(n - 1 - j);
            let col = j * ld + kv;
            let mut jp = 0;
            let mut big = self.ab[col].abs();
            for i in 1..=km {
                let a = self.ab[col + i].abs();
                if a > big {
                    big = a;
                    jp = i;
                }
            }
            self.ipiv[j] = j + jp;
            if big == 0.0 || !big.is_finite() {
                return Err(SingularMatrix);
            }
            ju = ju.max((j + self.ku + jp).min(n - 1));
            if jp != 0 {
                // swap rows j and j + jp in columns j ..= ju
                for c in j..=ju {
                    let base = c * ld + kv;
                    self.ab.swap(base + j - c, base + j + jp - c);
                }
            }
            let piv = self.ab[col];
            for x in &mut self.ab[col + 1..=col + km] {
                *x /= piv;
            }
            // columns j + 1 ..= ju: U(j, c) times the multipliers off rows j + 1 ..= j + km
            let (left, right) = self.ab.split_at_mut((j + 1) * ld);
            let mult = &left[col + 1..=col + km];
            for (k, column) in right.chunks_exact_mut(ld).take(ju - j).enumerate() {
                let at = kv - (k + 1); // row j in column j + 1 + k
                let f = column[at];
                if f != 0.0 {
                    for (x, &l) in column[at + 1..=at + km].iter_mut().zip(mult) {
                        *x -= l * f;
                    }
                }
            }
        }
        // the nonzero profile inside the band, so that the solves skip the band's zeros
        for j in 0..n {
            let column = &self.ab[j * ld..(j + 1) * ld];
            let below = &column[kv + 1..=kv + kl.min(n - 1 - j)];
            self.l_len[j] = below.iter().rposition(|&x| x != 0.0).map_or(0, |i| i + 1);
            let lo = j.saturating_sub(kv);
            let above = &column[kv - (j - lo)..kv];
            self.u_top[j] = lo + above.iter().position(|&x| x != 0.0).unwrap_or(j - lo);
            self.inv_diag[j] = 1.0 / column[kv];
        }
        Ok(())
    }

    /// Solves A x = b in place (b in the pattern's order).
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let (n, ld) = (self.n, self.ld);
        let kv = self.kl + self.ku;
        let b = &mut self.work;
        for (bi, &old) in b.iter_mut().zip(&self.perm) {
            *bi = rhs[old];
        }
        // slices and zips, not indices: the loops then have no bounds checks and vectorize
        // (element-wise, so the sums are those of the scalar loop, bit for bit)
        for j in 0..n {
            let l = self.ipiv[j];
            if l != j {
                b.swap(l, j);
            }
            let m = self.l_len[j];
            let (head, tail) = b.split_at_mut(j + 1);
            let bj = head[j];
            if bj != 0.0 && m > 0 {
                let col = j * ld + kv;
                for (x, &lij) in tail[..m].iter_mut().zip(&self.ab[col + 1..=col + m]) {
                    *x -= lij * bj;
                }
            }
        }
        for j in (0..n).rev() {
            let col = j * ld + kv;
            let (head, tail) = b.split_at_mut(j);
            tail[0] *= self.inv_diag[j];
            let bj = tail[0];
            if bj != 0.0 {
                let lo = self.u_top[j];
                for (x, &uij) in head[lo..].iter_mut().zip(&self.ab[col - (j - lo)..col]) {
                    *x -= uij * bj;
                }
            }
        }
        for (&bi, &old) in b.iter().zip(&self.perm) {
            rhs[old] = bi;
        }
    }
}

/// The inverse of a small Newton matrix, from its band factors, kept as a dense matrix so that a
/// held-matrix solve is one matrix-vector product.
///
/// A band solve is two triangular sweeps whose every column waits for the previous one (and,
/// with columns a few entries long, for the store of the previous update to reach the next
/// load); a product with the inverse has no such chain. For the planar 8-element rod (35
/// unknowns) it is the cheaper solve at every modified-Newton iteration (`docs/performance.md`);
/// its cost grows as n², so it is kept only up to [`super::INVERSE_MAX_DIM`] unknowns. The
/// product's error is about κ(A)·ε·|x|, against the LU solve's backward-stable one: a Newton
/// iteration, which corrects any solve error it contracts, does not notice.
#[derive(Debug, Clone)]
pub struct DenseInverse {
    n: usize,
    /// A⁻¹ in the pattern's (original) order, column-major: `inv[j * n + i]` = (A⁻¹)ᵢⱼ.
    inv: Vec<f64>,
    /// The permuted system's inverse, row-major (scratch of [`Self::invert`]).
    rows: Vec<f64>,
    /// Scratch for the product.
    work: Vec<f64>,
}

impl DenseInverse {
    /// Storage for an n × n inverse.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            inv: vec![0.0; n * n],
            rows: vec![0.0; n * n],
            work: vec![0.0; n],
        }
    }

    /// A⁻¹ from the factors of `lu` (`dgbtrs` with the identity as n right-hand sides, all
    /// swept together: each row operation is a vector operation across the n columns).
    pub fn invert(&mut self, lu: &BandLu) {
        let n = self.n;
        debug_assert_eq!(lu.n, n);
        let (ld, kv) = (lu.ld, lu.kl + lu.ku);
        // x: row-major n × n (row r of the permuted system across the n right-hand sides)
        let x = &mut self.rows;
        x.iter_mut().for_each(|v| *v = 0.0);
        for r in 0..n {
            x[r * n + r] = 1.0;
        }
        for j in 0..n {
            let l = lu.ipiv[j];
            if l != j {
                let (a, b) = x.split_at_mut(l * n);
                a[j * n..(j + 1) * n].swap_with_slice(&mut b[..n]);
            }
            let (head, tail) = x.split_at_mut((j + 1) * n);
            let xj = &head[j * n..];
            let col = j * ld + kv;
            for (row, &lij) in tail
                .chunks_exact_mut(n)
                .zip(&lu.ab[col + 1..=col + lu.l_len[j]])
            {
                for (v, &w) in row.iter_mut().zip(xj) {
                    *v -= lij * w;
                }
            }
        }
        for j in (0..n).rev() {
            let (head, tail) = x.split_at_mut(j * n);
            let xj = &mut tail[..n];
            let d = lu.inv_diag[j];
            xj.iter_mut().for_each(|v| *v *= d);
            let lo = lu.u_top[j];
            let col = j * ld + kv;
            for (row, &uij) in head[lo * n..]
                .chunks_exact_mut(n)
                .zip(&lu.ab[col - (j - lo)..col])
            {
                for (v, &w) in row.iter_mut().zip(&*xj) {
                    *v -= uij * w;
                }
            }
        }
        // x = P A⁻¹ Pᵀ with rows in the new order and columns the permuted unit vectors:
        // (A⁻¹)(perm[r], perm[c]) = x[r][c]; stored column-major in the original order
        for (r, row) in x.chunks_exact(n).enumerate() {
            for (&v, &pc) in row.iter().zip(&lu.perm) {
                self.inv[pc * n + lu.perm[r]] = v;
            }
        }
    }

    /// x = A⁻¹ b in place (b in the pattern's order): the columns of A⁻¹ are added four at a
    /// time, yᵢ += (aᵢⱼbⱼ + aᵢⱼ₊₁bⱼ₊₁) + (aᵢⱼ₊₂bⱼ₊₂ + aᵢⱼ₊₃bⱼ₊₃), then the remaining ones
    /// (a fixed order: the same bits on every machine).
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let n = self.n;
        let y = &mut self.work;
        y.iter_mut().for_each(|v| *v = 0.0);
        let mut cols = self.inv.chunks_exact(4 * n);
        let mut b = rhs.chunks_exact(4);
        for (c, b) in (&mut cols).zip(&mut b) {
            let (c0, rest) = c.split_at(n);
            let (c1, rest) = rest.split_at(n);
            let (c2, c3) = rest.split_at(n);
            let (b0, b1, b2, b3) = (b[0], b[1], b[2], b[3]);
            let (c0, c1, c2, c3, y) = (&c0[..n], &c1[..n], &c2[..n], &c3[..n], &mut y[..n]);
            for i in 0..n {
                y[i] += (c0[i] * b0 + c1[i] * b1) + (c2[i] * b2 + c3[i] * b3);
            }
        }
        for (col, &bj) in cols.remainder().chunks_exact(n).zip(b.remainder()) {
            for (v, &a) in y.iter_mut().zip(col) {
                *v += a * bj;
            }
        }
        rhs.copy_from_slice(y);
    }
}

#[cfg(test)]
mod tests {
    use super::super::{LuMethod, NewtonLu, SparsePattern};
    use super::*;

    /// Deterministic pseudo-random numbers in (−1, 1) (a linear congruential generator).
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    /// A chain's saddle-point matrix: `nodes` blocks of `b` coordinates coupled to their
    /// neighbours, a diagonal that dominates, and `c` constraint rows per joint between
    /// consecutive nodes (zero diagonal), numbered after all coordinates as the model does.
    fn chain(nodes: usize, b: usize, c: usize, seed: u64) -> (SparsePattern, Vec<f64>) {
        let n = nodes * b;
        let m = (nodes - 1) * c;
        let mut r = rng(seed);
        let mut entries = Vec::new();
        let mut vals = Vec::new();
        for k in 0..nodes {
            for other in [k.saturating_sub(1), k, (k + 1).min(nodes - 1)] {
                for i in 0..b {
                    for j in 0..b {
                        let (row, col) = (k * b + i, other * b + j);
                        let diag = if row == col { 8.0 } else { 0.0 };
                        entries.push((row, col));
                        vals.push(diag + r());
                    }
                }
            }
        }
        for joint in 0..nodes - 1 {
            for i in 0..c {
                let row = n + joint * c + i;
                for col in joint * b..(joint + 2) * b {
                    let v = r();
                    entries.push((row, col));
                    vals.push(v);
                    entries.push((col, row));
                    vals.push(v);
                }
            }
        }
        let p = SparsePattern::new(n + m, entries.clone());
        let mut values = vec![0.0; p.nnz()];
        for (&(row, col), v) in entries.iter().zip(vals) {
            values[p.slot(row, col) as usize] += v;
        }
        (p, values)
    }

    fn multiply(p: &SparsePattern, values: &[f64], x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; p.dim()];
        let mut k = 0;
        for c in 0..p.dim() {
            for r in p.column(c) {
                y[r] += values[k] * x[c];
                k += 1;
            }
        }
        y
    }

    #[test]
    fn reverse_cuthill_mckee_makes_a_chain_narrow() {
        // constraint rows numbered last give a band as wide as the matrix; the ordering
        // brings it to a few blocks, independent of the chain's length
        for nodes in [4, 40, 400] {
            let (p, _) = chain(nodes, 6, 3, 1);
            let natural = BandOrder::of(&p, (0..p.dim()).collect());
            let rcm = BandOrder::reverse_cuthill_mckee(&p);
            assert!(natural.kl + natural.ku >= p.dim() / 2);
            assert!(
                rcm.kl + rcm.ku <= 6 * 6,
                "{nodes} nodes: {} + {}",
                rcm.kl,
                rcm.ku
            );
            let mut sorted = rcm.perm.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..p.dim()).collect::<Vec<_>>());
        }
    }

    #[test]
    fn band_general_and_inverse_solve_saddle_point_chains_alike() {
        for (nodes, b, c, seed) in [(2, 4, 2, 3), (9, 4, 2, 5), (17, 6, 3, 7), (60, 9, 3, 11)] {
            let (p, values) = chain(nodes, b, c, seed);
            let mut r = rng(seed + 100);
            let x: Vec<f64> = (0..p.dim()).map(|_| r()).collect();
            let rhs = multiply(&p, &values, &x);
            let mut sols = Vec::new();
            for method in [LuMethod::Band, LuMethod::General, LuMethod::Inverse] {
                let mut lu = NewtonLu::with_method(p.clone(), method);
                assert_eq!(lu.method(), method);
                lu.factorize(&values).unwrap();
                let mut y = rhs.clone();
                assert!(lu.solve(&mut y));
                // twice with the same factors: the held factorization is not consumed
                let mut y2 = rhs.clone();
                assert!(lu.solve(&mut y2));
                assert_eq!(y, y2);
                let err = y
                    .iter()
                    .zip(&x)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(err < 1e-12, "{method:?} {nodes}x{b}: {err:e}");
                sols.push(y);
            }
        }
    }

    #[test]
    fn pivoting_handles_zero_diagonals_and_singular_matrices_are_refused() {
        // the constraint rows' zero diagonal needs row interchanges
        let (p, values) = chain(5, 4, 4, 13);
        let mut lu = NewtonLu::with_method(p.clone(), LuMethod::Band);
        lu.factorize(&values).unwrap();
        let x: Vec<f64> = (0..p.dim()).map(|i| i as f64).collect();
        let mut y = multiply(&p, &values, &x);
        assert!(lu.solve(&mut y));
        let err = y
            .iter()
            .zip(&x)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-11, "{err:e}");
        // a zero column is singular; a non-finite value too
        let mut zero_col = values.clone();
        let mut k = 0;
        for col in 0..p.dim() {
            for _ in p.column(col) {
                if col == 3 {
                    zero_col[k] = 0.0;
                }
                k += 1;
            }
        }
        assert!(lu.factorize(&zero_col).is_err());
        assert!(!lu.is_factored());
        let mut nan = values;
        nan[0] = f64::NAN;
        assert!(lu.factorize(&nan).is_err());
    }
}
