//! Numeric $LDL^\top$ of the quasi-definite KKT matrix on a reused [`Symbolic`] analysis,
//! with sign-aware dynamic regularization, and the triangular solves.
//!
//! Up-looking: row $k$ of $L$ solves $L_{0:k,0:k}\, y = A_{0:k,k}$ over the row's
//! precomputed nonzero columns, $L_{kj} = y_j / d_j$, $d_k = a_{kk} - \sum_j L_{kj} y_j$.
//! The expected pivot sign $s_k$ is known (+ primal, − constraint row); a pivot with
//! $s_k d_k \le \epsilon$ is replaced by $s_k \delta$ and counted. The factor is then that of
//! $K + E$ with a small diagonal $E$, which iterative refinement against $K$ corrects.
//! Constraint rows that the ordering eliminates before any unknown they couple to have a
//! structurally zero pivot; they take $-\delta$ always (static regularization, as in
//! quasi-definite solvers) and are not counted, so the count still means a (numerically)
//! singular system.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::Real;

use crate::symbolic::Symbolic;

/// Outcome of one numeric factorization.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

/// Numeric factor values and workspace for one [`Symbolic`] (sizes fixed at creation).
#[derive(Clone, Debug)]
pub struct Ldlt<T> {
    /// Strictly lower values of $L$ (in the symbolic's layout).
    pub l: Vec<T>,
    /// The pivots $D$.
    pub d: Vec<T>,
    /// Dense work vector, zero between uses.
    work: Vec<T>,
}

impl<T: Real> Ldlt<T> {
    /// Allocates the values for `symbolic`.
    #[must_use]
    pub fn new(symbolic: &Symbolic) -> Self {
        Self {
            l: vec![T::ZERO; symbolic.nnz_l()],
            d: vec![T::ZERO; symbolic.n],
            work: vec![T::ZERO; symbolic.n],
        }
    }

    /// Factorizes the KKT values `kkt` (indexed by the pattern's slots). Pivot $k$ (new
    /// order) with $s_k d_k \le$ `epsilon * scale[k]` becomes $s_k\,$`delta * scale[k]`.
    pub fn factor(
        &mut self,
        symbolic: &Symbolic,
        kkt: &[T],
        scale: &[T],
        epsilon: T,
        delta: T,
    ) -> FactorOutcome {
        let s = symbolic;
        let y = &mut self.work;
        let (mut regularized, mut regularized_primal) = (0, 0);
        for (k, &pivot_scale) in scale.iter().enumerate().take(s.n) {
            let mut diagonal = T::ZERO;
            for e in s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize {
                let i = s.a_row[e] as usize;
                let v = kkt[s.a_slot[e] as usize];
                if i == k {
                    diagonal += v;
                } else {
                    y[i] += v;
                }
            }
            for idx in s.row_ptr[k] as usize..s.row_ptr[k + 1] as usize {
                let j = s.row_col[idx] as usize;
                let pos = s.row_pos[idx] as usize;
                let yj = y[j];
                y[j] = T::ZERO;
                let start = s.l_ptr[j] as usize;
                for (&r, &l) in s.l_row[start..pos].iter().zip(&self.l[start..pos]) {
                    y[r as usize] -= l * yj;
                }
                let lkj = yj / self.d[j];
                diagonal -= lkj * yj;
                self.l[pos] = lkj;
            }
            if !diagonal.is_finite() {
                // Leave the work vector clean for the next call.
                y.iter_mut().for_each(|v| *v = T::ZERO);
                return FactorOutcome::NonFinite { pivot: k };
            }
            let sign = if s.signs[k] > 0 { T::ONE } else { -T::ONE };
            if s.structural_zero[k] {
                diagonal = sign * delta * pivot_scale;
            } else if sign * diagonal <= epsilon * pivot_scale {
                diagonal = sign * delta * pivot_scale;
                regularized += 1;
                regularized_primal += usize::from(s.signs[k] > 0);
            }
            self.d[k] = diagonal;
        }
        FactorOutcome::Factored {
            regularized,
            regularized_primal,
        }
    }

    /// Solves $L D L^\top z = b$ in place in the new order (`x` holds $P b$ on entry).
    pub fn solve_permuted(&self, symbolic: &Symbolic, x: &mut [T]) {
        let s = symbolic;
        for j in 0..s.n {
            let xj = x[j];
            let range = s.l_ptr[j] as usize..s.l_ptr[j + 1] as usize;
            for (&r, &l) in s.l_row[range.clone()].iter().zip(&self.l[range]) {
                x[r as usize] -= l * xj;
            }
        }
        for (xj, &dj) in x.iter_mut().zip(&self.d) {
            *xj /= dj;
        }
        for j in (0..s.n).rev() {
            let range = s.l_ptr[j] as usize..s.l_ptr[j + 1] as usize;
            let mut sum = x[j];
            for (&r, &l) in s.l_row[range.clone()].iter().zip(&self.l[range]) {
                sum -= l * x[r as usize];
            }
            x[j] = sum;
        }
    }

    /// Solves $K z = b$: permutes `b` into `scratch`, solves, and writes `z` to `out`.
    pub fn solve(&self, symbolic: &Symbolic, out: &mut [T], b: &[T], scratch: &mut [T]) {
        for (new, &old) in symbolic.perm.iter().enumerate() {
            scratch[new] = b[old as usize];
        }
        self.solve_permuted(symbolic, scratch);
        for (new, &old) in symbolic.perm.iter().enumerate() {
            out[old as usize] = scratch[new];
        }
    }
}
