//! Midline and cover inextensibility, $C_{\mathrm{iso2D}}$ of seed `000_…` eq. 6:
//! $$\varphi(x_i, x_j) = \lVert x_i - x_j\rVert^2 - \lVert x^0_i - x^0_j\rVert^2,$$
//! nodes `[x_i, x_j]`, one row. With $d = x_i - x_j$: $\nabla_{x_i}\varphi = 2d$,
//! $\nabla_{x_j}\varphi = -2d$, $\lambda\nabla^2\varphi = 2\lambda\thinspace[[I, -I], [-I, I]]$.
//! Units: length$^2$.

use crate::error::{KernelError, squared_rest_length};
use crate::real::{Mat3Ops, Real};
use crate::term::{Blocks, Constraint, NodeVecs, pair_blocks};

/// The squared-length constraint of one midline or cover edge (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iso2d<T> {
    /// $\lVert x^0_i - x^0_j\rVert^2$, length$^2$.
    pub rest_length_sq: T,
}

impl<T: Real> Iso2d<T> {
    /// From the rest length (page units, finite, $\ge 0$).
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] or [`KernelError::OutOfRange`] for a negative length.
    pub fn new(rest_length: T) -> Result<Self, KernelError> {
        Ok(Self {
            rest_length_sq: squared_rest_length(rest_length)?,
        })
    }
}

impl<T: Real> Constraint<T, 1, 2> for Iso2d<T> {
    fn value(&self, x: &NodeVecs<T, 2>) -> [T; 1] {
        let d = x[0] - x[1];
        [crate::real::Vec3Ops::dot(d, d) - self.rest_length_sq]
    }
    fn jacobian(&self, x: &NodeVecs<T, 2>) -> [NodeVecs<T, 2>; 1] {
        let d = (x[0] - x[1]) * T::TWO;
        [[d, -d]]
    }
    fn hessian(&self, _x: &NodeVecs<T, 2>, lambda: &[T; 1]) -> Blocks<T, 2> {
        pair_blocks::<T>(T::Mat3::IDENTITY * (T::TWO * lambda[0]))
    }
}
