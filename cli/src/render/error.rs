//! Why a contact sheet could not be set up.

use core::fmt;

/// A contact-sheet setting that cannot be used ([`super::ContactSheet::new`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RenderError {
    /// A tile dimension is 0 or above [`super::MAX_TILE_SIZE`] pixels.
    TileSize {
        /// The tile size given (width, height).
        tile: [u32; 2],
    },
    /// `columns` is 0 or above [`super::MAX_COLUMNS`].
    Columns {
        /// The count given.
        columns: u32,
    },
    /// `supersample` is 0 or above [`super::MAX_SUPERSAMPLE`].
    Supersample {
        /// The factor given.
        supersample: u32,
    },
    /// A paper parameter is out of its range.
    Paper {
        /// The field of [`super::Paper`].
        field: &'static str,
    },
    /// The bounds have a non-finite coordinate, or a minimum above its maximum.
    Bounds {
        /// The axis (0 = X, 1 = Y, 2 = Z).
        axis: usize,
    },
    /// The eye or light direction is not finite or is zero.
    Direction {
        /// `"eye"` or `"light"`.
        field: &'static str,
    },
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TileSize { tile } => write!(
                f,
                "tile size {}x{} must be between 1 and {} pixels",
                tile[0],
                tile[1],
                super::MAX_TILE_SIZE
            ),
            Self::Columns { columns } => write!(
                f,
                "columns {columns} must be between 1 and {}",
                super::MAX_COLUMNS
            ),
            Self::Supersample { supersample } => write!(
                f,
                "supersample {supersample} must be between 1 and {}",
                super::MAX_SUPERSAMPLE
            ),
            Self::Paper { field } => write!(f, "paper `{field}` is out of its range"),
            Self::Bounds { axis } => write!(
                f,
                "bounds on axis {axis} must be finite with minimum <= maximum"
            ),
            Self::Direction { field } => {
                write!(f, "the {field} direction must be finite and not zero")
            }
        }
    }
}

impl core::error::Error for RenderError {}
