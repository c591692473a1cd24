//! The structure of $J^\top$ for the normal equations: per dof, its Jacobian entries (the
//! constraint row and the KKT value slot of each), stored with the narrowest [`Index`] that
//! holds the KKT pattern's slots.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::Real;

use crate::index::Index;
use crate::pattern::KktPattern;

/// Per dof $d$, its Jacobian entries: `ptr[d]..ptr[d + 1]` into `row` (the constraint row
/// $a$) and `slot` (the KKT value slot of $J_{a d}$), rows ascending. One `I` per entry
/// twice, plus `dofs + 1` pointers.
#[derive(Clone, Debug)]
pub(super) struct Arrays<I> {
    ptr: Vec<I>,
    row: Vec<I>,
    slot: Vec<I>,
}

/// [`Arrays`] in `u16` when every slot of the KKT pattern fits, `u32` otherwise.
#[derive(Clone, Debug)]
pub(super) enum Transpose {
    /// Two bytes per index.
    Narrow(Arrays<u16>),
    /// Four bytes per index.
    Wide(Arrays<u32>),
}

impl Transpose {
    /// $J^\top$'s structure from the constraint columns of `kkt` (module docs).
    #[must_use]
    pub(super) fn new(kkt: &KktPattern) -> Self {
        // Every pointer, row and slot is below the KKT's nnz.
        if kkt.nnz() <= <u16 as Index>::MAX {
            Self::Narrow(Arrays::new(kkt))
        } else {
            Self::Wide(Arrays::new(kkt))
        }
    }

    /// The constraint rows $a$ of dof `d`'s Jacobian entries, ascending, as `usize`, each
    /// visited with its value $J_{a d}$ from `kkt_values` (see [`Arrays::for_each`]).
    #[inline]
    pub(super) fn for_each<T: Real>(
        &self,
        d: usize,
        kkt_values: &[T],
        visit: impl FnMut(usize, T) -> bool,
    ) {
        match self {
            Self::Narrow(a) => a.for_each(d, kkt_values, visit),
            Self::Wide(a) => a.for_each(d, kkt_values, visit),
        }
    }

    /// Calls `visit(a)` for the constraint rows $a$ of dof `d`'s Jacobian entries,
    /// ascending.
    pub(super) fn for_each_row(&self, d: usize, visit: impl FnMut(usize)) {
        match self {
            Self::Narrow(a) => a.rows(d).iter().map(|a| a.get()).for_each(visit),
            Self::Wide(a) => a.rows(d).iter().map(|a| a.get()).for_each(visit),
        }
    }
}

impl<I: Index> Arrays<I> {
    /// Counts the entries per dof, then fills them column by column of $J^\top$ (the
    /// constraint rows of `kkt` in order, so each dof's rows come out ascending).
    fn new(kkt: &KktPattern) -> Self {
        let (dofs, rows) = (kkt.dofs, kkt.rows);
        let mut count = vec![0usize; dofs + 1];
        for c in 0..rows {
            for &d in super::jacobian_rows(kkt, c) {
                count[d as usize + 1] += 1;
            }
        }
        for d in 0..dofs {
            count[d + 1] += count[d];
        }
        let entries = count[dofs];
        let (mut row, mut slot) = (vec![I::new(0); entries], vec![I::new(0); entries]);
        let ptr = count.iter().map(|&p| I::new(p)).collect();
        for c in 0..rows {
            let start = kkt.col_ptr[dofs + c] as usize;
            for (k, &d) in super::jacobian_rows(kkt, c).iter().enumerate() {
                let at = &mut count[d as usize];
                row[*at] = I::new(c);
                slot[*at] = I::new(start + k);
                *at += 1;
            }
        }
        Self { ptr, row, slot }
    }

    /// The constraint rows of dof `d`'s Jacobian entries, ascending.
    #[inline]
    fn rows(&self, d: usize) -> &[I] {
        &self.row[self.ptr[d].get()..self.ptr[d + 1].get()]
    }

    /// Calls `visit(a, J_ad)` for the Jacobian entries of dof `d`, rows $a$ ascending,
    /// until it returns `false`.
    #[inline]
    fn for_each<T: Real>(
        &self,
        d: usize,
        kkt_values: &[T],
        mut visit: impl FnMut(usize, T) -> bool,
    ) {
        let range = self.ptr[d].get()..self.ptr[d + 1].get();
        for (&a, &slot) in self.row[range.clone()].iter().zip(&self.slot[range]) {
            if !visit(a.get(), kkt_values[slot.get()]) {
                break;
            }
        }
    }
}
