//! A squared linear stencil $V(x) = \lVert \sum_k a_k x_k \rVert^2$ with constant scalar
//! weights $a_k$: the common form of every discrete Laplacian bending energy in Folio
//! ([`crate::dog_laplacian`], [`crate::curve_laplacian`]; seed `000_…` eq. 10).
//!
//! With $L = \sum_k a_k x_k$: $\nabla_{x_k} V = 2 a_k L$ and
//! $\nabla^2_{x_k x_m} V = 2 a_k a_m I_3$ (constant: assemble once).
//! Units: $V$ in length$^2$ times the square of the weights' units.

use crate::real::{Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, add_scalar_kron, zero_blocks};

/// $\lVert \sum_k a_k x_k \rVert^2$ over `N` nodes (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SquaredStencil<T, const N: usize> {
    /// The weights $a_k$, in the node order of the constructor that built the stencil.
    pub weights: [T; N],
}

impl<T: Real, const N: usize> SquaredStencil<T, N> {
    /// The stencil vector $L = \sum_k a_k x_k$.
    #[inline]
    #[must_use]
    pub fn apply(&self, x: &NodeVecs<T, N>) -> T::Vec3 {
        let mut l = T::Vec3::ZERO;
        for (&a, &p) in self.weights.iter().zip(x) {
            l += p * a;
        }
        l
    }
}

impl<T: Real, const N: usize> Potential<T, N> for SquaredStencil<T, N> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, N>) -> T {
        let l = self.apply(x);
        l.dot(l)
    }

    fn gradient(&self, x: &NodeVecs<T, N>) -> NodeVecs<T, N> {
        let l = self.apply(x) * T::TWO;
        self.weights.map(|a| l * a)
    }

    fn hessian(&self, _x: &NodeVecs<T, N>) -> Blocks<T, N> {
        let mut h = zero_blocks::<T, N>();
        add_scalar_kron(&mut h, &self.weights, T::TWO);
        h
    }
}
