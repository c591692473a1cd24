//! Numeric $LDL^\top$ of the quasi-definite KKT matrix on a reused [`Symbolic`] analysis,
//! with sign-aware dynamic regularization, and the triangular solves.
//!
//! Up-looking (Davis, "Algorithm 849: A concise sparse Cholesky factorization package",
//! 2005; as QDLDL): row $k$ of $L$ solves $L_{0:k,0:k}\thinspace y = A_{0:k,k}$ over the
//! row's nonzero columns $j$, $L_{kj} = y_j / d_j$, $d_k = a_{kk} - \sum_j L_{kj} y_j$. The
//! row's columns are the reach of column $k$'s entries up the elimination tree, taken in
//! ascending $j$ (so that the rounding does not depend on a walk's order); the analysis
//! hands them over as $L$'s row structure ([`Symbolic`]), so a row's factorization walks no
//! tree and sorts nothing. $L_{kj}$ goes to the next free position of column $j$. (The
//! halves of a split factor still find their separator rows' columns by walking the tree:
//! they see only part of each row.)
//! The expected pivot sign $s_k$ is known (+ primal, − constraint row); a pivot with
//! $s_k d_k \le \epsilon$ is replaced by $s_k \delta$ and counted. The factor is then that of
//! $K + E$ with a small diagonal $E$, which iterative refinement against $K$ corrects.
//! Constraint rows that the ordering eliminates before any unknown they couple to have a
//! structurally zero pivot: their $d_k$ is the stored diagonal $a_{kk}$ alone. An exact zero
//! there takes $-\delta$ (static regularization, as in quasi-definite solvers) and is not
//! counted, so the count still means a (numerically) singular system; a stored nonzero
//! $a_{kk}$ (a compliant constraint) is a pivot like any other, kept when its sign is right
//! and counted when it is replaced. A constraint row with no entry at all (its column of
//! $L$ empty as well) makes $K$ singular in any order: it is counted, shifted or not.
//!
//! With a dual shift $\delta_d > 0$ ([`Ldlt::set_dual_shift`]) every constraint pivot is
//! shifted by $-\delta_d \sigma_k$ before its sign test: the factor is then that of the
//! quasi-definite $K - \delta_d \thinspace\mathrm{diag}(0, \Sigma)$ (Vanderbei 1995; as QDLDL
//! in OSQP), stable in any elimination order, which a Krylov refinement against $K$
//! corrects ([`crate::gmres`]). Structurally zero pivots then take $-\delta_d \sigma_k$.
//!
//! On a split analysis ([`Symbolic::analyse_split`]: half $A$, half $B$, separator $S$, no
//! entry of $L$ joining $A$ and $B$) the work divides in two. Each half computes its own
//! rows, then its part of every separator row $k$: the triangular solve over its own
//! columns, which leaves partial sums $y^A_i$, $y^B_i$ ($i \in S$, $i < k$) and partial
//! diagonals; half $A$ starts from column $k$'s entries in $A$ and $S$ and $a_{kk}$, half $B$
//! from its entries in $B$ and zero. The halves share nothing but read-only input, so they
//! run on two threads ([`Ldlt::set_threads`]). Row $k$ then continues from
//! $y_i = y^A_i + y^B_i$ over the separator's columns, on one thread. This adds the halves'
//! contributions in another order than the row-by-row factor of the same order would (the
//! rounding differs in the last bits), and the same on one thread as on two: the split
//! factor is bit for bit the same whatever the threads. Without the `std` feature a split
//! analysis is factorized row by row like any other.

use alloc::vec::Vec;
use core::ops::Range;
use folio_kernels::Real;
use folio_kernels::fused::mul_sub;

use crate::error::SolverError;
use crate::index::Index;
use crate::nested_dissection::Split;
use crate::pattern::NONE;
use crate::room::{Room, refill};
use crate::symbolic::{Arrays, Structure, Symbolic};

/// Outcome of one numeric factorization.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FactorOutcome {
    /// Factorized; `regularized` pivots were replaced by $s_k \delta$ or belong to a
    /// constraint row with no entry at all (module docs): a (numerically) singular system.
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
/// of it is allocated by [`Ldlt::new`] at setup (or refilled by [`Ldlt::reset`]); factorizing
/// and solving allocate nothing.
/// For a split analysis ([`Symbolic::analyse_split`]) it also owns a second work vector,
/// row list and bit set for half $B$ ($n$ each), the halves' partial separator rows
/// ($m(m + 1)$ values for a separator of $m$ unknowns) and each half column's first
/// separator ancestor (one 32-bit index per half column). A two-thread factorization
/// ([`Ldlt::set_threads`]) spawns a scoped thread, which allocates its stack and handle.
/// It remembers the analysis it was made for (its order and [`Symbolic::fingerprint`]) and
/// its entry points refuse any other with [`SolverError::SymbolicMismatch`].
#[derive(Clone, Debug)]
pub struct Ldlt<T> {
    /// Strictly lower values of $L$ (in the symbolic's layout).
    l: Vec<T>,
    /// The pivots $D$.
    d: Vec<T>,
    /// Next free position of each column of $L$ during a factorization.
    fill: Vec<u32>,
    /// The work vector, row list and bit set of the factor (of half $A$ on a split
    /// analysis).
    first: Workspace<T>,
    /// [`Symbolic::fingerprint`] of the analysis this factor belongs to.
    fingerprint: u64,
    /// Static shift $\delta_d$ of the constraint pivots, relative to their scale (module
    /// docs); 0 for none.
    dual_shift: T,
    /// Half $B$'s work vector, row list and bit set (empty unless the analysis is split).
    second: Workspace<T>,
    /// The halves' partial separator rows, $m(m + 1)/2$ each for a separator of $m$
    /// ([`Part::factor_half`]).
    stash: Vec<T>,
    /// The first separator ancestor of each column of the halves (`split.b` entries).
    top: Vec<u32>,
    /// Threads of a factorization: 1, or 2 on a split analysis with `std`.
    threads: usize,
}

/// The per-thread work vectors of the up-looking factor ([`Ldlt`]).
#[derive(Clone, Debug, Default)]
struct Workspace<T> {
    /// Dense work vector ($n$), zero between rows.
    y: Vec<T>,
    /// The current row's nonzero columns ($n$).
    reach: Vec<u32>,
    /// Visited bit per column ($n$ bits), zero between rows.
    seen: Vec<usize>,
}

impl<T: Real> Workspace<T> {
    /// Zeroed buffers for order `n` (empty for 0), within their capacity when it suffices.
    fn reset(&mut self, n: usize) {
        refill(&mut self.y, n, T::ZERO);
        refill(&mut self.reach, n, 0);
        refill(&mut self.seen, n.div_ceil(BITS), 0);
    }

    /// Room for order `n`.
    fn reserve(&mut self, n: usize) {
        self.y.room_for(n);
        self.reach.room_for(n);
        self.seen.room_for(n.div_ceil(BITS));
    }
}

impl<T: Real> Ldlt<T> {
    /// Allocates the values and the workspace for `symbolic`.
    #[must_use]
    pub fn new(symbolic: &Symbolic) -> Self {
        let mut factor = Self {
            l: Vec::new(),
            d: Vec::new(),
            fill: Vec::new(),
            first: Workspace::default(),
            fingerprint: 0,
            dual_shift: T::ZERO,
            second: Workspace::default(),
            stash: Vec::new(),
            top: Vec::new(),
            threads: 1,
        };
        factor.reset(symbolic);
        factor
    }

    /// Makes this factor [`Ldlt::new`]'s for `symbolic`, in its own buffers: no allocation
    /// when they hold it ([`Ldlt::reserve`]). The dual shift is kept; the threads go back
    /// to 1.
    pub fn reset(&mut self, symbolic: &Symbolic) {
        let n = symbolic.n;
        refill(&mut self.l, symbolic.nnz_l(), T::ZERO);
        refill(&mut self.d, n, T::ZERO);
        refill(&mut self.fill, n, 0);
        self.first.reset(n);
        self.fingerprint = symbolic.fingerprint;
        let split = symbolic.split;
        self.second.reset(if split.is_some() { n } else { 0 });
        let m = split.map_or(0, |split| n - split.b);
        refill(&mut self.stash, m * (m + 1), T::ZERO);
        self.top.clear();
        if let Some(split) = split {
            separator_ancestors(&symbolic.parent, split.b, &mut self.top);
        }
        self.threads = 1;
    }

    /// Room for a factor of order `n` with `nnz_l` entries in $L$, on one thread.
    pub fn reserve(&mut self, n: usize, nnz_l: usize) {
        self.l.room_for(nnz_l);
        self.d.room_for(n);
        self.fill.room_for(n);
        self.first.reserve(n);
    }

    /// Sets the static shift $\delta_d \ge 0$ of the constraint pivots (module docs): pivot
    /// $k$ with $s_k < 0$ becomes $d_k - \delta_d \sigma_k$, $\sigma_k$ its scale. 0 (the
    /// default) switches it off.
    pub fn set_dual_shift(&mut self, shift: T) {
        self.dual_shift = shift;
    }

    /// Threads of the next factorizations: 2 splits the work of a split analysis
    /// ([`Symbolic::analyse_split`]) between this thread and a scoped second one, which
    /// compute the two halves concurrently before this thread finishes the separator's
    /// rows (module docs). The result is bit for bit that of one thread: each half runs
    /// the same operations in the same order either way. Without a split, or without the
    /// `std` feature, the factor stays on one thread. Returns the threads it will use.
    pub fn set_threads(&mut self, threads: usize) -> usize {
        let two = cfg!(feature = "std") && threads >= 2 && !self.second.y.is_empty();
        self.threads = if two { 2 } else { 1 };
        self.threads
    }

    /// Threads of a factorization ([`Ldlt::set_threads`]).
    #[inline]
    #[must_use]
    pub fn threads(&self) -> usize {
        self.threads
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
        let job = Job {
            symbolic,
            values,
            scale,
            limits,
            dual_shift: self.dual_shift,
        };
        self.fill.copy_from_slice(&symbolic.l_ptr[..symbolic.n]);
        match &symbolic.structure {
            Structure::Narrow(a) => self.factor_parts(job, a),
            Structure::Wide(a) => self.factor_parts(job, a),
        }
    }

    /// The up-looking factorization of every row: in one pass, or on a split analysis the
    /// halves (on one thread or two), then the separator's rows.
    fn factor_parts<I: Index + Sync>(
        &mut self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
    ) -> FactorOutcome {
        let n = job.symbolic.n;
        // Without `std` a split analysis is factorized row by row like any other (the
        // microcontroller's flash does not carry the split factor).
        let split = job.symbolic.split.filter(|_| cfg!(feature = "std"));
        let Some(split) = split else {
            return self.whole().0.factor(job, arrays, 0..n);
        };
        let halves = self.factor_halves(job, arrays, split);
        if let FactorOutcome::NonFinite { .. } = halves {
            return halves;
        }
        let (rows, stash, top) = self.whole();
        let halves_rows = stash.split_at(stash.len() / 2);
        rows.factor_separator(job, arrays, split.b, halves_rows, top)
            .after(halves)
    }

    /// Half $A$'s work (its rows, then its part of the separator's rows) and half $B$'s,
    /// on this thread and, with two threads, a scoped second one: half $B$ reads and
    /// writes only its own columns ([`crate::nested_dissection`]).
    fn factor_halves<I: Index + Sync>(
        &mut self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
        split: Split,
    ) -> FactorOutcome {
        let (a, b) = (split.a, split.b);
        let l_a = job.symbolic.l_ptr[a] as usize;
        let l_b = job.symbolic.l_ptr[b] as usize;
        let (l_first, l_second) = self.l[..l_b].split_at_mut(l_a);
        let (d_first, d_second) = self.d[..b].split_at_mut(a);
        let (fill_first, fill_second) = self.fill[..b].split_at_mut(a);
        let half = self.stash.len() / 2;
        let (stash_first, stash_second) = self.stash.split_at_mut(half);
        let columns = Columns::new(l_first, d_first, fill_first, (0, 0));
        let half_a = Part::new(&mut self.first, columns);
        let columns = Columns::new(l_second, d_second, fill_second, (a, l_a));
        let half_b = Part::new(&mut self.second, columns);
        let run_b = move || half_b.factor_half(job, arrays, a..b, b, stash_second);
        #[cfg(feature = "std")]
        if self.threads == 2 {
            return std::thread::scope(|scope| {
                let second = scope.spawn(run_b);
                let first = half_a.factor_half(job, arrays, 0..a, b, stash_first);
                match second.join() {
                    Ok(second) => second.after(first),
                    Err(panic) => std::panic::resume_unwind(panic),
                }
            });
        }
        let first = half_a.factor_half(job, arrays, 0..a, b, stash_first);
        if let FactorOutcome::NonFinite { .. } = first {
            return first;
        }
        run_b().after(first)
    }

    /// This factor's buffers as one [`Part`], every column, with the halves' partial
    /// separator rows and the first separator ancestors.
    fn whole(&mut self) -> (Part<'_, T>, &[T], &[u32]) {
        let columns = Columns::new(&mut self.l, &mut self.d, &mut self.fill, (0, 0));
        let part = Part::new(&mut self.first, columns);
        (part, &self.stash, &self.top)
    }
}

/// One factorization's read-only inputs ([`Ldlt::factor_paired`]).
#[derive(Clone, Copy)]
struct Job<'a, T> {
    symbolic: &'a Symbolic,
    values: Values<'a, T>,
    scale: &'a [T],
    limits: (T, T),
    /// [`Ldlt::set_dual_shift`]'s $\delta_d$.
    dual_shift: T,
}

/// The buffers one thread of the up-looking factor writes: the work vector, row list and
/// bit set ($n$ each), and its columns.
struct Part<'a, T> {
    y: &'a mut [T],
    reach: &'a mut [u32],
    seen: &'a mut [usize],
    columns: Columns<'a, T>,
}

/// Columns `first..` of $D$ and of the next free positions, with their values of $L$ from
/// position `l_first` on.
struct Columns<'a, T> {
    l: &'a mut [T],
    d: &'a mut [T],
    fill: &'a mut [u32],
    first: usize,
    l_first: usize,
}

impl<'a, T: Real> Part<'a, T> {
    /// The buffers of `workspace`, on `columns`.
    fn new(workspace: &'a mut Workspace<T>, columns: Columns<'a, T>) -> Self {
        Self {
            y: &mut workspace.y,
            reach: &mut workspace.reach,
            seen: &mut workspace.seen,
            columns,
        }
    }

    /// The up-looking factorization (module docs) of rows `rows`, whose columns all lie in
    /// this part's range.
    fn factor<I: Index>(
        mut self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
        rows: Range<usize>,
    ) -> FactorOutcome {
        self.factor_rows(job, arrays, rows)
    }

    /// [`Part::factor`] of rows `rows`, borrowing the part.
    fn factor_rows<I: Index>(
        &mut self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
        rows: Range<usize>,
    ) -> FactorOutcome {
        let (s, values) = (job.symbolic, job.values);
        let (a_row, a_slot) = (&arrays.a_row, &arrays.a_slot);
        let y = &mut *self.y;
        let mut pivots = Pivots::default();
        for k in rows {
            let mut diagonal = T::ZERO;
            for e in s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize {
                let i = a_row[e].get();
                let v = values.get(a_slot[e].get(), i, k);
                if i == k {
                    diagonal += v;
                    continue;
                }
                y[i] += v;
            }
            // Row k's columns, ascending, from the analysis (module docs).
            let row = &arrays.r_col[s.r_ptr[k] as usize..s.r_ptr[k + 1] as usize];
            let diagonal = self.columns.eliminate(y, s, &arrays.l_row, row, diagonal);
            if let Err(outcome) =
                pivots.set(self.columns.d, k - self.columns.first, job, k, diagonal)
            {
                clear(y, &mut *self.seen);
                return outcome;
            }
        }
        pivots.outcome()
    }

    /// This half's rows `columns`, then its part of every separator row $k \ge b$: the
    /// entries of column $k$ in its columns (and, for half $A$, those in the separator and
    /// the diagonal) less the updates of its columns, stored to `stash` (rows $b..k$ and
    /// the diagonal, $(k - b)(k - b + 1)/2$ on) for [`Part::factor_separator`].
    fn factor_half<I: Index>(
        mut self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
        columns: Range<usize>,
        b: usize,
        stash: &mut [T],
    ) -> FactorOutcome {
        let own = self.factor_rows(job, arrays, columns.clone());
        if let FactorOutcome::NonFinite { .. } = own {
            return own;
        }
        let (s, values) = (job.symbolic, job.values);
        let (a_row, a_slot) = (&arrays.a_row, &arrays.a_slot);
        let (y, reach, seen) = (&mut *self.y, &mut *self.reach, &mut *self.seen);
        let (first, end) = (columns.start == 0, columns.end);
        for k in b..s.n {
            let mut diagonal = T::ZERO;
            let (mut count, mut low) = (0, end);
            for e in s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize {
                let i = a_row[e].get();
                let inside = columns.contains(&i);
                if !(inside || first && i >= b) {
                    continue;
                }
                let v = values.get(a_slot[e].get(), i, k);
                if i == k {
                    diagonal += v;
                    continue;
                }
                y[i] += v;
                if inside {
                    low = low.min(i);
                    count = walk(reach, seen, &s.parent, (i, end), count);
                }
            }
            let row = ascending(&mut reach[..count], seen, low, end);
            let diagonal = self.columns.eliminate(y, s, &arrays.l_row, row, diagonal);
            let at = (k - b) * (k - b + 1) / 2;
            let (partial, rest) = stash[at..=at + k - b].split_at_mut(k - b);
            partial.copy_from_slice(&y[b..k]);
            y[b..k].iter_mut().for_each(|v| *v = T::ZERO);
            rest[0] = diagonal;
        }
        own
    }

    /// The separator's rows $b..n$ after both halves ([`Part::factor_half`]): row $k$
    /// starts from the sum of the halves' partial rows and diagonals, then eliminates its
    /// separator columns, reached from each entry's first separator ancestor (`top`, for
    /// entries below $b$) up the elimination tree.
    fn factor_separator<I: Index>(
        self,
        job: Job<'_, T>,
        arrays: &Arrays<I>,
        b: usize,
        (first, second): (&[T], &[T]),
        top: &[u32],
    ) -> FactorOutcome {
        let s = job.symbolic;
        let Self {
            y,
            reach,
            seen,
            mut columns,
        } = self;
        let mut pivots = Pivots::default();
        for k in b..s.n {
            let at = (k - b) * (k - b + 1) / 2;
            let m = k - b;
            for ((v, &p), &q) in y[b..k]
                .iter_mut()
                .zip(&first[at..at + m])
                .zip(&second[at..at + m])
            {
                *v = p + q;
            }
            let diagonal = first[at + m] + second[at + m];
            let (mut count, mut low) = (0, k);
            for &i in &arrays.a_row[s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize] {
                let i = i.get();
                let j = if i < b { top[i] as usize } else { i };
                if j < k {
                    low = low.min(j);
                    count = walk(reach, seen, &s.parent, (j, k), count);
                }
            }
            let row = ascending(&mut reach[..count], seen, low, k);
            let diagonal = columns.eliminate(y, s, &arrays.l_row, row, diagonal);
            if let Err(outcome) = pivots.set(columns.d, k, job, k, diagonal) {
                clear(y, seen);
                return outcome;
            }
        }
        pivots.outcome()
    }
}

impl<'a, T: Real> Columns<'a, T> {
    /// Columns `first..` of `d` and `fill`, their values of $L$ in `l` from position
    /// `l_first` on.
    fn new(
        l: &'a mut [T],
        d: &'a mut [T],
        fill: &'a mut [u32],
        (first, l_first): (usize, usize),
    ) -> Self {
        Self {
            l,
            d,
            fill,
            first,
            l_first,
        }
    }

    /// Row $k$'s columns `row`, ascending: $L_{kj} = y_j / d_j$ goes to column $j$'s next
    /// free position, $y \mathrel{-}= L_{:j}\thinspace y_j$ over the column's earlier rows,
    /// and the returned diagonal is `diagonal` $- \sum_j L_{kj} y_j$. Leaves $y_j = 0$.
    #[inline]
    fn eliminate<I: Index, R: Index>(
        &mut self,
        y: &mut [T],
        s: &Symbolic,
        l_row: &[I],
        row: &[R],
        mut diagonal: T,
    ) -> T {
        let (l, d, fill) = (&mut *self.l, &*self.d, &mut *self.fill);
        let (first, l_first) = (self.first, self.l_first);
        assert!(y.len() >= s.n, "work vector shorter than the analysis");
        // Row k's columns j, ascending: L_kj = y_j / d_j, and y -= L_{:j} y_j.
        for &j in row {
            let j = j.get();
            let pos = fill[j - first] as usize;
            fill[j - first] += 1;
            let yj = y[j];
            y[j] = T::ZERO;
            let start = s.l_ptr[j] as usize;
            let values = &l[start - l_first..pos - l_first];
            for (&r, &lr) in l_row[start..pos].iter().zip(values) {
                let r = r.get();
                debug_assert!(r < s.n);
                // SAFETY: `l_row` holds row indices of L below n = `s.n` (built by
                // `Symbolic::analyse` from a pattern of order n, never changed after), and
                // `y.len() >= s.n` was asserted above.
                #[allow(unsafe_code)]
                let yr = unsafe { y.get_unchecked_mut(r) };
                *yr = mul_sub(*yr, lr, yj);
            }
            let lkj = yj / d[j - first];
            diagonal = mul_sub(diagonal, lkj, yj);
            l[pos - l_first] = lkj;
        }
        diagonal
    }
}

/// Up the elimination tree (`parent`) from column `j` to the first visited column or to
/// `limit`, marking each in `seen` and appending it to `reach` after `count` entries;
/// returns the new count.
#[inline]
fn walk(
    reach: &mut [u32],
    seen: &mut [usize],
    parent: &[u32],
    (mut j, limit): (usize, usize),
    mut count: usize,
) -> usize {
    while j < limit && seen[j / BITS] & (1 << (j % BITS)) == 0 {
        seen[j / BITS] |= 1 << (j % BITS);
        reach[count] = j as u32;
        count += 1;
        j = parent[j] as usize;
    }
    count
}

/// The first ancestor at or after `b` of each column below `b` in the elimination tree
/// `parent` ([`NONE`] for a root below `b`), into `top`.
fn separator_ancestors(parent: &[u32], b: usize, top: &mut Vec<u32>) {
    refill(top, b, NONE);
    for j in (0..b).rev() {
        let p = parent[j];
        top[j] = if p == NONE || p as usize >= b {
            p
        } else {
            top[p as usize]
        };
    }
}

/// Zeroes the work vector and the visited bits (after a non-finite pivot, for the next
/// call).
fn clear<T: Real>(y: &mut [T], seen: &mut [usize]) {
    y.iter_mut().for_each(|v| *v = T::ZERO);
    seen.iter_mut().for_each(|w| *w = 0);
}

/// The regularized pivots of a factorization so far.
#[derive(Default)]
struct Pivots {
    regularized: usize,
    regularized_primal: usize,
}

impl Pivots {
    /// Stores pivot $k$, `diagonal` after the module docs' sign test and regularization,
    /// at `d[at]`; `Err` with the outcome when it is not finite (nothing stored).
    #[inline]
    fn set<T: Real>(
        &mut self,
        d: &mut [T],
        at: usize,
        job: Job<'_, T>,
        k: usize,
        mut diagonal: T,
    ) -> Result<(), FactorOutcome> {
        let (s, (epsilon, delta)) = (job.symbolic, job.limits);
        if !diagonal.is_finite() {
            return Err(FactorOutcome::NonFinite { pivot: k });
        }
        let pivot_scale = job.scale[k];
        let sign = if s.signs[k] > 0 { T::ONE } else { -T::ONE };
        let shifted = s.signs[k] < 0 && job.dual_shift > T::ZERO;
        let stored_zero = diagonal == T::ZERO;
        if s.structural_zero[k] && stored_zero && s.l_ptr[k] == s.l_ptr[k + 1] {
            // No entry in its row or column of K (an empty column of L too): the system
            // is singular in any order, which the count says.
            self.regularized += 1;
        }
        if shifted {
            diagonal -= job.dual_shift * pivot_scale;
        }
        if s.structural_zero[k] && !shifted && stored_zero {
            diagonal = sign * delta * pivot_scale;
        } else if sign * diagonal <= epsilon * pivot_scale {
            diagonal = sign * delta * pivot_scale;
            self.regularized += 1;
            self.regularized_primal += usize::from(s.signs[k] > 0);
        }
        d[at] = diagonal;
        Ok(())
    }

    /// The outcome of a factorization that ended here.
    fn outcome(self) -> FactorOutcome {
        FactorOutcome::Factored {
            regularized: self.regularized,
            regularized_primal: self.regularized_primal,
        }
    }
}

impl FactorOutcome {
    /// Factorized with every primal pivot positive: the KKT matrix has the inertia of a
    /// minimum (its primal block positive definite where eliminated).
    #[must_use]
    pub fn primal_definite(&self) -> bool {
        matches!(
            self,
            Self::Factored {
                regularized_primal: 0,
                ..
            }
        )
    }

    /// The outcome of a factorization whose earlier rows ended in `earlier`: the first
    /// non-finite pivot, or the regularized pivots of both.
    fn after(self, earlier: Self) -> Self {
        match (earlier, self) {
            (Self::NonFinite { .. }, _) => earlier,
            (
                Self::Factored {
                    regularized: r0,
                    regularized_primal: p0,
                },
                Self::Factored {
                    regularized,
                    regularized_primal,
                },
            ) => Self::Factored {
                regularized: r0 + regularized,
                regularized_primal: p0 + regularized_primal,
            },
            (_, Self::NonFinite { .. }) => self,
        }
    }
}

impl<T: Real> Ldlt<T> {
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
        // Both loops index `x` by `l_row` unchecked (the factor's hot loops, ~10 % of a
        // book step's instructions as bounds checks): `l_row` holds row indices of L below
        // n, built by `Symbolic::analyse` from a pattern of order n and never changed after.
        assert!(x.len() >= n, "right-hand side shorter than the analysis");
        for j in 0..n {
            let xj = x[j];
            let range = l_ptr[j] as usize..l_ptr[j + 1] as usize;
            for (&r, &l) in l_row[range.clone()].iter().zip(&self.l[range]) {
                debug_assert!(r.get() < n);
                // SAFETY: r < n (above) and x.len() >= n (asserted).
                #[allow(unsafe_code)]
                let xr = unsafe { x.get_unchecked_mut(r.get()) };
                *xr = mul_sub(*xr, l, xj);
            }
        }
        for (xj, &dj) in x.iter_mut().zip(&self.d) {
            *xj /= dj;
        }
        for j in (0..n).rev() {
            let range = l_ptr[j] as usize..l_ptr[j + 1] as usize;
            let mut sum = x[j];
            for (&r, &l) in l_row[range.clone()].iter().zip(&self.l[range]) {
                debug_assert!(r.get() < n);
                // SAFETY: r < n (above) and x.len() >= n (asserted).
                #[allow(unsafe_code)]
                let xr = unsafe { *x.get_unchecked(r.get()) };
                sum = mul_sub(sum, l, xr);
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
    use crate::kkt::Kkt;
    use crate::ordering::Ordering;
    use crate::pattern::KktPattern;
    use crate::settings::Parallelism;
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

    /// The analysis's row structure of $L$ is each row's reach up the elimination tree,
    /// ascending: what the factor found as it ran before the analysis handed it over
    /// (`walk` and `ascending`, which a split factor's separator rows still use), for a
    /// chain under every order, with and without the constraint Hessian.
    #[test]
    fn row_structure_is_each_rows_sorted_reach() {
        for hessian in [false, true] {
            let pattern = Chain::new(23).pattern(hessian);
            for ordering in [
                Ordering::Natural,
                Ordering::Amd,
                Ordering::AmdDelayedDuals,
                Ordering::AmdQuasiDefinite,
            ] {
                let s = Symbolic::analyse(&pattern, ordering);
                let Structure::Narrow(arrays) = &s.structure else {
                    panic!("a small chain takes 16-bit indices");
                };
                let n = s.n;
                let (mut reach, mut seen) = (vec![0u32; n], vec![0usize; n.div_ceil(BITS)]);
                assert_eq!(s.r_ptr.len(), n + 1);
                assert_eq!(s.r_ptr[n] as usize, s.nnz_l());
                for k in 0..n {
                    let (mut count, mut low) = (0, k);
                    for e in s.a_ptr[k] as usize..s.a_ptr[k + 1] as usize {
                        let i = arrays.a_row[e] as usize;
                        if i < k {
                            low = low.min(i);
                            count = super::walk(&mut reach, &mut seen, &s.parent, (i, k), count);
                        }
                    }
                    let expected = ascending(&mut reach[..count], &mut seen, low, k).to_vec();
                    let row: Vec<u32> = arrays.r_col[s.r_ptr[k] as usize..s.r_ptr[k + 1] as usize]
                        .iter()
                        .map(|&j| u32::from(j))
                        .collect();
                    assert_eq!(row, expected, "row {k}, {ordering:?}, hessian {hessian}");
                }
            }
        }
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

    /// On a split analysis the factor on two threads is bit for bit the factor on one (and
    /// so are the refined solves), and the refined solution matches a dense Gaussian
    /// elimination with partial pivoting of the same system.
    #[test]
    fn two_threads_match_one_and_a_dense_solve() {
        let pattern = Chain::new(40).pattern(true);
        let values = kkt_values(&pattern);
        let n = pattern.order();
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64).collect();
        let want = gauss(dense(&pattern, &values), b.clone());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for ordering in [Ordering::Amd, Ordering::AmdDelayedDuals] {
            let mut kkt = Kkt::with_parallelism(pattern.clone(), ordering, Parallelism::Two);
            assert!(kkt.symbolic().split().is_some());
            kkt.values_mut().copy_from_slice(&values);
            let mut results = Vec::new();
            for threads in [1, 2] {
                assert_eq!(kkt.set_threads(threads), threads);
                let outcome = kkt.factorize(1e-12, 1e-8);
                assert!(matches!(outcome, FactorOutcome::Factored { .. }));
                let mut z = vec![0.0; n];
                let refinement = kkt.solve_refined(&mut z, &b, 10, 1e-14);
                assert!(refinement.relative_residual <= 1e-14, "{ordering:?}");
                for (zi, wi) in z.iter().zip(&want) {
                    assert!((zi - wi).abs() <= 1e-12 * (1.0 + wi.abs()), "{ordering:?}");
                }
                let factor = kkt.factor();
                results.push((bits(factor.l()), bits(factor.d()), bits(&z)));
            }
            assert_eq!(results[0], results[1], "{ordering:?}");
        }
    }

    /// $A^{-1} b$ by Gaussian elimination with partial pivoting (dense, row-major).
    fn gauss(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
        let n = b.len();
        for c in 0..n {
            let p = (c..n)
                .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
                .unwrap();
            a.swap(c, p);
            b.swap(c, p);
            for r in c + 1..n {
                let f = a[r][c] / a[c][c];
                let (pivot, below) = a.split_at_mut(r);
                for (x, &y) in below[0][c..].iter_mut().zip(&pivot[c][c..]) {
                    *x -= f * y;
                }
                b[r] -= f * b[c];
            }
        }
        for c in (0..n).rev() {
            let sum: f64 = (c + 1..n).map(|k| a[c][k] * b[k]).sum();
            b[c] = (b[c] - sum) / a[c][c];
        }
        b
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
