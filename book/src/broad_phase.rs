//! The broad phase of the active page's collisions with the blocks (seed `000_…` Sec. 3.4):
//! an XY box around each free column of the page grid (the nodes `(i, j)` of one `i`, which
//! lie close together in XY since the blocks are constant along Z) and one around them all,
//! so that a wall tests only the columns whose box it may reach ([`Wall::misses`]), and
//! none when it cannot reach the page's box.
//!
//! A box is taken when a round starts and grows with every node a wall pushes, so it holds
//! its column's positions at each test; a skipped pair is one whose point test would have
//! found no contact, and the pairs tested run in the brute-force order (walls, then nodes in
//! node order), so the contacts, their order and their arithmetic are unchanged.

use alloc::vec::Vec;
use folio_geometry::{Bounds, Corner, Wall};
use folio_kernels::Real;

use super::model::NodeMap;

/// An obstacle whose reach over a box can be bounded: no point of a box it misses touches it.
pub(crate) trait Reach<T> {
    /// `true` when no point of `bounds` penetrates the obstacle.
    fn misses(&self, bounds: &Bounds<T>) -> bool;
}

impl<T: Real> Reach<T> for Wall<T> {
    #[inline]
    fn misses(&self, bounds: &Bounds<T>) -> bool {
        Wall::misses(self, bounds)
    }
}

impl<T: Real> Reach<T> for Corner<T> {
    #[inline]
    fn misses(&self, bounds: &Bounds<T>) -> bool {
        Corner::misses(self, bounds)
    }
}

/// Per-column boxes, the page's box and the columns a wall may reach. Owns two buffers of
/// `nx - 1` entries each (the free columns of the page grid), allocated at setup.
#[derive(Clone, Debug, Default)]
pub(crate) struct PageBroadPhase<T> {
    /// The box of all free columns (`None` before the first [`PageBroadPhase::bound`]).
    page: Option<Bounds<T>>,
    /// The box of free column `i` at index `i - 1`.
    columns: Vec<Bounds<T>>,
    /// The free columns (`i`, ascending) whose box the current wall may reach.
    near: Vec<usize>,
    /// Keeps every column (the brute-force pass the tests compare with).
    #[cfg(test)]
    pub(crate) exhaustive: bool,
}

impl<T: Real> PageBroadPhase<T> {
    /// Buffers for the page grid of `nodes`.
    pub(crate) fn new(nodes: NodeMap) -> Self {
        let free = nodes.grid.nx - 1;
        Self {
            page: None,
            columns: Vec::with_capacity(free),
            near: Vec::with_capacity(free),
            #[cfg(test)]
            exhaustive: false,
        }
    }

    /// Bounds each free column of the page at the positions `x`.
    pub(crate) fn bound(&mut self, nodes: NodeMap, x: &[T::Vec3]) {
        self.columns.clear();
        let mut page = Bounds::at(x[nodes.page(1, 0)]);
        for i in 1..nodes.grid.nx {
            let mut b = Bounds::at(x[nodes.page(i, 0)]);
            for j in 1..nodes.grid.nz {
                b.include(x[nodes.page(i, j)]);
            }
            page.include_bounds(&b);
            self.columns.push(b);
        }
        self.page = Some(page);
    }

    /// Selects the columns `wall` (or corner) may reach ([`PageBroadPhase::near`]): none
    /// when it misses the page's box; returns the boxes tested.
    pub(crate) fn select(&mut self, wall: &impl Reach<T>) -> usize {
        self.near.clear();
        match self.page {
            Some(page) if !self.misses(wall, &page) => {}
            Some(_) => return 1,
            None => return 0,
        }
        for k in 0..self.columns.len() {
            if !self.misses(wall, &self.columns[k]) {
                self.near.push(k + 1);
            }
        }
        1 + self.columns.len()
    }

    /// [`Reach::misses`], never in the brute-force pass of the tests.
    fn misses(&self, wall: &impl Reach<T>, bounds: &Bounds<T>) -> bool {
        #[cfg(test)]
        if self.exhaustive {
            return false;
        }
        wall.misses(bounds)
    }

    /// The free columns the last [`PageBroadPhase::select`] kept, ascending.
    #[inline]
    #[must_use]
    pub(crate) fn near(&self) -> &[usize] {
        &self.near
    }

    /// Grows the box of free column `i` to hold `p` (a node of it that moved).
    #[inline]
    pub(crate) fn include(&mut self, i: usize, p: T::Vec3) {
        self.columns[i - 1].include(p);
        if let Some(page) = &mut self.page {
            page.include(p);
        }
    }
}
