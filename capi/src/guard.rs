//! The boundary guard: every exported function runs its body here, so that a panic never
//! unwinds into C and every failure leaves a message for the caller.

use alloc::boxed::Box;
use alloc::string::String;
use core::any::Any;
use core::panic::AssertUnwindSafe;
use std::panic::catch_unwind;

use crate::failure::Failure;
use crate::last_error;
use crate::status::FolioStatus;

/// The text of a panic payload (`panic!` with a literal or a formatted message).
fn panic_text(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        String::from(*s)
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        String::from("(no message)")
    }
}

/// Drops a panic payload without letting a panic in its destructor escape: a second panic
/// is caught and its payload leaked.
fn drop_payload(payload: Box<dyn Any + Send>) {
    if let Err(again) = catch_unwind(AssertUnwindSafe(move || drop(payload))) {
        core::mem::forget(again);
    }
}

/// Runs `body`, catching any panic: `Ok` → `FOLIO_STATUS_OK`, `Err` → the failure's status,
/// a panic → `FOLIO_STATUS_PANIC`. Nothing unwinds out of this function.
///
/// `AssertUnwindSafe` is sound here because nothing `body` may leave half-updated is
/// observed after a panic without a check: a book is behind a `Mutex` whose poisoning is
/// reported as `FOLIO_STATUS_POISONED`, and the registry's updates cannot panic between
/// their writes (see `registry`).
fn run(body: impl FnOnce() -> Result<(), Failure>) -> Result<(), Failure> {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(result) => result,
        Err(payload) => {
            let text = panic_text(payload.as_ref());
            drop_payload(payload);
            Err(Failure::new(
                FolioStatus::Panic,
                format!("internal panic (a bug in Folio): {text}"),
            ))
        }
    }
}

/// [`run`] for exported function `function`: keeps the failure's message, prefixed with the
/// function's name, as the thread's last error, or clears the last error on success.
pub(crate) fn call(
    function: &'static str,
    body: impl FnOnce() -> Result<(), Failure>,
) -> FolioStatus {
    match run(body) {
        Ok(()) => {
            last_error::clear();
            FolioStatus::Ok
        }
        Err(failure) => {
            last_error::set(format!("{function}: {}", failure.message));
            failure.status
        }
    }
}

/// [`run`] without touching the last error (for `folio_last_error_message` itself).
pub(crate) fn call_quiet(body: impl FnOnce() -> Result<(), Failure>) -> FolioStatus {
    match run(body) {
        Ok(()) => FolioStatus::Ok,
        Err(failure) => failure.status,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let status = call("folio_test", || panic!("boom {}", 7));
        assert_eq!(status, FolioStatus::Panic);
        let message = last_error::get();
        assert!(
            message.starts_with("folio_test: internal panic"),
            "{message}"
        );
        assert!(message.ends_with("boom 7"), "{message}");
        assert_eq!(call("folio_test", || Ok(())), FolioStatus::Ok);
        assert_eq!(last_error::get(), "");
    }

    #[test]
    fn a_panicking_payload_destructor_does_not_escape() {
        struct Loud;
        impl Drop for Loud {
            fn drop(&mut self) {
                panic!("payload destructor");
            }
        }
        let status = call("folio_test", || std::panic::panic_any(Loud));
        assert_eq!(status, FolioStatus::Panic);
        assert!(last_error::get().ends_with("(no message)"));
    }
}
