//! Typed errors of the book's setup and input.

use core::fmt;

use crate::LayoutError;
use folio_kernels::KernelError;

use folio_solvers::error::SolverError;

/// Why a book could not be built or an input was refused. A refused input leaves the book
/// exactly as it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BookError {
    /// The book's parameters (pages, sizes, thickness) are unusable.
    Layout(LayoutError),
    /// A weight, mass or other parameter a kernel refused.
    Kernel(KernelError),
    /// The time stepper's settings or the model's analysis failed.
    Solver(SolverError),
    /// A book setting is out of range.
    InvalidSetting {
        /// The field of [`super::BookSettings`].
        field: &'static str,
        /// What it must be.
        requirement: &'static str,
    },
    /// An input (ray, camera direction, page count) is NaN, infinite or zero where it may not be.
    InvalidInput {
        /// Which input.
        what: &'static str,
    },
}

impl fmt::Display for BookError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Layout(e) => write!(f, "book layout: {e}"),
            Self::Kernel(e) => write!(f, "book term: {e}"),
            Self::Solver(e) => write!(f, "book solver: {e}"),
            Self::InvalidSetting { field, requirement } => {
                write!(f, "book setting `{field}` must be {requirement}")
            }
            Self::InvalidInput { what } => write!(f, "invalid input: {what}"),
        }
    }
}

#[cfg(feature = "std")]
impl core::error::Error for BookError {}

impl From<LayoutError> for BookError {
    fn from(e: LayoutError) -> Self {
        Self::Layout(e)
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
