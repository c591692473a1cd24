//! What an input did: the outcomes of a grab, a drag and a finger-bookmarking request
//! ([`crate::Book::grab`], [`crate::Book::drag`], [`crate::Book::bookmark`]), and of any input
//! of a script ([`InputOutcome`]).

use crate::layout::BlockSide;

/// How a grab ended. Only `Grabbed` changes the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GrabOutcome {
    /// The page node `node` (index into the page grid) is held; the page came from `side`.
    Grabbed {
        /// The block the active page came from.
        side: BlockSide,
        /// Grid index of the held node.
        node: usize,
    },
    /// The ray does not hit the book.
    Missed,
    /// The block hit holds fewer pages than asked for.
    NotEnoughPages,
}

/// How a drag ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DragOutcome {
    /// The target moved.
    Moved,
    /// Nothing is held.
    NotHeld,
    /// The ray does not meet the drag plane (parallel or behind the camera); target kept.
    Missed,
}

/// How a finger-bookmarking request ended. Only `Started` changes the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BookmarkOutcome {
    /// A page started its flight.
    Started,
    /// Nothing is held.
    NotHeld,
    /// No page left to add (the block is empty) or to remove (one page held).
    NoPage,
    /// `max_flips` pages are already in flight.
    Busy,
    /// Finger-bookmarking is not among the book's effects.
    Disabled,
}

/// What an input did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum InputOutcome {
    /// A grab.
    Grab(GrabOutcome),
    /// A drag.
    Drag(DragOutcome),
    /// A release; `true` if something was held.
    Release(bool),
    /// A finger-bookmarking request.
    Bookmark(BookmarkOutcome),
}
