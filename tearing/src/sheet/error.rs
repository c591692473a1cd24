//! [`TearingSheetError`]: why a tearing sheet could not be built or a finger placed.

use core::fmt;

use folio_geometry::sheet::SheetError;
use folio_kernels::SettingError;

use folio_solvers::error::SolverError;

/// Why a [`super::TearingSheet`] refused a request. The sheet is unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum TearingSheetError {
    /// A setting of [`super::SheetSettings`] is NaN, infinite or out of range; the path is
    /// the field's from [`super::SheetSettings`] (`width`, `cones.flip_margin`,
    /// `tearing.fibers.scale`).
    InvalidSetting(SettingError),
    /// The sheet mesh was refused or an edit failed.
    Mesh(SheetError),
    /// The solver refused the sheet's model.
    Solver(SolverError),
    /// A kernel refused a triangle or hinge of the mesh (a degenerate pattern triangle).
    Kernel {
        /// The triangle or edge.
        index: usize,
    },
    /// The finger's material point is not on the sheet.
    FingerOffSheet,
    /// Another finger already holds that material point (the vertex).
    CoincidentFingers {
        /// The vertex both would hold.
        vertex: u32,
    },
    /// No finger with that index.
    NoSuchFinger {
        /// The index given.
        index: usize,
    },
    /// A finger target is NaN, infinite or beyond the coordinate bound.
    NonFiniteTarget,
}

impl fmt::Display for TearingSheetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidSetting(e) => write!(f, "sheet setting {e}"),
            Self::Mesh(e) => write!(f, "sheet mesh: {e}"),
            Self::Solver(e) => write!(f, "solver: {e}"),
            Self::Kernel { index } => write!(f, "element {index} of the sheet is degenerate"),
            Self::FingerOffSheet => write!(f, "the finger's material point is off the sheet"),
            Self::CoincidentFingers { vertex } => {
                write!(f, "another finger already holds vertex {vertex}")
            }
            Self::NoSuchFinger { index } => write!(f, "there is no finger {index}"),
            Self::NonFiniteTarget => write!(f, "the finger target is not finite"),
        }
    }
}

impl core::error::Error for TearingSheetError {}

impl From<SheetError> for TearingSheetError {
    fn from(e: SheetError) -> Self {
        Self::Mesh(e)
    }
}

impl From<SolverError> for TearingSheetError {
    fn from(e: SolverError) -> Self {
        Self::Solver(e)
    }
}

impl From<SettingError> for TearingSheetError {
    fn from(e: SettingError) -> Self {
        Self::InvalidSetting(e)
    }
}
