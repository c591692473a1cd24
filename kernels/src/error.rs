//! Typed errors of term constructors (evaluation itself never fails).

use core::fmt;

/// Why a term could not be built from its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum KernelError {
    /// A rest length (or edge length of a rest configuration) is zero, negative, below
    /// [`crate::Real::LENGTH_FLOOR`] or not finite; `index` names the edge in the term's
    /// documented node order.
    NonPositiveRestLength {
        /// Which edge of the term.
        index: usize,
    },
    /// A parameter is NaN or infinite.
    NonFiniteParameter {
        /// The parameter's name as in the constructor.
        name: &'static str,
    },
    /// A parameter is finite but outside its documented range.
    OutOfRange {
        /// The parameter's name as in the constructor.
        name: &'static str,
    },
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonPositiveRestLength { index } => {
                write!(
                    f,
                    "rest length of edge {index} is not a positive finite length"
                )
            }
            Self::NonFiniteParameter { name } => write!(f, "parameter `{name}` is not finite"),
            Self::OutOfRange { name } => write!(f, "parameter `{name}` is out of its range"),
        }
    }
}

impl core::error::Error for KernelError {}

use crate::real::Real;

/// `Ok(v)` if `v` is finite, else [`KernelError::NonFiniteParameter`].
pub(crate) fn finite<T: Real>(v: T, name: &'static str) -> Result<T, KernelError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(KernelError::NonFiniteParameter { name })
    }
}

/// `Ok(1/l)` if `l` is a usable rest length, else [`KernelError::NonPositiveRestLength`].
pub(crate) fn inverse_length<T: Real>(l: T, index: usize) -> Result<T, KernelError> {
    if l.is_finite() && l >= T::LENGTH_FLOOR {
        Ok(T::ONE / l)
    } else {
        Err(KernelError::NonPositiveRestLength { index })
    }
}

/// `Ok(l^2)` for a finite rest length `l >= 0` (the squared-length terms, eq. 6 and 13).
pub(crate) fn squared_rest_length<T: Real>(l: T) -> Result<T, KernelError> {
    let l = finite(l, "rest_length")?;
    if l < T::ZERO {
        Err(KernelError::OutOfRange {
            name: "rest_length",
        })
    } else {
        Ok(l * l)
    }
}
