//! `folio_book_step`.

use crate::guard;
use crate::handle::FolioBookHandle;
use crate::pointer;
use crate::registry;
use crate::status::FolioStatus;
use crate::step_report::FolioStepReport;

/// Advances the book by one time step $h$: the implicit-Euler step of the blocks (and of the
/// active page, if any), collision handling, the constraint projection, and the merge of a
/// released page that came to rest. Writes the step's report to `*out`.
///
/// A step that did not converge is not a failure of the call: see `out->status`. Returns
/// `FOLIO_STATUS_NULL_POINTER` for a NULL `out` (the book is not stepped),
/// `FOLIO_STATUS_STALE_HANDLE`, or `FOLIO_STATUS_BOOK_ERROR` if the solver's setup failed.
///
/// # Safety
/// `out` is NULL or valid for a write of one `FolioStepReport`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_step(
    handle: FolioBookHandle,
    out: *mut FolioStepReport,
) -> FolioStatus {
    guard::call("folio_book_step", || {
        pointer::check(out, "out")?;
        let report = registry::with_entry(handle, |e| e.step())?;
        // SAFETY: `out` is non-NULL and aligned (checked above) and valid for one write
        // (contract).
        unsafe { pointer::write(out, report, "out") }
    })
}
