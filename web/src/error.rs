//! The web crate's error: a message for the page to show (the wasm boundary turns it into a
//! JavaScript `Error`).

use core::fmt;

use folio_book::BookError;

/// Why a call was refused, in words for the page.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WebError {
    /// What went wrong.
    pub message: String,
}

impl WebError {
    /// An error saying `message`.
    #[must_use]
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }

    /// A book's refusal.
    #[must_use]
    pub fn book(e: BookError) -> Self {
        Self::new(format!("the book refused: {e}"))
    }
}

impl fmt::Display for WebError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl core::error::Error for WebError {}
