//! Numeric $LDL^\top$ of the quasi-definite KKT matrix on a reused [`Symbolic`] analysis,
//! with sign-aware dynamic regularization, and the triangular solves.
//!
//! Up-looking (Davis, "Algorithm 849: A concise sparse Cholesky factorization package",
//! 2005; as QDLDL): row $k$ of $L$ solves $L_{0:k,0:k}\thinspace y = A_{0:k,k}$ over the
//! row's nonzero columns $j$, $L_{kj} = y_j / d_j$, $d_k = a_{kk} - \sum_j L_{kj} y_j$. The
//! row's columns are the reach of column $k$'s entries up the elimination tree, found as the
//! row is factorized and taken in ascending $j$ (so that the rounding does not depend on the
//! walk's order); $L_{kj}$ goes to the next free position of column $j$.
//! The expected pivot sign $s_k$ is known (+ primal, − constraint row); a pivot with
//! $s_k d_k \le \epsilon$ is replaced by $s_k \delta$ and counted. The factor is then that of
//! $K + E$ with a small diagonal $E$, which iterative refinement against $K$ corrects.
//! Constraint rows that the ordering eliminates before any unknown they couple to have a
//! structurally zero pivot; they take $-\delta$ always (static regularization, as in
//! quasi-definite solvers) and are not counted, so the count still means a (numerically)
//! singular system.
//!
//! With a dual shift $\delta_d > 0$ ([`Ldlt::set_dual_shift`]) every constraint pivot is
//! shifted by $-\delta_d \sigma_k$ before its sign test: the factor is then that of the
//! quasi-definite $K - \delta_d \thinspace\mathrm{diag}(0, \Sigma)$ (Vanderbei 1995; as QDLDL
//! in OSQP), stable in any elimination order, which a Krylov refinement against $K$
//! corrects ([`crate::gmres`]). Structurally zero pivots then take $-\delta_d \sigma_k$.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::Real;
use folio_kernels::fused::mul_sub;

use crate::error::SolverError;
use crate::index::Index;
use crate::symbolic::{Arrays, Structure, Symbolic};

/// Outcome of one numeric factorization.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FactorOutcome {
    /// Factorized; `regularized` pivots were replaced by $s_k \delta$.
    Factored {
        /// Number of regularized pivots.
        regularized: usize,
        /// How many of them were primal: the primal block is not positive definite where
        /// it is eliminated (an indefinite Hessian, e.g. with the constraint Hessian on).
        regularized_primal: usize,
    },
    /// A pivot came out NaN or infinite (non-finite matrix values).
    NonFinite {
        /// The pivot's index in the new order.
        pivot: usize,
    },
}

/// Numeric factor values and workspace for one [`Symbolic`].
///
/// Owns $L$'s strictly lower values ([`Symbolic::nnz_l`]), the pivots $D$ ($n$), one dense
/// work vector ($n$), and the row-pattern workspace: the next free position of each column
/// and the current row's columns ($n$ 32-bit indices each) and a visited bit per column. All
/// of it is allocated by [`Ldlt::new`] at setup; factorizing and solving allocate nothing.
/// It remembers the analysis it was made for (its order and [`Symbolic::fingerprint`]) and
/// its entry points refuse any other with [`SolverError::SymbolicMismatch`].
#[derive(Clone, Debug)]
pub struct Ldlt<T> {
    /// Strictly lower values of $L$ (in the symbolic's layout).
    l: Vec<T>,
    /// The pivots $D$.
    d: Vec<T>,
    /// Dense work vector, zero between uses.
    work: Vec<T>,
    /// Next free position of each column of $L$ during a factorization.
    fill: Vec<u32>,
    /// The current row's nonzero columns.
    reach: Vec<u32>,
    /// One bit per column: visited by the current row's walk; zero between rows.
    seen: Vec<usize>,
    /// [`Symbolic::fingerprint`] of the analysis this factor belongs to.
    fingerprint: u64,
    /// Static shift $\delta_d$ of the constraint pivots, relative to their scale (module
    /// docs); 0 for none.
    dual_shift: T,
}

impl<T: Real> Ldlt<T> {
    /// Allocates the values and the workspace for `symbolic`.
    #[must_use]
    pub fn new(symbolic: &Symbolic) -> Self {
        let n = symbolic.n;
        Self {
            l: vec![T::ZERO; symbolic.nnz_l()],
            d: vec![T::ZERO; n],
            work: vec![T::ZERO; n],
            fill: vec![0; n],
            reach: vec![0; n],
            seen: vec![0; n.div_ceil(BITS)],
            fingerprint: symbolic.fingerprint,
            dual_shift: T::ZERO,
        }
    }

    /// Sets the static shift $\delta_d \ge 0$ of the constraint pivots (module docs): pivot
    /// $k$ with $s_k < 0$ becomes $d_k - \delta_d \sigma_k$, $\sigma_k$ its scale. 0 (the
    /// default) switches it off.
    pub fn set_dual_shift(&mut self, shift: T) {
        self.dual_shift = shift;
    }

    /// Strictly lower values of $L$, [`Symbolic::nnz_l`] entries in the symbolic's layout:
    /// column $j$ (new order) at [`Symbolic::l_col_ptr`]`[j]..[j + 1]`, rows in
    /// [`Symbolic::l_row_idx`]. Valid after a successful [`Ldlt::factor`].
    #[inline]
    #[must_use]
    pub fn l(&self) -> &[T] {
        &self.l
    }

    /// The pivots $D$, $n$ entries in the new order (after regularization). Valid after a
    /// successful [`Ldlt::factor`].
    #[inline]
    #[must_use]
    pub fn d(&self) -> &[T] {
        &self.d
    }

    /// `Ok` when this factor was made for `symbolic` (same order and fingerprint).
    ///
    /// # Errors
    /// [`SolverError::SymbolicMismatch`] otherwise.
    pub fn check(&self, symbolic: &Symbolic) -> Result<(), SolverError> {
        if symbolic.n == self.d.len()
            && symbolic.nnz_l() == self.l.len()
            && symbolic.fingerprint == self.fingerprint
        {
            Ok(())
        } else {
            Err(SolverError::SymbolicMismatch {
                factor_order: self.d.len(),
                symbolic_order: symbolic.n,
            })
        }
    }

    /// Factorizes the KKT values `kkt` (indexed by the pattern's slots, `nnz` of the
    /// pattern). Pivot $k$ (new order) with $s_k d_k \le$ `epsilon * scale[k]` becomes
    /// $s_k\thinspace $`delta * scale[k]`; `scale` has $n$ entries.
    ///
    /// # Errors
    /// [`SolverError::SymbolicMismatch`] when `symbolic` is not the analysis this factor was
    /// made for; nothing is written then.
    pub fn factor(
        &mut self,
        symbolic: &Symbolic,
        kkt: &[T],
        scale: &[T],
        epsilon: T,
        delta: T,
    ) -> Result<FactorOutcome, SolverError> {
        self.check(symbolic)?;
        Ok(self.factor_paired(symbolic, kkt, None, scale, (epsilon, delta)))
    }

    /// [`Ldlt::factor`] for a caller that holds this factor together with its own
    /// `symbolic` (a [`crate::Kkt`]) and so cannot mismatch them. With `scaling` ($D_s$,
    /// $n$ entries in the original order) it factorizes $D_s K D_s$: the entry of slot
    /// $(r, c)$, $r \le c$ in the original order, is taken as `scaling[r] * kkt * scaling[c]`.
    pub(crate) fn factor_paired(
        &mut self,
        symbolic: &Symbolic,
        kkt: &[T],
        scaling: Option<&[T]>,
        scale: &[T],
        limits: (T, T),
    ) -> FactorOutcome {
        let values = Values {
            kkt,
            scaling,
            perm: &symbolic.perm,
        };
        match &symbolic.structure {
            Structure::Narrow(a) => self.factor_rows(symbolic, a, values, scale, limits),
            Structure::Wide(a) => self.factor_rows(symbolic, a, values, scale, limits),
        }
    }

    /// The up-looking factorization (module docs) on `arrays`, `symbolic`'s index arrays.
    fn factor_rows<I: Index>(
        &mut self,
        symbolic: &Symbolic,
        arrays: &Arrays<I>,
        values: Values<'_, T>,
        scale: &[T],
        (epsilon, delta): (T, T),
    ) -> FactorOutcome {
        let s = symbolic;
        let (a_row, a_slot, l_row) = (&arrays.a_row, &arrays.a_slot, &arrays.l_row);
        let (y, l, d) = (&mut self.work[..], &mut self.l[..], &mut self.d[..]);
        let (fill, reach, seen) = (&mut self.fill[..], &mut self.reach[..], &mut self.seen[..]);
        fill.copy_from_slice(&s.l_ptr[..s.n]);
        let (mut regularized, mut regularized_primal) = (0, 0);
        for (k, &pivot_scale) in scale.iter().enumerate().take(s.n) {
            let mut diagonal = T::ZERO;
            let (mut count, mut low) = (0, k);
            for e in s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize {
                let i = a_row[e].get();
                let v = values.get(a_slot[e].get(), i, k);
                if i == k {
                    diagonal += v;
                    continue;
                }
                y[i] += v;
                low = low.min(i);
                // Up the elimination tree to the first visited column, or to k.
                let mut j = i;
                while j < k && seen[j / BITS] & (1 << (j % BITS)) == 0 {
                    seen[j / BITS] |= 1 << (j % BITS);
                    reach[count] = j as u32;
                    count += 1;
                    j = s.parent[j] as usize;
                }
            }
            let row = ascending(&mut reach[..count], seen, low, k);
            // Row k's columns j, ascending: L_kj = y_j / d_j, and y -= L_{:j} y_j.
            for &j in row.iter() {
                let j = j as usize;
                let pos = fill[j] as usize;
                fill[j] += 1;
                let yj = y[j];
                y[j] = T::ZERO;
                let start = s.l_ptr[j] as usize;
                for (&r, &lr) in l_row[start..pos].iter().zip(&l[start..pos]) {
                    y[r.get()] = mul_sub(y[r.get()], lr, yj);
                }
                let lkj = yj / d[j];
                diagonal = mul_sub(diagonal, lkj, yj);
                l[pos] = lkj;
            }
            if !diagonal.is_finite() {
                // Leave the work vectors clean for the next call.
                y.iter_mut().for_each(|v| *v = T::ZERO);
                seen.iter_mut().for_each(|w| *w = 0);
                return FactorOutcome::NonFinite { pivot: k };
            }
            let sign = if s.signs[k] > 0 { T::ONE } else { -T::ONE };
            let shifted = s.signs[k] < 0 && self.dual_shift > T::ZERO;
            if shifted {
                diagonal -= self.dual_shift * pivot_scale;
            }
            if s.structural_zero[k] && !shifted {
                diagonal = sign * delta * pivot_scale;
            } else if sign * diagonal <= epsilon * pivot_scale {
                diagonal = sign * delta * pivot_scale;
                regularized += 1;
                regularized_primal += usize::from(s.signs[k] > 0);
            }
            d[k] = diagonal;
        }
        FactorOutcome::Factored {
            regularized,
            regularized_primal,
        }
    }

    /// Solves $L D L^\top z = b$ in place in the new order (`x` holds $P b$ on entry, $n$
    /// entries).
    ///
    /// # Errors
    /// [`SolverError::SymbolicMismatch`] when `symbolic` is not this factor's analysis; `x`
    /// is left as it was.
    pub fn solve_permuted(&self, symbolic: &Symbolic, x: &mut [T]) -> Result<(), SolverError> {
        self.check(symbolic)?;
        self.solve_permuted_paired(symbolic, x);
        Ok(())
    }

    /// [`Ldlt::solve_permuted`] for a caller that holds the pair (see
    /// [`Ldlt::factor_paired`]).
    fn solve_permuted_paired(&self, symbolic: &Symbolic, x: &mut [T]) {
        match &symbolic.structure {
            Structure::Narrow(a) => self.solve_rows(&symbolic.l_ptr, &a.l_row, x),
            Structure::Wide(a) => self.solve_rows(&symbolic.l_ptr, &a.l_row, x),
        }
    }

    /// $x \leftarrow L^{-\top} D^{-1} L^{-1} x$ with $L$'s columns `l_ptr` / `l_row`.
    fn solve_rows<I: Index>(&self, l_ptr: &[u32], l_row: &[I], x: &mut [T]) {
        let n = l_ptr.len() - 1;
        for j in 0..n {
            let xj = x[j];
            let range = l_ptr[j] as usize..l_ptr[j + 1] as usize;
            for (&r, &l) in l_row[range.clone()].iter().zip(&self.l[range]) {
                x[r.get()] = mul_sub(x[r.get()], l, xj);
            }
        }
        for (xj, &dj) in x.iter_mut().zip(&self.d) {
            *xj /= dj;
        }
        for j in (0..n).rev() {
            let range = l_ptr[j] as usize..l_ptr[j + 1] as usize;
            let mut sum = x[j];
            for (&r, &l) in l_row[range.clone()].iter().zip(&self.l[range]) {
                sum = mul_sub(sum, l, x[r.get()]);
            }
            x[j] = sum;
        }
    }

    /// Solves $K z = b$: permutes `b` into `scratch`, solves, and writes `z` to `out` (all
    /// $n$ entries, in the original order).
    ///
    /// # Errors
    /// [`SolverError::SymbolicMismatch`] when `symbolic` is not this factor's analysis;
    /// nothing is written then.
    pub fn solve(
        &self,
        symbolic: &Symbolic,
        out: &mut [T],
        b: &[T],
        scratch: &mut [T],
    ) -> Result<(), SolverError> {
        self.check(symbolic)?;
        self.solve_paired(symbolic, out, b, scratch);
        Ok(())
    }

    /// [`Ldlt::solve`] for a caller that holds the pair (see [`Ldlt::factor_paired`]).
    pub(crate) fn solve_paired(
        &self,
        symbolic: &Symbolic,
        out: &mut [T],
        b: &[T],
        scratch: &mut [T],
    ) {
        for (new, &old) in symbolic.perm.iter().enumerate() {
            scratch[new] = b[old as usize];
        }
        self.solve_permuted_paired(symbolic, scratch);
        for (new, &old) in symbolic.perm.iter().enumerate() {
            out[old as usize] = scratch[new];
        }
    }
}

/// Bits per word of the visited-column set.
const BITS: usize = usize::BITS as usize;

/// The values the factorization reads: `kkt` by slot, scaled by `scaling` (original order)
/// if given; `perm` maps new indices to original ones.
#[derive(Clone, Copy)]
struct Values<'a, T> {
    kkt: &'a [T],
    scaling: Option<&'a [T]>,
    perm: &'a [u32],
}

impl<T: Real> Values<'_, T> {
    /// The entry in `slot`, at new row `i` and column `k`: $k_s$, or $d_r k_s d_c$ with
    /// $(r, c)$ its original row and column ($r \le c$) when scaled.
    #[inline]
    fn get(&self, slot: usize, i: usize, k: usize) -> T {
        match self.scaling {
            None => self.kkt[slot],
            Some(d) => {
                let (a, b) = (self.perm[i] as usize, self.perm[k] as usize);
                let (r, c) = if a <= b { (a, b) } else { (b, a) };
                d[r] * self.kkt[slot] * d[c]
            }
        }
    }
}

/// Sorts `row`, the columns a row's walk visited (their bits set in `seen`, all in
/// `low..k`), and clears their bits. Reads the bits in order when they are dense enough
/// (no more words than columns), else heap-sorts the list.
#[inline]
fn ascending<'a>(row: &'a mut [u32], seen: &mut [usize], low: usize, k: usize) -> &'a [u32] {
    if row.is_empty() {
        return row;
    }
    let words = low / BITS..(k - 1) / BITS + 1;
    if words.len() <= row.len() {
        let mut at = 0;
        for w in words {
            let mut bits = seen[w];
            seen[w] = 0;
            while bits != 0 {
                row[at] = (BITS * w) as u32 + bits.trailing_zeros();
                at += 1;
                bits &= bits - 1;
            }
        }
    } else {
        heapsort(row);
        for &j in row.iter() {
            seen[j as usize / BITS] = 0;
        }
    }
    row
}

/// Sorts `v` ascending in $O(m \log m)$ with no allocation and little code (the
/// microcontroller's flash): build a max-heap, then move its top to the end, $m$ times.
fn heapsort(v: &mut [u32]) {
    /// Moves `v[root]` down the max-heap `v[..end]`.
    fn sift_down(v: &mut [u32], mut root: usize, end: usize) {
        loop {
            let mut child = 2 * root + 1;
            if child >= end {
                return;
            }
            if child + 1 < end && v[child + 1] > v[child] {
                child += 1;
            }
            if v[root] >= v[child] {
                return;
            }
            v.swap(root, child);
            root = child;
        }
    }
    let m = v.len();
    for root in (0..m / 2).rev() {
        sift_down(v, root, m);
    }
    for end in (1..m).rev() {
        v.swap(0, end);
        sift_down(v, 0, end);
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::{BITS, FactorOutcome, Ldlt, ascending, heapsort};
    use crate::chain::{Chain, dense, kkt_values};
    use crate::error::SolverError;
    use crate::ordering::Ordering;
    use crate::pattern::KktPattern;
    use crate::symbolic::{IndexWidth, Structure, Symbolic};

    /// A pattern from its upper columns (no term maps).
    fn upper(dofs: usize, rows: usize, col_ptr: &[u32], row_idx: &[u32]) -> KktPattern {
        KktPattern {
            dofs,
            rows,
            col_ptr: col_ptr.to_vec(),
            row_idx: row_idx.to_vec(),
            ..KktPattern::default()
        }
    }

    /// Analyses `pattern` in the natural order and factorizes `values` (unit scales, no
    /// regularization expected).
    fn factor(pattern: &KktPattern, values: &[f64]) -> (Symbolic, Ldlt<f64>) {
        let symbolic = Symbolic::analyse(pattern, Ordering::Natural);
        let mut ldlt = Ldlt::new(&symbolic);
        let scale = vec![1.0; pattern.order()];
        let outcome = ldlt.factor(&symbolic, values, &scale, 1e-12, 1e-8);
        assert_eq!(
            outcome,
            Ok(FactorOutcome::Factored {
                regularized: 0,
                regularized_primal: 0
            })
        );
        (symbolic, ldlt)
    }

    /// $K z = b$ through [`Ldlt::solve`].
    fn solve(symbolic: &Symbolic, ldlt: &Ldlt<f64>, b: &[f64]) -> Vec<f64> {
        let (mut z, mut scratch) = (vec![0.0; b.len()], vec![0.0; b.len()]);
        ldlt.solve(symbolic, &mut z, b, &mut scratch).unwrap();
        z
    }

    /// $K = [[4, 2], [2, 0]]$: $L_{10} = 1/2$, $D = (4, -1)$, and $K (1/2, 0) = (2, 1)$.
    #[test]
    fn two_by_two_kkt() {
        let pattern = upper(1, 1, &[0, 1, 3], &[0, 0, 1]);
        let (symbolic, ldlt) = factor(&pattern, &[4.0, 2.0, 0.0]);
        assert_eq!(symbolic.l_col_ptr(), &[0, 1, 1]);
        assert_eq!(symbolic.l_row_idx().to_u32(), [1]);
        assert_eq!(ldlt.l(), &[0.5]);
        assert_eq!(ldlt.d(), &[4.0, -1.0]);
        assert_eq!(solve(&symbolic, &ldlt, &[2.0, 1.0]), [0.5, 0.0]);
    }

    /// With a dual shift of 1/2 the constraint pivot of $[[4, 2], [2, 0]]$ is
    /// $-1 - 1/2$, the factor that of $[[4, 2], [2, -1/2]]$; the zero constraint pivot of
    /// $[[4, 0], [0, 0]]$ becomes $-1/2$, not a regularized (and counted) $-\delta$.
    #[test]
    fn dual_shift_makes_the_factor_quasi_definite() {
        let pattern = upper(1, 1, &[0, 1, 3], &[0, 0, 1]);
        let symbolic = Symbolic::analyse(&pattern, Ordering::Natural);
        let mut ldlt = Ldlt::new(&symbolic);
        ldlt.set_dual_shift(0.5);
        let outcome = ldlt.factor(&symbolic, &[4.0, 2.0, 0.0], &[1.0, 1.0], 1e-12, 1e-8);
        let clean = FactorOutcome::Factored {
            regularized: 0,
            regularized_primal: 0,
        };
        assert_eq!(outcome, Ok(clean));
        assert_eq!(ldlt.d(), &[4.0, -1.5]);
        let outcome = ldlt.factor(&symbolic, &[4.0, 0.0, 0.0], &[1.0, 1.0], 1e-12, 1e-8);
        assert_eq!(outcome, Ok(clean));
        assert_eq!(ldlt.d(), &[4.0, -0.5]);
        ldlt.set_dual_shift(0.0);
        ldlt.factor(&symbolic, &[4.0, 2.0, 0.0], &[1.0, 1.0], 1e-12, 1e-8)
            .unwrap();
        assert_eq!(ldlt.d(), &[4.0, -1.0]);
    }

    /// $H = \mathrm{diag}(2, 4)$, $J = (1, 1)$: $L_{20} = 1/2$, $L_{21} = 1/4$,
    /// $D = (2, 4, -3/4)$ (the Schur complement $-J H^{-1} J^\top$), and
    /// $K (1, -1, 2) = (4, -2, 0)$.
    #[test]
    fn three_by_three_kkt() {
        let pattern = upper(2, 1, &[0, 1, 2, 5], &[0, 1, 0, 1, 2]);
        let (symbolic, ldlt) = factor(&pattern, &[2.0, 4.0, 1.0, 1.0, 0.0]);
        assert_eq!(symbolic.perm(), &[0, 1, 2]);
        assert_eq!(symbolic.signs(), &[1, 1, -1]);
        assert_eq!(symbolic.etree(), &[2, 2, crate::pattern::NONE]);
        assert_eq!(symbolic.l_col_ptr(), &[0, 1, 2, 2]);
        assert_eq!(symbolic.l_row_idx().to_u32(), [2, 2]);
        assert_eq!(ldlt.l(), &[0.5, 0.25]);
        assert_eq!(ldlt.d(), &[2.0, 4.0, -0.75]);
        assert_eq!(solve(&symbolic, &ldlt, &[4.0, -2.0, 0.0]), [1.0, -1.0, 2.0]);
    }

    /// $L D L^\top = P K P^\top$ on the chain's KKT for the orders that leave no structural
    /// zero, read through the accessors.
    #[test]
    fn factor_reproduces_permuted_matrix() {
        let pattern = Chain::new(7).pattern(false);
        let values = kkt_values(&pattern);
        let k = dense(&pattern, &values);
        let n = pattern.order();
        for ordering in [Ordering::Natural, Ordering::AmdDelayedDuals] {
            let symbolic = Symbolic::analyse(&pattern, ordering);
            let mut ldlt = Ldlt::new(&symbolic);
            let outcome = ldlt.factor(&symbolic, &values, &vec![1.0; n], 1e-12, 1e-8);
            assert!(matches!(
                outcome,
                Ok(FactorOutcome::Factored { regularized: 0, .. })
            ));
            assert!(!symbolic.structural_zero().contains(&true));
            // Dense unit lower L from the column storage.
            let mut l = vec![vec![0.0; n]; n];
            for (j, row) in l.iter_mut().enumerate() {
                row[j] = 1.0;
            }
            let ptr = symbolic.l_col_ptr();
            for j in 0..n {
                for at in ptr[j] as usize..ptr[j + 1] as usize {
                    l[symbolic.l_row_idx().get(at)][j] = ldlt.l()[at];
                }
            }
            let perm = symbolic.perm();
            for r in 0..n {
                for c in 0..n {
                    let ldl: f64 = (0..n).map(|j| l[r][j] * ldlt.d()[j] * l[c][j]).sum();
                    let want = k[perm[r] as usize][perm[c] as usize];
                    assert!((ldl - want).abs() <= 1e-13, "{ordering:?} ({r}, {c})");
                }
            }
        }
    }

    /// The 16-bit and the 32-bit layouts of one analysis factorize and solve bit for bit
    /// alike, and have the same fingerprint.
    #[test]
    fn index_widths_agree() {
        let pattern = Chain::new(9).pattern(true);
        let values = kkt_values(&pattern);
        let n = pattern.order();
        let narrow = Symbolic::analyse(&pattern, Ordering::AmdDelayedDuals);
        assert_eq!(narrow.indices().0, IndexWidth::U16);
        let (perm, signs) = (narrow.perm().to_vec(), narrow.signs().to_vec());
        let wide = Symbolic::build::<u32>(&pattern, perm, signs, Structure::Wide);
        assert_eq!(wide.indices(), (IndexWidth::U32, 2 * narrow.indices().1));
        assert_eq!(wide.fingerprint(), narrow.fingerprint());
        assert_eq!(wide.l_row_idx().to_u32(), narrow.l_row_idx().to_u32());
        let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut results = Vec::new();
        for symbolic in [&narrow, &wide] {
            let mut ldlt = Ldlt::new(symbolic);
            let outcome = ldlt.factor(symbolic, &values, &vec![1.0; n], 1e-12, 1e-8);
            assert!(matches!(outcome, Ok(FactorOutcome::Factored { .. })));
            let z = solve(symbolic, &ldlt, &b);
            results.push((bits(ldlt.l()), bits(ldlt.d()), bits(&z)));
        }
        assert_eq!(results[0], results[1]);
    }

    /// A row's visited columns come out ascending with their bits cleared, whether read
    /// from the bits (dense) or heap-sorted (sparse: fewer columns than words).
    #[test]
    fn rows_come_out_ascending() {
        let n = 40 * BITS;
        let (dense, sparse) = (
            &[5u32, 3, 9, 4, 8][..],
            &[1000, 7, 555, 1200, 9, 1100, 3][..],
        );
        for (columns, k) in [(dense, 10), (sparse, n - 1)] {
            let mut seen = vec![0usize; n / BITS];
            for &j in columns {
                seen[j as usize / BITS] |= 1 << (j as usize % BITS);
            }
            let low = *columns.iter().min().unwrap() as usize;
            let mut row = columns.to_vec();
            let mut want = columns.to_vec();
            want.sort_unstable();
            assert_eq!(ascending(&mut row, &mut seen, low, k), want);
            assert!(seen.iter().all(|&w| w == 0));
        }
        for m in 0..40u32 {
            let mut v: Vec<u32> = (0..m).map(|i| (i * 7919) % 61).collect();
            let mut want = v.clone();
            want.sort_unstable();
            heapsort(&mut v);
            assert_eq!(v, want);
        }
    }

    /// A factor made for one analysis refuses another of the same order and the same
    /// number of factor entries, and writes nothing.
    #[test]
    fn refuses_another_symbolic() {
        // H with a coupling (0, 1) and J = (0, 1), against H diagonal and J = (1, 1).
        let coupled = upper(2, 1, &[0, 1, 3, 5], &[0, 0, 1, 1, 2]);
        let separate = upper(2, 1, &[0, 1, 2, 5], &[0, 1, 0, 1, 2]);
        let values = [2.0, 4.0, 1.0, 1.0, 0.0];
        let (ours, mut ldlt) = factor(&separate, &values);
        let theirs = Symbolic::analyse(&coupled, Ordering::Natural);
        assert_eq!(
            (theirs.order(), theirs.nnz_l()),
            (ours.order(), ours.nnz_l())
        );
        let mismatch = SolverError::SymbolicMismatch {
            factor_order: 3,
            symbolic_order: 3,
        };
        let before = ldlt.clone();
        let outcome = ldlt.factor(&theirs, &values, &[1.0; 3], 1e-12, 1e-8);
        assert_eq!(outcome, Err(mismatch));
        assert_eq!((ldlt.l(), ldlt.d()), (before.l(), before.d()));
        let mut x = [1.0, 2.0, 3.0];
        assert_eq!(ldlt.solve_permuted(&theirs, &mut x), Err(mismatch));
        assert_eq!(x, [1.0, 2.0, 3.0]);
        let (mut out, mut scratch) = ([0.0; 3], [0.0; 3]);
        assert_eq!(
            ldlt.solve(&theirs, &mut out, &x, &mut scratch),
            Err(mismatch)
        );
        assert_eq!(out, [0.0; 3]);
        // Its own analysis, or a fresh analysis of the same pattern, is accepted.
        assert_eq!(ldlt.check(&ours), Ok(()));
        assert_eq!(
            ldlt.check(&Symbolic::analyse(&separate, Ordering::Natural)),
            Ok(())
        );
    }
}
