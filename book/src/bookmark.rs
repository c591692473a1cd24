//! Finger-bookmarking (seed `000_…` Sec. 4.1, Fig. 11): the strictly ordered history of the
//! active page's geometries since the grab, and single pages interpolated along it that
//! animate a page flipping from the block into the grip (or back).
//!
//! The history starts with the page as it lay on the block and gains a snapshot every
//! `interval` steps while the page is held. Its storage is allocated with the book; when
//! it is full every other snapshot is dropped and the interval doubles, so it always spans
//! the whole path from the block to the hand, in order.

use alloc::vec::Vec;
use folio_kernels::{Real, Vec3Ops};

/// Snapshots of the active page (module docs).
#[derive(Clone, Debug)]
pub struct History<T: Real> {
    nodes: usize,
    capacity: usize,
    len: usize,
    interval: u32,
    base_interval: u32,
    countdown: u32,
    data: Vec<T::Vec3>,
}

impl<T: Real> History<T> {
    /// Room for `capacity` (at least 2) snapshots of `nodes` positions, one every `interval`
    /// (at least 1) steps.
    #[must_use]
    pub fn new(nodes: usize, capacity: usize, interval: u32) -> Self {
        let capacity = capacity.max(2);
        Self {
            nodes,
            capacity,
            len: 0,
            interval: interval.max(1),
            base_interval: interval.max(1),
            countdown: 0,
            data: alloc::vec![T::Vec3::ZERO; nodes * capacity],
        }
    }

    /// Forgets everything and records `page` as the first snapshot.
    pub fn restart(&mut self, page: &[T::Vec3]) {
        self.len = 0;
        self.interval = self.base_interval;
        self.countdown = self.interval;
        self.push(page);
    }

    /// Snapshots recorded.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` before the first snapshot.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Snapshot `k` (0 is the page as it lay on the block).
    #[must_use]
    pub fn snapshot(&self, k: usize) -> &[T::Vec3] {
        &self.data[k * self.nodes..(k + 1) * self.nodes]
    }

    fn push(&mut self, page: &[T::Vec3]) {
        if page.len() != self.nodes {
            return;
        }
        if self.len == self.capacity {
            for k in 1..self.capacity / 2 + usize::from(self.capacity % 2 == 1) {
                let (dst, src) = (k * self.nodes, 2 * k * self.nodes);
                self.data.copy_within(src..src + self.nodes, dst);
            }
            self.len = self.capacity.div_ceil(2);
            self.interval = self.interval.saturating_mul(2);
        }
        let at = self.len * self.nodes;
        self.data[at..at + self.nodes].copy_from_slice(page);
        self.len += 1;
    }

    /// Called once per step while the page is held: records `page` every `interval` steps;
    /// `true` when it did.
    pub fn tick(&mut self, page: &[T::Vec3]) -> bool {
        if self.len == 0 {
            return false;
        }
        self.countdown = self.countdown.saturating_sub(1);
        if self.countdown == 0 {
            self.push(page);
            self.countdown = self.interval;
            return true;
        }
        false
    }

    /// The page at position `u` in $[0, 1]$ along the history followed by `current` (the
    /// page now): with the $n$ snapshots and `current` as $g_0 \dots g_n$, position
    /// $s = u\,n$ gives $(1 - f) g_{\lfloor s\rfloor} + f\, g_{\lfloor s\rfloor + 1}$,
    /// $f = s - \lfloor s\rfloor$. Writes nothing if the sizes disagree or nothing was recorded.
    pub fn interpolate(&self, out: &mut [T::Vec3], current: &[T::Vec3], u: T) {
        if self.len == 0 || out.len() != self.nodes || current.len() != self.nodes {
            return;
        }
        let u = folio_kernels::real::clamp_keep_nan(u, T::ZERO, T::ONE);
        let u = if u.is_finite() { u } else { T::ZERO };
        let s = u.to_f64() * self.len as f64;
        // `s >= 0`, so truncation is the floor.
        let k = (s as usize).min(self.len);
        let f = T::from_f64(s - k as f64);
        let at = |i: usize| -> &[T::Vec3] {
            if i >= self.len {
                current
            } else {
                self.snapshot(i)
            }
        };
        let (a, b) = (at(k), at((k + 1).min(self.len)));
        for ((o, &p), &q) in out.iter_mut().zip(a).zip(b) {
            *o = p * (T::ONE - f) + q * f;
        }
    }
}

/// A page on its way between a block and the grip (seed Fig. 11).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flip<T> {
    /// Position along the history, 0 = on the block, 1 = in the grip.
    pub position: T,
    /// Change of `position` per step (positive: into the grip).
    pub rate: T,
}
