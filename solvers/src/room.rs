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

/// Sets `v` to `n` copies of `value`, within its capacity when that suffices (the
/// allocation-free form of `vec![value; n]` for a buffer that is refilled).
pub fn refill<E: Clone>(v: &mut Vec<E>, n: usize, value: E) {
    v.clear();
    v.resize(n, value);
}

/// `len` grown by `scale` (at least 1), rounded up: the room for a buffer of `len` elements
/// when the problem it serves grows by that factor.
#[must_use]
pub fn scaled(len: usize, scale: f64) -> usize {
    let grown = len as f64 * scale.max(1.0);
    if grown.is_finite() && grown < usize::MAX as f64 {
        // In range: finite, non-negative and below usize::MAX.
        let whole = grown as usize;
        if (whole as f64) < grown {
            whole + 1
        } else {
            whole
        }
    } else {
        len
    }
}
