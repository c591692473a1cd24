//! The KKT sparsity pattern and the scatter maps from each term's local block into it.
//!
//! Unknowns are the free coordinates ("dofs") numbered node-major, followed by one unknown per
//! constraint row (its multiplier). The KKT matrix
//! $$K = \begin{bmatrix} M/h^2 + \nabla^2 V\ (+\textstyle\sum_l \lambda_l \nabla^2 C_l) & \nabla C^\top \cr \nabla C & 0 \end{bmatrix}$$
//! (DESIGN.md "Time step", seed `000_…` eq. 3-4) is stored as its upper triangle in compressed
//! sparse columns with sorted rows and every diagonal entry present. Each Jacobian entry of
//! a term has a precomputed slot (index into the value array) or [`NONE`] when it falls on
//! an eliminated coordinate. A term's Hessian block is found by node pair: a node's free
//! coordinates are consecutive dofs and consecutive rows of every column that holds one of
//! them, so one depth per pair of distinct nodes places all nine of its entries
//! (`hessian_slot`). Assembly is then a scatter through these maps: no search, no
//! allocation.

use alloc::vec::Vec;
use folio_kernels::{Constraint, Potential, Real};

use crate::error::SolverError;
use crate::model::{ConstraintSet, Model, PotentialSet, TermVisitor};
use crate::room::{Room, refill, scaled};
use crate::slots::Slots;

/// Marks an eliminated coordinate or a dropped (lower-triangle) entry in the maps (defined
/// with the index types, [`crate::index::NONE`]).
pub use crate::index::NONE;

/// Where one term family's maps start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Family {
    /// Number of terms.
    pub terms: usize,
    /// Nodes per term.
    pub nodes: usize,
    /// Constraint rows per term (0 for potentials).
    pub rows: usize,
    /// Whether the family's Hessian blocks are assembled (always for potentials; for
    /// nonlinear constraints when the constraint Hessian is on).
    pub has_hessian: bool,
    /// Offset into [`KktPattern::local_dofs`] (`3 N` entries per term).
    pub dof_offset: usize,
    /// Whether a term's Hessian block is scattered as its upper local triangle ($p \le q$,
    /// which with its mirror $(q, p)$ covers the block); `false` when a term repeats a dof,
    /// whose mirrored entries then land on one slot: the full local block is scattered, row
    /// by row, in its order.
    pub hessian_upper: bool,
    /// Offset into [`KktPattern::hessian_depths`] ([`Family::hessian_pairs_per_term`] per
    /// term).
    pub hessian_offset: usize,
    /// Offset into [`KktPattern::jacobian_slots`] (`3 N R` per term).
    pub jacobian_offset: usize,
    /// First global constraint row.
    pub first_row: usize,
}

impl Family {
    /// Hessian depths per term ([`KktPattern::hessian_depths`]): none without a Hessian,
    /// else one per pair of local nodes $a < b$, $N(N - 1)/2$.
    #[inline]
    #[must_use]
    pub fn hessian_pairs_per_term(&self) -> usize {
        if self.has_hessian {
            self.nodes * (self.nodes - 1) / 2
        } else {
            0
        }
    }
}

/// The upper-triangle KKT pattern of a model and every term's scatter map.
///
/// Owns the coordinate numbering (`3 * nodes` and `dofs` entries), the compressed upper
/// columns (`order + 1` pointers, `nnz` rows) and the term maps (`3 N` local dofs per term,
/// $N(N - 1)/2$ Hessian depths per term with a Hessian, `3 N R` Jacobian slots per term),
/// all allocated by [`KktPattern::build`] at setup. Fields are read through the accessors.
#[derive(Clone, Debug, Default)]
pub struct KktPattern {
    /// Number of free coordinates (primal unknowns).
    pub(crate) dofs: usize,
    /// Number of constraint rows (dual unknowns).
    pub(crate) rows: usize,
    /// `dof_of[3 * node + axis]`: the free coordinate's index, or [`NONE`] when eliminated.
    pub(crate) dof_of: Vec<u32>,
    /// `coordinate_of[dof] = 3 * node + axis`.
    pub(crate) coordinate_of: Vec<u32>,
    /// Column pointers, `dofs + rows + 1` entries.
    pub(crate) col_ptr: Vec<u32>,
    /// Row index of each stored entry; rows are sorted within a column and the last entry of
    /// every column is its diagonal.
    pub(crate) row_idx: Vec<u32>,
    pub(crate) families: Vec<Family>,
    pub(crate) local_dofs: Vec<u32>,
    /// The Hessian map, by node pair: for each term with a Hessian and each pair of its
    /// local nodes $a < b$, row by row, how deep the first free row of the one numbered
    /// first lies in the columns of the other (`slot - col_ptr[column]`, the same in each
    /// of that node's columns), or [`NONE`] when either node has no free coordinate or the
    /// two are one node ([`hessian_slot`]; [`Slots`]: `u16` for fewer than 65,535 stored
    /// entries). A pair's nine slots were nine map entries; this keeps one.
    pub(crate) hessian_depths: Slots,
    /// The Jacobian scatter map, in the same width.
    pub(crate) jacobian_slots: Slots,
    /// Whether the constraint Hessian blocks are part of the pattern.
    pub(crate) with_constraint_hessian: bool,
}

impl KktPattern {
    /// Number of free coordinates (primal unknowns): the first `dofs()` rows and columns.
    #[inline]
    #[must_use]
    pub fn dofs(&self) -> usize {
        self.dofs
    }

    /// Number of constraint rows (dual unknowns): the last `rows()` rows and columns.
    #[inline]
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Order of the KKT matrix, `dofs + rows`.
    #[inline]
    #[must_use]
    pub fn order(&self) -> usize {
        self.dofs + self.rows
    }

    /// Number of stored (upper-triangle) entries.
    #[inline]
    #[must_use]
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Per model coordinate `3 * node + axis` (`3 * nodes` entries): its free coordinate's
    /// index, or [`NONE`] when the model eliminates it.
    #[inline]
    #[must_use]
    pub fn dof_of(&self) -> &[u32] {
        &self.dof_of
    }

    /// Per free coordinate (`dofs` entries): its model coordinate `3 * node + axis`.
    #[inline]
    #[must_use]
    pub fn coordinate_of(&self) -> &[u32] {
        &self.coordinate_of
    }

    /// Column pointers of the upper triangle, `order + 1` entries: column `c`'s rows and
    /// value slots are `col_ptr()[c]..col_ptr()[c + 1]`.
    #[inline]
    #[must_use]
    pub fn col_ptr(&self) -> &[u32] {
        &self.col_ptr
    }

    /// Row index of each stored entry (`nnz` entries): sorted within a column, the last
    /// entry of every column its diagonal.
    #[inline]
    #[must_use]
    pub fn row_idx(&self) -> &[u32] {
        &self.row_idx
    }

    /// Whether the constraint Hessian blocks are part of the pattern.
    #[inline]
    #[must_use]
    pub fn with_constraint_hessian(&self) -> bool {
        self.with_constraint_hessian
    }

    /// Slot of diagonal entry `k` (the last entry of column `k`).
    #[inline]
    #[must_use]
    pub fn diagonal_slot(&self, k: usize) -> usize {
        self.col_ptr[k + 1] as usize - 1
    }

    /// Builds the pattern of `model`; `with_constraint_hessian` adds the constraint stencils'
    /// node couplings to the primal block.
    ///
    /// # Errors
    /// [`SolverError::NodeOutOfRange`] for a term naming a missing node,
    /// [`SolverError::TooLarge`] beyond 32-bit indices.
    pub fn build<T: Real, M: Model<T>>(
        model: &M,
        with_constraint_hessian: bool,
    ) -> Result<Self, SolverError> {
        let mut pattern = Self::default();
        pattern.rebuild(model, with_constraint_hessian, &mut Vec::new())?;
        pattern.shrink_to_fit();
        Ok(pattern)
    }

    /// [`KktPattern::build`] into this pattern's buffers, with `entries` as the buffer of
    /// the entries' keys: no allocation when the buffers hold the new pattern. Returns how
    /// many keys `entries` held before duplicates merged (the room it needed). On error the
    /// pattern is left partly built (rebuild it before use).
    ///
    /// # Errors
    /// As [`KktPattern::build`].
    pub fn rebuild<T: Real, M: Model<T>>(
        &mut self,
        model: &M,
        with_constraint_hessian: bool,
        entries: &mut Vec<u64>,
    ) -> Result<usize, SolverError> {
        let node_count = model.node_count();
        if node_count.saturating_mul(3) >= NONE as usize {
            return Err(SolverError::TooLarge);
        }
        self.dof_of.clear();
        self.coordinate_of.clear();
        self.dof_of.reserve_exact(3 * node_count);
        for c in 0..3 * node_count {
            if model.is_fixed(c / 3, c % 3) {
                self.dof_of.push(NONE);
            } else {
                self.dof_of.push(self.coordinate_of.len() as u32);
                self.coordinate_of.push(c as u32);
            }
        }
        let mut families = core::mem::take(&mut self.families);
        let mut local_dofs = core::mem::take(&mut self.local_dofs);
        families.clear();
        local_dofs.clear();
        entries.clear();
        let mut declare = Declare {
            dof_of: &self.dof_of,
            node_count,
            with_constraint_hessian,
            families,
            local_dofs,
            entries,
            rows: 0,
            jacobian_len: 0,
            error: None,
        };
        model.visit_terms(&mut declare);
        let Declare {
            families,
            local_dofs,
            rows,
            jacobian_len,
            error,
            ..
        } = declare;
        self.families = families;
        self.local_dofs = local_dofs;
        if let Some(e) = error {
            return Err(e);
        }
        self.dofs = self.coordinate_of.len();
        self.rows = rows;
        self.with_constraint_hessian = with_constraint_hessian;
        let keys = compress(self, entries)?;
        self.jacobian_slots.clear_for(self.row_idx.len());
        self.jacobian_slots.room_for(jacobian_len);
        self.fill_slots();
        Ok(keys)
    }

    /// Every array of the pattern, for what is done to all of them alike.
    fn arrays_mut(&mut self) -> [&mut Vec<u32>; 5] {
        [
            &mut self.dof_of,
            &mut self.coordinate_of,
            &mut self.col_ptr,
            &mut self.row_idx,
            &mut self.local_dofs,
        ]
    }

    /// The scatter maps, for what is done to both alike.
    fn maps_mut(&mut self) -> [&mut Slots; 2] {
        [&mut self.hessian_depths, &mut self.jacobian_slots]
    }

    /// Frees the room of the arrays beyond their lengths (a pattern built once).
    pub fn shrink_to_fit(&mut self) {
        for v in self.arrays_mut() {
            v.shrink_to_fit();
        }
        for m in self.maps_mut() {
            m.shrink_to_fit();
        }
    }

    /// Room for a pattern `scale` times this one's size (every array in proportion).
    pub fn reserve_scaled(&mut self, scale: f64) {
        for v in self.arrays_mut() {
            v.room_for(scaled(v.len(), scale));
        }
        for m in self.maps_mut() {
            m.reserve_scaled(scale);
        }
    }

    /// Chooses each family's Hessian layout and fills the slot maps ([`KktPattern::fill_maps`]).
    fn fill_slots(&mut self) {
        let mut families = core::mem::take(&mut self.families);
        for f in &mut families {
            let s = 3 * f.nodes;
            f.hessian_upper =
                (0..f.terms).all(|t| !repeats(&self.local_dofs[f.dof_offset + t * s..][..s]));
        }
        self.families = families;
        self.fill_maps();
    }

    /// Fills the Hessian depths and the Jacobian slots from the local dofs.
    ///
    /// A pair of distinct nodes costs one search ([`locate`]) for the depth of the first
    /// free row of the node numbered first in the first column of the other. A Jacobian
    /// row's slots are guessed one past the previous one when the local dofs follow each
    /// other (a column's rows are sorted and distinct), and a guess is kept when the row
    /// stored there is the one sought; only the first free dof of each node is searched.
    pub(crate) fn fill_maps(&mut self) {
        let families = core::mem::take(&mut self.families);
        let nnz = self.row_idx.len();
        self.hessian_depths.clear_for(nnz);
        self.jacobian_slots.clear_for(nnz);
        let pairs_len = families
            .iter()
            .map(|f| f.terms * f.hessian_pairs_per_term())
            .sum();
        self.hessian_depths.room_for(pairs_len);
        let (col_ptr, row_idx) = (&self.col_ptr, &self.row_idx);
        let mut families = families;
        for f in &mut families {
            f.hessian_offset = self.hessian_depths.len();
            f.jacobian_offset = self.jacobian_slots.len();
            let s = 3 * f.nodes;
            for t in 0..f.terms {
                let local = &self.local_dofs[f.dof_offset + t * s..][..s];
                if f.has_hessian {
                    for a in 0..f.nodes {
                        let first_a = first_free(&local[3 * a..3 * a + 3]);
                        for b in a + 1..f.nodes {
                            let first_b = first_free(&local[3 * b..3 * b + 3]);
                            let depth = if first_a == NONE || first_b == NONE || first_a == first_b
                            {
                                NONE
                            } else {
                                let (row, col) = (first_a.min(first_b), first_a.max(first_b));
                                let slot = locate(col_ptr, row_idx, row, col, NONE);
                                debug_assert!(slot != NONE, "a coupled pair is stored");
                                slot - col_ptr[col as usize]
                            };
                            self.hessian_depths.push(depth);
                        }
                    }
                    debug_assert!(
                        self.depths_place_every_entry(f, t),
                        "the Hessian depths of term {t}"
                    );
                }
                // Whether local dof `p` is one past local dof `p - 1` (both free).
                let follows =
                    |p: usize| p > 0 && local[p - 1] != NONE && local[p - 1] + 1 == local[p];
                for r in 0..f.rows {
                    let col = (self.dofs + f.first_row + t * f.rows + r) as u32;
                    let mut previous = NONE;
                    for (p, &a) in local.iter().enumerate() {
                        let slot = if a == NONE {
                            NONE
                        } else {
                            let guess = if follows(p) && previous != NONE {
                                previous + 1
                            } else {
                                NONE
                            };
                            locate(col_ptr, row_idx, a, col, guess)
                        };
                        self.jacobian_slots.push(slot);
                        previous = slot;
                    }
                }
            }
        }
        self.families = families;
    }

    /// Whether every free entry of term `t`'s Hessian block lands, through the depths, on
    /// the stored upper entry of its dofs (the depths' premise, checked in debug builds).
    fn depths_place_every_entry(&self, f: &Family, t: usize) -> bool {
        let s = 3 * f.nodes;
        let local = &self.local_dofs[f.dof_offset + t * s..][..s];
        (0..s).all(|p| {
            (0..s).all(|q| {
                let (a, b) = (local[p], local[q]);
                match self.hessian_slot(f, t, p, q) {
                    None => a == NONE || b == NONE,
                    Some(slot) => {
                        let col = a.max(b) as usize;
                        (self.col_ptr[col] as usize..self.col_ptr[col + 1] as usize).contains(&slot)
                            && self.row_idx[slot] == a.min(b)
                    }
                }
            })
        })
    }

    /// The slot of the stored (upper) entry of local dofs `(p, q)` of term `t` of family
    /// `f` (a family with a Hessian), or `None` when either is eliminated
    /// ([`hessian_slot`]).
    #[must_use]
    pub(crate) fn hessian_slot(&self, f: &Family, t: usize, p: usize, q: usize) -> Option<usize> {
        let s = 3 * f.nodes;
        let local = &self.local_dofs[f.dof_offset + t * s..][..s];
        let (a, b) = (local[p], local[q]);
        if a == NONE || b == NONE {
            return None;
        }
        let (na, nb) = (p / 3, q / 3);
        let depth = if na == nb {
            NONE
        } else {
            let (lo, hi) = (na.min(nb), na.max(nb));
            let at =
                f.hessian_offset + t * f.hessian_pairs_per_term() + pair_index(f.nodes, lo, hi);
            self.hessian_depths.get(at)
        };
        let first = |n: usize| first_free(&local[3 * n..3 * n + 3]);
        Some(hessian_slot(
            &self.col_ptr,
            a,
            b,
            first(na),
            first(nb),
            depth,
        ))
    }
}

/// The first free dof of a node's three local dofs, or [`NONE`] when all are eliminated
/// (its free dofs are consecutive, in axis order).
#[inline(always)]
pub(crate) fn first_free(node_dofs: &[u32]) -> u32 {
    node_dofs
        .iter()
        .copied()
        .find(|&d| d != NONE)
        .unwrap_or(NONE)
}

/// Index of local node pair $a < b$ among a term's $N(N - 1)/2$ pairs, row by row.
#[inline(always)]
pub(crate) fn pair_index(nodes: usize, a: usize, b: usize) -> usize {
    a * (2 * nodes - a - 1) / 2 + (b - a - 1)
}

/// Slot of the stored (upper) entry of free dofs `a` and `b` of two nodes whose first free
/// dofs are `first_a` and `first_b`, with their pair's depth `depth` (read only when the
/// nodes differ). Node $n$'s free dofs are consecutive, and every column that holds one of
/// them holds them all, consecutively:
/// - one node ($f_a = f_b$): column $\max(a, b)$ ends with the node's dofs up to its
///   diagonal, so the entry is $\lvert a - b\rvert$ before the column's end;
/// - two nodes: the rows of the one numbered first start `depth` into each column of the
///   other, so the entry is $\min(a, b) - \min(f_a, f_b)$ past that.
#[inline(always)]
pub(crate) fn hessian_slot(
    col_ptr: &[u32],
    a: u32,
    b: u32,
    first_a: u32,
    first_b: u32,
    depth: u32,
) -> usize {
    let (lo, hi) = (a.min(b), a.max(b));
    let slot = if first_a == first_b {
        col_ptr[hi as usize + 1] - 1 - (hi - lo)
    } else {
        col_ptr[hi as usize] + depth + (lo - first_a.min(first_b))
    };
    slot as usize
}

/// Slot of upper-triangle entry `(row, col)`, `row <= col`, of the compressed columns
/// `col_ptr` / `row_idx`, or [`NONE`] when it is not stored: `guess` when it lies in the
/// column and holds `row`, else found by binary search. Setup only.
fn locate(col_ptr: &[u32], row_idx: &[u32], row: u32, col: u32, guess: u32) -> u32 {
    let start = col_ptr[col as usize] as usize;
    let end = col_ptr[col as usize + 1] as usize;
    if (start..end).contains(&(guess as usize)) && row_idx[guess as usize] == row {
        return guess;
    }
    match row_idx[start..end].binary_search(&row) {
        Ok(p) => (start + p) as u32,
        Err(_) => NONE,
    }
}

/// Whether a term's local dofs name one dof twice (eliminated coordinates aside).
fn repeats(dofs: &[u32]) -> bool {
    dofs.iter()
        .enumerate()
        .any(|(p, &a)| a != NONE && dofs[p + 1..].contains(&a))
}

/// The declaring visitor: numbers rows, records local dofs and the pattern's entries.
struct Declare<'a> {
    dof_of: &'a [u32],
    node_count: usize,
    with_constraint_hessian: bool,
    families: Vec<Family>,
    local_dofs: Vec<u32>,
    /// `(col << 32) | row` keys of the node pairs the Hessian blocks couple, `row <= col`.
    entries: &'a mut Vec<u64>,
    rows: usize,
    jacobian_len: usize,
    error: Option<SolverError>,
}

impl Declare<'_> {
    /// Records one family: its local dofs, Hessian entries (`with_hessian`) and `rows`
    /// Jacobian rows per term.
    fn family<const N: usize>(
        &mut self,
        nodes: impl Iterator<Item = [u32; N]>,
        rows: usize,
        with_hessian: bool,
    ) {
        let index = self.families.len();
        let dof_offset = self.local_dofs.len();
        let first_row = self.rows;
        let mut terms = 0;
        for (t, term_nodes) in nodes.enumerate() {
            terms += 1;
            for &node in &term_nodes {
                if node as usize >= self.node_count {
                    self.error.get_or_insert(SolverError::NodeOutOfRange {
                        family: index,
                        term: t,
                        node,
                        node_count: self.node_count,
                    });
                    self.local_dofs.extend_from_slice(&[NONE; 3]);
                    continue;
                }
                let c = 3 * node as usize;
                self.local_dofs.extend_from_slice(&self.dof_of[c..c + 3]);
            }
            if with_hessian {
                self.couple(&term_nodes);
            }
            self.rows += rows;
        }
        self.jacobian_len += terms * 3 * N * rows;
        self.families.push(Family {
            terms,
            nodes: N,
            rows,
            has_hessian: with_hessian,
            dof_offset,
            hessian_upper: true,
            hessian_offset: 0,
            jacobian_offset: 0,
            first_row,
        });
    }

    /// Records the node pairs a term's Hessian block couples, each node with itself
    /// included (a node out of range is left out: its error is recorded).
    fn couple(&mut self, nodes: &[u32]) {
        for (i, &n) in nodes.iter().enumerate() {
            for &m in &nodes[i..] {
                if (n.max(m) as usize) < self.node_count {
                    self.entries
                        .push((u64::from(n.max(m)) << 32) | u64::from(n.min(m)));
                }
            }
        }
    }
}

/// The compressed upper columns of `pattern` (its `col_ptr` and `row_idx`; every other
/// field set) from the node pairs its Hessian blocks couple, `(col << 32) | row` keys in
/// `entries` (rows sorted within each column, the diagonal last and always present).
/// Node $n$'s free coordinates are consecutive dofs, numbered node by node, so primal
/// column $b$ of node $n$ holds the free dofs of every node $m < n$ coupled to $n$, in the
/// order of the nodes, then those of $n$ up to $b$ when $n$ couples to itself (else $b$
/// alone); a constraint row's column holds its term's distinct free dofs and the diagonal.
/// The pairs are sorted and merged first ([`sort_distinct_by_column`]), among nodes, not
/// dofs: nine times fewer keys. Returns how many keys `entries` held before they merged.
///
/// # Errors
/// [`SolverError::TooLarge`] beyond 32-bit indices.
fn compress(pattern: &mut KktPattern, entries: &mut Vec<u64>) -> Result<usize, SolverError> {
    let order = pattern.order();
    let node_count = pattern.dof_of.len() / 3;
    if order >= NONE as usize {
        return Err(SolverError::TooLarge);
    }
    let keys = entries.len();
    let KktPattern {
        dof_of,
        col_ptr,
        row_idx,
        families,
        local_dofs,
        dofs,
        ..
    } = pattern;
    sort_distinct_by_column(entries, node_count, col_ptr, row_idx);
    let free = |n: u64| {
        dof_of[3 * n as usize..][..3]
            .iter()
            .copied()
            .filter(|&d| d != NONE)
    };
    let mut nnz = 0usize;
    let mut from = 0;
    for n in 0..node_count {
        let (couples, to) = coupled(entries, from, n);
        from = to;
        let own = free(n as u64).count();
        let below: usize = couples
            .clone()
            .filter(|&m| m != n as u64)
            .map(|m| free(m).count())
            .sum();
        let itself = couples.clone().any(|m| m == n as u64);
        nnz += own * below + if itself { own * (own + 1) / 2 } else { own };
    }
    for f in families.iter().filter(|f| f.rows > 0) {
        let s = 3 * f.nodes;
        for t in 0..f.terms {
            let local = &local_dofs[f.dof_offset + t * s..][..s];
            let distinct = local
                .iter()
                .enumerate()
                .filter(|&(p, &a)| a != NONE && !local[..p].contains(&a))
                .count();
            nnz += f.rows * (distinct + 1);
        }
    }
    if nnz >= NONE as usize {
        return Err(SolverError::TooLarge);
    }
    col_ptr.clear();
    col_ptr.reserve_exact(order + 1);
    col_ptr.push(0);
    row_idx.clear();
    row_idx.reserve_exact(nnz);
    let mut from = 0;
    for n in 0..node_count {
        let (couples, to) = coupled(entries, from, n);
        from = to;
        for b in free(n as u64) {
            for m in couples.clone() {
                row_idx.extend(free(m).filter(|&d| d <= b));
            }
            if row_idx.last() != Some(&b) {
                row_idx.push(b);
            }
            col_ptr.push(row_idx.len() as u32);
        }
    }
    for f in families.iter().filter(|f| f.rows > 0) {
        let s = 3 * f.nodes;
        for t in 0..f.terms {
            let start = row_idx.len();
            row_idx.extend(
                local_dofs[f.dof_offset + t * s..][..s]
                    .iter()
                    .filter(|&&a| a != NONE),
            );
            row_idx[start..].sort_unstable();
            let mut end = start;
            for k in start..row_idx.len() {
                if k == start || row_idx[k] != row_idx[end - 1] {
                    row_idx[end] = row_idx[k];
                    end += 1;
                }
            }
            row_idx.truncate(end);
            for r in 0..f.rows {
                if r > 0 {
                    row_idx.extend_from_within(start..end);
                }
                row_idx.push((*dofs + f.first_row + t * f.rows + r) as u32);
                col_ptr.push(row_idx.len() as u32);
            }
        }
    }
    debug_assert_eq!((col_ptr.len(), row_idx.len()), (order + 1, nnz));
    Ok(keys)
}

/// The nodes coupled to node `n` (`m <= n`, ascending) in the sorted, distinct node pairs
/// `keys`, whose column `n` starts at `from`; and where the next column starts.
fn coupled(keys: &[u64], from: usize, n: usize) -> (impl Iterator<Item = u64> + Clone + '_, usize) {
    let len = keys[from..]
        .iter()
        .take_while(|&&key| (key >> 32) as usize == n)
        .count();
    let column = keys[from..from + len]
        .iter()
        .map(|&key| key & u64::from(u32::MAX));
    (column, from + len)
}

/// Sorts `(col << 32) | row` keys (every column below `order`, every row below `order`)
/// and merges duplicates, as `sort_unstable` then `dedup` would, leaving `col_ptr` the
/// `order + 1` starts of the distinct keys' columns. Three passes: an in-place bucket sort
/// by column (American flag sort: count the keys of each column, then swap each key into
/// its column's next free place, $O(n)$); then, column by column, the first key of each
/// row is kept (a row marked with its column), the others dropped, compacting in place;
/// then the few dozen distinct keys of each column are sorted. A global sort of the
/// active page's keys compared each about $\log_2 n \approx 15$ times, in 64 bits, which a
/// Cortex-M4 does in several instructions; and most keys are duplicates (a pair of nodes
/// shares several terms). `scratch` is scratch.
fn sort_distinct_by_column(
    entries: &mut Vec<u64>,
    order: usize,
    col_ptr: &mut Vec<u32>,
    scratch: &mut Vec<u32>,
) {
    refill(col_ptr, order + 1, 0);
    for &key in entries.iter() {
        col_ptr[(key >> 32) as usize + 1] += 1;
    }
    for k in 0..order {
        col_ptr[k + 1] += col_ptr[k];
    }
    let cursor = scratch;
    cursor.clear();
    cursor.extend_from_slice(&col_ptr[..order]);
    for c in 0..order {
        let end = col_ptr[c + 1];
        while cursor[c] < end {
            let at = cursor[c] as usize;
            let home = (entries[at] >> 32) as usize;
            if home == c {
                cursor[c] += 1;
            } else {
                entries.swap(at, cursor[home] as usize);
                cursor[home] += 1;
            }
        }
    }
    // The column each row was last kept in.
    let seen = cursor;
    refill(seen, order, NONE);
    let mut kept = 0;
    for c in 0..order {
        let (start, end) = (col_ptr[c] as usize, col_ptr[c + 1] as usize);
        col_ptr[c] = kept as u32;
        for at in start..end {
            let key = entries[at];
            let row = key as u32 as usize;
            if seen[row] != c as u32 {
                seen[row] = c as u32;
                entries[kept] = key;
                kept += 1;
            }
        }
        entries[col_ptr[c] as usize..kept].sort_unstable();
    }
    col_ptr[order] = kept as u32;
    entries.truncate(kept);
}

impl<T: Real> TermVisitor<T> for Declare<'_> {
    fn potentials<P: Potential<T, N>, const N: usize>(&mut self, set: &PotentialSet<T, P, N>) {
        self.family::<N>(set.terms().iter().map(|t| t.nodes), 0, true);
    }

    fn constraints<C: Constraint<T, R, N>, const R: usize, const N: usize>(
        &mut self,
        set: &ConstraintSet<C, N>,
    ) {
        let with_hessian = self.with_constraint_hessian && !C::LINEAR;
        self.family::<N>(set.terms().iter().map(|t| t.nodes), R, with_hessian);
    }
}

#[cfg(test)]
mod tests {
    use super::{KktPattern, NONE, sort_distinct_by_column};
    use crate::chain::Chain;
    use crate::model::{ConstraintSet, Model, PotentialSet, TermVisitor};
    use alloc::collections::BTreeSet;
    use alloc::vec::Vec;
    use folio_kernels::iso2d::Iso2d;
    use folio_kernels::splitmix::SplitMix64;
    use folio_kernels::spring::Spring;

    /// The sort by column orders and merges keys as one global sort and `dedup` do: random
    /// keys with many duplicates, empty columns, a single column, and none.
    #[test]
    fn sorting_by_column_equals_a_global_sort_and_dedup() {
        let mut rng = SplitMix64::new(0x50_27);
        for (order, count) in [(1, 40), (7, 0), (7, 300), (60, 5), (300, 20_000)] {
            let mut keys: Vec<u64> = (0..count)
                .map(|_| {
                    let col = rng.next_u64() % order;
                    // Rows at most the column (upper triangle), few distinct: duplicates.
                    let row = rng.next_u64() % (col + 1) % 9;
                    (col << 32) | row
                })
                .collect();
            let mut expected = keys.clone();
            expected.sort_unstable();
            expected.dedup();
            let (mut col_ptr, mut scratch) = (Vec::new(), Vec::new());
            sort_distinct_by_column(&mut keys, order as usize, &mut col_ptr, &mut scratch);
            assert_eq!(keys, expected, "order {order}, {count} keys");
            assert_eq!(col_ptr.len(), order as usize + 1);
            assert_eq!(col_ptr[order as usize] as usize, expected.len());
            for c in 0..order as usize {
                let column = &keys[col_ptr[c] as usize..col_ptr[c + 1] as usize];
                assert!(
                    column.iter().all(|&k| (k >> 32) as usize == c),
                    "column {c}"
                );
            }
        }
    }

    /// A model of random springs and length constraints (some on one node twice) among
    /// `nodes` nodes with random coordinates eliminated.
    struct Scatter {
        nodes: usize,
        fixed: Vec<bool>,
        springs: PotentialSet<f64, Spring<f64>, 2>,
        lengths: ConstraintSet<Iso2d<f64>, 2>,
    }

    impl Model<f64> for Scatter {
        fn topology_version(&self) -> u64 {
            0
        }
        fn node_count(&self) -> usize {
            self.nodes
        }
        fn is_fixed(&self, node: usize, axis: usize) -> bool {
            self.fixed[3 * node + axis]
        }
        fn mass(&self, _node: usize) -> f64 {
            1.0
        }
        fn visit_terms<V: TermVisitor<f64>>(&self, visitor: &mut V) {
            visitor.potentials(&self.springs);
            visitor.constraints(&self.lengths);
        }
    }

    /// The pattern equals the one read off every term's local dofs pair by pair (the
    /// definition: each free pair of a Hessian block, each free dof of a Jacobian row,
    /// every diagonal), over random models with eliminated coordinates, isolated nodes
    /// and terms that name a node twice; and every slot lands on its entry.
    #[test]
    fn pattern_equals_the_pairs_of_the_terms() {
        let mut rng = SplitMix64::new(0xd0f5);
        for case in 0..60 {
            let nodes = 1 + (rng.next_u64() % 30) as usize;
            let mut pick = || (rng.next_u64() % nodes as u64) as u32;
            let mut model = Scatter {
                nodes,
                fixed: Vec::new(),
                springs: PotentialSet::new(1.0),
                lengths: ConstraintSet::new(),
            };
            for _ in 0..(case % 7) * nodes / 3 {
                let pair = [pick(), pick()];
                model.springs.push(Spring::new(1.0, 1.0).unwrap(), pair);
            }
            for _ in 0..case % 5 {
                let pair = [pick(), pick()];
                model.lengths.push(Iso2d::new(1.0).unwrap(), pair);
            }
            model.fixed = (0..3 * nodes).map(|_| rng.next_u64() % 4 == 0).collect();
            for hessian in [false, true] {
                let p = KktPattern::build(&model, hessian).unwrap();
                let mut expected = BTreeSet::new();
                for k in 0..p.order() as u32 {
                    expected.insert((k, k));
                }
                let dofs = |n: u32| p.dof_of[3 * n as usize..][..3].to_vec();
                // Every free pair of a Hessian block on `nodes`, upper.
                let mut block = |nodes: &[u32; 2]| {
                    let local: Vec<u32> = nodes.iter().flat_map(|&n| dofs(n)).collect();
                    for &a in &local {
                        for &b in &local {
                            if a != NONE && b != NONE && a <= b {
                                expected.insert((b, a));
                            }
                        }
                    }
                };
                for t in model.springs.terms() {
                    block(&t.nodes);
                }
                if hessian {
                    for t in model.lengths.terms() {
                        block(&t.nodes);
                    }
                }
                for (r, t) in model.lengths.terms().iter().enumerate() {
                    let col = (p.dofs + r) as u32;
                    for a in t.nodes.iter().flat_map(|&n| dofs(n)) {
                        if a != NONE {
                            expected.insert((col, a));
                        }
                    }
                }
                let built: Vec<(u32, u32)> = (0..p.order())
                    .flat_map(|c| {
                        p.row_idx[p.col_ptr[c] as usize..p.col_ptr[c + 1] as usize]
                            .iter()
                            .map(move |&r| (c as u32, r))
                    })
                    .collect();
                let expected: Vec<(u32, u32)> = expected.into_iter().collect();
                assert_eq!(built, expected, "case {case}, constraint Hessian {hessian}");
                for f in &p.families {
                    let s = 3 * f.nodes;
                    for t in 0..f.terms {
                        let local = &p.local_dofs[f.dof_offset + t * s..][..s];
                        for (row, q) in (0..s).flat_map(|r| (0..s).map(move |q| (r, q))) {
                            if !f.has_hessian {
                                break;
                            }
                            let (a, b) = (local[row], local[q]);
                            match p.hessian_slot(f, t, row, q) {
                                None => assert!(a == NONE || b == NONE, "case {case}"),
                                Some(slot) => assert!(
                                    holds(&p, slot as u32, a.min(b), a.max(b)),
                                    "case {case}"
                                ),
                            }
                        }
                        for r in 0..f.rows {
                            let col = (p.dofs + f.first_row + t * f.rows + r) as u32;
                            for (q, &a) in local.iter().enumerate() {
                                let slot = p
                                    .jacobian_slots
                                    .get(f.jacobian_offset + s * (t * f.rows + r) + q);
                                if a == NONE {
                                    assert_eq!(slot, NONE);
                                } else {
                                    assert!(holds(&p, slot, a, col), "case {case}");
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Slot `s` holds upper entry `(row, col)`.
    fn holds(p: &KktPattern, s: u32, row: u32, col: u32) -> bool {
        let range = p.col_ptr[col as usize]..p.col_ptr[col as usize + 1];
        range.contains(&s) && p.row_idx[s as usize] == row
    }

    /// Nine coordinates less node 0's Z: dofs 0-1 on node 0, 2-4 on node 1, 5-7 on node 2.
    #[test]
    fn dof_numbering_skips_eliminated_coordinates() {
        let p = Chain::new(3).pattern(false);
        assert_eq!((p.dofs, p.rows, p.order()), (8, 1, 9));
        assert_eq!(p.dof_of, [0, 1, NONE, 2, 3, 4, 5, 6, 7]);
        assert_eq!(p.coordinate_of, [0, 1, 3, 4, 5, 6, 7, 8]);
    }

    /// Springs `[0, 1]` and `[1, 2]` couple dofs 0-4 and 2-7 (15 + 21 - 6 upper entries);
    /// the constraint `[0, 2]` adds its column (dofs 0, 1, 5, 6, 7 and the diagonal), and its
    /// Hessian the 6 couplings of node 0 with node 2.
    #[test]
    fn upper_pattern_of_a_tiny_chain() {
        for (hessian, nnz) in [(false, 36), (true, 42)] {
            let p = Chain::new(3).pattern(hessian);
            assert_eq!(p.nnz(), nnz, "with constraint Hessian: {hessian}");
            assert_eq!(&p.row_idx[p.col_ptr[8] as usize..], [0, 1, 5, 6, 7, 8]);
            for c in 0..p.order() {
                let rows = &p.row_idx[p.col_ptr[c] as usize..p.col_ptr[c + 1] as usize];
                assert!(rows.windows(2).all(|w| w[0] < w[1]), "column {c} sorted");
                assert_eq!(
                    rows.last(),
                    Some(&(c as u32)),
                    "column {c} ends on its diagonal"
                );
                assert_eq!(p.diagonal_slot(c), p.col_ptr[c + 1] as usize - 1);
            }
        }
    }

    /// Every term's Hessian entry, placed by its node pair's depth, and every Jacobian scatter
    /// index lands on the upper-triangle slot of its local dofs, or is none for an
    /// eliminated coordinate.
    #[test]
    fn scatter_maps_land_on_their_entries() {
        let chain = Chain::new(5);
        let nodes: [&[[u32; 2]]; 2] = [&[[0, 1], [1, 2], [2, 3], [3, 4]], &[[0, 2], [2, 4]]];
        for hessian in [false, true] {
            let p = chain.pattern(hessian);
            assert_eq!(p.families.len(), 2);
            for (f, terms) in p.families.iter().zip(nodes) {
                assert_eq!((f.terms, f.nodes), (terms.len(), 2));
                assert_eq!(f.has_hessian, f.rows == 0 || hessian);
                assert!(f.hessian_upper, "no term repeats a dof");
                assert_eq!(f.hessian_pairs_per_term(), usize::from(f.has_hessian));
                let len = f.terms * f.hessian_pairs_per_term();
                assert!(f.hessian_offset + len <= p.hessian_depths.len());
                for (t, term) in terms.iter().enumerate() {
                    let local = &p.local_dofs[f.dof_offset + 6 * t..][..6];
                    let expected: [u32; 6] =
                        core::array::from_fn(|q| p.dof_of[3 * term[q / 3] as usize + q % 3]);
                    assert_eq!(local, expected);
                    for (a, &da) in local.iter().enumerate() {
                        for (b, &db) in local.iter().enumerate().filter(|_| f.has_hessian) {
                            match p.hessian_slot(f, t, a, b) {
                                None => assert!(da == NONE || db == NONE),
                                Some(s) => {
                                    let (lo, hi) = (da.min(db), da.max(db));
                                    assert!(
                                        holds(&p, s as u32, lo, hi),
                                        "Hessian ({a}, {b}) of term {t}"
                                    );
                                }
                            }
                        }
                        for r in 0..f.rows {
                            let s = p
                                .jacobian_slots
                                .get(f.jacobian_offset + 6 * (t * f.rows + r) + a);
                            let col = (p.dofs + f.first_row + t * f.rows + r) as u32;
                            if da == NONE {
                                assert_eq!(s, NONE);
                            } else {
                                assert!(holds(&p, s, da, col), "Jacobian row {r}, dof {a}");
                            }
                        }
                    }
                }
            }
        }
    }
}
