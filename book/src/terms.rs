//! The book's own term shapes over `folio-kernels`: DOG stars with the flat-star Jacobian
//! remedy, the binding-midpoint fix restricted to the plane with the binding edge kept
//! level, the grab's pull with a bounded force, and switchable one-node potentials (the
//! grab pull, the contact springs).

use folio_kernels::contact::ContactPlane;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::fix::Fix;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::term::{Blocks, NodeVecs, zero_blocks, zero_vecs};
use folio_kernels::{Constraint, Mat3Ops, Potential, Real, Vec3Ops, math};

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

/// The soft isometry of one page edge (seed `000_…` eq. 13, [`Iso3d`]) with the Hessian
/// the book's settings ask for ([`crate::IsometryHessian`]): exact, or with the compressive
/// part dropped (positive semi-definite). Value and gradient are the edge's own.
/// Units: length⁴.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Isometry<T: Real> {
    /// The edge's energy.
    pub edge: Iso3d<T>,
    /// Assemble [`Iso3d::hessian_projected`] instead of the exact Hessian.
    pub projected: bool,
}

impl<T: Real> Potential<T, 2> for Isometry<T> {
    fn value(&self, x: &NodeVecs<T, 2>) -> T {
        self.edge.value(x)
    }
    fn gradient(&self, x: &NodeVecs<T, 2>) -> NodeVecs<T, 2> {
        self.edge.gradient(x)
    }
    fn hessian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        if self.projected {
            self.edge.hessian_projected(x)
        } else {
            self.edge.hessian(x)
        }
    }
    /// The projected Hessian whatever `projected` says: what a convexifying solver takes
    /// where the exact one makes the step indefinite.
    fn convex_hessian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        self.edge.convex_hessian(x)
    }
}

/// The grab's pull, seed `000_…` eq. 14 with a bounded force: the held node $x_i$ pulled
/// towards the target $p$, $d = x_i - p$,
/// $$V = \begin{cases}\lVert d\rVert^2 & \lVert d\rVert \le \rho\\
///   2\rho\lVert d\rVert - \rho^2 & \text{beyond,}\end{cases}\qquad
///   \nabla V = 2\,d\,\min\!\left(1, \frac{\rho}{\lVert d\rVert}\right),$$
/// $\nabla^2 V = 2I$ inside the radius $\rho$ and
/// $\frac{2\rho}{\lVert d\rVert}(I - \hat d \hat d^{\mathsf T})$ beyond (positive
/// semidefinite). Weighted by $w_{\mathrm{pos}}$, the force is at most $2 w \rho$: the
/// book sets $\rho$ so that this is the grip of [`crate::BookSettings::grip_strain`], and a
/// finger that pulls harder slips instead of stretching the paper. With $\rho$ at least
/// the leash ([`crate::BookSettings::pull_reach`]) it is the seed's quadratic.
/// Units: length².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grip<T: Real> {
    /// $p$, page units.
    pub target: T::Vec3,
    /// $\rho$, page units (positive; infinite for the plain quadratic).
    pub radius: T,
}

impl<T: Real> Grip<T> {
    /// $d$, $\lVert d\rVert$ and whether $x$ lies beyond the radius.
    #[inline]
    fn offset(&self, x: &NodeVecs<T, 1>) -> (T::Vec3, T, bool) {
        let d = x[0] - self.target;
        let len = math::length::<T>(d);
        (d, len, len > self.radius)
    }
}

impl<T: Real> Potential<T, 1> for Grip<T> {
    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        let (d, len, beyond) = self.offset(x);
        if beyond {
            T::TWO * self.radius * len - self.radius * self.radius
        } else {
            d.dot(d)
        }
    }
    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        let (d, len, beyond) = self.offset(x);
        if beyond {
            [d * (T::TWO * self.radius / len)]
        } else {
            [d * T::TWO]
        }
    }
    fn hessian(&self, x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        let (d, len, beyond) = self.offset(x);
        if beyond {
            let u = d / len;
            let across = T::Mat3::IDENTITY - T::Mat3::outer(u, u);
            [[across * (T::TWO * self.radius / len)]]
        } else {
            [[T::Mat3::IDENTITY * T::TWO]]
        }
    }
}

/// The grab pull ([`Grip`]), on for the grabbed node only; declared on every node a user
/// may grab (the ring one in from the page border). Its `target` follows the drag.
pub type Pull<T> = Switched<Grip<T>>;

/// A contact found by the collision handling of one step, held as a spring in the next
/// (see [`ContactPlane`]); declared on every page node.
pub type Contact<T> = Switched<ContactPlane<T>>;

/// The finger's pad on one quad ([`crate::pad`]), on while a pad holds a point of that
/// quad; declared on every quad of a book whose settings ask for a pad.
pub type PadGrip<T> = Switched<crate::pad::PadQuad<T>>;

impl<T: Real, P: Potential<T, N>, const N: usize> Potential<T, N> for Switched<P> {
    const CONSTANT_HESSIAN: bool = P::CONSTANT_HESSIAN;
    fn value(&self, x: &NodeVecs<T, N>) -> T {
        if self.active {
            self.kernel.value(x)
        } else {
            T::ZERO
        }
    }
    fn gradient(&self, x: &NodeVecs<T, N>) -> NodeVecs<T, N> {
        if self.active {
            self.kernel.gradient(x)
        } else {
            zero_vecs::<T, N>()
        }
    }
    fn hessian(&self, x: &NodeVecs<T, N>) -> Blocks<T, N> {
        if self.active {
            self.kernel.hessian(x)
        } else {
            zero_blocks::<T, N>()
        }
    }
    fn convex_hessian(&self, x: &NodeVecs<T, N>) -> Blocks<T, N> {
        if self.active {
            self.kernel.convex_hessian(x)
        } else {
            zero_blocks::<T, N>()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Grip;
    use folio_kernels::{Potential, Real};

    type DVec3 = <f64 as Real>::Vec3;

    /// Central differences of the value and the gradient match the gradient and the
    /// Hessian inside and beyond the radius, and the force never exceeds $2\rho$.
    #[test]
    fn the_grip_is_the_quadratic_inside_and_bounded_beyond() {
        let grip = Grip::<f64> {
            target: DVec3::new(1.0, -2.0, 0.5),
            radius: 0.3,
        };
        let h = 1e-6;
        for x in [
            DVec3::new(1.1, -2.05, 0.52),
            DVec3::new(3.0, 1.0, -2.0),
            DVec3::new(1.0, -2.0, 0.9),
        ] {
            let g = grip.gradient(&[x])[0];
            let hess = grip.hessian(&[x])[0][0];
            assert!(g.length() <= 2.0 * grip.radius + 1e-12, "{g}");
            for k in 0..3 {
                let e = DVec3::AXES[k] * h;
                let dv = (grip.value(&[x + e]) - grip.value(&[x - e])) / (2.0 * h);
                assert!((dv - g[k]).abs() < 1e-6, "{x} {k}: {dv} vs {}", g[k]);
                let dg = (grip.gradient(&[x + e])[0] - grip.gradient(&[x - e])[0]) / (2.0 * h);
                assert!(
                    (dg - hess.col(k)).length() < 1e-5,
                    "{x} {k}: {dg} vs {}",
                    hess.col(k)
                );
            }
        }
        // Inside the radius it is the seed's quadratic.
        let x = DVec3::new(1.1, -2.0, 0.5);
        assert!((grip.value(&[x]) - 0.01).abs() < 1e-12);
    }
}
