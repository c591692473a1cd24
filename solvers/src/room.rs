//! [`Room`]: capacity reserved at setup, so that the steps that refill a buffer allocate
//! nothing (DESIGN.md: "setup allocates; stepping does not").

use alloc::vec::Vec;

/// A buffer that can make room for a number of elements in all.
pub trait Room {
    /// Capacity for at least `total` elements (beyond the current length: none when the
    /// buffer holds `total` already).
    fn room_for(&mut self, total: usize);
}

impl<E> Room for Vec<E> {
    fn room_for(&mut self, total: usize) {
        self.reserve(total.saturating_sub(self.len()));
    }
}
