//! The grab, $V_{\mathrm{pos}}$ of seed `000_…` eq. 14: the grabbed node $x_i$ pulled towards
//! the target $p$:
//! $$V = \lVert x_i - p\rVert^2,\quad \nabla V = 2(x_i - p),\quad \nabla^2 V = 2I.$$
//! Unweighted ($w_{\mathrm{pos}}$ = 400 by default). Units: length².

use crate::error::KernelError;
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential};

/// Quadratic pull of one node towards a target point (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Positional<T: Real> {
    /// $p$, page units.
    pub target: T::Vec3,
}

impl<T: Real> Positional<T> {
    /// From the target point.
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] if a coordinate is not finite.
    pub fn new(target: T::Vec3) -> Result<Self, KernelError> {
        if !crate::real::vec_is_finite::<T>(target) {
            return Err(KernelError::NonFiniteParameter { name: "target" });
        }
        Ok(Self { target })
    }
}

impl<T: Real> Potential<T, 1> for Positional<T> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        let d = x[0] - self.target;
        d.dot(d)
    }
    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        [(x[0] - self.target) * T::TWO]
    }
    fn hessian(&self, _x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        [[T::Mat3::IDENTITY * T::TWO]]
    }
}
