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
    /// A rest triangle of a 2D pattern is degenerate or wrongly oriented: its signed area
    /// (counter-clockwise positive, nodes in the term's documented order) is zero, negative,
    /// not above the relative threshold of [`crate::membrane`] or not finite, or the
    /// triangle is too small to carry a length (longest edge below
    /// [`crate::Real::LENGTH_FLOOR`], or below $\sqrt{\varepsilon}$ page units for a
    /// [`crate::membrane::Membrane`]); `index` names the triangle in the term's documented
    /// order.
    NonPositiveRestArea {
        /// Which triangle of the term.
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
            Self::NonPositiveRestArea { index } => {
                write!(
                    f,
                    "rest triangle {index} is degenerate or not counter-clockwise in the pattern"
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

/// Twice the signed area $2A = (u_1 - u_0) \times (u_2 - u_0)$ of a rest triangle of a 2D
/// pattern, if it is usable: finite, counter-clockwise and not a sliver, i.e.
/// $2A > \sqrt{\varepsilon}\thinspace\ell_{\max}^2$ with $\ell_{\max}$ the longest edge and
/// $\ell_{\max} \ge$ [`Real::LENGTH_FLOOR`]. Else [`KernelError::NonPositiveRestArea`].
pub(crate) fn rest_triangle_area2<T: Real>(u: [[T; 2]; 3], index: usize) -> Result<T, KernelError> {
    let edge = |a: [T; 2], b: [T; 2]| [b[0] - a[0], b[1] - a[1]];
    let (e1, e2, e3) = (edge(u[0], u[1]), edge(u[0], u[2]), edge(u[1], u[2]));
    let sq = |e: [T; 2]| e[0] * e[0] + e[1] * e[1];
    let (l1, l2, l3) = (sq(e1), sq(e2), sq(e3));
    let longest = if l1 > l2 { l1 } else { l2 };
    let longest = if longest > l3 { longest } else { l3 };
    let area2 = e1[0] * e2[1] - e1[1] * e2[0];
    let usable = l1.is_finite()
        && l2.is_finite()
        && l3.is_finite()
        && area2.is_finite()
        && longest >= T::LENGTH_FLOOR * T::LENGTH_FLOOR
        && area2 > crate::math::sqrt(T::EPSILON) * longest;
    if usable {
        Ok(area2)
    } else {
        Err(KernelError::NonPositiveRestArea { index })
    }
}
