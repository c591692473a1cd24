//! A scatter map's slots (indices into the KKT value array) in the narrowest width that
//! holds them: `u16` for a pattern of fewer than $2^{16} - 1$ stored entries, `u32` beyond.
//!
//! The Hessian and Jacobian maps ([`crate::pattern::KktPattern`]) hold one slot per entry of
//! every term's local block: on the default book's `f32` page they were the pattern's
//! largest arrays (17,133 Hessian and 5,460 Jacobian slots, 90,372 B in `u32`). The width
//! is chosen at each build from the number of stored entries, as
//! [`crate::symbolic::Symbolic`] chooses its own; a map reserved in one width and rebuilt
//! in the other allocates. The eliminated or dropped entry
//! ([`crate::index::NONE`] while the maps are built) is the width's largest value.

use alloc::vec::Vec;

use crate::index::{Index, NONE};
use crate::room::{Room, scaled};

/// One scatter map (module docs).
#[derive(Clone, Debug)]
pub(crate) enum Slots {
    /// Slots below `u16::MAX`; `u16::MAX` marks no slot.
    Narrow(Vec<u16>),
    /// Slots below `u32::MAX`; `u32::MAX` ([`NONE`]) marks no slot.
    Wide(Vec<u32>),
}

impl Default for Slots {
    fn default() -> Self {
        Self::Narrow(Vec::new())
    }
}

/// The slot `s` stands for: `None` for the width's mark of no slot.
#[inline(always)]
pub(crate) fn slot<I: Index>(s: I) -> Option<usize> {
    let s = s.get();
    (s != I::MAX).then_some(s)
}

impl Slots {
    /// Empties the map and sets its width for a pattern of `nnz` stored entries, keeping
    /// the room of a map already in that width.
    pub fn clear_for(&mut self, nnz: usize) {
        let narrow = nnz < usize::from(u16::MAX);
        match (&mut *self, narrow) {
            (Self::Narrow(v), true) => v.clear(),
            (Self::Wide(v), false) => v.clear(),
            (_, true) => *self = Self::Narrow(Vec::new()),
            (_, false) => *self = Self::Wide(Vec::new()),
        }
    }

    /// Room for `total` slots in all.
    pub fn room_for(&mut self, total: usize) {
        match self {
            Self::Narrow(v) => v.room_for(total),
            Self::Wide(v) => v.room_for(total),
        }
    }

    /// Room for `scale` times the current length ([`scaled`]).
    pub fn reserve_scaled(&mut self, scale: f64) {
        let total = scaled(self.len(), scale);
        self.room_for(total);
    }

    /// Frees the room beyond the length.
    pub fn shrink_to_fit(&mut self) {
        match self {
            Self::Narrow(v) => v.shrink_to_fit(),
            Self::Wide(v) => v.shrink_to_fit(),
        }
    }

    /// Appends `slot`, a slot of the pattern [`Slots::clear_for`] sized the map for, or
    /// [`NONE`].
    pub fn push(&mut self, slot: u32) {
        match self {
            Self::Narrow(v) => v.push(if slot == NONE {
                u16::MAX
            } else {
                debug_assert!(slot < u32::from(u16::MAX));
                slot as u16
            }),
            Self::Wide(v) => v.push(slot),
        }
    }

    /// Number of slots.
    #[must_use]
    pub fn len(&self) -> usize {
        match self {
            Self::Narrow(v) => v.len(),
            Self::Wide(v) => v.len(),
        }
    }

    /// Slot `k` as a `u32`, [`NONE`] for no slot (for checks; the scatters read the map in
    /// its own width).
    #[must_use]
    pub fn get(&self, k: usize) -> u32 {
        let s = match self {
            Self::Narrow(v) => slot(v[k]),
            Self::Wide(v) => slot(v[k]),
        };
        s.map_or(NONE, |s| s as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::{NONE, Slots};

    #[test]
    fn the_width_follows_the_pattern_and_none_survives_it() {
        let mut s = Slots::default();
        for (nnz, narrow) in [(10, true), (65_534, true), (65_535, false), (70_000, false)] {
            s.clear_for(nnz);
            assert_eq!(matches!(s, Slots::Narrow(_)), narrow, "nnz {nnz}");
            let top = (nnz - 1) as u32;
            for v in [0, 7, top, NONE] {
                s.push(v);
            }
            assert_eq!(s.len(), 4);
            assert_eq!([s.get(0), s.get(1), s.get(2), s.get(3)], [0, 7, top, NONE]);
        }
    }
}
