//! Soft isometry of the active page, $V_{\mathrm{iso3D}}$ of seed `000_…` eq. 13, for a
//! grid edge with nodes `[x_i, x_j]`:
//! $$V = \left(\lVert d\rVert^2 - (L^0)^2\right)^2,\quad d = x_i - x_j,\ s = \lVert d\rVert^2 - (L^0)^2,$$
//! $$\nabla_{x_i} V = 4 s\thinspace d,\qquad \nabla^2_{x_i x_i} V = 8\thinspace d d^T + 4 s\thinspace I$$
//! (and $\pm$ the same blocks for $x_j$). Unweighted ($w_{\mathrm{iso3D}}$ = 4000 by
//! default). Units: length$^4$.
//!
//! The exact Hessian is indefinite when the edge is compressed ($s < 0$);
//! [`Iso3d::hessian_projected`] drops the $4sI$ part there, a positive semi-definite
//! alternative for solvers that want one.

use crate::error::{KernelError, squared_rest_length};
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, pair_blocks};

/// Squared-length isometry energy of one active-page grid edge (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iso3d<T> {
    /// $(L^0)^2$, length$^2$.
    pub rest_length_sq: T,
}

impl<T: Real> Iso3d<T> {
    /// From the rest length (page units, finite, $\ge 0$).
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] or [`KernelError::OutOfRange`] for a negative length.
    pub fn new(rest_length: T) -> Result<Self, KernelError> {
        Ok(Self {
            rest_length_sq: squared_rest_length(rest_length)?,
        })
    }

    fn strain(&self, x: &NodeVecs<T, 2>) -> (T::Vec3, T) {
        let d = x[0] - x[1];
        (d, d.dot(d) - self.rest_length_sq)
    }

    /// The Hessian with the compressive part $4sI$ ($s<0$) dropped: positive semi-definite.
    #[must_use]
    pub fn hessian_projected(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        let (d, s) = self.strain(x);
        let s = if s > T::ZERO { s } else { T::ZERO };
        let four = T::from_f64(4.0);
        pair_blocks::<T>(T::Mat3::outer(d, d) * T::from_f64(8.0) + T::Mat3::IDENTITY * (four * s))
    }
}

impl<T: Real> Potential<T, 2> for Iso3d<T> {
    fn value(&self, x: &NodeVecs<T, 2>) -> T {
        let (_, s) = self.strain(x);
        s * s
    }
    fn gradient(&self, x: &NodeVecs<T, 2>) -> NodeVecs<T, 2> {
        let (d, s) = self.strain(x);
        let g = d * (T::from_f64(4.0) * s);
        [g, -g]
    }
    fn hessian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        let (d, s) = self.strain(x);
        let four = T::from_f64(4.0);
        pair_blocks::<T>(T::Mat3::outer(d, d) * T::from_f64(8.0) + T::Mat3::IDENTITY * (four * s))
    }
    /// [`Iso3d::hessian_projected`].
    fn convex_hessian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        self.hessian_projected(x)
    }
}
