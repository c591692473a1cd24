//! The two page blocks, named by integers.

/// A page block: `FOLIO_SIDE_LEFT` or `FOLIO_SIDE_RIGHT` (inputs), or
/// `FOLIO_SIDE_NONE` in outputs that name no block. A plain integer so that any value a
/// caller passes is defined; an unknown value is refused with
/// `FOLIO_STATUS_INVALID_ARGUMENT`.
pub type FolioSide = u32;

/// The left block ($x < 0$ in the book frame).
pub const FOLIO_SIDE_LEFT: FolioSide = 0;

/// The right block ($x > 0$ in the book frame).
pub const FOLIO_SIDE_RIGHT: FolioSide = 1;

/// No block (outputs only: e.g. no page merged in this step).
pub const FOLIO_SIDE_NONE: FolioSide = 2;

/// The block a side value names, if it names one.
#[must_use]
pub(crate) fn block_side(side: FolioSide) -> Option<folio_geometry::BlockSide> {
    match side {
        FOLIO_SIDE_LEFT => Some(folio_geometry::BlockSide::Left),
        FOLIO_SIDE_RIGHT => Some(folio_geometry::BlockSide::Right),
        _ => None,
    }
}

/// The side value of a block.
#[must_use]
pub(crate) fn side_value(side: Option<folio_geometry::BlockSide>) -> FolioSide {
    match side {
        Some(folio_geometry::BlockSide::Left) => FOLIO_SIDE_LEFT,
        Some(folio_geometry::BlockSide::Right) => FOLIO_SIDE_RIGHT,
        None => FOLIO_SIDE_NONE,
    }
}
