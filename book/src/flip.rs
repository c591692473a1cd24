//! Finger-bookmarking on the book (seed `000_…` Sec. 4.1, Fig. 11): pages flip between the
//! block the active page came from and the grip, drawn along the active page's history
//! ([`crate::bookmark`]).

use folio_kernels::Real;

use super::bookmark::{Flip, History};
use super::outcome::BookmarkOutcome;
use super::simulation::Book;

impl<T: Real> Book<T> {
    /// Moves every flying page one step along its flight; drops the ones that arrived.
    pub(crate) fn advance_flips(&mut self) {
        for f in &mut self.flips {
            f.position += f.rate;
        }
        self.flips
            .retain(|f| f.position > T::ZERO && f.position < T::ONE);
    }

    /// Finger-bookmarking (seed Sec. 4.1): one more page of the block the active page came
    /// from flips into the grip (`add`) or one held page flips back (`!add`). Counts, masses
    /// and $q$ change at once; the flying page is drawn from [`Book::flip_page`].
    pub fn bookmark(&mut self, add: bool) -> BookmarkOutcome {
        if !self.settings.effects.bookmarks() {
            return BookmarkOutcome::Disabled;
        }
        let Some(a) = self.active.filter(|a| a.hold.is_some()) else {
            return BookmarkOutcome::NotHeld;
        };
        if self.flips.len() >= self.settings.max_flips {
            return BookmarkOutcome::Busy;
        }
        let rate = T::ONE / T::from_f64(f64::from(self.settings.flip_frames.max(1)));
        let flip = if add {
            if self.counts.block(a.from) == 0 {
                return BookmarkOutcome::NoPage;
            }
            *self.counts.block_mut(a.from) -= 1;
            self.counts.active += 1;
            Flip {
                position: T::ZERO,
                rate,
            }
        } else {
            if self.counts.active <= 1 {
                return BookmarkOutcome::NoPage;
            }
            *self.counts.block_mut(a.from) += 1;
            self.counts.active -= 1;
            Flip {
                position: T::ONE,
                rate: -rate,
            }
        };
        self.flips.push(flip);
        self.update_masses();
        BookmarkOutcome::Started
    }

    /// Pages in flight between the block and the grip.
    #[must_use]
    pub fn flips(&self) -> &[Flip<T>] {
        &self.flips
    }

    /// The geometry of flying page `k` (grid order) into `out`, interpolated along the
    /// history of the active page (seed Fig. 11). Writes nothing for a bad `k` or size.
    pub fn flip_page(&self, k: usize, out: &mut [T::Vec3]) {
        let (Some(f), Some(page)) = (self.flips.get(k), self.page()) else {
            return;
        };
        self.history.interpolate(out, page, f.position);
    }

    /// The history of active-page geometries (seed Fig. 11).
    #[must_use]
    pub fn history(&self) -> &History<T> {
        &self.history
    }
}

#[cfg(test)]
mod tests {
    use super::BookmarkOutcome;
    use crate::{Book, BookSettings};
    use folio_geometry::BlockSide;

    #[test]
    fn a_flip_moves_a_page_at_once_and_lands_after_its_frames() {
        let mut b = Book::<f64>::new(BookSettings {
            settle_steps: 0,
            flip_frames: 4,
            ..BookSettings::default()
        })
        .unwrap();
        assert_eq!(b.bookmark(true), BookmarkOutcome::NotHeld);
        b.grab_at(BlockSide::Right, [10.0, 8.0], 1).unwrap();
        let before = b.counts();
        assert_eq!(b.bookmark(false), BookmarkOutcome::NoPage);
        assert_eq!(b.bookmark(true), BookmarkOutcome::Started);
        let after = b.counts();
        assert_eq!(after.right + 1, before.right);
        assert_eq!(after.active, 2);
        assert_eq!(b.flips().len(), 1);
        for frame in 1..=4 {
            b.advance_flips();
            assert_eq!(b.flips().len(), usize::from(frame < 4), "frame {frame}");
        }
    }
}
