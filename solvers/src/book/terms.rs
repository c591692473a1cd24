//! The book's own term shapes over `folio-kernels`: DOG stars with the flat-star Jacobian
//! remedy, the binding-midpoint fix restricted to the plane, and a switchable grab pull.

use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::fix::Fix;
use folio_kernels::positional::Positional;
use folio_kernels::term::{Blocks, NodeVecs, zero_blocks, zero_vecs};
use folio_kernels::{Constraint, Potential, Real};

/// The inner-star DOG constraints (seed `000_…` Sec. 3.2, three rows on
/// `[p0, xf, yf, xb, yb]`) with the Jacobian of [`FlatStarRemedy`]: on a flat star the exact
/// Jacobian is rank deficient (a page lying on a block is flat everywhere), so it is
/// evaluated at $p_0$ nudged along the star normal (RHS19). Values and Hessians are exact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DogInner<T: Real>(pub FlatStarRemedy<T>);

/// The 3-neighbour boundary DOG constraint (one row on `[p0, a, b, c]`) with the flat-star
/// remedy (see [`DogInner`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DogBoundary<T: Real>(pub FlatStarRemedy<T>);

impl<T: Real> Constraint<T, 3, 5> for DogInner<T> {
    fn value(&self, x: &NodeVecs<T, 5>) -> [T; 3] {
        DogInnerStar::<T>::new().value(x)
    }
    fn jacobian(&self, x: &NodeVecs<T, 5>) -> [NodeVecs<T, 5>; 3] {
        self.0.inner_jacobian(x)
    }
    fn hessian(&self, x: &NodeVecs<T, 5>, lambda: &[T; 3]) -> Blocks<T, 5> {
        DogInnerStar::<T>::new().hessian(x, lambda)
    }
}

impl<T: Real> Constraint<T, 1, 4> for DogBoundary<T> {
    fn value(&self, x: &NodeVecs<T, 4>) -> [T; 1] {
        DogBoundaryStar::<T>::new().value(x)
    }
    fn jacobian(&self, x: &NodeVecs<T, 4>) -> [NodeVecs<T, 4>; 1] {
        self.0.boundary_jacobian(x)
    }
    fn hessian(&self, x: &NodeVecs<T, 4>, lambda: &[T; 1]) -> Blocks<T, 4> {
        DogBoundaryStar::<T>::new().hessian(x, lambda)
    }
}

/// $C_{\mathrm{fix}}$ of seed `000_…` eq. 8 without its Z row: the binding nodes' Z
/// coordinates are eliminated, so that row is constant and would make the KKT matrix
/// singular. Nodes `[x_b1, x_b2]`, rows X and Y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarFix<T: Real>(pub Fix<T>);

impl<T: Real> Constraint<T, 2, 2> for PlanarFix<T> {
    const LINEAR: bool = true;
    fn value(&self, x: &NodeVecs<T, 2>) -> [T; 2] {
        let [cx, cy, _] = self.0.value(x);
        [cx, cy]
    }
    fn jacobian(&self, x: &NodeVecs<T, 2>) -> [NodeVecs<T, 2>; 2] {
        let [jx, jy, _] = self.0.jacobian(x);
        [jx, jy]
    }
    fn hessian(&self, _x: &NodeVecs<T, 2>, _lambda: &[T; 2]) -> Blocks<T, 2> {
        zero_blocks::<T, 2>()
    }
}

/// The positional objective of seed `000_…` eq. 14, $\lVert x_i - p\rVert^2$, switched on
/// for the grabbed node only. The book declares one on every node a user may grab (the ring
/// one in from the page border), so that moving the grab to another node changes values,
/// not the KKT pattern: a grab never re-runs the symbolic analysis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pull<T: Real> {
    /// The objective; its `target` follows the drag.
    pub positional: Positional<T>,
    /// Whether this node is held.
    pub active: bool,
}

impl<T: Real> Potential<T, 1> for Pull<T> {
    const CONSTANT_HESSIAN: bool = true;
    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        if self.active {
            self.positional.value(x)
        } else {
            T::ZERO
        }
    }
    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        if self.active {
            self.positional.gradient(x)
        } else {
            zero_vecs::<T, 1>()
        }
    }
    fn hessian(&self, x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        if self.active {
            self.positional.hessian(x)
        } else {
            zero_blocks::<T, 1>()
        }
    }
}
