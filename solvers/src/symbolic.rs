//! The symbolic $LDL^\top$ analysis: indices only, computed once per topology.
//!
//! From the upper KKT pattern and an [`Ordering`] it builds the permuted column lists with
//! their source slots, the elimination tree (Liu's algorithm with path compression) and the
//! column structure of $L$, and the row structure of $L$ too: the columns of each row, in
//! ascending order, which the up-looking numeric phase ([`crate::ldlt`]) walks instead of
//! finding each row's pattern as it runs (the reach of row $k$'s entries up the elimination
//! tree, then a sort, as Davis's LDL (2005) and QDLDL do): the numeric phase then does
//! little but arithmetic. The stored indices are `u16` when the order and the pattern's
//! size allow it, `u32` otherwise ([`Index`]).

use alloc::vec;
use alloc::vec::Vec;

use crate::index::{Index, Indices};
use crate::nested_dissection::{Split, split_candidates};
use crate::ordering::{OrderScratch, Ordering, permutation_into};
use crate::pattern::{KktPattern, NONE};
use crate::room::{Room, refill};

/// Indices-only analysis of a KKT pattern of order $n$ (see module docs).
///
/// Owns the permutation, the pivot signs and the elimination tree ($n$ entries each), the
/// permuted upper matrix's structure ($n + 1$ column pointers, and a row and a value slot per
/// stored entry) and the structure of $L$ twice: by columns ($n + 1$ column pointers, a row
/// index per nonzero) and by rows ($n + 1$ row pointers, a column index per nonzero). Pointers and the permutation are 32-bit; rows and slots are 16-bit when
/// $n \le 65536$ and $\mathrm{nnz}(A) \le 65536$, 32-bit otherwise ([`Symbolic::indices`]). All
/// of it is allocated by [`Symbolic::analyse`] at setup (once per topology), or refilled by
/// [`Symbolic::reanalyse`] within the room of [`Symbolic::reserve`]. Nothing here
/// changes afterwards, and the numeric phase ([`crate::ldlt::Ldlt`]) allocates nothing.
/// Fields are read through the accessors; an [`crate::ldlt::Ldlt`] made for one analysis
/// refuses any other.
#[derive(Clone, Debug)]
pub struct Symbolic {
    /// Matrix order.
    pub(crate) n: usize,
    /// `perm[new] = old`.
    pub(crate) perm: Vec<u32>,
    /// `+1` for a primal unknown, `-1` for a constraint row, in the new order: the expected
    /// pivot signs of the quasi-definite KKT matrix.
    pub(crate) signs: Vec<i8>,
    /// Column pointers of the permuted upper matrix.
    pub(crate) a_ptr: Vec<u32>,
    /// Constraint rows eliminated before any unknown they couple to: their pivot is exactly
    /// 0 whatever the values (an empty row of $L$ and a zero diagonal), so the numeric phase
    /// regularizes them statically and does not count them.
    pub(crate) structural_zero: Vec<bool>,
    /// Elimination tree: parent of each column, or [`NONE`] for a root.
    pub(crate) parent: Vec<u32>,
    /// Column pointers of the strictly lower part of $L$.
    pub(crate) l_ptr: Vec<u32>,
    /// Row pointers of the strictly lower part of $L$ (its columns in
    /// [`Arrays::r_col`]).
    pub(crate) r_ptr: Vec<u32>,
    /// The rows and slots, in the width chosen by [`Symbolic::analyse`].
    pub(crate) structure: Structure,
    /// Hash of everything the numeric phase reads (see [`Symbolic::fingerprint`]).
    pub(crate) fingerprint: u64,
    /// The two halves and the separator of a split order ([`Symbolic::analyse_split`]).
    pub(crate) split: Option<Split>,
    /// Working memory of [`Symbolic::reanalyse`], kept between analyses.
    scratch: AnalysisScratch,
}

/// The working memory of an analysis: the order's, the inverse permutation, and the
/// per-column marks and counters of the tree and column walks. It is kept between analyses
/// only once [`Symbolic::reserve`] made room (an analysis that will run again); otherwise
/// each analysis frees it.
#[derive(Debug, Default)]
struct AnalysisScratch {
    /// [`Symbolic::reserve`] was called: keep the scratch.
    kept: bool,
    order: OrderScratch,
    inverse: Vec<u32>,
    next: Vec<u32>,
    row_empty: Vec<bool>,
    mark: Vec<u32>,
    ancestor: Vec<u32>,
}

impl Clone for AnalysisScratch {
    /// Empty: the scratch holds nothing from one analysis to the next.
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// The index arrays of a [`Symbolic`] in one of the two widths.
#[derive(Clone, Debug)]
pub(crate) enum Structure {
    /// `u16` rows and slots.
    Narrow(Arrays<u16>),
    /// `u32` rows and slots.
    Wide(Arrays<u32>),
}

/// The index arrays of a [`Symbolic`]: `nnz(A)` rows and slots of the permuted upper
/// matrix, `nnz(L)` rows of $L$.
#[derive(Clone, Debug)]
pub(crate) struct Arrays<I> {
    /// Row (new index) of each permuted upper entry.
    pub a_row: Vec<I>,
    /// Slot in the KKT value array of each permuted upper entry.
    pub a_slot: Vec<I>,
    /// Row indices of $L$ (ascending within a column).
    pub l_row: Vec<I>,
    /// Column indices of $L$ by rows (ascending within a row): row $k$'s columns at
    /// `r_ptr[k]..r_ptr[k + 1]`, the order in which the up-looking factor eliminates them.
    pub r_col: Vec<I>,
}

impl Symbolic {
    /// Analyses `pattern` under `ordering`.
    #[must_use]
    pub fn analyse(pattern: &KktPattern, ordering: Ordering) -> Self {
        let mut symbolic = Self::empty();
        symbolic.reanalyse(pattern, ordering);
        symbolic
    }

    /// [`Symbolic::analyse`] into this analysis's arrays, which it replaces: no allocation
    /// when they hold the new analysis (and the index width stays), for the AMD orders.
    pub fn reanalyse(&mut self, pattern: &KktPattern, ordering: Ordering) {
        let mut perm = core::mem::take(&mut self.perm);
        permutation_into(pattern, ordering, &mut perm, &mut self.scratch.order);
        if !self.scratch.kept {
            // Not reserved: free the order's stack before the next arrays are made, as a
            // one-off analysis does (a heap peak matters on a microcontroller).
            self.scratch.order = OrderScratch::default();
        }
        self.of_permutation_into(pattern, perm);
        if !self.scratch.kept {
            self.scratch = AnalysisScratch::default();
        }
    }

    /// Room for an analysis of order `n` with `nnz` stored entries and `nnz_l` entries in
    /// $L$ (in the index width of the current analysis; a change of width allocates).
    pub fn reserve(&mut self, n: usize, nnz: usize, nnz_l: usize) {
        for v in [
            &mut self.perm,
            &mut self.a_ptr,
            &mut self.parent,
            &mut self.l_ptr,
            &mut self.r_ptr,
        ] {
            v.room_for(n + 1);
        }
        self.signs.room_for(n);
        self.structural_zero.room_for(n);
        let s = &mut self.scratch;
        s.kept = true;
        s.order.reserve(n, nnz);
        for v in [&mut s.inverse, &mut s.next, &mut s.mark, &mut s.ancestor] {
            v.room_for(n + 1);
        }
        s.row_empty.room_for(n);
        match &mut self.structure {
            Structure::Narrow(a) => a.reserve(nnz, nnz_l),
            Structure::Wide(a) => a.reserve(nnz, nnz_l),
        }
    }

    /// An analysis of nothing (order 0), to be filled.
    pub(crate) fn empty() -> Self {
        Self {
            n: 0,
            perm: Vec::new(),
            signs: Vec::new(),
            a_ptr: Vec::new(),
            structural_zero: Vec::new(),
            parent: Vec::new(),
            l_ptr: vec![0],
            r_ptr: vec![0],
            structure: Structure::Narrow(Arrays::default()),
            fingerprint: 0,
            split: None,
            scratch: AnalysisScratch::default(),
        }
    }

    /// Analyses `pattern` in a split order ([`crate::nested_dissection`]): two halves, each
    /// ordered by `ordering` on its own, then the separator between them. Its factor can
    /// run on two threads ([`crate::ldlt::Ldlt::set_threads`]); the parts are in
    /// [`Symbolic::split`], and the fingerprint covers them. Of the candidate separators it
    /// keeps the one with the least two-thread work: with $w_j = c_j (c_j + 1)/2$ for a
    /// column of $c_j$ off-diagonal entries, $\max(\sum_A w_j, \sum_B w_j) + \sum_S w_j$
    /// (each half's columns are eliminated by its thread, the separator's after both).
    #[must_use]
    pub fn analyse_split(pattern: &KktPattern, ordering: Ordering) -> Self {
        let mut best: Option<(f64, Self, Split)> = None;
        for (perm, split) in split_candidates(pattern, ordering) {
            let symbolic = Self::of_permutation(pattern, perm);
            let work = |columns: core::ops::Range<usize>| -> f64 {
                columns
                    .map(|j| {
                        let c = f64::from(symbolic.l_ptr[j + 1] - symbolic.l_ptr[j]);
                        c * (c + 1.0) / 2.0
                    })
                    .sum()
            };
            let cost = work(0..split.a).max(work(split.a..split.b)) + work(split.b..symbolic.n);
            if best.as_ref().is_none_or(|(least, ..)| cost < *least) {
                best = Some((cost, symbolic, split));
            }
        }
        let Some((_, mut symbolic, split)) = best else {
            return Self::analyse(pattern, ordering);
        };
        symbolic.fingerprint = Fingerprint(symbolic.fingerprint)
            .word(split.a as u32)
            .word(split.b as u32)
            .finish();
        symbolic.split = Some(split);
        symbolic
    }

    /// The analysis of `pattern` in the order `perm` (`perm[new] = old`), in the narrowest
    /// index width that holds it.
    fn of_permutation(pattern: &KktPattern, perm: Vec<u32>) -> Self {
        let mut symbolic = Self::empty();
        symbolic.of_permutation_into(pattern, perm);
        symbolic
    }

    /// [`Symbolic::of_permutation`] into this analysis's arrays.
    fn of_permutation_into(&mut self, pattern: &KktPattern, perm: Vec<u32>) {
        let n = pattern.order();
        self.perm = perm;
        self.signs.clear();
        self.signs
            .extend((0..n).map(|k| signs_of(&self.perm, pattern.dofs, k)));
        let old = core::mem::replace(&mut self.structure, Structure::Narrow(Arrays::default()));
        if n <= u16::MAX as usize + 1 && pattern.nnz() <= u16::MAX as usize + 1 {
            let arrays = match old {
                Structure::Narrow(a) => a,
                Structure::Wide(_) => Arrays::default(),
            };
            self.fill(pattern, arrays, Structure::Narrow);
        } else {
            let arrays = match old {
                Structure::Wide(a) => a,
                Structure::Narrow(_) => Arrays::default(),
            };
            self.fill(pattern, arrays, Structure::Wide);
        }
    }

    /// [`Symbolic::analyse`] with indices of type `I` (each at most `I::MAX`), wrapped by
    /// `wrap`.
    #[cfg(test)]
    pub(crate) fn build<I: Index>(
        pattern: &KktPattern,
        perm: Vec<u32>,
        signs: Vec<i8>,
        wrap: fn(Arrays<I>) -> Structure,
    ) -> Self {
        let mut symbolic = Self::empty();
        symbolic.perm = perm;
        symbolic.signs = signs;
        symbolic.fill(pattern, Arrays::default(), wrap);
        symbolic
    }

    /// Fills everything but the permutation and the signs (set already) for `pattern`, with
    /// indices of type `I` in `arrays`, wrapped by `wrap`.
    fn fill<I: Index>(
        &mut self,
        pattern: &KktPattern,
        mut arrays: Arrays<I>,
        wrap: fn(Arrays<I>) -> Structure,
    ) {
        let n = pattern.order();
        let s = &mut self.scratch;
        refill(&mut s.inverse, n, 0);
        for (new, &old) in self.perm.iter().enumerate() {
            s.inverse[old as usize] = new as u32;
        }
        let a = &mut arrays;
        permuted_upper(pattern, &s.inverse, &mut self.a_ptr, a, &mut s.next);
        elimination_tree(n, &self.a_ptr, &a.a_row, &mut self.parent, &mut s.ancestor);
        column_counts(
            &self.a_ptr,
            &a.a_row,
            &self.parent,
            &mut self.l_ptr,
            &mut s.row_empty,
            &mut s.mark,
        );
        self.structural_zero.clear();
        self.structural_zero
            .extend((0..n).map(|k| self.signs[k] < 0 && s.row_empty[k]));
        column_rows(
            &self.a_ptr,
            &a.a_row,
            &self.parent,
            &self.l_ptr,
            &mut a.l_row,
            &mut s.next,
            &mut s.mark,
        );
        row_columns(&self.l_ptr, &a.l_row, &mut self.r_ptr, &mut a.r_col);
        self.fingerprint = Fingerprint::new()
            .words(&self.perm, |&w| w)
            .words(&self.a_ptr, |&w| w)
            .words(&a.a_row, |w| w.get() as u32)
            .words(&a.a_slot, |w| w.get() as u32)
            .words(&self.l_ptr, |&w| w)
            .all(&self.signs, |&s| u32::from(s > 0))
            .finish();
        self.n = n;
        self.structure = wrap(arrays);
        self.split = None;
    }

    /// Matrix order $n$ (`dofs + rows` of the analysed pattern).
    #[inline]
    #[must_use]
    pub fn order(&self) -> usize {
        self.n
    }

    /// The fill-reducing permutation, `perm()[new] = old`: $n$ entries, each of $0..n$ once.
    #[inline]
    #[must_use]
    pub fn perm(&self) -> &[u32] {
        &self.perm
    }

    /// Expected pivot sign per new index, $n$ entries: `+1` for a primal unknown, `-1` for a
    /// constraint row (the inertia of the quasi-definite KKT matrix).
    #[inline]
    #[must_use]
    pub fn signs(&self) -> &[i8] {
        &self.signs
    }

    /// Per new index, $n$ entries: `true` for a constraint row eliminated before any unknown
    /// it couples to (an empty row of $L$; its pivot is its stored diagonal alone, which the
    /// numeric phase regularizes statically when it is exactly zero, see [`crate::ldlt`]).
    #[inline]
    #[must_use]
    pub fn structural_zero(&self) -> &[bool] {
        &self.structural_zero
    }

    /// The elimination tree, $n$ entries: the parent of each column (new order), or
    /// [`NONE`] for a root.
    #[inline]
    #[must_use]
    pub fn etree(&self) -> &[u32] {
        &self.parent
    }

    /// Column pointers of the strictly lower part of $L$, $n + 1$ entries: column $j$'s row
    /// indices and values are at `l_col_ptr()[j]..l_col_ptr()[j + 1]` of
    /// [`Symbolic::l_row_idx`] and [`crate::ldlt::Ldlt::l`].
    #[inline]
    #[must_use]
    pub fn l_col_ptr(&self) -> &[u32] {
        &self.l_ptr
    }

    /// Row indices (new order) of the strictly lower part of $L$, [`Symbolic::nnz_l`]
    /// entries, ascending within each column, in the analysis's index width.
    #[inline]
    #[must_use]
    pub fn l_row_idx(&self) -> Indices<'_> {
        match &self.structure {
            Structure::Narrow(a) => Indices::U16(&a.l_row),
            Structure::Wide(a) => Indices::U32(&a.l_row),
        }
    }

    /// Nonzeros of the strictly lower part of $L$ (the length of the numeric factor's
    /// values).
    #[inline]
    #[must_use]
    pub fn nnz_l(&self) -> usize {
        self.l_ptr[self.n] as usize
    }

    /// The analysis's index width and the bytes of its index arrays (everything but the
    /// permutation, the signs, the tree and the two pointer arrays): $L$'s rows, and the
    /// permuted upper matrix's rows and value slots.
    #[must_use]
    pub fn indices(&self) -> (IndexWidth, usize) {
        match &self.structure {
            Structure::Narrow(a) => (IndexWidth::U16, 2 * (a.l_row.len() + 2 * a.a_row.len())),
            Structure::Wide(a) => (IndexWidth::U32, 4 * (a.l_row.len() + 2 * a.a_row.len())),
        }
    }

    /// A 64-bit hash (FNV-1a over the 32-bit words) of the permutation, the permuted upper
    /// structure with its value slots, $L$'s column pointers and the pivot signs, computed once by
    /// [`Symbolic::analyse`]. Two analyses with equal fingerprints and orders lay out the
    /// same factorization; [`crate::ldlt::Ldlt`] compares it to refuse a symbolic it was
    /// not made for.
    #[inline]
    #[must_use]
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    /// The two halves and the separator of an order made by [`Symbolic::analyse_split`]
    /// (`None` for [`Symbolic::analyse`]).
    #[inline]
    #[must_use]
    pub fn split(&self) -> Option<Split> {
        self.split
    }

    /// Floating-point operations of one numeric factorization: for a column with $c_j$
    /// off-diagonal entries, $c_j(c_j - 1)$ for the updates it makes to later rows
    /// (a multiply and a subtract each) plus $3 c_j$ for its scaling and pivot updates.
    #[must_use]
    pub fn factor_flops(&self) -> f64 {
        (0..self.n)
            .map(|j| {
                let c = f64::from(self.l_ptr[j + 1] - self.l_ptr[j]);
                c * (c - 1.0) + 3.0 * c
            })
            .sum()
    }
}

/// The index width [`Symbolic::analyse`] chose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum IndexWidth {
    /// Two bytes per stored row and slot.
    U16,
    /// Four bytes per stored row and slot.
    U32,
}

impl<I> Default for Arrays<I> {
    fn default() -> Self {
        Self {
            a_row: Vec::new(),
            a_slot: Vec::new(),
            l_row: Vec::new(),
            r_col: Vec::new(),
        }
    }
}

impl<I: Index> Arrays<I> {
    /// Room for `nnz` stored entries and `nnz_l` entries of $L$.
    fn reserve(&mut self, nnz: usize, nnz_l: usize) {
        self.a_row.room_for(nnz);
        self.a_slot.room_for(nnz);
        self.l_row.room_for(nnz_l);
        self.r_col.room_for(nnz_l);
    }
}

/// The upper triangle of $P A P^\top$ in compressed columns: `a_ptr` ($n + 1$ column
/// pointers) and, per entry, its row (new index) and its slot in the pattern's value array
/// (`arrays.a_row`, `arrays.a_slot`); `next` is scratch. Entry $(r, c)$ lands in column
/// $\max(r', c')$ at row $\min$.
fn permuted_upper<I: Index>(
    pattern: &KktPattern,
    inverse: &[u32],
    a_ptr: &mut Vec<u32>,
    arrays: &mut Arrays<I>,
    next: &mut Vec<u32>,
) {
    let n = pattern.order();
    refill(a_ptr, n + 1, 0);
    for c in 0..n {
        for &r in &pattern.row_idx[pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize] {
            let (i, j) = (inverse[r as usize], inverse[c]);
            a_ptr[i.max(j) as usize + 1] += 1;
        }
    }
    prefix_sum(a_ptr);
    next.clear();
    next.extend_from_slice(a_ptr);
    refill(&mut arrays.a_row, pattern.nnz(), I::new(0));
    refill(&mut arrays.a_slot, pattern.nnz(), I::new(0));
    for c in 0..n {
        for s in pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize {
            let (i, j) = (inverse[pattern.row_idx[s] as usize], inverse[c]);
            let col = i.max(j) as usize;
            let at = next[col] as usize;
            arrays.a_row[at] = I::new(i.min(j) as usize);
            arrays.a_slot[at] = I::new(s);
            next[col] += 1;
        }
    }
}

/// Column pointers of $L$ and the empty rows: `l_ptr` gets $n + 1$ pointers (the prefix sum
/// of each column's count of row-pattern entries) and `row_empty`, per row, whether its
/// pattern is empty; `mark` is scratch.
fn column_counts<I: Index>(
    a_ptr: &[u32],
    a_row: &[I],
    parent: &[u32],
    l_ptr: &mut Vec<u32>,
    row_empty: &mut Vec<bool>,
    mark: &mut Vec<u32>,
) {
    let n = parent.len();
    refill(l_ptr, n + 1, 0);
    refill(row_empty, n, true);
    refill(mark, n, NONE);
    for (k, empty) in row_empty.iter_mut().enumerate() {
        row_walk(k, a_ptr, a_row, parent, mark, |j| {
            l_ptr[j + 1] += 1;
            *empty = false;
        });
    }
    prefix_sum(l_ptr);
}

/// Row indices of $L$ into `l_row`, ascending within each column: row $k$ is appended to
/// every column of its pattern, rows in increasing order; `fill` and `mark` are scratch.
fn column_rows<I: Index>(
    a_ptr: &[u32],
    a_row: &[I],
    parent: &[u32],
    l_ptr: &[u32],
    l_row: &mut Vec<I>,
    fill: &mut Vec<u32>,
    mark: &mut Vec<u32>,
) {
    let n = parent.len();
    fill.clear();
    fill.extend_from_slice(&l_ptr[..n]);
    refill(l_row, l_ptr[n] as usize, I::new(0));
    refill(mark, n, NONE);
    for k in 0..n {
        row_walk(k, a_ptr, a_row, parent, mark, |j| {
            l_row[fill[j] as usize] = I::new(k);
            fill[j] += 1;
        });
    }
}

/// The row structure of $L$ from its column structure (`l_ptr`, `l_row`): `r_ptr` gets
/// $n + 1$ row pointers and `r_col` each row's columns, ascending (the columns are read in
/// order, so each row receives them in order).
fn row_columns<I: Index>(l_ptr: &[u32], l_row: &[I], r_ptr: &mut Vec<u32>, r_col: &mut Vec<I>) {
    let n = l_ptr.len() - 1;
    refill(r_ptr, n + 1, 0);
    for &r in l_row {
        r_ptr[r.get() + 1] += 1;
    }
    prefix_sum(r_ptr);
    refill(r_col, l_row.len(), I::new(0));
    // r_ptr[r] serves as row r's next free position, then is shifted back.
    for j in 0..n {
        for &r in &l_row[l_ptr[j] as usize..l_ptr[j + 1] as usize] {
            let at = &mut r_ptr[r.get()];
            r_col[*at as usize] = I::new(j);
            *at += 1;
        }
    }
    for k in (1..=n).rev() {
        r_ptr[k] = r_ptr[k - 1];
    }
    r_ptr[0] = 0;
}

/// Calls `visit` on every column $j < k$ of row $k$ of $L$: the elimination-tree paths from
/// the entries of column $k$ of the permuted upper matrix up to $k$ (`mark` holds, per
/// column, the last row that visited it).
fn row_walk<I: Index>(
    k: usize,
    a_ptr: &[u32],
    a_row: &[I],
    parent: &[u32],
    mark: &mut [u32],
    mut visit: impl FnMut(usize),
) {
    mark[k] = k as u32;
    for &i in &a_row[a_ptr[k] as usize..a_ptr[k + 1] as usize] {
        let mut j = i.get();
        while mark[j] != k as u32 {
            mark[j] = k as u32;
            visit(j);
            j = parent[j] as usize;
        }
    }
}

/// Expected pivot sign of new index `k`.
fn signs_of(perm: &[u32], dofs: usize, k: usize) -> i8 {
    if (perm[k] as usize) < dofs { 1 } else { -1 }
}

/// FNV-1a over 32-bit words ([`Symbolic::fingerprint`]).
struct Fingerprint(u64);

impl Fingerprint {
    /// The FNV-1a offset basis.
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    /// Hashes `array`'s length, then its words through `word` (the length first, so that
    /// moving a word from one array to the next changes the hash).
    fn words<W>(self, array: &[W], word: impl Fn(&W) -> u32) -> Self {
        self.word(array.len() as u32).all(array, word)
    }

    /// Hashes `array`'s words through `word`, without its length.
    fn all<W>(mut self, array: &[W], word: impl Fn(&W) -> u32) -> Self {
        for w in array {
            self = self.word(word(w));
        }
        self
    }

    /// Hashes one word, its bytes little-endian.
    fn word(mut self, word: u32) -> Self {
        const PRIME: u64 = 0x0000_0100_0000_01b3;
        for byte in word.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(PRIME);
        }
        self
    }

    /// The hash.
    fn finish(self) -> u64 {
        self.0
    }
}

/// In-place exclusive prefix sum of counts stored at `[1..]`.
fn prefix_sum(ptr: &mut [u32]) {
    for k in 1..ptr.len() {
        ptr[k] += ptr[k - 1];
    }
}

/// Elimination tree of a symmetric matrix from its upper columns into `parent` (Liu, with
/// path compression through `ancestor`, scratch).
fn elimination_tree<I: Index>(
    n: usize,
    a_ptr: &[u32],
    a_row: &[I],
    parent: &mut Vec<u32>,
    ancestor: &mut Vec<u32>,
) {
    refill(parent, n, NONE);
    refill(ancestor, n, NONE);
    for k in 0..n {
        for &i in &a_row[a_ptr[k] as usize..a_ptr[k + 1] as usize] {
            let mut r = i.get();
            while r < k {
                let next = ancestor[r];
                ancestor[r] = k as u32;
                if next == NONE {
                    parent[r] = k as u32;
                    break;
                }
                r = next as usize;
            }
        }
    }
}
