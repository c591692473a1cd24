//! Bending energy of the page-block midline (seed `000_…` eq. 10, $\lVert L(x_i)\rVert^2$):
//! the discrete curve Laplacian with edge-length weights at an inner polyline node, nodes
//! `[x_i, x_prev, x_next]`, rest edge lengths $l_p = \lvert x^0_i - x^0_{prev}\rvert$,
//! $l_n = \lvert x^0_{next} - x^0_i\rvert$:
//! $$L(x_i) = \frac{2}{l_p + l_n}\left(\frac{x_{prev} - x_i}{l_p} + \frac{x_{next} - x_i}{l_n}\right),$$
//! the second derivative $d^2x/ds^2$ on a non-uniform grid (curvature vector, 1/length).
//! As a [`SquaredStencil`]; the model multiplies by $w_{\mathrm{bend2D}}$ (200 by default).

use crate::error::{KernelError, inverse_length};
use crate::math;
use crate::real::Real;
use crate::stencil::SquaredStencil;
use crate::term::NodeVecs;

/// The midline curve-Laplacian energy, nodes `[x_i, x_prev, x_next]`.
pub type CurveLaplacian<T> = SquaredStencil<T, 3>;

/// Stencil from the rest lengths `[l_prev, l_next]` (page units, positive).
///
/// # Errors
/// [`KernelError::NonPositiveRestLength`] naming the first unusable length.
pub fn new<T: Real>(rest_lengths: [T; 2]) -> Result<CurveLaplacian<T>, KernelError> {
    let p = inverse_length(rest_lengths[0], 0)?;
    let n = inverse_length(rest_lengths[1], 1)?;
    let s = T::TWO / (rest_lengths[0] + rest_lengths[1]);
    Ok(SquaredStencil {
        weights: [-s * (p + n), s * p, s * n],
    })
}

/// Stencil with rest lengths measured on a rest configuration `[x_i, x_prev, x_next]`.
///
/// # Errors
/// As [`new`].
pub fn from_rest<T: Real>(x0: &NodeVecs<T, 3>) -> Result<CurveLaplacian<T>, KernelError> {
    new([1, 2].map(|k| math::length::<T>(x0[k] - x0[0])))
}
