//! Checked access through the caller's raw pointers: every read, write and copy of the C API
//! goes through here, after a NULL, alignment and length check.

use core::ptr;

use crate::failure::Failure;
use crate::status::FolioStatus;

/// `Ok` when `ptr` is not NULL and is aligned for `T`; else `NULL_POINTER` or
/// `INVALID_ARGUMENT`, naming argument `what`.
pub(crate) fn check<T>(ptr: *const T, what: &str) -> Result<(), Failure> {
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    if !ptr.is_aligned() {
        return Err(Failure::invalid(format!(
            "`{what}` is not aligned to {} bytes",
            core::mem::align_of::<T>()
        )));
    }
    Ok(())
}

/// Checks a caller buffer of `len` elements that must receive `needed` elements: `Ok(true)`
/// to copy, `Ok(false)` to skip (`optional` buffers may be NULL with `len` 0), else
/// `NULL_POINTER`, `INVALID_ARGUMENT` (misaligned) or `BUFFER_TOO_SMALL` naming `what` and
/// the `needed` count of `unit`s.
pub(crate) fn check_buffer<T>(
    ptr: *const T,
    len: usize,
    needed: usize,
    optional: bool,
    what: &str,
    unit: &str,
) -> Result<bool, Failure> {
    if ptr.is_null() && optional && len == 0 {
        return Ok(false);
    }
    check(ptr, what)?;
    if len < needed {
        return Err(Failure::new(
            FolioStatus::BufferTooSmall,
            format!("`{what}` holds {len} {unit}, {needed} needed"),
        ));
    }
    Ok(true)
}

/// Reads `*ptr` after [`check`].
///
/// # Safety
/// `ptr` is NULL or points to a readable `T`, and every bit pattern of `T`'s size is a valid
/// `T` (plain integers and floats, as in `FolioBookSettings`), so that whatever the caller
/// put there is defined.
pub(crate) unsafe fn read<T: Copy>(ptr: *const T, what: &str) -> Result<T, Failure> {
    check(ptr, what)?;
    // SAFETY: non-NULL and aligned (checked), readable and valid for any bits (contract).
    Ok(unsafe { ptr.read() })
}

/// Writes `value` to `*ptr` after [`check`]; the old contents are not read.
///
/// # Safety
/// `ptr` is NULL or valid for a write of one `T`.
pub(crate) unsafe fn write<T>(ptr: *mut T, value: T, what: &str) -> Result<(), Failure> {
    check(ptr, what)?;
    // SAFETY: non-NULL and aligned (checked), writable (contract); `write` does not drop or
    // read the previous contents, which may be uninitialized.
    unsafe { ptr.write(value) };
    Ok(())
}

/// Copies `src` to the caller buffer at `dst`.
///
/// # Safety
/// `dst` is non-NULL, aligned for `T` and valid for writes of `src.len()` elements (the
/// callers check NULL, alignment and the length with [`check_buffer`] first). `src` is
/// memory of this library, which the caller never sees, so the two cannot overlap.
pub(crate) unsafe fn copy_into<T: Copy>(dst: *mut T, src: &[T]) {
    // SAFETY: as the function's contract; `src` is valid for `src.len()` reads.
    unsafe { ptr::copy_nonoverlapping(src.as_ptr(), dst, src.len()) };
}
