//! [`Ring`]: a fixed-capacity history of states, each a row of `width` values (a model's node
//! positions at one step), oldest first.
//!
//! It lives here, beside the step that produces the states, because the models above
//! (`folio-book`'s bookmark history, `folio-pages`' key frames) each record such a history;
//! it needs `alloc`, so it cannot sit in `folio-kernels`.
//!
//! **What it owns.** One `Vec<T>` of `capacity` $\times$ `width` values, allocated by
//! [`Ring::with_capacity`] and never again: pushing, thinning and clearing only copy within
//! it. Rows are stored in a circle starting at the oldest, so [`Ring::push_overwrite`] drops
//! the oldest row in $O(1)$; a ring that is never overwritten keeps its rows in place.

use alloc::vec;
use alloc::vec::Vec;

/// Up to `capacity` rows of `width` values, oldest first (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Ring<T> {
    width: usize,
    capacity: usize,
    start: usize,
    len: usize,
    data: Vec<T>,
}

impl<T: Copy> Ring<T> {
    /// An empty ring of room for `capacity` rows of `width` values, every slot set to `fill`.
    /// The only allocation: `capacity * width` values (saturating).
    #[must_use]
    pub fn with_capacity(width: usize, capacity: usize, fill: T) -> Self {
        Self {
            width,
            capacity,
            start: 0,
            len: 0,
            data: vec![fill; capacity.saturating_mul(width)],
        }
    }

    /// Values per row.
    #[inline]
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Rows the ring can hold.
    #[inline]
    #[must_use]
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Rows held.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` when no row is held.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `true` when `len() == capacity()`.
    #[inline]
    #[must_use]
    pub fn is_full(&self) -> bool {
        self.len == self.capacity
    }

    /// Row `k` counted from the oldest (0), if held.
    #[must_use]
    pub fn get(&self, k: usize) -> Option<&[T]> {
        if k < self.len {
            let at = self.slot(k) * self.width;
            self.data.get(at..at + self.width)
        } else {
            None
        }
    }

    /// Forgets every row (keeps the memory).
    pub fn clear(&mut self) {
        self.start = 0;
        self.len = 0;
    }

    /// Appends `row` as the newest; `false` (and nothing stored) when the ring is full or
    /// `row` is not `width` long. Does not allocate.
    pub fn push(&mut self, row: &[T]) -> bool {
        if row.len() != self.width || self.len >= self.capacity {
            return false;
        }
        self.write(self.len, row);
        self.len += 1;
        true
    }

    /// Appends `row` as the newest, dropping the oldest row when full; `false` (and nothing
    /// stored) when `row` is not `width` long or the capacity is 0. Does not allocate.
    pub fn push_overwrite(&mut self, row: &[T]) -> bool {
        if row.len() != self.width || self.capacity == 0 {
            return false;
        }
        // When full, the slot after the newest is the oldest's.
        self.write(self.len, row);
        if self.len == self.capacity {
            self.start = (self.start + 1) % self.capacity;
        } else {
            self.len += 1;
        }
        true
    }

    /// Keeps every other row, starting with the oldest: rows $0, 2, 4, \dots$ become rows
    /// $0, 1, 2, \dots$ and $\lceil n/2 \rceil$ remain of $n$. Does not allocate.
    pub fn thin(&mut self) {
        let kept = self.len.div_ceil(2);
        for k in 1..kept {
            let (dst, src) = (self.slot(k) * self.width, self.slot(2 * k) * self.width);
            self.data.copy_within(src..src + self.width, dst);
        }
        self.len = kept;
    }

    /// The storage slot of row `k` (any `k <= capacity`; `capacity` wraps to the oldest's).
    #[inline]
    fn slot(&self, k: usize) -> usize {
        let s = self.start + k;
        if s >= self.capacity {
            s - self.capacity
        } else {
            s
        }
    }

    /// Copies `row` (`width` long) into the slot of row `k`.
    fn write(&mut self, k: usize, row: &[T]) {
        let at = self.slot(k) * self.width;
        self.data[at..at + self.width].copy_from_slice(row);
    }
}

#[cfg(test)]
mod tests {
    use super::Ring;
    use alloc::vec::Vec;

    fn rows(r: &Ring<u32>) -> Vec<Vec<u32>> {
        (0..r.len()).map(|k| r.get(k).unwrap().to_vec()).collect()
    }

    #[test]
    fn empty() {
        let r = Ring::with_capacity(3, 4, 0u32);
        assert!(r.is_empty());
        assert!(!r.is_full());
        assert_eq!(r.len(), 0);
        assert_eq!(r.get(0), None);
        let z = Ring::with_capacity(2, 0, 0u32);
        assert!(z.is_empty() && z.is_full());
        let mut z = z;
        assert!(!z.push(&[1, 2]));
        assert!(!z.push_overwrite(&[1, 2]));
        assert_eq!(z.get(0), None);
    }

    #[test]
    fn order_and_capacity() {
        let mut r = Ring::with_capacity(2, 3, 0u32);
        for k in 0..3 {
            assert!(r.push(&[k, 10 * k]));
        }
        assert!(r.is_full());
        assert!(!r.push(&[9, 9]), "a full ring refuses");
        assert!(
            !r.push_overwrite(&[9]),
            "a row of the wrong width is refused"
        );
        assert_eq!(rows(&r), [[0, 0], [1, 10], [2, 20]]);
        assert_eq!((r.capacity(), r.width()), (3, 2));
        r.clear();
        assert!(r.is_empty());
        assert!(r.push(&[7, 7]));
        assert_eq!(rows(&r), [[7, 7]]);
    }

    #[test]
    fn wrap_around() {
        let mut r = Ring::with_capacity(1, 3, 0u32);
        for k in 0..7 {
            assert!(r.push_overwrite(&[k]));
        }
        assert_eq!(rows(&r), [[4], [5], [6]], "the newest three, oldest first");
        assert_eq!(r.get(3), None);
        r.thin();
        assert_eq!(rows(&r), [[4], [6]], "thinning across the seam");
        assert!(r.push_overwrite(&[7]));
        assert!(r.push_overwrite(&[8]));
        assert_eq!(rows(&r), [[6], [7], [8]]);
    }

    #[test]
    fn thin_keeps_every_other_from_the_oldest() {
        for n in 0..8u32 {
            let mut r = Ring::with_capacity(2, 8, 0u32);
            for k in 0..n {
                r.push(&[k, k + 1]);
            }
            r.thin();
            let want: Vec<Vec<u32>> = (0..n).step_by(2).map(|k| [k, k + 1].to_vec()).collect();
            assert_eq!(rows(&r), want, "{n} rows");
        }
    }
}
