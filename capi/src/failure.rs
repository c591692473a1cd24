//! A failed call: the status to return and the message to keep for the caller.

use alloc::string::String;

use folio_book::BookError;
use folio_solvers::SolverError;

use crate::status::FolioStatus;

/// Why a call failed (the crate's internal error type; it never crosses the boundary).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Failure {
    /// What the C function returns.
    pub status: FolioStatus,
    /// What [`crate::folio_last_error_message`] returns (without the function name, which
    /// the guard prepends).
    pub message: String,
}

impl Failure {
    /// A failure with `status` and `message`.
    pub fn new(status: FolioStatus, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
        }
    }

    /// `FOLIO_STATUS_NULL_POINTER` for argument `what`.
    pub fn null(what: &str) -> Self {
        Self::new(FolioStatus::NullPointer, format!("`{what}` is NULL"))
    }

    /// `FOLIO_STATUS_INVALID_ARGUMENT` with `message`.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(FolioStatus::InvalidArgument, message)
    }

    /// The status for a [`BookError`]: unusable settings or input are the caller's
    /// (`INVALID_ARGUMENT`: a setting, solver setting, kernel parameter or input error),
    /// anything else is the book's (`BOOK_ERROR`).
    pub fn book(e: BookError) -> Self {
        let status = match e {
            BookError::Kernel(_)
            | BookError::Solver(SolverError::InvalidSetting(_))
            | BookError::InvalidSetting(_)
            | BookError::InvalidInput { .. } => FolioStatus::InvalidArgument,
            _ => FolioStatus::BookError,
        };
        Self::new(status, e.to_string())
    }
}
