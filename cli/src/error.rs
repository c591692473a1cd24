//! Why a checked scene could not run.

/// Why a checked scene could not run.
#[derive(Debug)]
pub struct RunError(pub String);

impl core::fmt::Display for RunError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.0)
    }
}

impl core::error::Error for RunError {}

pub(crate) fn fail(e: impl core::fmt::Display) -> RunError {
    RunError(e.to_string())
}
