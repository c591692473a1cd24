//! Fixing the book in place, $C_{\mathrm{fix}}$ of seed `000_…` eq. 8: the midpoint of the
//! binding edge stays at $p_{\mathrm{fix}}$. Nodes `[x_b1, x_b2]`, three rows (X, Y, Z):
//! $$\varphi = \tfrac12 (x_{b_1} + x_{b_2}) - p_{\mathrm{fix}}.$$
//! Affine. When the model eliminates the midline's Z coordinates the Z row is constant and
//! the model drops it. Units: length.

use crate::error::KernelError;
use crate::real::{Real, Vec3Ops};
use crate::term::{Blocks, Constraint, NodeVecs, zero_blocks};

/// Pins the binding-edge midpoint (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fix<T: Real> {
    /// $p_{\mathrm{fix}}$, page units.
    pub target: T::Vec3,
}

impl<T: Real> Fix<T> {
    /// From the pinned point.
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

impl<T: Real> Constraint<T, 3, 2> for Fix<T> {
    const LINEAR: bool = true;

    fn value(&self, x: &NodeVecs<T, 2>) -> [T; 3] {
        let d = (x[0] + x[1]) * T::HALF - self.target;
        [d.x(), d.y(), d.z()]
    }
    fn jacobian(&self, _x: &NodeVecs<T, 2>) -> [NodeVecs<T, 2>; 3] {
        T::Vec3::AXES.map(|e| [e * T::HALF, e * T::HALF])
    }
    fn hessian(&self, _x: &NodeVecs<T, 2>, _lambda: &[T; 3]) -> Blocks<T, 2> {
        zero_blocks::<T, 2>()
    }
}
