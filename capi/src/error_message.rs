//! `folio_last_error_message`: the calling thread's last error ([`crate::last_error`]) copied
//! into the caller's buffer.

use core::ffi::c_char;

use crate::failure::Failure;
use crate::guard;
use crate::last_error;
use crate::pointer;
use crate::status::FolioStatus;

/// The longest prefix of `s` of at most `max` bytes that ends on a character boundary.
fn prefix(s: &str, max: usize) -> &str {
    let mut end = max.min(s.len());
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

/// Copies the message of the calling thread's last failed call into `buf` as UTF-8 text
/// followed by a NUL. The message is the empty string after a call that succeeded; it
/// names the function and the problem, e.g.
/// `folio_book_drag: drag target (x, y, z) = (NaN, 1, 2) is not finite`.
///
/// - `needed` (may be NULL) receives the buffer size the whole message needs, its NUL
///   included ($\text{strlen} + 1$ bytes).
/// - `buf` NULL with `len` 0 is a size query: only `needed` is written; returns OK.
/// - If `len` is at least `needed`, the whole message is copied; returns OK.
/// - If `len` is smaller (but not 0), the message is cut at a character boundary to at
///   most `len - 1` bytes and NUL-terminated; returns `FOLIO_STATUS_BUFFER_TOO_SMALL`.
/// - `buf` NULL with `len` > 0 returns `FOLIO_STATUS_NULL_POINTER`; `len` 0 with a
///   non-NULL `buf` writes nothing and returns `FOLIO_STATUS_BUFFER_TOO_SMALL`.
///
/// This function does not replace the last error, so it can be called again with a larger
/// buffer; its own failures are reported only through its return value.
///
/// # Safety
/// `buf` is NULL or valid for writes of `len` bytes; `needed` is NULL or valid for a write
/// of one `size_t`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_last_error_message(
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> FolioStatus {
    guard::call_quiet(|| {
        let message = last_error::get();
        let whole = message.len() + 1;
        if !needed.is_null() {
            // SAFETY: `needed` is non-NULL and, by this function's contract, valid for one
            // write; `pointer::write` checks its alignment first.
            unsafe { pointer::write(needed, whole, "needed") }?;
        }
        if buf.is_null() {
            return if len == 0 {
                Ok(())
            } else {
                Err(Failure::null("buf"))
            };
        }
        if len == 0 {
            return Err(Failure::new(
                FolioStatus::BufferTooSmall,
                "`len` is 0: no room for the NUL",
            ));
        }
        let text = prefix(&message, len - 1);
        let mut bytes = alloc::vec::Vec::with_capacity(text.len() + 1);
        bytes.extend(text.bytes().map(|b| b as c_char));
        bytes.push(0);
        // SAFETY: `buf` is non-NULL and valid for `len` bytes by contract; `bytes` holds at
        // most `len - 1 + 1 = len` elements, and `c_char` has alignment 1.
        unsafe { pointer::copy_into(buf, &bytes) };
        if text.len() < message.len() {
            Err(Failure::new(
                FolioStatus::BufferTooSmall,
                format!("message truncated: {whole} bytes needed"),
            ))
        } else {
            Ok(())
        }
    })
}

#[cfg(test)]
mod tests {
    use super::prefix;

    /// A cut never splits a UTF-8 character.
    #[test]
    fn truncation_keeps_whole_characters() {
        let s = "a≥b"; // '≥' is 3 bytes: 1..4
        assert_eq!(prefix(s, 0), "");
        assert_eq!(prefix(s, 1), "a");
        assert_eq!(prefix(s, 2), "a");
        assert_eq!(prefix(s, 3), "a");
        assert_eq!(prefix(s, 4), "a≥");
        assert_eq!(prefix(s, 99), s);
    }
}
