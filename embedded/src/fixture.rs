//! The recorded page turn, compiled to binary by `build.rs` (format: [`crate::fixture_format`])
//! and read here with plain little-endian loads: no text, no float parsing, no allocation.

use folio_book::Action;

use crate::fixture_format::{BOOKMARK_ADD, BOOKMARK_REMOVE, DRAG, GRAB, HEADER_BYTES, RELEASE};

/// `tests/fixtures/page_turn.input` in binary form (`build.rs`).
static PAGE_TURN: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/page_turn.bin"));

/// The binary fixture is shorter than its header or an event says, or has an unknown event
/// kind, at this byte offset.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FixtureError {
    /// Byte offset of the field that could not be read.
    pub offset: usize,
}

/// A cursor over the binary fixture.
struct Reader {
    bytes: &'static [u8],
    at: usize,
}

impl Reader {
    /// The next `N` bytes.
    fn take<const N: usize>(&mut self) -> Result<[u8; N], FixtureError> {
        let error = FixtureError { offset: self.at };
        let end = self.at.checked_add(N).ok_or(error)?;
        let field = self.bytes.get(self.at..end).ok_or(error)?;
        self.at = end;
        field.try_into().map_err(|_| error)
    }

    fn u8(&mut self) -> Result<u8, FixtureError> {
        self.take::<1>().map(|[b]| b)
    }

    fn u32(&mut self) -> Result<u32, FixtureError> {
        self.take().map(u32::from_le_bytes)
    }

    /// Three `f64`s from their IEEE 754 bits.
    fn vec3(&mut self) -> Result<[f64; 3], FixtureError> {
        let mut v = [0.0; 3];
        for x in &mut v {
            *x = f64::from_bits(u64::from_le_bytes(self.take()?));
        }
        Ok(v)
    }
}

/// The page turn: its header, and its events read one by one in frame order.
pub struct Fixture {
    /// Frames to simulate.
    pub frames: u32,
    /// Camera position.
    pub camera: [f64; 3],
    /// Camera forward direction (the drag plane's normal).
    pub forward: [f64; 3],
    /// Events not read yet.
    remaining: u32,
    events: Reader,
}

impl Fixture {
    /// The recorded page turn (module docs).
    ///
    /// # Errors
    /// [`FixtureError`] when the header is cut short.
    pub fn page_turn() -> Result<Self, FixtureError> {
        let mut events = Reader {
            bytes: PAGE_TURN,
            at: 0,
        };
        let (frames, remaining) = (events.u32()?, events.u32()?);
        let (camera, forward) = (events.vec3()?, events.vec3()?);
        debug_assert_eq!(events.at, HEADER_BYTES);
        Ok(Self {
            frames,
            camera,
            forward,
            remaining,
            events,
        })
    }

    /// The next event if it applies at `frame` (call until `None` before stepping `frame`).
    ///
    /// # Errors
    /// [`FixtureError`] when the event is cut short or of an unknown kind.
    pub fn next_at(&mut self, frame: u32) -> Result<Option<Action>, FixtureError> {
        if self.remaining == 0 {
            return Ok(None);
        }
        let start = self.events.at;
        if self.events.u32()? != frame {
            // A later frame's event (`build.rs` wrote them in frame order, as
            // `Script::parse` accepted them).
            self.events.at = start;
            return Ok(None);
        }
        let kind_at = self.events.at;
        let action = match self.events.u8()? {
            GRAB => Action::Grab {
                direction: self.events.vec3()?,
                pages: self.events.u32()?,
            },
            DRAG => Action::Drag {
                direction: self.events.vec3()?,
            },
            RELEASE => Action::Release,
            BOOKMARK_ADD => Action::BookmarkAdd,
            BOOKMARK_REMOVE => Action::BookmarkRemove,
            _ => return Err(FixtureError { offset: kind_at }),
        };
        self.remaining -= 1;
        Ok(Some(action))
    }
}
