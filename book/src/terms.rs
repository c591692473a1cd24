//! The book's own term shapes over `folio-kernels`: DOG stars with the flat-star Jacobian
//! remedy, the binding-midpoint fix restricted to the plane with the binding edge kept
//! level, and switchable one-node potentials (the grab pull, the contact springs).

use folio_kernels::contact::ContactPlane;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::fix::Fix;
use folio_kernels::positional::Positional;
use folio_kernels::term::{Blocks, NodeVecs, zero_blocks, zero_vecs};
use folio_kernels::{Constraint, Potential, Real, Vec3Ops};

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

/// $C_{\mathrm{fix}}$ of seed `000_…` eq. 8 without its Z row, and the binding edge kept
/// level. Nodes `[x_b1, x_b2]`; rows: the midpoint's X and Y, and $y_{b_1} - y_{b_2}$.
///
/// The Z row is dropped because the binding nodes' Z coordinates are eliminated (the row
/// would be constant and make the KKT matrix singular). The level row is Folio's: the seed
/// leaves the binding edge free to turn about its pinned midpoint, and the glue (eq. 11)
/// stands the pages upright on that edge, with a lever of the binding's width
/// $n_{pages}\,t$. On a thin binding (one or two pages, or very thin paper) the glue's
/// torque on a block is then so large next to the edge's that the edge tips, the glue's
/// "upright" tips with it, and a block folds over onto the other side and falls through
/// the other cover board: a one-page book's empty block hung 4 units below the cover
/// after settling, and the page turned onto it was crushed to zero width, a unit deep in
/// the cover. A book's spine lies on its cover (or the table), so the edge stays level;
/// on the default book it tipped by at most $8 \cdot 10^{-6}$ rad over a page turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarFix<T: Real>(pub Fix<T>);

impl<T: Real> Constraint<T, 3, 2> for PlanarFix<T> {
    const LINEAR: bool = true;
    fn value(&self, x: &NodeVecs<T, 2>) -> [T; 3] {
        let [cx, cy, _] = self.0.value(x);
        [cx, cy, x[0].y() - x[1].y()]
    }
    fn jacobian(&self, x: &NodeVecs<T, 2>) -> [NodeVecs<T, 2>; 3] {
        let [jx, jy, _] = self.0.jacobian(x);
        let ey = T::Vec3::new(T::ZERO, T::ONE, T::ZERO);
        [jx, jy, [ey, -ey]]
    }
    fn hessian(&self, _x: &NodeVecs<T, 2>, _lambda: &[T; 3]) -> Blocks<T, 2> {
        zero_blocks::<T, 2>()
    }
}

/// A one-node potential that can be switched off without leaving the KKT pattern: the
/// book declares one on every node that may need it, so that switching changes values, not
/// the pattern, and never re-runs the symbolic analysis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Switched<P> {
    /// The potential while on.
    pub kernel: P,
    /// Whether it is on.
    pub active: bool,
}

/// The positional objective of seed `000_…` eq. 14, $\lVert x_i - p\rVert^2$, on for the
/// grabbed node only; declared on every node a user may grab (the ring one in from the page
/// border). Its `target` follows the drag.
pub type Pull<T> = Switched<Positional<T>>;

/// A contact found by the collision handling of one step, held as a spring in the next
/// (see [`ContactPlane`]); declared on every page node.
pub type Contact<T> = Switched<ContactPlane<T>>;

impl<T: Real, P: Potential<T, 1>> Potential<T, 1> for Switched<P> {
    const CONSTANT_HESSIAN: bool = P::CONSTANT_HESSIAN;
    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        if self.active {
            self.kernel.value(x)
        } else {
            T::ZERO
        }
    }
    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        if self.active {
            self.kernel.gradient(x)
        } else {
            zero_vecs::<T, 1>()
        }
    }
    fn hessian(&self, x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        if self.active {
            self.kernel.hessian(x)
        } else {
            zero_blocks::<T, 1>()
        }
    }
}
