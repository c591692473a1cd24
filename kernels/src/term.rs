//! The two shapes every kernel takes: a [`Potential`] (scalar energy of `N` nodes) and a
//! [`Constraint`] (`R` constraint rows on `N` nodes).
//!
//! Local blocks: node positions come in as `[T::Vec3; N]` in the order the term documents.
//! A gradient is one `Vec3` per node; a Jacobian row likewise; a Hessian is an `N x N`
//! array of `3 x 3` blocks, `H[a][b]` $= \partial^2 / \partial x_a \partial x_b$, which a
//! solver scatters into the global matrix through its own index maps.

use crate::real::Real;

/// `N x N` blocks of `3 x 3` matrices.
pub type Blocks<T, const N: usize> = [[<T as Real>::Mat3; N]; N];

/// One `Vec3` per node.
pub type NodeVecs<T, const N: usize> = [<T as Real>::Vec3; N];

/// A scalar energy $V(x_1, \dots, x_N)$ with its gradient and Hessian.
pub trait Potential<T: Real, const N: usize> {
    /// `true` when the Hessian does not depend on the positions (quadratic or linear terms),
    /// so a solver may assemble it once.
    const CONSTANT_HESSIAN: bool = false;

    /// $V(x)$.
    fn value(&self, x: &NodeVecs<T, N>) -> T;

    /// $\nabla V(x)$, one `Vec3` per node.
    fn gradient(&self, x: &NodeVecs<T, N>) -> NodeVecs<T, N>;

    /// $\nabla^2 V(x)$ as `3 x 3` blocks; symmetric.
    fn hessian(&self, x: &NodeVecs<T, N>) -> Blocks<T, N>;

    /// A positive semi-definite stand-in for [`Potential::hessian`], for a solver that
    /// convexifies an indefinite Newton system (`folio_solvers::Convexify`). By default
    /// the exact Hessian: a term without a convex form of its own.
    fn convex_hessian(&self, x: &NodeVecs<T, N>) -> Blocks<T, N> {
        self.hessian(x)
    }
}

/// `R` constraint functions $\varphi_l(x_1, \dots, x_N) = 0$ with their Jacobian rows and
/// the multiplier-weighted constraint Hessian.
pub trait Constraint<T: Real, const R: usize, const N: usize> {
    /// `true` when every row is affine in the positions (zero constraint Hessian).
    const LINEAR: bool = false;

    /// $\varphi(x)$, one entry per row.
    fn value(&self, x: &NodeVecs<T, N>) -> [T; R];

    /// $\nabla \varphi_l(x)$ for each row `l`, one `Vec3` per node.
    fn jacobian(&self, x: &NodeVecs<T, N>) -> [NodeVecs<T, N>; R];

    /// $\sum_l \lambda_l \nabla^2 \varphi_l(x)$ as `3 x 3` blocks; symmetric.
    fn hessian(&self, x: &NodeVecs<T, N>, lambda: &[T; R]) -> Blocks<T, N>;
}

/// All-zero `N x N` blocks.
#[inline(always)]
#[must_use]
pub fn zero_blocks<T: Real, const N: usize>() -> Blocks<T, N> {
    use crate::real::Mat3Ops;
    [[T::Mat3::ZERO; N]; N]
}

/// All-zero node vectors.
#[inline(always)]
#[must_use]
pub fn zero_vecs<T: Real, const N: usize>() -> NodeVecs<T, N> {
    use crate::real::Vec3Ops;
    [T::Vec3::ZERO; N]
}

/// Adds `w * k[a] k[b] I` to block `(a, b)`: the Hessian of $w\thinspace\lvert \sum_a k_a x_a \rvert^2 / 2$
/// for scalar node weights `k` (Kronecker form $w\thinspace k k^T \otimes I_3$).
#[inline]
pub fn add_scalar_kron<T: Real, const N: usize>(out: &mut Blocks<T, N>, k: &[T; N], w: T) {
    use crate::real::Mat3Ops;
    for a in 0..N {
        for b in 0..N {
            out[a][b] += T::Mat3::IDENTITY * (w * k[a] * k[b]);
        }
    }
}

/// Two nodes `(i, j)` joined by $d = x_i - x_j$, with a function of $d$ whose Hessian block
/// is `h`: writes `h` to `(0,0)` and `(1,1)` and `-h` to `(0,1)` and `(1,0)`.
#[inline]
#[must_use]
pub fn pair_blocks<T: Real>(h: T::Mat3) -> Blocks<T, 2> {
    [[h, -h], [-h, h]]
}
