//! What the one-page particle models (the mass-spring and XPBD pages) share: the grab (the
//! held material point, its rest position, mirrored across the spine for a page taken on
//! the left, and the finger) with the gestures that set it, and the range check of their
//! particles.

use crate::BlockSide;
use folio_kernels::{Real, Vec3Ops};

use crate::{PageError, check_finger};

/// The held material point and the finger.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hold<T: Real> {
    /// Material point $(u, v)$.
    pub at: [T; 2],
    /// Its rest position $P = (u, 0, v)$, mirrored to $(-u, 0, v)$ for a page held on the
    /// left.
    pub rest_point: T::Vec3,
    /// The page was taken on the left: the gripped particles' rest positions are mirrored
    /// across the spine, $(x, y, z) \to (-x, y, z)$.
    pub mirrored: bool,
    /// The finger, once dragged.
    pub finger: Option<T::Vec3>,
}

impl<T: Real> Hold<T> {
    /// A grab of material point `at` on the right of the spine, not yet dragged.
    pub fn new(at: [T; 2]) -> Self {
        Self {
            at,
            rest_point: T::Vec3::new(at[0], T::ZERO, at[1]),
            mirrored: false,
            finger: None,
        }
    }

    /// The finger's displacement from the held point's rest position, once dragged.
    pub fn displacement(&self) -> Option<T::Vec3> {
        self.finger.map(|f| f - self.rest_point)
    }
}

/// After `PageModel::grab` of a page taken on `side`: on the left the grip's rest
/// positions are mirrored across the spine, so that a finger starting at $(-u, 0, v)$ holds
/// the page where it lies.
pub(crate) fn taken_from<T: Real>(hold: &mut Option<Hold<T>>, side: BlockSide) {
    if let Some(hold) = hold.as_mut().filter(|_| side == BlockSide::Left) {
        hold.mirrored = true;
        hold.rest_point = T::Vec3::new(-hold.at[0], T::ZERO, hold.at[1]);
    }
}

/// `PageModel::drag` of a one-page model: the held point follows `finger` (a drag with
/// nothing held does nothing).
pub(crate) fn drag<T: Real>(hold: &mut Option<Hold<T>>, finger: T::Vec3) -> Result<(), PageError> {
    check_finger::<T>(finger)?;
    if let Some(hold) = hold.as_mut() {
        hold.finger = Some(finger);
    }
    Ok(())
}

/// Every coordinate of the particles `x` finite and within [`Real::COORD_MAX`].
pub(crate) fn all_in_range<T: Real>(x: &[T::Vec3]) -> bool {
    let ok = |c: T| c.is_finite() && c <= T::COORD_MAX && -c <= T::COORD_MAX;
    x.iter().all(|p| ok(p.x()) && ok(p.y()) && ok(p.z()))
}
