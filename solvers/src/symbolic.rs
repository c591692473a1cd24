//! The symbolic $LDL^\top$ analysis: indices only, computed once per topology.
//!
//! From the upper KKT pattern and an [`Ordering`] it builds the permuted column lists with
//! their source slots, the elimination tree (Liu's algorithm with path compression), the
//! column structure of $L$ and, for every row $k$ of $L$, the list of its nonzero columns
//! $j < k$ with the exact position of $L_{kj}$ in column $j$'s storage. The numeric phase
//! ([`crate::ldlt`]) then runs an up-looking factorization without walking the tree or
//! searching: row $k$ is a sparse triangular solve over a precomputed list.

use alloc::vec;
use alloc::vec::Vec;

use crate::ordering::{Ordering, permutation};
use crate::pattern::{KktPattern, NONE};

/// Indices-only analysis of a KKT pattern of order $n$ (see module docs).
///
/// Owns the permutation, the permuted upper matrix's structure and the structure of $L$:
/// $O(n + \mathrm{nnz}(A) + \mathrm{nnz}(L))$ 32-bit indices, all allocated by
/// [`Symbolic::analyse`] at setup (once per topology). Nothing here changes afterwards, and
/// the numeric phase ([`crate::ldlt::Ldlt`]) allocates nothing. Fields are read through the
/// accessors; an [`crate::ldlt::Ldlt`] made for one analysis refuses any other.
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
    /// Row (new index) of each permuted upper entry.
    pub(crate) a_row: Vec<u32>,
    /// Slot in the KKT value array of each permuted upper entry.
    pub(crate) a_slot: Vec<u32>,
    /// Constraint rows eliminated before any unknown they couple to: their pivot is exactly
    /// 0 whatever the values (an empty row of $L$ and a zero diagonal), so the numeric phase
    /// regularizes them statically and does not count them.
    pub(crate) structural_zero: Vec<bool>,
    /// Elimination tree: parent of each column, or [`NONE`] for a root.
    pub(crate) parent: Vec<u32>,
    /// Column pointers of the strictly lower part of $L$.
    pub(crate) l_ptr: Vec<u32>,
    /// Row indices of $L$ (ascending within a column).
    pub(crate) l_row: Vec<u32>,
    /// Pointers into `row_col` / `row_pos` per row of $L$.
    pub(crate) row_ptr: Vec<u32>,
    /// Nonzero columns $j$ of each row of $L$, ascending.
    pub(crate) row_col: Vec<u32>,
    /// Position of $L_{kj}$ in `l_row` / the numeric values.
    pub(crate) row_pos: Vec<u32>,
    /// Hash of everything the numeric phase reads (see [`Symbolic::fingerprint`]).
    pub(crate) fingerprint: u64,
}

impl Symbolic {
    /// Analyses `pattern` under `ordering`.
    #[must_use]
    pub fn analyse(pattern: &KktPattern, ordering: Ordering) -> Self {
        let n = pattern.order();
        let perm = permutation(pattern, ordering);
        let mut inverse = vec![0u32; n];
        for (new, &old) in perm.iter().enumerate() {
            inverse[old as usize] = new as u32;
        }
        let signs: Vec<i8> = (0..n).map(|k| signs_of(&perm, pattern.dofs, k)).collect();

        let (a_ptr, a_row, a_slot) = permuted_upper(pattern, &inverse);
        let parent = elimination_tree(n, &a_ptr, &a_row);
        let (row_ptr, row_col, col_count) = row_patterns(&a_ptr, &a_row, &parent);
        let structural_zero = (0..n)
            .map(|k| signs_of(&perm, pattern.dofs, k) < 0 && row_ptr[k] == row_ptr[k + 1])
            .collect();
        let (l_ptr, l_row, row_pos) = column_layout(&row_ptr, &row_col, col_count);
        let fingerprint = fingerprint(&[&perm, &a_ptr, &a_row, &a_slot, &l_ptr], &signs);
        Self {
            n,
            perm,
            signs,
            structural_zero,
            a_ptr,
            a_row,
            a_slot,
            parent,
            l_ptr,
            l_row,
            row_ptr,
            row_col,
            row_pos,
            fingerprint,
        }
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
    /// it couples to (an empty row of $L$; its pivot is structurally zero and the numeric
    /// phase regularizes it statically, see [`crate::ldlt`]).
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
    /// entries, ascending within each column.
    #[inline]
    #[must_use]
    pub fn l_row_idx(&self) -> &[u32] {
        &self.l_row
    }

    /// Nonzeros of the strictly lower part of $L$ (the length of the numeric factor's
    /// values).
    #[inline]
    #[must_use]
    pub fn nnz_l(&self) -> usize {
        self.l_row.len()
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

/// The upper triangle of $P A P^\top$ in compressed columns: `(a_ptr, a_row, a_slot)`, with
/// `n + 1` column pointers and, per entry, its row (new index) and its slot in the
/// pattern's value array. Entry $(r, c)$ lands in column $\max(r', c')$ at row $\min$.
fn permuted_upper(pattern: &KktPattern, inverse: &[u32]) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let n = pattern.order();
    let mut a_ptr = vec![0u32; n + 1];
    for c in 0..n {
        for &r in &pattern.row_idx[pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize] {
            let (i, j) = (inverse[r as usize], inverse[c]);
            a_ptr[i.max(j) as usize + 1] += 1;
        }
    }
    prefix_sum(&mut a_ptr);
    let mut next = a_ptr.clone();
    let mut a_row = vec![0u32; pattern.nnz()];
    let mut a_slot = vec![0u32; pattern.nnz()];
    for c in 0..n {
        for s in pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize {
            let (i, j) = (inverse[pattern.row_idx[s] as usize], inverse[c]);
            let col = i.max(j) as usize;
            let at = next[col] as usize;
            a_row[at] = i.min(j);
            a_slot[at] = s as u32;
            next[col] += 1;
        }
    }
    (a_ptr, a_row, a_slot)
}

/// Row patterns of $L$: the etree paths from each entry of column $k$ up to $k$, as
/// `(row_ptr, row_col, col_count)`: `n + 1` row pointers, each row's columns ascending,
/// and the entry count of each column of $L$ at `col_count[j + 1]`. Counted first so that
/// the lists are allocated at their exact length (the factor's index arrays are the largest
/// allocation on a microcontroller).
fn row_patterns(a_ptr: &[u32], a_row: &[u32], parent: &[u32]) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let n = parent.len();
    let mut row_ptr = vec![0u32; n + 1];
    let mut mark = vec![NONE; n];
    for k in 0..n {
        let mut count = 0;
        row_walk(k, a_ptr, a_row, parent, &mut mark, |_| count += 1);
        row_ptr[k + 1] = row_ptr[k] + count;
    }
    let mut row_col = vec![0u32; row_ptr[n] as usize];
    let mut col_count = vec![0u32; n + 1];
    mark.iter_mut().for_each(|m| *m = NONE);
    for (k, &start) in row_ptr.iter().enumerate().take(n) {
        let start = start as usize;
        let mut at = start;
        row_walk(k, a_ptr, a_row, parent, &mut mark, |j| {
            row_col[at] = j as u32;
            col_count[j + 1] += 1;
            at += 1;
        });
        row_col[start..at].sort_unstable();
    }
    (row_ptr, row_col, col_count)
}

/// Column storage of $L$ from its row patterns: `(l_ptr, l_row, row_pos)`, with `n + 1`
/// column pointers (the prefix sum of `col_count`), the rows of each column ascending, and
/// for each row-pattern entry the position of $L_{kj}$ in that storage.
fn column_layout(
    row_ptr: &[u32],
    row_col: &[u32],
    col_count: Vec<u32>,
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let mut l_ptr = col_count;
    prefix_sum(&mut l_ptr);
    let mut fill = l_ptr.clone();
    let mut l_row = vec![0u32; row_col.len()];
    let mut row_pos = vec![0u32; row_col.len()];
    for k in 0..row_ptr.len() - 1 {
        for idx in row_ptr[k] as usize..row_ptr[k + 1] as usize {
            let j = row_col[idx] as usize;
            let pos = fill[j];
            fill[j] += 1;
            l_row[pos as usize] = k as u32;
            row_pos[idx] = pos;
        }
    }
    (l_ptr, l_row, row_pos)
}

/// Calls `visit` on every column $j < k$ of row $k$ of $L$: the elimination-tree paths from
/// the entries of column $k$ of the permuted upper matrix up to $k$ (`mark` holds, per
/// column, the last row that visited it).
fn row_walk(
    k: usize,
    a_ptr: &[u32],
    a_row: &[u32],
    parent: &[u32],
    mark: &mut [u32],
    mut visit: impl FnMut(usize),
) {
    mark[k] = k as u32;
    for &i in &a_row[a_ptr[k] as usize..a_ptr[k + 1] as usize] {
        let mut j = i as usize;
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

/// FNV-1a over the 32-bit words of `arrays` and the pivot `signs`, each array preceded by
/// its length (so that moving a word from one array to the next changes the hash).
fn fingerprint(arrays: &[&[u32]], signs: &[i8]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let words = arrays
        .iter()
        .flat_map(|a| core::iter::once(a.len() as u32).chain(a.iter().copied()))
        .chain(signs.iter().map(|&s| u32::from(s > 0)));
    let mut hash = OFFSET;
    for word in words {
        for byte in word.to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(PRIME);
        }
    }
    hash
}

/// In-place exclusive prefix sum of counts stored at `[1..]`.
fn prefix_sum(ptr: &mut [u32]) {
    for k in 1..ptr.len() {
        ptr[k] += ptr[k - 1];
    }
}

/// Elimination tree of a symmetric matrix from its upper columns (Liu, with path
/// compression through `ancestor`).
fn elimination_tree(n: usize, a_ptr: &[u32], a_row: &[u32]) -> Vec<u32> {
    let mut parent = vec![NONE; n];
    let mut ancestor = vec![NONE; n];
    for k in 0..n {
        for &i in &a_row[a_ptr[k] as usize..a_ptr[k + 1] as usize] {
            let mut r = i as usize;
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
    parent
}
