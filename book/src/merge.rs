//! Release and merge (seed `000_…` Sec. 4.1): a released page falls under gravity and, once
//! all its nodes have come to rest, merges into the block under its fore-edge.

use folio_geometry::BlockSide;
use folio_kernels::{Real, Vec3Ops, math};

use super::simulation::Book;

impl<T: Real> Book<T> {
    /// Lets go of the active page; returns whether something was held.
    pub fn release(&mut self) -> bool {
        self.terms.set_pull(None);
        if self.terms.has_pad() {
            self.terms.set_pad(None);
            self.pad.center = None;
        }
        match self.active.as_mut() {
            Some(a) if a.hold.is_some() => {
                a.hold = None;
                a.slow_frames = 0;
                true
            }
            _ => false,
        }
    }

    /// The block the active page lies over (the one it merges into): left when the mean X
    /// of its fore-edge nodes is left of the midpoint of the blocks' binding nodes. `None`
    /// without an active page.
    #[must_use]
    pub fn active_side(&self) -> Option<BlockSide> {
        self.active.as_ref()?;
        let n = self.terms.nodes;
        let center =
            (self.state.x[n.block(false, 0)].x() + self.state.x[n.block(true, 0)].x()) * T::HALF;
        let mut edge = T::ZERO;
        for j in 0..n.grid.nz {
            edge += self.state.x[n.page(n.grid.nx - 1, j)].x();
        }
        Some(if edge < center * T::from_f64(n.grid.nz as f64) {
            BlockSide::Left
        } else {
            BlockSide::Right
        })
    }

    /// Merges a released page whose nodes have all been slower than `merge_speed` for
    /// `merge_frames` steps into the block under its fore-edge (seed Sec. 4.1).
    pub(crate) fn merge_if_settled(&mut self) -> Option<BlockSide> {
        let n = self.terms.nodes;
        let active = self.active.as_mut()?;
        if active.hold.is_some() {
            return None;
        }
        let speed = self.state.v[n.page_offset()..]
            .iter()
            .map(|v| math::length::<T>(*v))
            .fold(T::ZERO, |m, s| if s > m { s } else { m });
        if speed < self.settings.merge_speed {
            active.slow_frames += 1;
        } else {
            active.slow_frames = 0;
        }
        if active.slow_frames < self.settings.merge_frames {
            return None;
        }
        let side = self.active_side()?;
        *self.counts.block_mut(side) += self.counts.active;
        self.counts.active = 0;
        self.active = None;
        self.update_masses();
        Some(side)
    }
}
