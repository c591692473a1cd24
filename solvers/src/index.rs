//! The stored index type of the factor's structure: `u16` when the matrix is small enough,
//! `u32` otherwise, chosen by [`crate::symbolic::Symbolic::analyse`].
//!
//! On a microcontroller the factor's row indices are, with $L$'s values, its largest
//! allocation; halving them matters there (issue 19, "A lean $LDL^\top$").

use alloc::vec::Vec;

/// No index: an eliminated coordinate, a dropped entry, a missing parent, as a `u32`
/// ([`crate::pattern::NONE`] re-exports it).
pub const NONE: u32 = u32::MAX;

/// An unsigned index stored in the factor's structure ([`u16`] or [`u32`]; sealed).
pub trait Index: Copy + Ord + core::fmt::Debug + sealed::Sealed {
    /// Largest value this type holds.
    const MAX: usize;
    /// The index as a `usize`.
    #[must_use]
    fn get(self) -> usize;
    /// `value` as this type; the caller guarantees `value <= Self::MAX`.
    #[must_use]
    fn new(value: usize) -> Self;
}

impl Index for u16 {
    const MAX: usize = u16::MAX as usize;
    #[inline]
    fn get(self) -> usize {
        usize::from(self)
    }
    #[inline]
    fn new(value: usize) -> Self {
        value as u16
    }
}

impl Index for u32 {
    const MAX: usize = u32::MAX as usize;
    #[inline]
    fn get(self) -> usize {
        self as usize
    }
    #[inline]
    fn new(value: usize) -> Self {
        value as u32
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for u16 {}
    impl Sealed for u32 {}
}

/// Indices stored in one of the two widths (see [`Index`]): a read-only view of an array
/// of the factor's structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Indices<'a> {
    /// Two bytes per index.
    U16(&'a [u16]),
    /// Four bytes per index.
    U32(&'a [u32]),
}

impl Indices<'_> {
    /// Number of indices.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        match self {
            Self::U16(v) => v.len(),
            Self::U32(v) => v.len(),
        }
    }

    /// Whether there are none.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index `at` as a `usize`; panics when `at` is out of range, like slice indexing.
    #[inline]
    #[must_use]
    pub fn get(&self, at: usize) -> usize {
        match self {
            Self::U16(v) => usize::from(v[at]),
            Self::U32(v) => v[at] as usize,
        }
    }

    /// Bytes the indices occupy.
    #[inline]
    #[must_use]
    pub fn bytes(&self) -> usize {
        match self {
            Self::U16(v) => 2 * v.len(),
            Self::U32(v) => 4 * v.len(),
        }
    }

    /// The indices widened to `u32` (a copy, for tests and reports).
    #[must_use]
    pub fn to_u32(&self) -> Vec<u32> {
        (0..self.len()).map(|at| self.get(at) as u32).collect()
    }
}
