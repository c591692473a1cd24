//! DOG bending energy (seed `000_…` eq. 10, the DOG Laplacian $\tilde L$ of RHS18b) with
//! rest lengths $L^0$, as a [`SquaredStencil`]:
//!
//! * inner vertex, nodes `[p0, xf, yf, xb, yb]`:
//!   $V = \lVert \sum_{j \in \lbrace xf,yf,xb,yb\rbrace} (p_0 - p_j)/L^0_j \rVert^2$;
//! * boundary vertex with three neighbours, along its full grid curve, nodes `[p0, xf, xb]`:
//!   $V = \lVert 2\thinspace((p_0 - p_{xf})/L^0_{xf} + (p_0 - p_{xb})/L^0_{xb}) \rVert^2$.
//!
//! Unweighted: the model multiplies by $w_{\mathrm{bend3D}}$. Units: dimensionless
//! (length / length).
//!
//! **Area-weighted form** ([`inner_area`], [`boundary_area`]): the same stencils as a
//! quadrature of $\int \lVert\Delta x\rVert^2\,dA$, $V = A\,\lVert \Delta_h p_0 \rVert^2$
//! with $A$ the vertex's dual-cell area and $\Delta_h$ the sum of the second differences
//! along the star's grid curves, on spacings $L_f$ (forward) and $L_b$ (back)
//! $$\partial^2_h p_0 = \frac{2}{L_f + L_b}\Big(\frac{p_f - p_0}{L_f} + \frac{p_b - p_0}{L_b}\Big)$$
//! (second order on a uniform spacing). On square cells of side $h$ the inner form is the
//! seed's $\lVert\tilde L\rVert^2$ exactly ($A = h^2$, $\Delta_h = -\tilde L / h$); on
//! oblong cells it is isotropic where $\tilde L$ weighs the two grid directions by $h_x^2$
//! and $h_y^2$. The boundary form, along the boundary curve alone, is the seed's boundary
//! term divided by 4 and by $h^2$, times $A$. Units: dimensionless ($A$ in length$^2$,
//! $\Delta_h p$ in 1/length).

use crate::error::{KernelError, finite, inverse_length};
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

/// The second-difference weights $[2/(L_f(L_f+L_b)),\ 2/(L_b(L_f+L_b))]$ of the module
/// docs, scaled by `scale`, from the rest lengths `[L_f, L_b]` with their indices in the
/// caller's order.
fn second_difference<T: Real>(
    lengths: [T; 2],
    indices: [usize; 2],
    scale: T,
) -> Result<[T; 2], KernelError> {
    let f = inverse_length(lengths[0], indices[0])?;
    let b = inverse_length(lengths[1], indices[1])?;
    let mean = T::TWO / (lengths[0] + lengths[1]);
    Ok([scale * mean * f, scale * mean * b])
}

/// $\sqrt A$ for a usable dual-cell area: finite and positive.
fn root_area<T: Real>(area: T) -> Result<T, KernelError> {
    let area = finite(area, "area")?;
    if area > T::ZERO {
        Ok(math::sqrt(area))
    } else {
        Err(KernelError::OutOfRange { name: "area" })
    }
}

/// Area-weighted inner stencil (module docs), $V = A\lVert\Delta_h p_0\rVert^2$, from the
/// rest lengths `[L_xf, L_yf, L_xb, L_yb]` and the dual-cell area `area` (page units,
/// positive).
///
/// # Errors
/// [`KernelError::NonPositiveRestLength`] naming the first unusable length;
/// [`KernelError::NonFiniteParameter`] or [`KernelError::OutOfRange`] for the area.
pub fn inner_area<T: Real>(
    rest_lengths: [T; 4],
    area: T,
) -> Result<DogLaplacianInner<T>, KernelError> {
    let r = root_area(area)?;
    let [l0, l1, l2, l3] = rest_lengths;
    let [xf, xb] = second_difference([l0, l2], [0, 2], r)?;
    let [yf, yb] = second_difference([l1, l3], [1, 3], r)?;
    Ok(SquaredStencil {
        weights: [xf + yf + xb + yb, -xf, -yf, -xb, -yb],
    })
}

/// Area-weighted boundary stencil (module docs), $V = A\lVert\partial^2_h p_0\rVert^2$
/// along the boundary curve, from the rest lengths `[L_xf, L_xb]` and the dual-cell area
/// `area` (page units, positive).
///
/// # Errors
/// As [`inner_area`].
pub fn boundary_area<T: Real>(
    rest_lengths: [T; 2],
    area: T,
) -> Result<DogLaplacianBoundary<T>, KernelError> {
    let r = root_area(area)?;
    let [f, b] = second_difference(rest_lengths, [0, 1], r)?;
    Ok(SquaredStencil {
        weights: [f + b, -f, -b],
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
