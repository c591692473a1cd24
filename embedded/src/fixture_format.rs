//! The binary form of the page-turn fixture, shared by `build.rs` (which writes it from
//! `tests/fixtures/page_turn.input` on the host, parsed by `folio_book::Script::parse`) and
//! the firmware (which reads it, [`crate::fixture`]): no text and no float parsing on the
//! target.
//!
//! All integers are little-endian; an `f64` is its IEEE 754 bits as a `u64`, so every value
//! is the one the text parser gave, bit for bit.
//!
//! ```text
//! header  frames u32, events u32, camera [f64; 3], forward [f64; 3]   (56 bytes)
//! event   frame u32, kind u8, then by kind:
//!           GRAB             direction [f64; 3], pages u32            (33 bytes in all)
//!           DRAG             direction [f64; 3]                       (29 bytes)
//!           RELEASE, BOOKMARK_ADD, BOOKMARK_REMOVE  nothing           (5 bytes)
//! ```
//! Events come in frame order (`Script::parse` refuses decreasing frames) and every frame is
//! below `frames`.

/// Bytes of the header.
pub const HEADER_BYTES: usize = 56;
/// Event kind: grab along a ray, taking pages.
pub const GRAB: u8 = 0;
/// Event kind: drag along a ray.
pub const DRAG: u8 = 1;
/// Event kind: let go.
pub const RELEASE: u8 = 2;
/// Event kind: one more page into the grip.
pub const BOOKMARK_ADD: u8 = 3;
/// Event kind: one page back out of the grip.
pub const BOOKMARK_REMOVE: u8 = 4;
