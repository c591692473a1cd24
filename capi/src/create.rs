//! Creating and destroying books.

use folio_book::Book;

use crate::any_book::AnyBook;
use crate::entry::Entry;
use crate::failure::Failure;
use crate::guard;
use crate::handle::FolioBookHandle;
use crate::pointer;
use crate::registry;
use crate::settings::{FOLIO_PRECISION_F32, FOLIO_PRECISION_F64, FolioBookSettings};
use crate::status::FolioStatus;

/// Builds the book `settings` describe.
pub(crate) fn build(settings: &FolioBookSettings) -> Result<AnyBook, Failure> {
    match settings.precision {
        FOLIO_PRECISION_F32 => Book::new(settings.book_settings::<f32>()?)
            .map(AnyBook::F32)
            .map_err(Failure::book),
        FOLIO_PRECISION_F64 => Book::new(settings.book_settings::<f64>()?)
            .map(AnyBook::F64)
            .map_err(Failure::book),
        other => Err(Failure::invalid(format!(
            "`precision` must be FOLIO_PRECISION_F32 (32) or FOLIO_PRECISION_F64 (64), not {other}"
        ))),
    }
}

/// Registers `book` and writes its handle to `out`.
///
/// # Safety
/// `out` is non-NULL, aligned and valid for one write (checked by the callers before the
/// book is built, so that no book is built for nothing).
pub(crate) unsafe fn register(book: AnyBook, out: *mut FolioBookHandle) -> Result<(), Failure> {
    let handle = registry::insert(Entry::new(book))?;
    // SAFETY: as this function's contract.
    let written = unsafe { pointer::write(out, handle, "out") };
    if written.is_err() {
        // Unreachable after the callers' check; never leave an unreachable book behind.
        let _ = registry::remove(handle);
    }
    written
}

/// Creates a book from `settings` and writes its handle to `*out`. The book starts at rest,
/// its blocks settled into their rest shape (tens of block-only steps, a few hundred for
/// a book of two pages; typically a millisecond).
///
/// Returns `FOLIO_STATUS_NULL_POINTER` for a NULL argument, `FOLIO_STATUS_INVALID_ARGUMENT`
/// for out-of-range settings (the message names the field), `FOLIO_STATUS_BOOK_ERROR` if the
/// solver's setup fails, `FOLIO_STATUS_OUT_OF_HANDLES`. On failure `*out` is left as it was.
/// Destroy the book with `folio_book_destroy`.
///
/// # Safety
/// `settings` is NULL or points to a readable `FolioBookSettings`; `out` is NULL or valid
/// for a write of one `FolioBookHandle`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_create(
    settings: *const FolioBookSettings,
    out: *mut FolioBookHandle,
) -> FolioStatus {
    guard::call("folio_book_create", || {
        pointer::check(out, "out")?;
        // SAFETY: `settings` is NULL (refused by `read`) or readable (contract); every field
        // is an integer or a double, valid for any bits.
        let settings = unsafe { pointer::read(settings, "settings") }?;
        let book = build(&settings)?;
        // SAFETY: `out` was checked non-NULL and aligned above; writable by contract.
        unsafe { register(book, out) }
    })
}

/// Destroys the book `handle` names and frees its memory; the handle (and every copy of
/// it) becomes stale. Destroying a stale handle (twice, or one never created) returns
/// `FOLIO_STATUS_STALE_HANDLE` and does nothing. A book another thread is using is freed
/// when that call returns. A poisoned book can be destroyed.
#[unsafe(no_mangle)]
pub extern "C" fn folio_book_destroy(handle: FolioBookHandle) -> FolioStatus {
    guard::call("folio_book_destroy", || {
        let entry = registry::remove(handle)?;
        drop(entry);
        Ok(())
    })
}
