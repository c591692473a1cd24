//! Binding constraints, $C_{\mathrm{binding}}$ of seed `000_…` eq. 7: the XY projection of a
//! bound active-page node $x_i$ sits at parameter $q \in [0, 1]$ on the binding edge
//! $(x_{b_1}, x_{b_2})$. Nodes `[x_i, x_b1, x_b2]`, two rows (X, Y):
//! $$\varphi_X = x_i^X - \left((1-q)\thinspace x_{b_1}^X + q\thinspace x_{b_2}^X\right),\quad
//!   \varphi_Y = x_i^Y - \left((1-q)\thinspace x_{b_1}^Y + q\thinspace x_{b_2}^Y\right).$$
//! Affine: constant Jacobian, zero constraint Hessian. Units: length. $q$ is the number of
//! pages in the left block plus half the active pages, over the total (set per frame).

use crate::error::{KernelError, finite};
use crate::real::{Real, Vec3Ops};
use crate::term::{Blocks, Constraint, NodeVecs, zero_blocks};

/// Binding of one active-page node to the binding edge at parameter `q` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Binding<T> {
    /// $q \in [0, 1]$, dimensionless.
    pub q: T,
}

impl<T: Real> Binding<T> {
    /// From the binding parameter $q \in [0, 1]$.
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] or [`KernelError::OutOfRange`].
    pub fn new(q: T) -> Result<Self, KernelError> {
        let q = finite(q, "q")?;
        if q < T::ZERO || q > T::ONE {
            return Err(KernelError::OutOfRange { name: "q" });
        }
        Ok(Self { q })
    }
}

impl<T: Real> Constraint<T, 2, 3> for Binding<T> {
    const LINEAR: bool = true;

    fn value(&self, x: &NodeVecs<T, 3>) -> [T; 2] {
        let target = x[1] * (T::ONE - self.q) + x[2] * self.q;
        let d = x[0] - target;
        [d.x(), d.y()]
    }
    fn jacobian(&self, _x: &NodeVecs<T, 3>) -> [NodeVecs<T, 3>; 2] {
        [0, 1].map(|axis| {
            let e = T::Vec3::AXES[axis];
            [e, -(e * (T::ONE - self.q)), -(e * self.q)]
        })
    }
    fn hessian(&self, _x: &NodeVecs<T, 3>, _lambda: &[T; 2]) -> Blocks<T, 3> {
        zero_blocks::<T, 3>()
    }
}
