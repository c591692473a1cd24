//! The blocks' top pages as the active page's walls ([`crate::Gutter::TopPage`]): each
//! block's top page, settled by [`super::top_page`] at [`super::TOP_PAGE_SEGMENTS`] when the
//! page counts change, kept as a polyline of [`TOP_PAGE_WALLS`] segments of equal arc length
//! that the collisions test the active page against ([`Book::top_page_wall`]).

use alloc::vec::Vec;
use folio_geometry::{BlockSide, Wall};
use folio_kernels::{Real, Vec3Ops};

use super::Point2;
use crate::layout::resample;
use crate::settings::Gutter;
use crate::simulation::Book;

/// Segments of a block's top page as walls: a 12-unit page in 48 is a quarter unit a
/// segment, a sixth of the default grid's cell, so that the bend over the block's corner
/// near the binding (radius about $2L/\alpha$ and more) is resolved where a page node meets it.
pub const TOP_PAGE_WALLS: usize = 48;

/// `side`'s index in [`Book`]'s top pages.
fn index(side: BlockSide) -> usize {
    usize::from(side == BlockSide::Right)
}

impl<T: Real> Book<T> {
    /// Settles each block's top page again when the page counts changed since they were
    /// last settled (a grab, a merge, a flip); nothing under [`Gutter::Seed`]. A block with
    /// no pages has no top page (its walls are the seed's); a top page that does not settle
    /// is counted ([`Book::top_page_failures`]) and its block falls back to the seed's walls.
    pub(crate) fn refresh_top_pages(&mut self) {
        // Without the feature the setting is refused ([`crate::BookSettings::validate`]),
        // and the constant `false` drops the solver from the build.
        let on = cfg!(feature = "gutter") && self.settings.gutter == Gutter::TopPage;
        if !on || self.top_page_counts == Some(self.counts) {
            return;
        }
        self.top_page_counts = Some(self.counts);
        for side in [BlockSide::Left, BlockSide::Right] {
            let mut walls = core::mem::take(&mut self.top_pages[index(side)]);
            walls.clear();
            if self.counts.block(side) > 0 {
                match super::top_page(self, side, super::TOP_PAGE_SEGMENTS) {
                    Ok(settled) => {
                        let width = self.layout.params.page_width;
                        let spacing = width / TOP_PAGE_WALLS as f64;
                        let points: Vec<Point2> =
                            resample(&settled.points, spacing, TOP_PAGE_WALLS + 1);
                        walls.extend(
                            points.iter().map(|p| {
                                T::Vec3::new(T::from_f64(p[0]), T::from_f64(p[1]), T::ZERO)
                            }),
                        );
                    }
                    Err(_) => self.top_page_failures += 1,
                }
            }
            self.top_pages[index(side)] = walls;
        }
    }

    /// The top page of the block on `side` as the active page's walls: its points from the
    /// hinge out (XY, page units), empty under [`Gutter::Seed`], before the first grab, for
    /// an empty block, or where the top page did not settle.
    #[must_use]
    pub fn top_page_walls(&self, side: BlockSide) -> &[T::Vec3] {
        &self.top_pages[index(side)]
    }

    /// Top pages that did not settle since the book was made (settled at each grab, merge
    /// and flip under [`Gutter::TopPage`]):
    /// each left its block with the seed's walls.
    #[must_use]
    pub fn top_page_failures(&self) -> u32 {
        self.top_page_failures
    }

    /// Walls of the top page of the block on `side`.
    pub(crate) fn top_page_segments(&self, side: BlockSide) -> usize {
        self.top_pages[index(side)].len().saturating_sub(1)
    }

    /// Segment `k` of the top page of the block on `side` as a wall on its upper side, with
    /// the clearance of half the active page: where the top page lies on its block this is
    /// the seed's wall of that block.
    pub(crate) fn top_page_wall(&self, side: BlockSide, k: usize) -> Option<Wall<T>> {
        let line = &self.top_pages[index(side)];
        let clearance = self.active_thickness() * T::HALF;
        Self::wall_along(line, side, k, clearance)
    }
}
