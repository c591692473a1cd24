//! Typed errors of the book's setup and input.

use core::fmt;

use folio_kernels::{KernelError, SettingError};

use folio_solvers::error::SolverError;

/// Why a book could not be built or an input was refused. A refused input leaves the book
/// exactly as it was.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum BookError {
    /// A weight, mass or other parameter a kernel refused.
    Kernel(KernelError),
    /// The time stepper's settings or the model's analysis failed.
    Solver(SolverError),
    /// A book setting is NaN, infinite or out of its range; the path is the field's in
    /// [`super::BookSettings`] (`params.page_width`, `weights.glue`, `solver.time_step`).
    InvalidSetting(SettingError),
    /// An input (ray, camera direction, page count) is NaN, infinite or zero where it may not be.
    InvalidInput {
        /// Which input.
        what: &'static str,
    },
}

impl fmt::Display for BookError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Kernel(e) => write!(f, "book term: {e}"),
            Self::Solver(e) => write!(f, "book solver: {e}"),
            Self::InvalidSetting(e) => write!(f, "book setting {e}"),
            Self::InvalidInput { what } => write!(f, "invalid input: {what}"),
        }
    }
}

#[cfg(feature = "std")]
impl core::error::Error for BookError {}

impl From<SettingError> for BookError {
    fn from(e: SettingError) -> Self {
        Self::InvalidSetting(e)
    }
}

impl From<KernelError> for BookError {
    fn from(e: KernelError) -> Self {
        Self::Kernel(e)
    }
}

impl From<SolverError> for BookError {
    fn from(e: SolverError) -> Self {
        Self::Solver(e)
    }
}
