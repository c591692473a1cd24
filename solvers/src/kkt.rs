//! One KKT system: its pattern, values, symbolic analysis and numeric factor, with the
//! symmetric product and the refined solve.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::Real;

use crate::ldlt::{FactorOutcome, Ldlt};
use crate::ordering::Ordering;
use crate::pattern::KktPattern;
use crate::symbolic::Symbolic;

/// Most primal shifts of [`Kkt::factorize_with_inertia_correction`] ($\beta$ up to
/// $10^{3}$ times the largest primal diagonal).
pub const MAX_SHIFTS: u32 = 8;

/// Result of a refined solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refinement<T> {
    /// $\lVert K z - b\rVert_\infty / \lVert b\rVert_\infty$ of the returned solution.
    pub relative_residual: T,
    /// Refinement steps taken after the first solve.
    pub steps: u32,
}

/// A KKT matrix with a fixed pattern, its symbolic analysis and a numeric factor; every
/// buffer is sized at construction.
#[derive(Clone, Debug)]
pub struct Kkt<T> {
    /// The pattern and scatter maps.
    pub pattern: KktPattern,
    /// The symbolic analysis of the pattern.
    pub symbolic: Symbolic,
    /// The numeric factor (valid after [`Kkt::factorize`]).
    pub factor: Ldlt<T>,
    /// Upper-triangle values, indexed by the pattern's slots.
    pub values: Vec<T>,
    /// Natural size of each pivot (new order), the unit of the regularization thresholds.
    pivot_scale: Vec<T>,
    scratch: Vec<T>,
    residual: Vec<T>,
    correction: Vec<T>,
}

impl<T: Real> Kkt<T> {
    /// Analyses `pattern` (allocates every buffer).
    #[must_use]
    pub fn new(pattern: KktPattern, ordering: Ordering) -> Self {
        let symbolic = Symbolic::analyse(&pattern, ordering);
        let n = pattern.order();
        Self {
            factor: Ldlt::new(&symbolic),
            values: vec![T::ZERO; pattern.nnz()],
            symbolic,
            pattern,
            pivot_scale: vec![T::ONE; n],
            scratch: vec![T::ZERO; n],
            residual: vec![T::ZERO; n],
            correction: vec![T::ZERO; n],
        }
    }

    /// `out = K z` with the full symmetric matrix from its upper triangle.
    pub fn multiply(&self, out: &mut [T], z: &[T]) {
        out.iter_mut().for_each(|v| *v = T::ZERO);
        let p = &self.pattern;
        for c in 0..p.order() {
            let range = p.col_ptr[c] as usize..p.col_ptr[c + 1] as usize;
            let mut sum = T::ZERO;
            for (&r, &v) in p.row_idx[range.clone()].iter().zip(&self.values[range]) {
                let r = r as usize;
                out[r] += v * z[c];
                if r != c {
                    sum += v * z[r];
                }
            }
            out[c] += sum;
        }
    }

    /// Largest primal diagonal magnitude, the scale of the regularization thresholds (1 if
    /// the primal block has a zero diagonal).
    #[must_use]
    pub fn primal_scale(&self) -> T {
        let mut scale = T::ZERO;
        for k in 0..self.pattern.dofs {
            let v = self.values[self.pattern.diagonal_slot(k)];
            let v = if v < T::ZERO { -v } else { v };
            if v > scale {
                scale = v;
            }
        }
        if scale > T::ZERO { scale } else { T::ONE }
    }

    /// Numeric factorization on the reused symbolic analysis; pivot $k$ with
    /// $s_k d_k \le \epsilon_{rel} \sigma_k$ becomes $s_k \delta_{rel} \sigma_k$. The natural
    /// size $\sigma_k$ of a primal pivot is $P$, the largest primal diagonal
    /// ([`Kkt::primal_scale`]); that of constraint row $c$ is the size of its Schur complement
    /// $J_c H^{-1} J_c^\top \approx \lVert J_c\rVert_2^2 / P$.
    pub fn factorize(&mut self, epsilon_rel: T, delta_rel: T) -> FactorOutcome {
        let primal = self.primal_scale();
        let p = &self.pattern;
        for (new, &old) in self.symbolic.perm.iter().enumerate() {
            let old = old as usize;
            self.pivot_scale[new] = if old < p.dofs {
                primal
            } else {
                let mut sum = T::ZERO;
                for s in p.col_ptr[old] as usize..p.diagonal_slot(old) {
                    sum += self.values[s] * self.values[s];
                }
                if sum > T::ZERO {
                    sum / primal
                } else {
                    T::ONE / primal
                }
            };
        }
        self.factor.factor(
            &self.symbolic,
            &self.values,
            &self.pivot_scale,
            epsilon_rel,
            delta_rel,
        )
    }

    /// [`Kkt::factorize`], shifting the primal block by $\beta I$ until its pivots come out
    /// positive (inertia correction, as in interior-point and SQP codes): a regularized or
    /// non-finite primal pivot means the Hessian is indefinite where it was eliminated, and a
    /// tiny $+\delta$ in its place would make the factor explode. $\beta$ starts at
    /// $10^{-4} P$ ($P$ the largest primal diagonal) and grows tenfold, at most
    /// [`MAX_SHIFTS`] times. The shift stays in the values, so the solve and its refinement
    /// are of the shifted (convexified) system. Returns the outcome and $\beta$ (0 if none).
    pub fn factorize_with_inertia_correction(
        &mut self,
        epsilon_rel: T,
        delta_rel: T,
    ) -> (FactorOutcome, T) {
        let first = T::from_f64(1e-4) * self.primal_scale();
        let mut shift = T::ZERO;
        let mut attempt = 0;
        loop {
            let outcome = self.factorize(epsilon_rel, delta_rel);
            let indefinite = !matches!(
                outcome,
                FactorOutcome::Factored {
                    regularized_primal: 0,
                    ..
                }
            );
            if !indefinite || attempt == MAX_SHIFTS {
                return (outcome, shift);
            }
            let next = if shift == T::ZERO {
                first
            } else {
                shift * T::from_f64(10.0)
            };
            for k in 0..self.pattern.dofs {
                self.values[self.pattern.diagonal_slot(k)] += next - shift;
            }
            shift = next;
            attempt += 1;
        }
    }

    /// Solves $K z = b$ with the current factor, then refines $z \leftarrow z + \hat K^{-1}(b - K z)$
    /// until the relative residual is at most `target`, stops falling by half, or
    /// `max_steps` refinements are done.
    pub fn solve_refined(
        &mut self,
        z: &mut [T],
        b: &[T],
        max_steps: u32,
        target: T,
    ) -> Refinement<T> {
        let b_norm = max_abs(b);
        self.factor.solve(&self.symbolic, z, b, &mut self.scratch);
        if b_norm == T::ZERO {
            return Refinement {
                relative_residual: T::ZERO,
                steps: 0,
            };
        }
        let mut relative = self.residual_into(z, b) / b_norm;
        let mut steps = 0;
        while steps < max_steps && relative > target {
            self.factor.solve(
                &self.symbolic,
                &mut self.correction,
                &self.residual,
                &mut self.scratch,
            );
            for (zi, ci) in z.iter_mut().zip(&self.correction) {
                *zi += *ci;
            }
            steps += 1;
            let previous = relative;
            relative = self.residual_into(z, b) / b_norm;
            if !relative.is_finite() || relative >= previous {
                break;
            }
        }
        Refinement {
            relative_residual: relative,
            steps,
        }
    }

    /// Writes `b - K z` into the residual buffer and returns its max norm (NaN propagates).
    fn residual_into(&mut self, z: &[T], b: &[T]) -> T {
        let mut r = core::mem::take(&mut self.residual);
        self.multiply(&mut r, z);
        for (ri, &bi) in r.iter_mut().zip(b) {
            *ri = bi - *ri;
        }
        let norm = max_abs(&r);
        self.residual = r;
        norm
    }
}

/// $\lVert v\rVert_\infty$; NaN if any entry is NaN.
#[must_use]
pub fn max_abs<T: Real>(v: &[T]) -> T {
    let mut m = T::ZERO;
    for &x in v {
        if !x.is_finite() {
            return if x < T::ZERO { -x } else { x };
        }
        let a = if x < T::ZERO { -x } else { x };
        if a > m {
            m = a;
        }
    }
    m
}
