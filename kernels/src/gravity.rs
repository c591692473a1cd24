//! Gravity, $V_{\mathrm{gravity}}$ of seed `000_…` eq. 12, for one node:
//! $$V = g\thinspace m\thinspace x^Y,\quad \nabla V = (0, g m, 0),\quad \nabla^2 V = 0,$$
//! gravity along −Y. Units: $g$ in length/s², $m$ in page masses (a page weighs 1),
//! $V$ in mass·length²/s².

use crate::error::{KernelError, finite};
use crate::real::{Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, zero_blocks};

/// Potential energy of one node in uniform gravity (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gravity<T> {
    /// $g\thinspace m$: gravitational acceleration times the node's mass.
    pub weight: T,
}

impl<T: Real> Gravity<T> {
    /// From the acceleration `g` (finite) and the node mass `mass` (finite, $\ge 0$).
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`], or [`KernelError::OutOfRange`] for a negative mass.
    pub fn new(g: T, mass: T) -> Result<Self, KernelError> {
        let g = finite(g, "g")?;
        let m = finite(mass, "mass")?;
        if m < T::ZERO {
            return Err(KernelError::OutOfRange { name: "mass" });
        }
        Ok(Self { weight: g * m })
    }
}

impl<T: Real> Potential<T, 1> for Gravity<T> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        self.weight * x[0].y()
    }
    fn gradient(&self, _x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        [T::Vec3::new(T::ZERO, self.weight, T::ZERO)]
    }
    fn hessian(&self, _x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        zero_blocks::<T, 1>()
    }
}
