//! The calling thread's last error message: kept by every call ([`crate::guard`]), read by
//! `folio_last_error_message` ([`crate::error_message`]).

use alloc::string::String;
use core::cell::RefCell;

std::thread_local! {
    /// The message of the thread's last call: empty after a success.
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Keeps `message` as the calling thread's last error. Never panics: if the thread's
/// storage is being torn down or is in use, the message is dropped.
pub(crate) fn set(message: String) {
    let _ = LAST_ERROR.try_with(|cell| {
        if let Ok(mut last) = cell.try_borrow_mut() {
            *last = message;
        }
    });
}

/// Clears the calling thread's last error (a success), releasing its storage.
pub(crate) fn clear() {
    let _ = LAST_ERROR.try_with(|cell| {
        if let Ok(mut last) = cell.try_borrow_mut() {
            if !last.is_empty() {
                *last = String::new();
            }
        }
    });
}

/// A copy of the calling thread's last error ("" if there is none).
pub(crate) fn get() -> String {
    LAST_ERROR
        .try_with(|cell| cell.try_borrow().map(|s| s.clone()).unwrap_or_default())
        .unwrap_or_default()
}
