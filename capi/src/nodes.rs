//! The simulated nodes out: the active page's grid and positions, the held node.

use crate::failure::Failure;
use crate::guard;
use crate::handle::FolioBookHandle;
use crate::pointer;
use crate::registry;
use crate::status::FolioStatus;

/// Writes the active page's grid size: `columns` nodes across the page (from the binding,
/// column 0, to the fore-edge) and `rows` along the binding; `columns = quads_across + 1`,
/// `rows = quads_along + 1`. Fixed for the book's life, so it works at rest too.
///
/// # Safety
/// `columns` and `rows` are NULL or valid for a write of one `uint32_t` each.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_page_grid(
    handle: FolioBookHandle,
    columns: *mut u32,
    rows: *mut u32,
) -> FolioStatus {
    guard::call("folio_book_page_grid", || {
        pointer::check(columns, "columns")?;
        pointer::check(rows, "rows")?;
        let grid = registry::with_entry(handle, |e| Ok(e.book.grid()))?;
        let size = |n: usize| u32::try_from(n).map_err(|_| Failure::invalid("grid too large"));
        let (nx, nz) = (size(grid.nx)?, size(grid.nz)?);
        // SAFETY: both checked non-NULL and aligned above; writable by contract.
        unsafe {
            pointer::write(columns, nx, "columns")?;
            pointer::write(rows, nz, "rows")
        }
    })
}

/// Copies the active page's simulated node positions (the DOG grid, seed `000_…` Sec. 3.2)
/// into `xyz`: $(x, y, z)$ per node in the book frame, node $(i, j)$ (column $i$, row $j$)
/// at index $i + \text{columns}\cdot j$, so `3 * columns * rows` doubles. Exact in both
/// precisions.
///
/// Returns `FOLIO_STATUS_NO_ACTIVE_PAGE` when no page is held or falling,
/// `FOLIO_STATUS_NULL_POINTER`, `FOLIO_STATUS_BUFFER_TOO_SMALL`,
/// `FOLIO_STATUS_STALE_HANDLE`; on failure nothing is written.
///
/// # Safety
/// `xyz` is NULL or valid for writes of `xyz_len` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_page_positions(
    handle: FolioBookHandle,
    xyz: *mut f64,
    xyz_len: usize,
) -> FolioStatus {
    guard::call("folio_book_page_positions", || {
        registry::with_entry(handle, |e| {
            let needed = 3 * e.book.grid().len();
            pointer::check_buffer(xyz, xyz_len, needed, false, "xyz", "doubles")?;
            let mut values = alloc::vec![0.0; needed];
            if !e.book.page_positions(&mut values) {
                return Err(Failure::new(FolioStatus::NoActivePage, "no active page"));
            }
            // SAFETY: `check_buffer` found `xyz` non-NULL, aligned and at least `needed`
            // long; writable for `xyz_len` doubles by contract.
            unsafe { pointer::copy_into(xyz, &values) };
            Ok(())
        })
    })
}

/// Writes the held page node's current position (3 doubles, book frame) to `xyz`: where a
/// grab took hold, the starting point of a drag path.
///
/// Returns `FOLIO_STATUS_NOT_HELD` when no page is held, `FOLIO_STATUS_NULL_POINTER`,
/// `FOLIO_STATUS_STALE_HANDLE`.
///
/// # Safety
/// `xyz` is NULL or valid for writes of 3 doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_held_position(
    handle: FolioBookHandle,
    xyz: *mut f64,
) -> FolioStatus {
    guard::call("folio_book_held_position", || {
        pointer::check(xyz, "xyz")?;
        let p = registry::with_entry(handle, |e| {
            e.book
                .held_position()
                .ok_or_else(|| Failure::new(FolioStatus::NotHeld, "no page is held"))
        })?;
        // SAFETY: `xyz` was checked non-NULL and aligned above; valid for 3 doubles by
        // contract.
        unsafe { pointer::copy_into(xyz, &p) };
        Ok(())
    })
}
