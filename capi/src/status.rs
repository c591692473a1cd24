//! The status code every fallible function of the C API returns.

use core::ffi::{CStr, c_char};

/// What a call did. `FOLIO_STATUS_OK` is 0; every other value is a failure whose message
/// `folio_last_error_message` returns on the same thread. A call that fails
/// changes nothing: the book, the out-parameters and the caller's buffers are as they were
/// (except where a function documents otherwise).
///
/// New codes may be appended in a later version without changing `FOLIO_API_VERSION`;
/// treat any code you do not know as a failure.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FolioStatus {
    /// Success.
    Ok = 0,
    /// A pointer argument that must not be NULL was NULL.
    NullPointer = 1,
    /// The handle names no live book: destroyed, never created, or zero.
    StaleHandle = 2,
    /// A caller buffer is shorter than the data to copy; the message gives the length
    /// needed, and the size queries return it before the copy.
    BufferTooSmall = 3,
    /// An argument is out of range: NaN or infinite, an unknown side, precision or effect
    /// flag, settings the book refuses, a misaligned pointer.
    InvalidArgument = 4,
    /// A scene text that does not parse or check, or names another page model.
    InvalidScene = 5,
    /// The book reported an error while stepping or meshing (a non-finite node, a solver
    /// setup failure).
    BookError = 6,
    /// Drag or release with no page held.
    NotHeld = 7,
    /// A grab asked for more pages than the block holds.
    NotEnoughPages = 8,
    /// The query needs an active page (grabbed or falling) and there is none.
    NoActivePage = 9,
    /// An earlier call panicked while it held this book; its state may be inconsistent.
    /// Only `folio_book_destroy` accepts the handle.
    Poisoned = 10,
    /// No handle is left: too many live books, or every serial number was used.
    OutOfHandles = 11,
    /// The library panicked; the panic was caught at the boundary. A bug: please report
    /// the message.
    Panic = 12,
}

impl FolioStatus {
    /// The constant's name as in the header, NUL-terminated.
    #[must_use]
    pub fn name(self) -> &'static CStr {
        match self {
            Self::Ok => c"FOLIO_STATUS_OK",
            Self::NullPointer => c"FOLIO_STATUS_NULL_POINTER",
            Self::StaleHandle => c"FOLIO_STATUS_STALE_HANDLE",
            Self::BufferTooSmall => c"FOLIO_STATUS_BUFFER_TOO_SMALL",
            Self::InvalidArgument => c"FOLIO_STATUS_INVALID_ARGUMENT",
            Self::InvalidScene => c"FOLIO_STATUS_INVALID_SCENE",
            Self::BookError => c"FOLIO_STATUS_BOOK_ERROR",
            Self::NotHeld => c"FOLIO_STATUS_NOT_HELD",
            Self::NotEnoughPages => c"FOLIO_STATUS_NOT_ENOUGH_PAGES",
            Self::NoActivePage => c"FOLIO_STATUS_NO_ACTIVE_PAGE",
            Self::Poisoned => c"FOLIO_STATUS_POISONED",
            Self::OutOfHandles => c"FOLIO_STATUS_OUT_OF_HANDLES",
            Self::Panic => c"FOLIO_STATUS_PANIC",
        }
    }

    /// The status with numeric value `code`, if there is one.
    #[must_use]
    pub fn from_code(code: u32) -> Option<Self> {
        const ALL: [FolioStatus; 13] = [
            FolioStatus::Ok,
            FolioStatus::NullPointer,
            FolioStatus::StaleHandle,
            FolioStatus::BufferTooSmall,
            FolioStatus::InvalidArgument,
            FolioStatus::InvalidScene,
            FolioStatus::BookError,
            FolioStatus::NotHeld,
            FolioStatus::NotEnoughPages,
            FolioStatus::NoActivePage,
            FolioStatus::Poisoned,
            FolioStatus::OutOfHandles,
            FolioStatus::Panic,
        ];
        ALL.into_iter().find(|s| *s as u32 == code)
    }
}

/// The name of status `code` (e.g. `"FOLIO_STATUS_STALE_HANDLE"`), or `"FOLIO_STATUS_UNKNOWN"`
/// for a value this library does not define. The string is static and NUL-terminated; do
/// not free it. Takes the code as an integer so that any value is accepted.
#[unsafe(no_mangle)]
pub extern "C" fn folio_status_name(code: u32) -> *const c_char {
    FolioStatus::from_code(code)
        .map_or(c"FOLIO_STATUS_UNKNOWN", FolioStatus::name)
        .as_ptr()
}
