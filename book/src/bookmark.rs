//! Finger-bookmarking (seed `000_…` Sec. 4.1, Fig. 11): the strictly ordered history of the
//! active page's geometries since the grab, and single pages interpolated along it that
//! animate a page flipping from the block into the grip (or back).
//!
//! The history starts with the page as it lay on the block and gains a snapshot every
//! `interval` steps while the page is held. Its storage is allocated with the book; when
//! it is full every other snapshot is dropped and the interval doubles, so it always spans
//! the whole path from the block to the hand, in order.

use folio_kernels::{Real, Vec3Ops};
use folio_solvers::Ring;

/// Snapshots of the active page (module docs).
#[derive(Clone, Debug)]
pub struct History<T: Real> {
    interval: u32,
    base_interval: u32,
    countdown: u32,
    /// The snapshots, one row of `nodes` positions each, allocated with the book.
    ring: Ring<T::Vec3>,
}

impl<T: Real> History<T> {
    /// Room for `capacity` (at least 2) snapshots of `nodes` positions, one every `interval`
    /// (at least 1) steps.
    #[must_use]
    pub fn new(nodes: usize, capacity: usize, interval: u32) -> Self {
        Self {
            interval: interval.max(1),
            base_interval: interval.max(1),
            countdown: 0,
            ring: Ring::with_capacity(nodes, capacity.max(2), T::Vec3::ZERO),
        }
    }

    /// Forgets everything and records `page` as the first snapshot.
    pub fn restart(&mut self, page: &[T::Vec3]) {
        self.ring.clear();
        self.interval = self.base_interval;
        self.countdown = self.interval;
        self.push(page);
    }

    /// Snapshots recorded.
    #[must_use]
    pub fn len(&self) -> usize {
        self.ring.len()
    }

    /// `true` before the first snapshot.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.ring.is_empty()
    }

    /// Snapshot `k` (0 is the page as it lay on the block); empty past the last recorded.
    #[must_use]
    pub fn snapshot(&self, k: usize) -> &[T::Vec3] {
        self.ring.get(k).unwrap_or(&[])
    }

    fn push(&mut self, page: &[T::Vec3]) {
        if page.len() != self.ring.width() {
            return;
        }
        if self.ring.is_full() {
            self.ring.thin();
            self.interval = self.interval.saturating_mul(2);
        }
        self.ring.push(page);
    }

    /// Called once per step while the page is held: records `page` every `interval` steps;
    /// `true` when it did.
    pub fn tick(&mut self, page: &[T::Vec3]) -> bool {
        if self.ring.is_empty() {
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
    /// $s = u\thinspace n$ gives $(1 - f) g_{\lfloor s\rfloor} + f\thinspace g_{\lfloor s\rfloor + 1}$,
    /// $f = s - \lfloor s\rfloor$. Writes nothing if the sizes disagree or nothing was recorded.
    pub fn interpolate(&self, out: &mut [T::Vec3], current: &[T::Vec3], u: T) {
        let (len, nodes) = (self.ring.len(), self.ring.width());
        if len == 0 || out.len() != nodes || current.len() != nodes {
            return;
        }
        let u = folio_kernels::real::clamp_keep_nan(u, T::ZERO, T::ONE);
        let u = if u.is_finite() { u } else { T::ZERO };
        let s = u.to_f64() * len as f64;
        // `s >= 0`, so truncation is the floor.
        let k = (s as usize).min(len);
        let f = T::from_f64(s - k as f64);
        let at = |i: usize| -> &[T::Vec3] { if i >= len { current } else { self.snapshot(i) } };
        let (a, b) = (at(k), at((k + 1).min(len)));
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
