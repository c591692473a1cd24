//! The constraint projection's normal equations: the Schur complement
//! $S = J W^{-1} J^\top$ of a KKT system whose primal block $W$ is diagonal.
//!
//! The fast projection (Goldenthal et al. 2007; [`crate::Solver::project_constraints`])
//! solves
//! $$\begin{bmatrix} W & J^\top \cr J & 0\end{bmatrix}\begin{bmatrix}\delta \cr \mu\end{bmatrix}
//!   = \begin{bmatrix} 0 \cr -C\end{bmatrix}$$
//! with $W$ the diagonal mass matrix over $h^2$. The first row gives
//! $\delta = -W^{-1} J^\top \mu$; put into the second, it leaves
//! $$S\mu = C,\qquad S = J W^{-1} J^\top,\qquad \delta = -W^{-1} J^\top \mu,$$
//! a symmetric positive semidefinite system of the order of the constraint rows alone (301
//! against the KKT's 677 unknowns on the book's 11×8 page), whose pattern (rows that share
//! a free coordinate) is analysed once per topology.
//!
//! Each solve factorizes $S$ and runs conjugate gradients preconditioned with the factor:
//! one iteration solves up to the regularization of near-zero pivots and rounding, and the
//! next ones refine. $S$'s factor has nnz(L) = 10,896 and 0.53 M flops on the book's page,
//! against the KKT's 16,756 and 0.68 M in AMD's order (f64's, and f32's quasi-definite
//! one; 49,875 and 4.1 M in the delayed-duals order), and the step's own KKT factor is left
//! untouched.
//!
//! A factor kept from an earlier $S$ (an earlier iteration or frame) was tried as the
//! preconditioner first, refactorizing only when three iterations fell short. On the page
//! turn (`cargo run --release -p folio-bench --example frame_work`) it served one
//! projection iteration in ten in f64 and one in sixteen in f32: the DOG rows of nearly
//! flat stars make $S$ nearly singular, and their directions change from one iteration to
//! the next. The failed attempts cost more than the factorizations saved, so every solve
//! factorizes.
//!
//! The residual of $S\mu = C$ is what the projection leaves of $C$ to first order:
//! $C(x + \delta) \approx C + J\delta = C - S\mu$. So the caller's target is its
//! constraint tolerance, not a multiple of the machine epsilon.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::Real;
use folio_kernels::fused::{mul_add, mul_sub};

use crate::kkt::symmetric_product;
use crate::ldlt::{FactorOutcome, Ldlt};
use crate::ordering::Ordering;
use crate::pattern::KktPattern;
use crate::symbolic::Symbolic;
use crate::vector::{dot, max_abs};

mod transpose;

use transpose::Transpose;

/// How one [`NormalEquations::solve`] went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalSolve<T> {
    /// $\lVert S\mu - C\rVert_\infty$ of the returned $\mu$.
    pub residual: T,
    /// The factorization met a non-finite pivot: $\mu$ is not a solution.
    pub failed: bool,
    /// Whether the solve factorized $S$ (not when $C$ was already within the target).
    pub factorized: bool,
    /// Triangular solves done.
    pub solves: u32,
}

/// $S = J W^{-1} J^\top$ for one KKT pattern: its pattern, symbolic analysis, values and a
/// factor (module docs).
///
/// Owns the transpose of $J$'s structure (one entry per Jacobian slot of the KKT pattern,
/// two indices each, plus `dofs + 1` pointers; `u16` when the KKT has at most 65,535
/// slots, `u32` otherwise), the upper pattern of $S$ and its symbolic
/// analysis, the factor, the values, $W^{-1}$ (one per dof) and seven work vectors of the
/// row count, all allocated by [`NormalEquations::new`]; nothing else allocates.
#[derive(Clone, Debug)]
pub struct NormalEquations<T> {
    /// Free coordinates of the KKT pattern.
    dofs: usize,
    /// Per dof, its Jacobian entries (constraint row and KKT value slot), rows ascending.
    transpose: Transpose,
    /// Upper pattern of $S$ (`rows` unknowns, all with positive pivots).
    pattern: KktPattern,
    symbolic: Symbolic,
    factor: Ldlt<T>,
    /// Upper values of $S$, in `pattern`'s slots.
    values: Vec<T>,
    /// $W^{-1}$ per dof (set by the caller before [`NormalEquations::assemble`]).
    pub(crate) inverse_w: Vec<T>,
    /// Dense accumulator of one column of $S$, zero between uses.
    column: Vec<T>,
    /// The rows one node's dofs touch ([`NormalEquations::pin_along`]), capacity `rows`.
    touched: Vec<u32>,
    pivot_scale: Vec<T>,
    /// The conjugate gradients' residual, preconditioned residual, direction and product.
    residual: Vec<T>,
    preconditioned: Vec<T>,
    direction: Vec<T>,
    product: Vec<T>,
    scratch: Vec<T>,
}

impl<T: Real> NormalEquations<T> {
    /// Analyses $S$ for the Jacobian block of `kkt` (its constraint columns' primal
    /// entries): builds $J^\top$'s structure and $S$'s upper pattern, and orders $S$ by AMD.
    #[must_use]
    pub fn new(kkt: &KktPattern) -> Self {
        let (dofs, rows) = (kkt.dofs, kkt.rows);
        let (transpose, pattern, symbolic) = structure(kkt);
        Self {
            dofs,
            transpose,
            factor: Ldlt::new(&symbolic),
            values: vec![T::ZERO; pattern.nnz()],
            symbolic,
            pattern,
            inverse_w: vec![T::ZERO; dofs],
            column: vec![T::ZERO; rows],
            touched: Vec::with_capacity(rows),
            pivot_scale: vec![T::ONE; rows],
            residual: vec![T::ZERO; rows],
            preconditioned: vec![T::ZERO; rows],
            direction: vec![T::ZERO; rows],
            product: vec![T::ZERO; rows],
            scratch: vec![T::ZERO; rows],
        }
    }

    /// The upper pattern of $S$ (as a [`KktPattern`] with no constraint rows).
    #[must_use]
    pub fn pattern(&self) -> &KktPattern {
        &self.pattern
    }

    /// The symbolic analysis of $S$.
    #[must_use]
    pub fn symbolic(&self) -> &Symbolic {
        &self.symbolic
    }

    /// The upper values of $S$ from the last [`NormalEquations::assemble`].
    #[must_use]
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// $W^{-1}$ per dof, to be set before [`NormalEquations::assemble`] and
    /// [`NormalEquations::back_substitute`].
    pub fn inverse_w_mut(&mut self) -> &mut [T] {
        &mut self.inverse_w
    }

    /// $S_\rho = J W^{-1} J^\top + \rho\thinspace\mathrm{diag}(J W^{-1} J^\top)$ from the
    /// Jacobian entries in the KKT values `kkt_values` and the weights set through
    /// [`NormalEquations::inverse_w_mut`]: column $b$ is
    /// $S_{ab} = \sum_d J_{ad} W^{-1}_d J_{bd}$ over the dofs $d$ of row $b$, accumulated
    /// densely and gathered into the pattern. The damping $\rho$ = `damping` (a
    /// Levenberg-Marquardt term, [`crate::Settings::projection_damping`]) shortens the
    /// projection step along the directions in which $S$ is nearly singular.
    pub fn assemble(&mut self, kkt: &KktPattern, kkt_values: &[T], damping: T) {
        let rows = self.pattern.dofs;
        for b in 0..rows {
            let j_row = kkt.col_ptr[self.dofs + b] as usize..kkt.diagonal_slot(self.dofs + b);
            for (&d, &j_bd) in kkt.row_idx[j_row.clone()].iter().zip(&kkt_values[j_row]) {
                let d = d as usize;
                let w = j_bd * self.inverse_w[d];
                let column = &mut self.column;
                self.transpose.for_each(d, kkt_values, |a, j_ad| {
                    if a > b {
                        return false;
                    }
                    column[a] = mul_add(column[a], j_ad, w);
                    true
                });
            }
            let range = self.pattern.col_ptr[b] as usize..self.pattern.col_ptr[b + 1] as usize;
            for (&a, v) in self.pattern.row_idx[range.clone()]
                .iter()
                .zip(&mut self.values[range.clone()])
            {
                *v = self.column[a as usize];
                self.column[a as usize] = T::ZERO;
            }
            if let Some(diagonal) = self.values[range].last_mut() {
                *diagonal = mul_add(*diagonal, damping, *diagonal);
            }
        }
    }

    /// Makes one node's $W^{-1}$ block anisotropic after [`NormalEquations::assemble`]:
    /// $W_i^{-1} = w_i^{-1} I - c\thinspace n n^\top$ on its three dofs `dofs`, with $n$ =
    /// `normal` (unit) and $0 \le c \le w_i^{-1}$, so that the node moves freely along its
    /// contact surface and $c\thinspace w_i$ less (not at all for $c = w_i^{-1}$) along $n$.
    /// Since $S = \sum_i J_i W_i^{-1} J_i^\top$ over the nodes' column blocks $J_i$, this
    /// subtracts the rank-one term $c\thinspace u u^\top$, $u = J_i n$, from the rows the
    /// node touches, its diagonal scaled by $1 + \rho$ as [`NormalEquations::assemble`]
    /// scales it. A pair of rows that share none of the node's dofs (a row on its $x$ alone
    /// and one on its $z$ alone) has no slot in $S$'s pattern and keeps its isotropic
    /// value; the book's pinned page nodes have none (their DOG rows hold all three dofs).
    /// [`NormalEquations::back_substitute`] does not know of it: the caller applies
    /// [`slide`] to the node's $\delta$ with $c\thinspace w_i$.
    pub fn pin_along(
        &mut self,
        kkt_values: &[T],
        dofs: [usize; 3],
        normal: [T; 3],
        c: T,
        damping: T,
    ) {
        self.touched.clear();
        for (&d, &n) in dofs.iter().zip(&normal) {
            let (column, touched) = (&mut self.column, &mut self.touched);
            self.transpose.for_each(d, kkt_values, |a, j_ad| {
                if !touched.contains(&(a as u32)) {
                    touched.push(a as u32);
                }
                column[a] = mul_add(column[a], j_ad, n);
                true
            });
        }
        for (k, &p) in self.touched.iter().enumerate() {
            for &q in &self.touched[..=k] {
                let (a, b) = if p <= q { (p, q) } else { (q, p) };
                let (a, b) = (a as usize, b as usize);
                let range = self.pattern.col_ptr[b] as usize..self.pattern.col_ptr[b + 1] as usize;
                let Ok(slot) = self.pattern.row_idx[range.clone()].binary_search(&(a as u32))
                else {
                    continue;
                };
                let scale = if a == b { T::ONE + damping } else { T::ONE };
                let v = &mut self.values[range.start + slot];
                *v = mul_sub(*v, c * scale * self.column[a], self.column[b]);
            }
        }
        for &a in &self.touched {
            self.column[a as usize] = T::ZERO;
        }
    }

    /// $\delta = -W^{-1} J^\top \mu$ into the first `dofs` entries of `delta`.
    pub fn back_substitute(&self, delta: &mut [T], mu: &[T], kkt_values: &[T]) {
        for (d, out) in delta[..self.dofs].iter_mut().enumerate() {
            let mut sum = T::ZERO;
            self.transpose.for_each(d, kkt_values, |a, j_ad| {
                sum = mul_add(sum, j_ad, mu[a]);
                true
            });
            *out = -self.inverse_w[d] * sum;
        }
    }

    /// Factorizes the assembled $S$; pivot $k$ with $d_k \le \epsilon\thinspace s_k$
    /// becomes $\delta\thinspace s_k$, with $s_k$ the diagonal of $S$ (or the largest one
    /// for an empty row).
    pub fn factorize(&mut self, epsilon: T, delta: T) -> FactorOutcome {
        let p = &self.pattern;
        let largest = (0..p.dofs).fold(T::ZERO, |m, k| {
            let v = self.values[p.diagonal_slot(k)];
            if v > m { v } else { m }
        });
        let fallback = if largest > T::ZERO { largest } else { T::ONE };
        for (scale, &old) in self.pivot_scale.iter_mut().zip(&self.symbolic.perm) {
            let v = self.values[p.diagonal_slot(old as usize)];
            *scale = if v > T::ZERO { v } else { fallback };
        }
        self.factor.factor_paired(
            &self.symbolic,
            &self.values,
            None,
            &self.pivot_scale,
            (epsilon, delta),
        )
    }

    /// Solves $S\mu = $ `c` to $\lVert S\mu - c\rVert_\infty \le$ `target`: factorizes $S$
    /// (pivots below `epsilon` times their diagonal become `delta` times it) and runs at
    /// most `max_iterations` conjugate-gradient iterations preconditioned with the factor.
    pub fn solve(
        &mut self,
        mu: &mut [T],
        c: &[T],
        target: T,
        max_iterations: u32,
        epsilon: T,
        delta: T,
    ) -> NormalSolve<T> {
        let mut out = NormalSolve {
            residual: T::ZERO,
            failed: false,
            factorized: false,
            solves: 0,
        };
        mu.iter_mut().for_each(|m| *m = T::ZERO);
        self.residual.copy_from_slice(c);
        out.residual = max_abs(c);
        if out.residual <= target {
            return out;
        }
        out.factorized = true;
        if !matches!(
            self.factorize(epsilon, delta),
            FactorOutcome::Factored { .. }
        ) {
            out.failed = true;
            return out;
        }
        out.residual = self.conjugate_gradients(mu, max_iterations.max(1), target, &mut out.solves);
        out
    }

    /// Preconditioned conjugate gradients on $S\mu = c$ from the iterate `mu`, whose
    /// residual $r = c - S\mu$ is in the residual buffer: $z = \hat S^{-1} r$,
    /// $p \leftarrow z + \beta p$, $\alpha = r^\top z / p^\top S p$,
    /// $\mu \mathrel{+}= \alpha p$, $r \mathrel{-}= \alpha S p$, until
    /// $\lVert r\rVert_\infty \le$ `target` or `iterations` iterations, or a breakdown
    /// ($p^\top S p \le 0$ or non-finite). Adds the triangular solves to `solves`; returns
    /// $\lVert r\rVert_\infty$ of the recurrence.
    fn conjugate_gradients(
        &mut self,
        mu: &mut [T],
        iterations: u32,
        target: T,
        solves: &mut u32,
    ) -> T {
        let mut rz = T::ZERO;
        let mut residual = max_abs(&self.residual);
        for k in 0..iterations {
            self.factor.solve_paired(
                &self.symbolic,
                &mut self.preconditioned,
                &self.residual,
                &mut self.scratch,
            );
            *solves += 1;
            let rz_next = dot(&self.residual, &self.preconditioned);
            let beta = if k == 0 { T::ZERO } else { rz_next / rz };
            rz = rz_next;
            for (p, &z) in self.direction.iter_mut().zip(&self.preconditioned) {
                *p = mul_add(z, beta, *p);
            }
            symmetric_product(
                &self.pattern,
                &self.values,
                &mut self.product,
                &self.direction,
            );
            let curvature = dot(&self.direction, &self.product);
            if !(curvature > T::ZERO && rz.is_finite()) {
                break;
            }
            let alpha = rz / curvature;
            for ((m, r), (&p, &q)) in mu
                .iter_mut()
                .zip(self.residual.iter_mut())
                .zip(self.direction.iter().zip(&self.product))
            {
                *m = mul_add(*m, alpha, p);
                *r = mul_sub(*r, alpha, q);
            }
            residual = max_abs(&self.residual);
            if residual <= target || !residual.is_finite() {
                break;
            }
        }
        residual
    }

    /// $\lVert c - S\mu\rVert_\infty$ with the assembled $S$ (the true residual, against the
    /// one [`NormalEquations::solve`] reports from its recurrence).
    pub fn residual_of(&mut self, mu: &[T], c: &[T]) -> T {
        symmetric_product(&self.pattern, &self.values, &mut self.residual, mu);
        for (r, &ci) in self.residual.iter_mut().zip(c) {
            *r = ci - *r;
        }
        max_abs(&self.residual)
    }
}

/// The back-substitution of a node pinned along `normal` ([`NormalEquations::pin_along`]):
/// with $\delta_i = -w_i^{-1} g$ the isotropic step, its anisotropic one is
/// $-(w_i^{-1} I - c\thinspace n n^\top) g = \delta_i - c\thinspace w_i\thinspace n (n\cdot\delta_i)$;
/// `held` $= c\thinspace w_i \in [0, 1]$.
pub fn slide<T: Real>(delta: &mut [T], dofs: [usize; 3], normal: [T; 3], held: T) {
    let along = dofs
        .iter()
        .zip(&normal)
        .fold(T::ZERO, |s, (&d, &n)| mul_add(s, delta[d], n));
    for (&d, &n) in dofs.iter().zip(&normal) {
        delta[d] = mul_sub(delta[d], held * along, n);
    }
}

/// $J^\top$'s structure, $S$'s upper pattern and its AMD analysis for the Jacobian block of
/// `kkt` ([`NormalEquations::new`]). Not generic, and never inlined into the generic caller:
/// setup code, compiled once for every value type and with this crate's optimization
/// settings (the firmware optimizes this crate for size).
#[inline(never)]
fn structure(kkt: &KktPattern) -> (Transpose, KktPattern, Symbolic) {
    let rows = kkt.rows;
    let transpose = Transpose::new(kkt);
    // S's upper column b: rows a <= b sharing a dof with b, ascending, diagonal last.
    let mut mark = vec![u32::MAX; rows];
    let mut col_ptr = Vec::with_capacity(rows + 1);
    col_ptr.push(0u32);
    let mut row_idx = Vec::new();
    for b in 0..rows {
        let start = row_idx.len();
        mark[b] = b as u32;
        for &d in jacobian_rows(kkt, b) {
            transpose.for_each_row(d as usize, |a| {
                if a < b && mark[a] != b as u32 {
                    mark[a] = b as u32;
                    row_idx.push(a as u32);
                }
            });
        }
        row_idx[start..].sort_unstable();
        row_idx.push(b as u32);
        col_ptr.push(row_idx.len() as u32);
    }
    drop(mark);
    row_idx.shrink_to_fit();
    let pattern = KktPattern {
        dofs: rows,
        rows: 0,
        col_ptr,
        row_idx,
        ..KktPattern::default()
    };
    let symbolic = Symbolic::analyse(&pattern, Ordering::Amd);
    (transpose, pattern, symbolic)
}

/// The primal rows of constraint column `c` of `kkt`: the dofs of row `c` of $J$.
fn jacobian_rows(kkt: &KktPattern, c: usize) -> &[u32] {
    let col = kkt.dofs + c;
    &kkt.row_idx[kkt.col_ptr[col] as usize..kkt.diagonal_slot(col)]
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::NormalEquations;
    use crate::chain::{Chain, dense, kkt_values};
    use crate::pattern::KktPattern;
    use crate::vector::max_abs;

    /// The chain's KKT values, its dense $J$ (rows × dofs) and $W^{-1}_d = 1/(1 + d)$.
    fn chain() -> (KktPattern, Vec<f64>, Vec<Vec<f64>>, Vec<f64>) {
        let pattern = Chain::new(11).pattern(false);
        let values = kkt_values(&pattern);
        let k = dense(&pattern, &values);
        let (dofs, rows) = (pattern.dofs, pattern.rows);
        let j = (0..rows).map(|c| k[dofs + c][..dofs].to_vec()).collect();
        let inverse_w = (0..dofs).map(|d| 1.0 / (1.0 + d as f64)).collect();
        (pattern, values, j, inverse_w)
    }

    fn assembled(pattern: &KktPattern, values: &[f64], inverse_w: &[f64]) -> NormalEquations<f64> {
        let mut normal = NormalEquations::new(pattern);
        normal.inverse_w.copy_from_slice(inverse_w);
        normal.assemble(pattern, values, 0.0);
        normal
    }

    /// Every entry of $S$, stored or not, is $\sum_d J_{ad} W^{-1}_d J_{bd}$ from the dense
    /// $J$.
    #[test]
    fn assembles_j_w_inverse_j_transpose() {
        let (pattern, values, j, inverse_w) = chain();
        let normal = assembled(&pattern, &values, &inverse_w);
        let s = dense(normal.pattern(), normal.values());
        assert!(j.len() >= 4);
        for a in 0..j.len() {
            for b in 0..j.len() {
                let want: f64 = (0..pattern.dofs)
                    .map(|d| j[a][d] * inverse_w[d] * j[b][d])
                    .sum();
                assert!((s[a][b] - want).abs() <= 1e-14, "({a}, {b})");
            }
        }
        // The chain's rows share nodes: S is not diagonal.
        assert!(s[0][1] != 0.0);
    }

    /// A node held along a normal ([`NormalEquations::pin_along`] and [`super::slide`]):
    /// $S$ is $J W^{-1} J^\top$ with the node's block $w^{-1} I - c\thinspace n n^\top$, and
    /// the step solves $W\delta + J^\top\mu = 0$, $J\delta = -C$ with that block, so that
    /// the node moves along the normal by $1 - c\thinspace w$ of what it would.
    #[test]
    fn a_node_held_along_a_normal_solves_the_anisotropic_system() {
        let (pattern, values, j, mut inverse_w) = chain();
        let node = 2;
        let dofs: [usize; 3] = core::array::from_fn(|a| pattern.dof_of()[3 * node + a] as usize);
        let w_inv = inverse_w[dofs[0]];
        for &d in &dofs {
            inverse_w[d] = w_inv;
        }
        let n = [0.48, -0.6, 0.64];
        let c = 0.999 * w_inv;
        let mut normal = assembled(&pattern, &values, &inverse_w);
        normal.pin_along(&values, dofs, n, c, 0.0);
        // The dense W^{-1}: diagonal, with the node's 3x3 block.
        let dofs_n = pattern.dofs;
        let mut w = vec![vec![0.0; dofs_n]; dofs_n];
        for d in 0..dofs_n {
            w[d][d] = inverse_w[d];
        }
        for (a, &da) in dofs.iter().enumerate() {
            for (b, &db) in dofs.iter().enumerate() {
                w[da][db] -= c * n[a] * n[b];
            }
        }
        let s = dense(normal.pattern(), normal.values());
        let rows = j.len();
        for a in 0..rows {
            for b in 0..rows {
                let want: f64 = (0..dofs_n)
                    .flat_map(|p| (0..dofs_n).map(move |q| (p, q)))
                    .map(|(p, q)| j[a][p] * w[p][q] * j[b][q])
                    .sum();
                assert!(
                    (s[a][b] - want).abs() <= 1e-13,
                    "({a}, {b}): {} {want}",
                    s[a][b]
                );
            }
        }
        let c_rhs: Vec<f64> = (0..rows).map(|r| 0.01 * (r as f64 - 1.5)).collect();
        let mut mu = vec![0.0; rows];
        let solve = normal.solve(&mut mu, &c_rhs, 1e-14, 10, 1e-13, 1e-8);
        assert!(!solve.failed && solve.residual <= 1e-13, "{solve:?}");
        let mut delta = vec![0.0; dofs_n];
        normal.back_substitute(&mut delta, &mu, &values);
        let isotropic = delta.clone();
        super::slide(&mut delta, dofs, n, c / w_inv);
        for p in 0..dofs_n {
            let jt_mu: f64 = (0..dofs_n)
                .map(|q| w[p][q] * (0..rows).map(|r| j[r][q] * mu[r]).sum::<f64>())
                .sum();
            assert!((delta[p] + jt_mu).abs() <= 1e-13, "dof {p}");
        }
        for r in 0..rows {
            let linear: f64 = (0..dofs_n).map(|d| j[r][d] * delta[d]).sum();
            assert!((linear + c_rhs[r]).abs() <= 1e-12, "row {r}");
        }
        let along = |v: &[f64]| dofs.iter().zip(&n).map(|(&d, &k)| v[d] * k).sum::<f64>();
        assert!(
            along(&isotropic).abs() > 1e-4,
            "the test must move the node"
        );
        assert!(along(&delta).abs() <= 1.001e-3 * along(&isotropic).abs());
    }

    /// $\delta = -W^{-1}J^\top\mu$ with $S\mu = C$ solves the projection's KKT system:
    /// $W\delta + J^\top\mu = 0$ and $J\delta = -C$, checked with the dense $J$.
    #[test]
    fn solves_the_projection_system() {
        let (pattern, values, j, inverse_w) = chain();
        let mut normal = assembled(&pattern, &values, &inverse_w);
        let rows = j.len();
        let c: Vec<f64> = (0..rows).map(|r| 0.01 * (r as f64 - 1.5)).collect();
        let mut mu = vec![0.0; rows];
        let solve = normal.solve(&mut mu, &c, 1e-14, 10, 1e-13, 1e-8);
        assert!(solve.factorized && !solve.failed);
        assert!(solve.residual <= 1e-14);
        let mut delta = vec![0.0; pattern.dofs];
        normal.back_substitute(&mut delta, &mu, &values);
        for d in 0..pattern.dofs {
            let stationarity =
                delta[d] / inverse_w[d] + (0..rows).map(|r| j[r][d] * mu[r]).sum::<f64>();
            assert!(stationarity.abs() <= 1e-13, "dof {d}: {stationarity}");
        }
        for r in 0..rows {
            let linear: f64 = (0..pattern.dofs).map(|d| j[r][d] * delta[d]).sum();
            assert!((linear + c[r]).abs() <= 1e-13, "row {r}");
        }
    }

    /// With $W$ a thousand times heavier on half the dofs (as on pinned nodes) the solve
    /// still reaches its target, and the residual it reports is the true one up to the
    /// recurrence's rounding; a right-hand side already within the target costs nothing.
    #[test]
    fn solves_a_pinned_system_to_its_target() {
        let (pattern, values, j, mut inverse_w) = chain();
        for w in inverse_w.iter_mut().step_by(2) {
            *w *= 1e-3;
        }
        let mut normal = assembled(&pattern, &values, &inverse_w);
        let c: Vec<f64> = (0..j.len()).map(|r| 1e-3 * (1.0 + r as f64)).collect();
        let mut mu = vec![0.0; j.len()];
        let target = 1e-9;
        let solve = normal.solve(&mut mu, &c, target, 10, 1e-8, 1e-8);
        assert!(
            solve.factorized && !solve.failed && solve.residual <= target,
            "{solve:?}"
        );
        let mut check = normal.clone();
        let true_residual = check.residual_of(&mu, &c);
        assert!(true_residual <= 2.0 * target, "{true_residual}");
        let small: Vec<f64> = c.iter().map(|v| v * 1e-7).collect();
        let idle = normal.solve(&mut mu, &small, target, 10, 1e-8, 1e-8);
        assert!(!idle.factorized && idle.solves == 0 && max_abs(&mu) == 0.0);
    }
}
