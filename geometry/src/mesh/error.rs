//! Typed errors of the mesh builders and the input checks that produce them.

use core::fmt;

use folio_kernels::math;

use super::MAX_COORDINATE;

/// Why a mesh could not be built. The mesh passed in is left unchanged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// The number of node positions does not match the grid (`nx * nz`).
    PositionCount {
        /// Positions the grid needs.
        expected: usize,
        /// Positions given.
        found: usize,
    },
    /// Node `index` has a NaN or infinite coordinate.
    NonFinite {
        /// The node's index in the input slice.
        index: usize,
    },
    /// Node `index` has a coordinate of magnitude above [`MAX_COORDINATE`].
    CoordinateTooLarge {
        /// The node's index in the input slice.
        index: usize,
    },
    /// A length parameter is not a finite positive number.
    NonPositive {
        /// The parameter's name as in the builder's signature.
        field: &'static str,
    },
    /// A parameter is NaN or infinite, or finite but outside its documented range
    /// (a length above [`MAX_COORDINATE`], a negative overhang).
    OutOfRange {
        /// The parameter's name as in the builder's signature.
        field: &'static str,
    },
    /// Too few nodes: a grid needs at least 2 x 2 vertices, a midline at least 2 nodes.
    TooFewNodes {
        /// The count given (for a grid, the smaller of `nx` and `nz`).
        found: usize,
    },
    /// The mesh would exceed `u32` vertex indices, or its storage could not be allocated.
    TooManyVertices {
        /// Vertices the mesh would hold (`usize::MAX` if the count itself overflows).
        needed: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PositionCount { expected, found } => {
                write!(f, "{found} node positions given, the grid has {expected}")
            }
            Self::NonFinite { index } => write!(f, "node {index} has a non-finite coordinate"),
            Self::CoordinateTooLarge { index } => {
                write!(f, "node {index} has a coordinate beyond {MAX_COORDINATE:e}")
            }
            Self::NonPositive { field } => write!(f, "`{field}` must be finite and positive"),
            Self::OutOfRange { field } => write!(f, "`{field}` is out of its range"),
            Self::TooFewNodes { found } => {
                write!(f, "{found} nodes given, at least 2 are needed")
            }
            Self::TooManyVertices { needed } => {
                write!(
                    f,
                    "a mesh of {needed} vertices exceeds u32 indices or memory"
                )
            }
        }
    }
}

impl core::error::Error for MeshError {}

/// `Ok` unless some node has a non-finite coordinate or one beyond [`MAX_COORDINATE`].
pub(super) fn check_points<const D: usize>(points: &[[f64; D]]) -> Result<(), MeshError> {
    for (index, p) in points.iter().enumerate() {
        if p.iter().any(|c| !c.is_finite()) {
            return Err(MeshError::NonFinite { index });
        }
        if p.iter().any(|&c| math::abs::<f64>(c) > MAX_COORDINATE) {
            return Err(MeshError::CoordinateTooLarge { index });
        }
    }
    Ok(())
}

/// `Ok` for a length in $(0, M]$, $M$ = [`MAX_COORDINATE`].
pub(super) fn check_positive(field: &'static str, value: f64) -> Result<(), MeshError> {
    if !(value.is_finite() && value > 0.0) {
        Err(MeshError::NonPositive { field })
    } else if value > MAX_COORDINATE {
        Err(MeshError::OutOfRange { field })
    } else {
        Ok(())
    }
}

/// `Ok` for a length in $[0, M]$, $M$ = [`MAX_COORDINATE`].
pub(super) fn check_non_negative(field: &'static str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && (0.0..=MAX_COORDINATE).contains(&value) {
        Ok(())
    } else {
        Err(MeshError::OutOfRange { field })
    }
}

/// `Ok` for a point or direction whose coordinates are finite (and, with `bounded`, within
/// [`MAX_COORDINATE`]).
pub(super) fn check_vector<const D: usize>(
    field: &'static str,
    value: [f64; D],
    bounded: bool,
) -> Result<(), MeshError> {
    let ok = value
        .iter()
        .all(|&c| c.is_finite() && (!bounded || math::abs::<f64>(c) <= MAX_COORDINATE));
    if ok {
        Ok(())
    } else {
        Err(MeshError::OutOfRange { field })
    }
}
