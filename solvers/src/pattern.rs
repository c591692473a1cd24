//! The KKT sparsity pattern and the scatter maps from each term's local block into it.
//!
//! Unknowns are the free coordinates ("dofs") numbered node-major, followed by one unknown per
//! constraint row (its multiplier). The KKT matrix
//! $$K = \begin{bmatrix} M/h^2 + \nabla^2 V\ (+\textstyle\sum_l \lambda_l \nabla^2 C_l) & \nabla C^\top \cr \nabla C & 0 \end{bmatrix}$$
//! (DESIGN.md "Time step", seed `000_…` eq. 3-4) is stored as its upper triangle in compressed
//! sparse columns with sorted rows and every diagonal entry present. Each term's local
//! Hessian entry of its upper local triangle ($p \le q$, which with its mirror $(q, p)$ covers
//! the term's block) and each Jacobian entry has a precomputed slot (index into the value
//! array) or [`NONE`] when it falls on an eliminated coordinate. Assembly is then a scatter
//! through these maps: no search, no allocation.

use alloc::vec::Vec;
use core::ops::Range;
use folio_kernels::{Constraint, Potential, Real};

use crate::error::SolverError;
use crate::model::{ConstraintSet, Model, PotentialSet, TermVisitor};
use crate::room::{Room, refill, scaled};
use crate::slots::Slots;

/// Marks an eliminated coordinate or a dropped (lower-triangle) entry in the maps.
pub const NONE: u32 = u32::MAX;

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
    /// Whether the Hessian slots are of the upper local triangle only (see
    /// [`Family::hessian_per_term`]); `false` when a term repeats a dof, whose mirrored
    /// entries then land on one slot and keep the full local block's order.
    pub hessian_upper: bool,
    /// Offset into [`KktPattern::hessian_slots`] ([`Family::hessian_per_term`] per term).
    pub hessian_offset: usize,
    /// Offset into [`KktPattern::jacobian_slots`] (`3 N R` per term).
    pub jacobian_offset: usize,
    /// First global constraint row.
    pub first_row: usize,
}

impl Family {
    /// Hessian slots per term: none without a Hessian; $3N(3N + 1)/2$ for the upper local
    /// triangle, pairs $(p, q)$ with $p \le q$ row by row, each the slot of the stored
    /// (upper) entry of dofs $(a_p, a_q)$; or, for a family with a repeated dof, $9N^2$ for
    /// the full local block, row by row, with [`NONE`] for a lower entry.
    #[inline]
    #[must_use]
    pub fn hessian_per_term(&self) -> usize {
        let s = 3 * self.nodes;
        match (self.has_hessian, self.hessian_upper) {
            (false, _) => 0,
            (true, true) => s * (s + 1) / 2,
            (true, false) => s * s,
        }
    }
}

/// The upper-triangle KKT pattern of a model and every term's scatter map.
///
/// Owns the coordinate numbering (`3 * nodes` and `dofs` entries), the compressed upper
/// columns (`order + 1` pointers, `nnz` rows) and the term maps (`3 N` local dofs per term,
/// $3N(3N + 1)/2$ Hessian slots per term with a Hessian, the upper local triangle, or
/// $9N^2$ in a family whose terms repeat a dof; `3 N R` Jacobian slots per term), all
/// allocated by [`KktPattern::build`] at setup. Fields are read through the accessors.
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
    /// The Hessian scatter map ([`Slots`]: `u16` for fewer than 65,535 stored entries).
    pub(crate) hessian_slots: Slots,
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
            dofs: self.coordinate_of.len(),
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
        let keys = compress(
            entries,
            self.dofs + rows,
            &mut self.col_ptr,
            &mut self.row_idx,
        )?;
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
        [&mut self.hessian_slots, &mut self.jacobian_slots]
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

    /// Slot of upper-triangle entry `(row, col)`, `row <= col`; setup only (binary search).
    fn slot(&self, row: u32, col: u32) -> u32 {
        let start = self.col_ptr[col as usize] as usize;
        let end = self.col_ptr[col as usize + 1] as usize;
        match self.row_idx[start..end].binary_search(&row) {
            Ok(p) => (start + p) as u32,
            Err(_) => NONE,
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

    /// Fills the Hessian and Jacobian slot maps from the local dofs, in each family's
    /// layout ([`Family::hessian_per_term`]).
    pub(crate) fn fill_maps(&mut self) {
        let mut families = core::mem::take(&mut self.families);
        let nnz = self.row_idx.len();
        self.hessian_slots.clear_for(nnz);
        self.jacobian_slots.clear_for(nnz);
        let hessian_len = families
            .iter()
            .map(|f| f.terms * f.hessian_per_term())
            .sum();
        self.hessian_slots.room_for(hessian_len);
        for f in &mut families {
            f.hessian_offset = self.hessian_slots.len();
            f.jacobian_offset = self.jacobian_slots.len();
            let s = 3 * f.nodes;
            for t in 0..f.terms {
                let base = f.dof_offset + t * s;
                if f.has_hessian {
                    for p in 0..s {
                        let from = if f.hessian_upper { p } else { 0 };
                        for q in from..s {
                            let a = self.local_dofs[base + p];
                            let b = self.local_dofs[base + q];
                            let slot = if a == NONE || b == NONE || (a > b && !f.hessian_upper) {
                                NONE
                            } else {
                                self.slot(a.min(b), a.max(b))
                            };
                            self.hessian_slots.push(slot);
                        }
                    }
                }
                for r in 0..f.rows {
                    let col = (self.dofs + f.first_row + t * f.rows + r) as u32;
                    for p in 0..s {
                        let a = self.local_dofs[base + p];
                        let slot = if a == NONE { NONE } else { self.slot(a, col) };
                        self.jacobian_slots.push(slot);
                    }
                }
            }
        }
        self.families = families;
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
    dofs: usize,
    node_count: usize,
    with_constraint_hessian: bool,
    families: Vec<Family>,
    local_dofs: Vec<u32>,
    /// `(col << 32) | row` keys of upper-triangle entries.
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
            let base = self.local_dofs.len();
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
            self.term_entries(base..self.local_dofs.len(), rows, with_hessian);
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

    /// Records the entries of the term whose local dofs are `local_dofs[local]`: its Hessian
    /// couplings (`with_hessian`) and its `rows` Jacobian rows, whose multipliers are the
    /// next `rows` constraint rows.
    fn term_entries(&mut self, local: Range<usize>, rows: usize, with_hessian: bool) {
        if with_hessian {
            for p in local.clone() {
                for q in local.clone() {
                    let (a, b) = (self.local_dofs[p], self.local_dofs[q]);
                    if a != NONE && b != NONE && a <= b {
                        self.entries.push((u64::from(b) << 32) | u64::from(a));
                    }
                }
            }
        }
        for r in 0..rows {
            // The column of this row's multiplier.
            let col = (self.dofs + self.rows + r) as u64;
            for p in local.clone() {
                let a = self.local_dofs[p];
                if a != NONE {
                    self.entries.push((col << 32) | u64::from(a));
                }
            }
        }
    }
}

/// Compressed upper columns of order `order` from `(col << 32) | row` keys, with every
/// diagonal entry added, into `col_ptr` (`order + 1` pointers) and `row_idx` (rows sorted
/// within each column, duplicates merged). Sorts `entries` in place ([`sort_by_column`]);
/// returns how many keys it held before they merged.
///
/// # Errors
/// [`SolverError::TooLarge`] beyond 32-bit indices.
fn compress(
    entries: &mut Vec<u64>,
    order: usize,
    col_ptr: &mut Vec<u32>,
    row_idx: &mut Vec<u32>,
) -> Result<usize, SolverError> {
    if order >= NONE as usize {
        return Err(SolverError::TooLarge);
    }
    entries.extend((0..order as u64).map(|k| (k << 32) | k));
    let keys = entries.len();
    if keys >= NONE as usize {
        return Err(SolverError::TooLarge);
    }
    sort_by_column(entries, order, col_ptr, row_idx);
    entries.dedup();
    refill(col_ptr, order + 1, 0);
    row_idx.clear();
    row_idx.reserve_exact(entries.len());
    for &key in entries.iter() {
        col_ptr[(key >> 32) as usize + 1] += 1;
        row_idx.push(key as u32);
    }
    for k in 0..order {
        col_ptr[k + 1] += col_ptr[k];
    }
    Ok(keys)
}

/// Sorts `(col << 32) | row` keys (every column below `order`) as `sort_unstable` would,
/// in two passes: an in-place bucket sort by column (American flag sort: count the keys of
/// each column, then swap each key into its column's next free place, $O(n)$), then a sort
/// of each column's keys, a few dozen. A global sort of the active page's keys compared
/// each about $\log_2 n \approx 15$ times, in 64 bits, which a Cortex-M4 does in several
/// instructions. `col_ptr` and `cursor` are scratch (left holding the column starts and
/// ends).
fn sort_by_column(
    entries: &mut [u64],
    order: usize,
    col_ptr: &mut Vec<u32>,
    cursor: &mut Vec<u32>,
) {
    refill(col_ptr, order + 1, 0);
    for &key in entries.iter() {
        col_ptr[(key >> 32) as usize + 1] += 1;
    }
    for k in 0..order {
        col_ptr[k + 1] += col_ptr[k];
    }
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
    for c in 0..order {
        entries[col_ptr[c] as usize..col_ptr[c + 1] as usize].sort_unstable();
    }
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
    use super::{KktPattern, NONE, sort_by_column};
    use crate::chain::Chain;
    use alloc::vec::Vec;
    use folio_kernels::splitmix::SplitMix64;

    /// The two-pass sort orders keys as one global sort does: random keys with many
    /// duplicates, empty columns, a single column, and none.
    #[test]
    fn sorting_by_column_equals_a_global_sort() {
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
            let (mut col_ptr, mut cursor) = (Vec::new(), Vec::new());
            sort_by_column(&mut keys, order as usize, &mut col_ptr, &mut cursor);
            assert_eq!(keys, expected, "order {order}, {count} keys");
            assert_eq!(col_ptr.len(), order as usize + 1);
            assert_eq!(col_ptr[order as usize] as usize, count);
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

    /// Every term's Hessian scatter index (upper local triangle) and Jacobian scatter index
    /// lands on the upper-triangle slot of its local dofs, or is [`NONE`] for an eliminated
    /// coordinate.
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
                assert_eq!(f.hessian_per_term(), if f.has_hessian { 21 } else { 0 });
                let len = f.terms * f.hessian_per_term();
                assert!(f.hessian_offset + len <= p.hessian_slots.len());
                for (t, term) in terms.iter().enumerate() {
                    let local = &p.local_dofs[f.dof_offset + 6 * t..][..6];
                    let expected: [u32; 6] =
                        core::array::from_fn(|q| p.dof_of[3 * term[q / 3] as usize + q % 3]);
                    assert_eq!(local, expected);
                    for (a, &da) in local.iter().enumerate() {
                        // The upper local triangle, row by row: (a, b) for b >= a.
                        let row = f.hessian_offset + 21 * t + (0..a).map(|i| 6 - i).sum::<usize>();
                        for (b, &db) in local.iter().enumerate().filter(|_| f.has_hessian) {
                            if b < a {
                                continue;
                            }
                            let s = p.hessian_slots.get(row + b - a);
                            if da == NONE || db == NONE {
                                assert_eq!(s, NONE);
                            } else {
                                let (lo, hi) = (da.min(db), da.max(db));
                                assert!(holds(&p, s, lo, hi), "Hessian ({a}, {b}) of term {t}");
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
