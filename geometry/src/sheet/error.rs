//! Typed errors of the sheet mesh and its edits.

use core::fmt;

/// Why a sheet could not be built or edited. The mesh is left unchanged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SheetError {
    /// A parameter is not finite or outside its documented range.
    OutOfRange {
        /// The parameter's name.
        field: &'static str,
    },
    /// Vertex `index` has a non-finite pattern coordinate, position or velocity.
    NonFinite {
        /// The vertex.
        index: usize,
    },
    /// Triangle `index` names a vertex that does not exist.
    BadIndex {
        /// The triangle.
        index: usize,
    },
    /// Triangle `index` is clockwise or of (nearly) zero area in the pattern.
    Degenerate {
        /// The triangle.
        index: usize,
    },
    /// The edge `(a, b)` is used by more than two triangles or twice in one direction.
    NonManifoldEdge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// Vertex `index` has more than one fan of triangles (a bow tie) or no triangle.
    NonManifoldVertex {
        /// The vertex.
        index: usize,
    },
    /// The edge `(a, b)` does not exist or is already on the boundary, so it cannot be cut.
    NotInteriorEdge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// Cutting `(a, b)` would open a hole inside the sheet: neither end is on the boundary.
    InteriorCut {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// The point lies in no triangle of the sheet (or outside the edited fan).
    OutsideSheet,
    /// The edit would leave a triangle clockwise or thinner than the quality bound.
    WouldInvert {
        /// The triangle that would be degenerate.
        index: usize,
    },
    /// The mesh would exceed `u32` vertex or triangle indices.
    TooLarge,
}

impl fmt::Display for SheetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutOfRange { field } => write!(f, "`{field}` is not finite or out of range"),
            Self::NonFinite { index } => write!(f, "vertex {index} has a non-finite value"),
            Self::BadIndex { index } => write!(f, "triangle {index} names a missing vertex"),
            Self::Degenerate { index } => {
                write!(
                    f,
                    "triangle {index} is clockwise or degenerate in the pattern"
                )
            }
            Self::NonManifoldEdge { a, b } => write!(f, "edge ({a}, {b}) is not manifold"),
            Self::NonManifoldVertex { index } => write!(f, "vertex {index} is not manifold"),
            Self::NotInteriorEdge { a, b } => {
                write!(f, "edge ({a}, {b}) is not an interior edge of the sheet")
            }
            Self::InteriorCut { a, b } => {
                write!(
                    f,
                    "cutting ({a}, {b}) would open a hole: neither end is on the boundary"
                )
            }
            Self::OutsideSheet => write!(f, "the point is outside the sheet"),
            Self::WouldInvert { index } => {
                write!(f, "the edit would invert or flatten triangle {index}")
            }
            Self::TooLarge => write!(f, "the sheet would exceed u32 indices"),
        }
    }
}

impl core::error::Error for SheetError {}
