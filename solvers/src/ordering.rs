//! Fill-reducing orderings of the KKT matrix, computed once per topology.
//!
//! An unpivoted $LDL^\top$ of a KKT matrix is only as stable as its elimination order lets it
//! be. Plain AMD eliminates the constraint rows of a DOG-shaped KKT first (a DOG row touches
//! fewer unknowns than a coordinate does): their pivots are structurally zero, take the static
//! regularization $-\delta$, and the factor is that of a penalty system which iterative
//! refinement corrects. [`Ordering::AmdDelayedDuals`] holds each constraint row back until all
//! of its primal neighbours are eliminated; its pivot is then the Schur complement
//! $-J_c H^{-1} J_c^\top < 0$, an exact factorization without regularization, at about three
//! times the fill.
//!
//! Measured on the DOG-sheet KKTs (`cargo run --release -p folio-bench --example kkt_report`;
//! flops per factorization; residual after refinement, f64):
//!
//! | quads | n | nnz(L) AMD | nnz(L) delayed | flops AMD | flops delayed | residual AMD | residual delayed |
//! |---|---|---|---|---|---|---|---|
//! | 11x8 | 541 | 14,730 | 42,021 | 0.59 M | 4.1 M | 5.7e-13 | 9.1e-14 |
//! | 16x12 | 1,171 | 41,121 | 133,006 | 2.3 M | 19 M | 9.3e-13 | 2.2e-13 |
//! | 22x16 | 2,139 | 91,116 | 324,690 | 6.9 M | 63 M | 3.4e-10 | 4.9e-13 |
//! | 32x24 | 4,647 | 254,763 | 1,008,362 | 28 M | 293 M | 1.3e-10 | 1.8e-12 |
//!
//! In `f64` the refinement recovers AMD's penalty factor to ~1e-12 on the book's 11x8 grid at
//! a seventh of the flops, so AMD is the `f64` default. In `f32` the static $\delta$ must stay
//! near $\sqrt{\varepsilon}$ (at $10^{-6}$ and below the factor overflows) and refinement
//! then stalls (measured with $\delta = 10^{-4}$: 2.8e-6 at 11x8, 1.7e-3 at 22x16, 0.27 at
//! 32x24), so `f32` took the delayed order (3.3e-6 to 5.2e-6 at every size) until
//! [`Ordering::AmdQuasiDefinite`], its default now (below).
//!
//! On the book's f32 page turn (equilibrated, 750 frames, x86) the trade is the same:
//! the delayed order's worst KKT relative residual is 1.2e-4 and the turn takes 1.37 s of
//! steps; plain AMD takes 0.39 s (3.5 times faster) but leaves residuals up to 9.7e-2, and
//! the released page, which stands nearly upright for a while, falls at a frame that the
//! inexact solves decide: frame 591, then 169 once refinement kept its better iterate
//! ([`crate::Kkt::solve_refined`]); the same change moved the delayed order from 178 to 183
//! and f64 from 231 to 229.
//!
//! [`Ordering::AmdQuasiDefinite`] keeps AMD's order (and its fill: the same permutation) and
//! makes its factor trustworthy in `f32` in two parts. (1) Every constraint pivot is shifted
//! by $-\delta_d\sigma_k$ ([`crate::ldlt::Ldlt::set_dual_shift`]), $\delta_d$ =
//! [`QUASI_DEFINITE_SHIFT`]: the factor is that of the quasi-definite
//! $K_\delta = K - \delta_d\thinspace\mathrm{diag}(0, \Sigma)$, stable in any order when
//! $\delta_d$ is not too small (a structurally zero pivot with $\delta = \sqrt\varepsilon$
//! puts $J^\top J/\delta$ into the primal block; $10^{-2}$ keeps the growth to $10^2$).
//! (2) The solve is refined against the true $K$ by restarted GMRES(10) with that factor as
//! the preconditioner ([`crate::gmres`]). Plain refinement converges on a constraint mode of
//! Schur eigenvalue $s$ at the rate $\delta/(s + \delta)$ per step; the flat-star remedy
//! (`folio_kernels::dog::FlatStarRemedy`, offset $10^{-3}$ in `f32`) leaves modes with
//! $s \approx 10^{-6}$, where it stalls. GMRES resolves the spread of small eigenvalues.
//!
//! The book's `f32` page turn (fixture `page_turn.input`, 750 frames, equilibrated, one
//! Newton iteration, refinement to $\sqrt\varepsilon$; f64 merges at frame 223). Totals
//! over the active frames; "residual" is the worst KKT relative residual after refinement;
//! NE: the projection's normal-equation solves:
//!
//! | f32 variant | nnz(L) | merge | max DOG | residual | factorizations | refinement | NE |
//! |---|---|---|---|---|---|---|---|
//! | delayed duals | 49,875 | 196 | 1.54e-4 | 3.0e-4 | 244 | 0 | 1129 |
//! | AMD, $-\sqrt\varepsilon$ on structural zeros, plain refinement | 16,756 | 499 | 1.59e-4 | 8.1e-2 | 541 | 1562 | 1348 |
//! | AMD, $\delta_d = 10^{-3}$, plain refinement | 16,756 | 378 | 1.60e-4 | 1.4e-2 | 414 | 533 | 1487 |
//! | AMD, $\delta_d = 10^{-2}$, plain refinement | 16,756 | 203 | 2.80e-4 | 4.1e-3 | 273 | 90 | 1487 |
//! | AMD, $\delta_d = 10^{-2}$, refined to $K_\delta$ (a proximal step) | 16,756 | 189 | 3.71e-4 | ($K_\delta$) 3.3e-4 | 237 | 95 | 1790 |
//! | AMD, $\delta_d = 10^{-3}$, GMRES(10) | 16,756 | 195 | 1.59e-4 | 3.2e-2 | 277 | 356 | — |
//! | AMD, $\delta_d = 5 \cdot 10^{-3}$, GMRES(10) | 16,756 | 186 | 1.61e-4 | 7.1e-3 | 246 | 163 | 1288 |
//! | **AMD, $\delta_d = 10^{-2}$, GMRES(10)** ([`Ordering::AmdQuasiDefinite`]) | 16,756 | 196 | 3.51e-4 | 3.4e-4 | 272 | 94 | 1578 |
//! | AMD, $\delta_d = 2 \cdot 10^{-2}$, GMRES(10) | 16,756 | 201 | 1.05e-3 | 3.4e-4 | 288 | 64 | 1976 |
//! | AMD, $\delta_d = 10^{-1}$, GMRES(10) | 16,756 | 256 | 8.3e-4 | 3.1e-4 | 408 | 3 | — |
//!
//! Only $10^{-2}$ with GMRES reaches the refinement target in every solve. Below it the
//! shifted factor is too inexact in `f32` and GMRES stalls on a few solves; above it the
//! first solve already meets the relative target $\lVert Kz - b\rVert_\infty \le
//! \sqrt\varepsilon\lVert b\rVert_\infty$, whose norm the inertia rows dominate, while its
//! constraint rows carry the shift's error $\delta_d\Sigma\lambda$: the step leaves more of
//! $C$ to the projection (frame 33: $\lVert C\rVert_\infty$ 1.1e-2 before the projection
//! against 2.5e-3 with the delayed order, 12 projection iterations against 6) and the DOG
//! residual rises. Testing the equilibrated residual
//! $\lVert D(b - Kz)\rVert_\infty / \lVert Db\rVert_\infty$ instead (GMRES on $DKD$) brought
//! the DOG residual to 2.1e-4 and the normal-equation solves to 1,038, but that target is
//! below what `f32` resolves, so every solve ran its 10 iterations (1,590 in the turn).
//!
//! On the Cortex-M4F firmware (`python3 embedded/baseline.py --run`, QEMU instruction
//! counts), against the delayed order: median active step 45.1 M → 24.1 M instructions, p99
//! 104.6 M → 104.1 M, max 106.2 M → 127.5 M (frame 34, the projection's 12-iteration frames
//! above), median resting step 0.50 M → 0.56 M, heap peak 850,476 → 688,994 B, flash
//! 245,240 → 255,176 B (GMRES), the merge at frame 196 both; all five checks pass.
//!
//! The merge frame is not a precision-independent figure: the released page stands nearly
//! upright, and when it falls depends on rounding. With the refinement tolerance set to
//! $10^{-4}$, $2 \cdot 10^{-4}$, $\sqrt\varepsilon$, $6.4 \cdot 10^{-6}$ and $10^{-10}$ the
//! delayed order merges at 199, 184, 196, 341 and 187; [`Ordering::AmdQuasiDefinite`] at
//! 187, 177, 196 and 178 (the first four); f64 at tolerances $10^{-6}$ to $10^{-12}$ at 223,
//! 223, 240, 232 and 235.

use alloc::vec;
use alloc::vec::Vec;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::amd;

use crate::pattern::{KktPattern, NONE};
use crate::room::{Room, refill};

/// Which elimination order the symbolic analysis uses.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Ordering {
    /// Unknowns in their natural order (all coordinates, then all constraint rows): a
    /// Schur-complement order with dense fill; a reference point only.
    Natural,
    /// Approximate minimum degree (faer's AMD) on the whole KKT pattern (module docs).
    #[default]
    Amd,
    /// AMD, with each constraint row delayed until its primal neighbours are eliminated
    /// (module docs).
    AmdDelayedDuals,
    /// AMD's order, with every constraint pivot shifted by
    /// $-$[`QUASI_DEFINITE_SHIFT`]$\thinspace\sigma_k$ (a quasi-definite factor, stable in
    /// any order) and the solves refined against the true matrix by restarted GMRES with
    /// that factor as the preconditioner ([`crate::gmres`]; module docs).
    AmdQuasiDefinite,
}

/// The dual shift $\delta_d$ of [`Ordering::AmdQuasiDefinite`], relative to each constraint
/// pivot's natural size $\sigma_k = \lVert J_c\rVert_2^2 / P$ ([`crate::Kkt::factorize`];
/// module docs: $5 \cdot 10^{-3}$ leaves `f32` factors too inexact for the refinement,
/// $2 \cdot 10^{-2}$ raises the DOG residual to 1e-3).
pub const QUASI_DEFINITE_SHIFT: f64 = 1e-2;

/// Restart length of [`Ordering::AmdQuasiDefinite`]'s GMRES unless set otherwise
/// ([`crate::settings::Settings::krylov_restart`], [`crate::Kkt::set_krylov_restart`]).
pub const QUASI_DEFINITE_RESTART: usize = 10;

/// The permutation `perm[new] = old` of `ordering` on `pattern`.
#[must_use]
pub fn permutation(pattern: &KktPattern, ordering: Ordering) -> Vec<u32> {
    let mut perm = Vec::new();
    permutation_into(pattern, ordering, &mut perm, &mut OrderScratch::default());
    perm
}

/// The working memory of [`permutation_into`]: AMD's inverse permutation and its stack,
/// kept from one analysis to the next.
#[derive(Default)]
pub struct OrderScratch {
    perm_inv: Vec<u32>,
    stack: Option<MemBuffer>,
}

impl core::fmt::Debug for OrderScratch {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("OrderScratch")
            .field("perm_inv", &self.perm_inv.len())
            .field("stack", &self.stack.is_some())
            .finish()
    }
}

impl Clone for OrderScratch {
    /// Empty: the scratch holds nothing from one call to the next.
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl OrderScratch {
    /// Room for AMD on a pattern of order `n` with `nnz` stored entries.
    pub fn reserve(&mut self, n: usize, nnz: usize) {
        self.perm_inv.room_for(n);
        let req = amd::order_scratch::<u32>(n, nnz);
        let holds = self
            .stack
            .as_mut()
            .is_some_and(|buffer| MemStack::new(buffer).can_hold(req));
        if !holds {
            self.stack = Some(MemBuffer::new(req));
        }
    }
}

/// [`permutation`] into `perm`, with its working memory in `scratch`: for the AMD orders,
/// no allocation when `perm` and `scratch` hold the pattern's ([`OrderScratch::reserve`]);
/// the delayed order allocates its neighbour lists.
pub fn permutation_into(
    pattern: &KktPattern,
    ordering: Ordering,
    perm: &mut Vec<u32>,
    scratch: &mut OrderScratch,
) {
    let n = pattern.order();
    match ordering {
        Ordering::Natural => {
            perm.clear();
            perm.extend(0..n as u32);
        }
        Ordering::Amd | Ordering::AmdQuasiDefinite => amd_order(pattern, perm, scratch),
        Ordering::AmdDelayedDuals => {
            amd_order(pattern, perm, scratch);
            let delayed = delay_duals(pattern, perm);
            perm.clear();
            perm.extend_from_slice(&delayed);
        }
    }
}

/// faer's AMD on the upper pattern (it orders the pattern of $A + A^\top$), into `perm`.
fn amd_order(pattern: &KktPattern, perm: &mut Vec<u32>, scratch: &mut OrderScratch) {
    let n = pattern.order();
    scratch.reserve(n, pattern.nnz());
    refill(perm, n, 0);
    refill(&mut scratch.perm_inv, n, 0);
    let a = SymbolicSparseColMatRef::new_checked(n, n, &pattern.col_ptr, None, &pattern.row_idx);
    let ordered = scratch.stack.as_mut().is_some_and(|buffer| {
        let stack = MemStack::new(buffer);
        amd::order(
            perm,
            &mut scratch.perm_inv,
            a,
            amd::Control::default(),
            stack,
        )
        .is_ok()
    });
    if !ordered {
        // AMD fails only on allocation-size overflow; fall back to the natural order.
        perm.clear();
        perm.extend(0..n as u32);
    }
}

/// `order` with every constraint row moved to just after the last of its primal neighbours
/// (or kept where it is if that comes earlier).
fn delay_duals(pattern: &KktPattern, order: &[u32]) -> Vec<u32> {
    let dofs = pattern.dofs;
    let n = pattern.order();
    // Primal neighbours still to be eliminated, per constraint row; duals per primal.
    let mut waiting = vec![0u32; pattern.rows];
    let mut duals_ptr = vec![0u32; dofs + 1];
    for c in dofs..n {
        for &r in column_rows(pattern, c) {
            if (r as usize) < dofs {
                waiting[c - dofs] += 1;
                duals_ptr[r as usize + 1] += 1;
            }
        }
    }
    for k in 0..dofs {
        duals_ptr[k + 1] += duals_ptr[k];
    }
    let mut fill = duals_ptr.clone();
    let mut duals = vec![NONE; duals_ptr[dofs] as usize];
    for c in dofs..n {
        for &r in column_rows(pattern, c) {
            if (r as usize) < dofs {
                duals[fill[r as usize] as usize] = (c - dofs) as u32;
                fill[r as usize] += 1;
            }
        }
    }
    let mut reached = vec![false; pattern.rows];
    let mut out = Vec::with_capacity(n);
    for &k in order {
        let k = k as usize;
        if k >= dofs {
            let c = k - dofs;
            reached[c] = true;
            if waiting[c] == 0 {
                out.push(k as u32);
            }
            continue;
        }
        out.push(k as u32);
        for &c in &duals[duals_ptr[k] as usize..duals_ptr[k + 1] as usize] {
            let c = c as usize;
            waiting[c] -= 1;
            if waiting[c] == 0 && reached[c] {
                out.push((dofs + c) as u32);
            }
        }
    }
    out
}

/// Stored rows of column `c` (upper triangle, diagonal last).
fn column_rows(pattern: &KktPattern, c: usize) -> &[u32] {
    &pattern.row_idx[pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize]
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::{Ordering, permutation};
    use crate::chain::Chain;

    /// `inverse[old] = new` of `perm[new] = old`.
    fn inverse(perm: &[u32]) -> Vec<u32> {
        let mut inverse = vec![u32::MAX; perm.len()];
        for (new, &old) in perm.iter().enumerate() {
            inverse[old as usize] = new as u32;
        }
        inverse
    }

    #[test]
    fn every_order_is_a_permutation_with_an_inverse() {
        for hessian in [false, true] {
            let pattern = Chain::new(9).pattern(hessian);
            let n = pattern.order();
            for ordering in [
                Ordering::Natural,
                Ordering::Amd,
                Ordering::AmdDelayedDuals,
                Ordering::AmdQuasiDefinite,
            ] {
                let perm = permutation(&pattern, ordering);
                let mut sorted = perm.clone();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..n as u32).collect::<Vec<_>>(), "{ordering:?}");
                let inv = inverse(&perm);
                for k in 0..n {
                    assert_eq!(inv[perm[k] as usize] as usize, k);
                    assert_eq!(perm[inv[k] as usize] as usize, k);
                }
            }
            let natural = permutation(&pattern, Ordering::Natural);
            assert_eq!(natural, (0..n as u32).collect::<Vec<_>>());
            // The quasi-definite variant keeps AMD's order, so its fill.
            assert_eq!(
                permutation(&pattern, Ordering::AmdQuasiDefinite),
                permutation(&pattern, Ordering::Amd)
            );
        }
    }

    /// The delayed order eliminates every constraint row after all its primal neighbours,
    /// and keeps AMD's relative order of the primal unknowns.
    #[test]
    fn delayed_duals_follow_their_neighbours() {
        let pattern = Chain::new(9).pattern(false);
        let amd = permutation(&pattern, Ordering::Amd);
        let delayed = permutation(&pattern, Ordering::AmdDelayedDuals);
        let at = inverse(&delayed);
        for c in pattern.dofs..pattern.order() {
            let range = pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize;
            for &r in &pattern.row_idx[range] {
                if (r as usize) < pattern.dofs {
                    assert!(at[r as usize] < at[c], "row {c} before dof {r}");
                }
            }
        }
        let primal = |order: &[u32]| -> Vec<u32> {
            order
                .iter()
                .copied()
                .filter(|&k| (k as usize) < pattern.dofs)
                .collect()
        };
        assert_eq!(primal(&amd), primal(&delayed));
    }
}
