//! One KKT system: its pattern, values, symbolic analysis and numeric factor, with the
//! symmetric product and the refined solve.

use alloc::vec::Vec;
use folio_kernels::Real;
use folio_kernels::fused::mul_add;

use crate::gmres::{Gmres, Operator};
use crate::ldlt::{FactorOutcome, Ldlt};
use crate::ordering::{Ordering, QUASI_DEFINITE_RESTART, QUASI_DEFINITE_SHIFT};
use crate::pattern::KktPattern;
use crate::room::{Room, refill};
use crate::settings::Parallelism;
use crate::symbolic::Symbolic;
use crate::vector::max_abs;

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

/// A KKT matrix with a fixed pattern, its symbolic analysis and a numeric factor.
///
/// Owns the pattern, the symbolic analysis, the factor (sizes in their docs), the
/// upper-triangle values (`nnz` of the pattern) and five work vectors of the matrix order
/// $n$; [`Ordering::AmdQuasiDefinite`] adds its GMRES workspace ([`Gmres`], $m + 2$ vectors
/// of order $n$ for restart length $m$, [`Kkt::set_krylov_restart`]); [`Kkt::set_equilibration`] adds the scaling's three buffers of order $n$ (the
/// scaled values are not stored: the factorization scales each entry as it reads it). Everything is allocated at setup ([`Kkt::new`], [`Kkt::set_equilibration`]);
/// factorizing and solving allocate nothing (on one thread: a two-thread factorization,
/// [`Kkt::with_parallelism`], spawns a scoped thread). The factor is made for this very analysis, so the two always pair.
#[derive(Clone, Debug)]
pub struct Kkt<T> {
    /// The pattern and scatter maps.
    pub(crate) pattern: KktPattern,
    /// The symbolic analysis of the pattern.
    symbolic: Symbolic,
    /// The numeric factor (valid after [`Kkt::factorize`]).
    factor: Ldlt<T>,
    /// Upper-triangle values, indexed by the pattern's slots.
    pub(crate) values: Vec<T>,
    /// Natural size of each pivot (new order), the unit of the regularization thresholds.
    pivot_scale: Vec<T>,
    /// Symmetric equilibration $D$ (see [`Kkt::set_equilibration`]).
    equilibration: Option<Equilibration<T>>,
    scratch: Vec<T>,
    residual: Vec<T>,
    correction: Vec<T>,
    /// The iterate before a refinement step, restored if the step raised the residual.
    previous: Vec<T>,
    /// Numeric factorizations since [`Kkt::new`].
    factorizations: u64,
    /// The Krylov refinement of [`Ordering::AmdQuasiDefinite`]; plain refinement without.
    krylov: Option<Gmres<T>>,
    /// Its restart length ([`Kkt::set_krylov_restart`]).
    krylov_restart: usize,
}

/// $K$ and its (regularized) factor as the operator and preconditioner of GMRES.
impl<T: Real> Operator<T> for Kkt<T> {
    fn product(&mut self, out: &mut [T], v: &[T]) {
        self.multiply(out, v);
    }

    fn precondition(&mut self, out: &mut [T], v: &[T]) {
        self.solve_factor(out, v);
    }
}

impl<T: Real> Kkt<T> {
    /// Analyses `pattern` (allocates every buffer), for one thread.
    #[must_use]
    pub fn new(pattern: KktPattern, ordering: Ordering) -> Self {
        Self::with_parallelism(pattern, ordering, Parallelism::One)
    }

    /// Analyses `pattern` for the threads `parallelism` chooses at its order: one thread in
    /// `ordering` ([`Symbolic::analyse`]), or two in the split order
    /// ([`Symbolic::analyse_split`], its halves in `ordering`).
    #[must_use]
    pub fn with_parallelism(
        pattern: KktPattern,
        ordering: Ordering,
        parallelism: Parallelism,
    ) -> Self {
        Self::with_krylov_restart(pattern, ordering, parallelism, QUASI_DEFINITE_RESTART)
    }

    /// [`Kkt::with_parallelism`] with a GMRES of restart length `krylov_restart` (at least
    /// 1) under [`Ordering::AmdQuasiDefinite`], allocated at that length only.
    #[must_use]
    pub fn with_krylov_restart(
        pattern: KktPattern,
        ordering: Ordering,
        parallelism: Parallelism,
        krylov_restart: usize,
    ) -> Self {
        let symbolic = Symbolic::empty();
        let mut kkt = Self {
            factor: Ldlt::new(&symbolic),
            values: Vec::new(),
            symbolic,
            pattern,
            pivot_scale: Vec::new(),
            equilibration: None,
            scratch: Vec::new(),
            residual: Vec::new(),
            correction: Vec::new(),
            previous: Vec::new(),
            factorizations: 0,
            krylov: None,
            krylov_restart: krylov_restart.max(1),
        };
        kkt.reanalyse(ordering, parallelism);
        kkt
    }

    /// Analyses the pattern again (after [`KktPattern::rebuild`] changed it) as
    /// [`Kkt::with_parallelism`] does, in this system's buffers: on one thread, no allocation
    /// when they hold the new system ([`Kkt::reserve`]); a split analysis allocates its
    /// candidates. The equilibration stays on if it was.
    pub(crate) fn reanalyse(&mut self, ordering: Ordering, parallelism: Parallelism) {
        let pattern = &self.pattern;
        let threads = parallelism.threads(pattern.order());
        if cfg!(feature = "std") && threads == 2 {
            self.symbolic = Symbolic::analyse_split(pattern, ordering);
        } else {
            self.symbolic.reanalyse(pattern, ordering);
        }
        self.factor.reset(&self.symbolic);
        self.factor.set_threads(threads);
        let n = pattern.order();
        let quasi_definite = ordering == Ordering::AmdQuasiDefinite;
        self.factor.set_dual_shift(if quasi_definite {
            T::from_f64(QUASI_DEFINITE_SHIFT)
        } else {
            T::ZERO
        });
        refill(&mut self.values, pattern.nnz(), T::ZERO);
        refill(&mut self.pivot_scale, n, T::ONE);
        for v in [
            &mut self.scratch,
            &mut self.residual,
            &mut self.correction,
            &mut self.previous,
        ] {
            refill(v, n, T::ZERO);
        }
        self.factorizations = 0;
        if let Some(e) = &mut self.equilibration {
            e.reset(n);
        }
        match (&mut self.krylov, quasi_definite) {
            (Some(gmres), true) => gmres.reset(n, self.krylov_restart),
            (None, true) => self.krylov = Some(Gmres::new(n, self.krylov_restart)),
            (_, false) => self.krylov = None,
        }
    }

    /// Sets the restart length of [`Ordering::AmdQuasiDefinite`]'s GMRES (at least 1): its
    /// basis holds `krylov_restart + 1` vectors of the order. Allocates when it grows.
    pub fn set_krylov_restart(&mut self, krylov_restart: usize) {
        self.krylov_restart = krylov_restart.max(1);
        let n = self.pattern.order();
        if let Some(gmres) = &mut self.krylov {
            gmres.reset(n, self.krylov_restart);
        }
    }

    /// Room for a system of order `n` with `nnz` stored entries and `nnz_l` entries in $L$,
    /// on one thread, in the current index width and refinement.
    pub fn reserve(&mut self, n: usize, nnz: usize, nnz_l: usize) {
        self.symbolic.reserve(n, nnz, nnz_l);
        self.factor.reserve(n, nnz_l);
        self.values.room_for(nnz);
        for v in [
            &mut self.pivot_scale,
            &mut self.scratch,
            &mut self.residual,
            &mut self.correction,
            &mut self.previous,
        ] {
            v.room_for(n);
        }
        if let Some(e) = &mut self.equilibration {
            e.reserve(n);
        }
        if let Some(gmres) = &mut self.krylov {
            gmres.reserve(n);
        }
    }

    /// Threads of the next factorizations (see [`Ldlt::set_threads`]): 2 only on a split
    /// analysis with `std`. Returns the threads it will use.
    pub fn set_threads(&mut self, threads: usize) -> usize {
        self.factor.set_threads(threads)
    }

    /// Numeric factorizations since this system was made (inertia-correction retries
    /// included): the figure a caller compares per frame.
    #[inline]
    #[must_use]
    pub fn factorizations(&self) -> u64 {
        self.factorizations
    }

    /// The pattern and its scatter maps.
    #[inline]
    #[must_use]
    pub fn pattern(&self) -> &KktPattern {
        &self.pattern
    }

    /// The symbolic analysis of [`Kkt::pattern`].
    #[inline]
    #[must_use]
    pub fn symbolic(&self) -> &Symbolic {
        &self.symbolic
    }

    /// The numeric factor of the last [`Kkt::factorize`] (of $D K D$ when equilibrated), in
    /// [`Kkt::symbolic`]'s layout.
    #[inline]
    #[must_use]
    pub fn factor(&self) -> &Ldlt<T> {
        &self.factor
    }

    /// The upper-triangle values, one per pattern slot (`pattern().nnz()` entries, column
    /// $c$ at `col_ptr[c]..col_ptr[c + 1]`, rows in `row_idx`).
    #[inline]
    #[must_use]
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// The upper-triangle values, mutable (same layout as [`Kkt::values`]): set them before
    /// [`Kkt::factorize`]. The length is fixed by the pattern.
    #[inline]
    #[must_use]
    pub fn values_mut(&mut self) -> &mut [T] {
        &mut self.values
    }

    /// Factorizes $\tilde K = D K D$ instead of $K$, with $D$ from [`RUIZ_PASSES`] passes of
    /// Ruiz's symmetric scaling ($d_i \leftarrow d_i / \sqrt{\max_j |\tilde K_{ij}|}$), so
    /// that every row of $\tilde K$ has its largest entry near 1; solves then return
    /// $z = D \tilde K^{-1} D b$. Allocates its buffers when switched on.
    pub fn set_equilibration(&mut self, on: bool) {
        let n = self.pattern.order();
        self.equilibration = on.then(|| {
            let mut e = Equilibration {
                d: Vec::new(),
                largest: Vec::new(),
                rhs: Vec::new(),
            };
            e.reset(n);
            e
        });
    }

    /// `out = K z` with the full symmetric matrix from its upper triangle.
    pub fn multiply(&self, out: &mut [T], z: &[T]) {
        symmetric_product(&self.pattern, &self.values, out, z);
    }

    /// $z = K^{-1} b$ with the current factor (through $D$ when equilibrated).
    fn solve_factor(&mut self, out: &mut [T], b: &[T]) {
        match &mut self.equilibration {
            Some(e) => {
                for ((r, &bi), &di) in e.rhs.iter_mut().zip(b).zip(&e.d) {
                    *r = bi * di;
                }
                self.factor
                    .solve_paired(&self.symbolic, out, &e.rhs, &mut self.scratch);
                for (o, &di) in out.iter_mut().zip(&e.d) {
                    *o *= di;
                }
            }
            None => self
                .factor
                .solve_paired(&self.symbolic, out, b, &mut self.scratch),
        }
    }

    /// Largest primal diagonal magnitude, the scale of the regularization thresholds (1 if
    /// the primal block has a zero diagonal).
    #[must_use]
    pub fn primal_scale(&self) -> T {
        let p = &self.pattern;
        primal_scale(p, |k| self.values[p.diagonal_slot(k)])
    }

    /// Numeric factorization on the reused symbolic analysis; pivot $k$ with
    /// $s_k d_k \le \epsilon_{rel} \sigma_k$ becomes $s_k \delta_{rel} \sigma_k$. The natural
    /// size $\sigma_k$ of a primal pivot is $P$, the largest primal diagonal
    /// ([`Kkt::primal_scale`]); that of constraint row $c$ is the size of its Schur complement
    /// $J_c H^{-1} J_c^\top$, estimated as $\lVert J_c\rVert_2^2 / P$ on $K$ and, when
    /// equilibrated ([`Kkt::set_equilibration`]), as $\sum_i J_{ci}^2 / h_{ii}$ on $DKD$
    /// ($H$'s diagonal, $P$ for an entry that is not positive).
    ///
    /// Ruiz shrinks the diagonal of the unknowns a large Jacobian row couples to far below
    /// $P$, so that on $DKD$ the global estimate falls short of the Schur complement by as
    /// much: a fuzzed constraint row of Jacobian entries near $10^6$ and compliance
    /// $10^{-6}$, eliminated before its unknowns, kept a pivot of $-10^{-12}$ against a
    /// threshold of $2 \cdot 10^{-13}$, the next pivot grew to $10^{12}$ and the refined
    /// solve stalled at a relative residual of $6 \cdot 10^{-5}$ (backward error
    /// $2 \cdot 10^{-7}$, 100 times the bound; unscaled, the pivot is regularized and one
    /// refinement step reaches $4 \cdot 10^{-14}$). Taking $K$'s thresholds over to $DKD$
    /// instead fails the other way: on rows scaled over six decades in `f32` they
    /// regularized pivots that equilibration had made sound (residual $4.6 \cdot 10^{-2}$
    /// against $10^{-3}$, `tests/tests/solver_kkt.rs`). Unscaled, $P$ stays the estimate:
    /// the per-diagonal one would move every structurally zero constraint pivot
    /// ($-\delta_{rel}\sigma_c$) and the `f32` dual shift of the default book.
    pub fn factorize(&mut self, epsilon_rel: T, delta_rel: T) -> FactorOutcome {
        self.factorizations += 1;
        let p = &self.pattern;
        let values = &self.values;
        let scaling = self.equilibration.as_mut().map(|e| {
            e.update(p, values);
            &e.d[..]
        });
        // Entry `slot` of column `c` at row `r` (original order), scaled if equilibrated.
        let scaled = |slot: usize, r: usize, c: usize| match scaling {
            Some(d) => d[r] * values[slot] * d[c],
            None => values[slot],
        };
        let primal = primal_scale(p, |k| scaled(p.diagonal_slot(k), k, k));
        // Equilibrated: Jacobian entry `v` of row `r` over that unknown's diagonal (`P`
        // when it is not positive), a term of the Schur complement's estimate.
        let jacobi = |v: T, r: usize| {
            let h = scaled(p.diagonal_slot(r), r, r);
            v * v / if h > T::ZERO { h } else { primal }
        };
        let equilibrated = scaling.is_some();
        for (new, &old) in self.symbolic.perm.iter().enumerate() {
            let old = old as usize;
            self.pivot_scale[new] = if old < p.dofs {
                primal
            } else {
                let column = p.col_ptr[old] as usize..p.diagonal_slot(old);
                let sum = column.fold(T::ZERO, |acc, slot| {
                    let r = p.row_idx[slot] as usize;
                    let v = scaled(slot, r, old);
                    acc + if equilibrated { jacobi(v, r) } else { v * v }
                });
                match (sum > T::ZERO, equilibrated) {
                    (false, _) => T::ONE / primal,
                    (true, true) => sum,
                    (true, false) => sum / primal,
                }
            };
        }
        self.factor.factor_paired(
            &self.symbolic,
            values,
            scaling,
            &self.pivot_scale,
            (epsilon_rel, delta_rel),
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
            if outcome.primal_definite() || attempt == MAX_SHIFTS {
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

    /// Solves $K z = b$ with the current factor, then refines
    /// $z \leftarrow z + \hat K^{-1}(b - K z)$ until the relative residual
    /// $\lVert b - Kz\rVert_\infty / \lVert b\rVert_\infty$ is at most `target`, a step stops
    /// lowering it (that step is undone: the better iterate is returned), or `max_steps`
    /// steps are done. With [`Ordering::AmdQuasiDefinite`] a step is a GMRES cycle
    /// ([`Gmres::cycle`], stopping at $\lVert b - Kz\rVert_2 \le$ `target`
    /// $\lVert b\rVert_\infty$), and `steps` counts its iterations (one solve with the factor
    /// and one product with $K$ each).
    pub fn solve_refined(
        &mut self,
        z: &mut [T],
        b: &[T],
        max_steps: u32,
        target: T,
    ) -> Refinement<T> {
        let b_norm = max_abs(b);
        self.solve_factor(z, b);
        if b_norm == T::ZERO {
            return Refinement {
                relative_residual: T::ZERO,
                steps: 0,
            };
        }
        let mut relative = self.residual_into(z, b) / b_norm;
        let mut steps = 0;
        let mut krylov = self.krylov.take();
        while steps < max_steps && relative > target {
            self.previous.copy_from_slice(z);
            let (mut correction, residual) = (
                core::mem::take(&mut self.correction),
                core::mem::take(&mut self.residual),
            );
            if let Some(gmres) = krylov.as_mut() {
                let cycle = gmres.cycle(z, &residual, target * b_norm, self);
                steps += cycle.iterations.max(1);
            } else {
                self.solve_factor(&mut correction, &residual);
                for (zi, ci) in z.iter_mut().zip(&correction) {
                    *zi += *ci;
                }
                steps += 1;
            }
            (self.correction, self.residual) = (correction, residual);
            let before = relative;
            relative = self.residual_into(z, b) / b_norm;
            if relative.partial_cmp(&before) != Some(core::cmp::Ordering::Less) {
                // The step lost (rounding, a nearly singular factor): keep the better z.
                z.copy_from_slice(&self.previous);
                relative = before;
                break;
            }
        }
        self.krylov = krylov;
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

/// `out = A z` for the symmetric $A$ stored as its upper triangle `values` on `pattern`.
pub(crate) fn symmetric_product<T: Real>(
    pattern: &KktPattern,
    values: &[T],
    out: &mut [T],
    z: &[T],
) {
    out.iter_mut().for_each(|v| *v = T::ZERO);
    for c in 0..pattern.order() {
        let range = pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize;
        let mut sum = T::ZERO;
        for (&r, &v) in pattern.row_idx[range.clone()].iter().zip(&values[range]) {
            let r = r as usize;
            out[r] = mul_add(out[r], v, z[c]);
            if r != c {
                sum = mul_add(sum, v, z[r]);
            }
        }
        out[c] += sum;
    }
}

/// Largest primal diagonal magnitude, `diagonal(k)` for $k$ below `p.dofs` (1 if zero).
fn primal_scale<T: Real>(p: &KktPattern, diagonal: impl Fn(usize) -> T) -> T {
    let mut scale = T::ZERO;
    for k in 0..p.dofs {
        let v = diagonal(k);
        let v = if v < T::ZERO { -v } else { v };
        if v > scale {
            scale = v;
        }
    }
    if scale > T::ZERO { scale } else { T::ONE }
}

/// Passes of Ruiz's scaling per factorization ([`Kkt::set_equilibration`]).
pub const RUIZ_PASSES: usize = 4;

/// The scaling $D$ of [`Kkt::set_equilibration`] and its work vectors (order $n$ each).
#[derive(Clone, Debug)]
struct Equilibration<T> {
    /// $D$, in the original order.
    d: Vec<T>,
    /// Largest magnitude per row during a pass.
    largest: Vec<T>,
    /// $D b$ for a solve.
    rhs: Vec<T>,
}

impl<T: Real> Equilibration<T> {
    /// $D = I$ and zeroed buffers for order `n`, within their capacity when it suffices.
    fn reset(&mut self, n: usize) {
        refill(&mut self.d, n, T::ONE);
        refill(&mut self.largest, n, T::ZERO);
        refill(&mut self.rhs, n, T::ZERO);
    }

    /// Room for order `n`.
    fn reserve(&mut self, n: usize) {
        self.d.room_for(n);
        self.largest.room_for(n);
        self.rhs.room_for(n);
    }

    /// Recomputes $D$ for `values` (Ruiz: each pass divides $d_i$ by the square root of the
    /// largest magnitude in row $i$ of $D K D$).
    ///
    /// The pass is one sweep over the stored upper triangle: entry $(r, c)$, $r \le c$,
    /// updates row $r$'s largest magnitude in memory and column $c$'s in a register (no later
    /// column has an entry in row $c$ before its own column is done: they come after it),
    /// with $d_c$ read once per column. The maxima are exact, so the order changes no bit.
    fn update(&mut self, p: &KktPattern, values: &[T]) {
        let n = p.order();
        let (d, largest) = (&mut self.d[..n], &mut self.largest[..n]);
        d.iter_mut().for_each(|d| *d = T::ONE);
        for _ in 0..RUIZ_PASSES {
            largest.iter_mut().for_each(|m| *m = T::ZERO);
            for c in 0..n {
                let range = p.col_ptr[c] as usize..p.col_ptr[c + 1] as usize;
                let dc = d[c];
                let mut column = T::ZERO;
                for (&r, &value) in p.row_idx[range.clone()].iter().zip(&values[range]) {
                    let r = r as usize;
                    let v = d[r] * value * dc;
                    let a = if v < T::ZERO { -v } else { v };
                    if a > largest[r] {
                        largest[r] = a;
                    }
                    if a > column {
                        column = a;
                    }
                }
                if column > largest[c] {
                    largest[c] = column;
                }
            }
            for (d, &m) in d.iter_mut().zip(largest.iter()) {
                if m > T::ZERO && m.is_finite() {
                    *d /= folio_kernels::math::sqrt(m);
                }
            }
        }
    }
}
