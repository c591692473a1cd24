//! The book handle: a 64-bit value, not a pointer, so that a stale one can be detected.

/// An opaque reference to a book. `id` packs the registry slot (low 24 bits) and the book's
/// serial number (high 40 bits). Serial numbers start at 1 and are never reused, so the
/// handle of a destroyed book stays invalid even after its slot holds another book, and the
/// zero handle (`FolioBookHandle h = {0};`) is never valid. Copy it freely; treat `id` as
/// opaque.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FolioBookHandle {
    /// Slot and serial number (type docs).
    pub id: u64,
}

/// Bits of the slot index in `FolioBookHandle::id`: at most $2^{24}$ live books.
pub(crate) const SLOT_BITS: u32 = 24;

/// The largest serial number: $2^{40} - 1$ books over the life of the process.
pub(crate) const MAX_SERIAL: u64 = (1 << (64 - SLOT_BITS)) - 1;

impl FolioBookHandle {
    /// The handle of the book with serial number `serial` in slot `slot`.
    #[must_use]
    pub(crate) fn new(slot: usize, serial: u64) -> Self {
        Self {
            id: (serial << SLOT_BITS) | slot as u64,
        }
    }

    /// The slot index.
    #[must_use]
    pub(crate) fn slot(self) -> usize {
        (self.id & ((1 << SLOT_BITS) - 1)) as usize
    }

    /// The serial number (0 for the zero handle, which no book has).
    #[must_use]
    pub(crate) fn serial(self) -> u64 {
        self.id >> SLOT_BITS
    }
}
