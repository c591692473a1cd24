//! DOG bending energy (seed `000_…` eq. 10, the DOG Laplacian $\tilde L$ of RHS18b) with
//! rest lengths $L^0$, as a [`SquaredStencil`]:
//!
//! * inner vertex, nodes `[p0, xf, yf, xb, yb]`:
//!   $V = \lVert \sum_{j \in \lbrace xf,yf,xb,yb\rbrace} (p_0 - p_j)/L^0_j \rVert^2$;
//! * boundary vertex with three neighbours, along its full grid curve, nodes `[p0, xf, xb]`:
//!   $V = \lVert 2\thinspace((p_0 - p_{xf})/L^0_{xf} + (p_0 - p_{xb})/L^0_{xb}) \rVert^2$.
//!
//! Unweighted: the model multiplies by $w_{\mathrm{bend3D}}$ (120 at the seed's 11x8 grid)
//! and rescales with the cell size. Units: dimensionless (length / length).

use crate::error::{KernelError, inverse_length};
use crate::math;
use crate::real::Real;
use crate::stencil::SquaredStencil;
use crate::term::NodeVecs;

/// The inner-vertex DOG Laplacian energy, nodes `[p0, xf, yf, xb, yb]`.
pub type DogLaplacianInner<T> = SquaredStencil<T, 5>;

/// The boundary-vertex DOG Laplacian energy, nodes `[p0, xf, xb]`.
pub type DogLaplacianBoundary<T> = SquaredStencil<T, 3>;

/// Inner stencil from the rest lengths `[L_xf, L_yf, L_xb, L_yb]` (page units, positive).
///
/// # Errors
/// [`KernelError::NonPositiveRestLength`] naming the first unusable length.
pub fn inner<T: Real>(rest_lengths: [T; 4]) -> Result<DogLaplacianInner<T>, KernelError> {
    let mut w = [T::ZERO; 5];
    for (k, &l) in rest_lengths.iter().enumerate() {
        let inv = inverse_length(l, k)?;
        w[0] += inv;
        w[k + 1] = -inv;
    }
    Ok(SquaredStencil { weights: w })
}

/// Boundary stencil from the rest lengths `[L_xf, L_xb]` (page units, positive).
///
/// # Errors
/// [`KernelError::NonPositiveRestLength`] naming the first unusable length.
pub fn boundary<T: Real>(rest_lengths: [T; 2]) -> Result<DogLaplacianBoundary<T>, KernelError> {
    let f = inverse_length(rest_lengths[0], 0)?;
    let b = inverse_length(rest_lengths[1], 1)?;
    Ok(SquaredStencil {
        weights: [T::TWO * (f + b), -T::TWO * f, -T::TWO * b],
    })
}

/// Inner stencil with the rest lengths measured on a rest configuration `[p0, xf, yf, xb, yb]`.
///
/// # Errors
/// As [`inner`].
pub fn inner_from_rest<T: Real>(x0: &NodeVecs<T, 5>) -> Result<DogLaplacianInner<T>, KernelError> {
    inner([1, 2, 3, 4].map(|k| math::length::<T>(x0[k] - x0[0])))
}

/// Boundary stencil with the rest lengths measured on a rest configuration `[p0, xf, xb]`.
///
/// # Errors
/// As [`boundary`].
pub fn boundary_from_rest<T: Real>(
    x0: &NodeVecs<T, 3>,
) -> Result<DogLaplacianBoundary<T>, KernelError> {
    boundary([1, 2].map(|k| math::length::<T>(x0[k] - x0[0])))
}
