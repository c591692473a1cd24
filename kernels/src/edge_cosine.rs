//! The cosine of the angle between two edge vectors, with exact first and second
//! derivatives. Shared by the DOG angle constraints ([`crate::dog`], seed `000_…` eq. 5,
//! Sec. 3.2) and the binding glue ([`crate::glue`], seed `000_…` eq. 11).
//!
//! For $u, v \in \mathbb{R}^3$, $a = \lVert u\rVert$, $b = \lVert v\rVert$,
//! $\hat u = u/a$, $\hat v = v/b$:
//! $$c(u, v) = \hat u \cdot \hat v,\quad
//! \nabla_u c = \frac{\hat v - c\thinspace\hat u}{a},\quad \nabla_v c = \frac{\hat u - c\thinspace\hat v}{b},$$
//! $$\nabla^2_{uu} c = -\frac{\hat u \hat v^T + \hat v \hat u^T + c\thinspace(I - 3\hat u\hat u^T)}{a^2},\quad
//! \nabla^2_{uv} c = \frac{I - \hat u \hat u^T - \hat v \hat v^T + c\thinspace\hat u \hat v^T}{a b}.$$
//!
//! Degenerate edges: if $a$ or $b$ is below [`Real::LENGTH_FLOOR`] or below
//! $\varepsilon$ times the other length, the angle is undefined; the fallback is $c = 0$
//! with zero derivatives (the term then neither pushes nor pulls through that angle).

use crate::math;
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs};

/// $c(u,v)$ with its gradient and Hessian blocks (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct EdgeCosine<T: Real> {
    /// $c = \hat u \cdot \hat v \in [-1, 1]$.
    pub value: T,
    /// $\nabla_u c$.
    pub grad_u: T::Vec3,
    /// $\nabla_v c$.
    pub grad_v: T::Vec3,
    /// $\nabla^2_{uu} c$.
    pub h_uu: T::Mat3,
    /// $\nabla^2_{uv} c$ ($\nabla^2_{vu} c$ is its transpose).
    pub h_uv: T::Mat3,
    /// $\nabla^2_{vv} c$.
    pub h_vv: T::Mat3,
}

/// Lengths that take the degenerate fallback (see module docs). NaN is *not* degenerate,
/// so NaN input propagates instead of turning into the finite fallback.
#[inline(always)]
fn degenerate<T: Real>(a: T, b: T) -> bool {
    a < T::LENGTH_FLOOR || b < T::LENGTH_FLOOR || a < T::EPSILON * b || b < T::EPSILON * a
}

impl<T: Real> EdgeCosine<T> {
    /// The all-zero fallback for degenerate edges.
    const DEGENERATE: Self = Self {
        value: T::ZERO,
        grad_u: T::Vec3::ZERO,
        grad_v: T::Vec3::ZERO,
        h_uu: T::Mat3::ZERO,
        h_uv: T::Mat3::ZERO,
        h_vv: T::Mat3::ZERO,
    };

    /// Value only.
    #[inline]
    #[must_use]
    pub fn value(u: T::Vec3, v: T::Vec3) -> T {
        let (a, b) = (math::length::<T>(u), math::length::<T>(v));
        if degenerate(a, b) {
            T::ZERO
        } else {
            u.dot(v) / (a * b)
        }
    }

    /// Value and gradient; the Hessian fields are left zero.
    #[inline]
    #[must_use]
    pub fn with_gradient(u: T::Vec3, v: T::Vec3) -> Self {
        let (a, b) = (math::length::<T>(u), math::length::<T>(v));
        if degenerate(a, b) {
            return Self::DEGENERATE;
        }
        let (uh, vh) = (u / a, v / b);
        let c = uh.dot(vh);
        Self {
            value: c,
            grad_u: (vh - uh * c) / a,
            grad_v: (uh - vh * c) / b,
            ..Self::DEGENERATE
        }
    }

    /// Value, gradient and Hessian.
    #[inline]
    #[must_use]
    pub fn with_hessian(u: T::Vec3, v: T::Vec3) -> Self {
        let (a, b) = (math::length::<T>(u), math::length::<T>(v));
        if degenerate(a, b) {
            return Self::DEGENERATE;
        }
        let (uh, vh) = (u / a, v / b);
        let c = uh.dot(vh);
        let three = T::from_f64(3.0);
        let id = T::Mat3::IDENTITY;
        let uu = T::Mat3::outer(uh, uh);
        let vv = T::Mat3::outer(vh, vh);
        let uv = T::Mat3::outer(uh, vh);
        let vu = uv.transposed();
        Self {
            value: c,
            grad_u: (vh - uh * c) / a,
            grad_v: (uh - vh * c) / b,
            h_uu: -(uv + vu + (id - uu * three) * c) * (T::ONE / (a * a)),
            h_uv: (id - uu - vv + uv * c) * (T::ONE / (a * b)),
            h_vv: -(uv + vu + (id - vv * three) * c) * (T::ONE / (b * b)),
        }
    }
}

/// An edge of a local block: `u = x[head] - x[tail]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// Index of the node the edge starts at.
    pub tail: usize,
    /// Index of the node the edge ends at.
    pub head: usize,
}

impl Edge {
    /// The edge from `tail` to `head`.
    #[must_use]
    pub const fn new(tail: usize, head: usize) -> Self {
        Self { tail, head }
    }

    /// `x[head] - x[tail]`.
    #[inline(always)]
    #[must_use]
    pub fn vector<T: Real, const N: usize>(self, x: &NodeVecs<T, N>) -> T::Vec3 {
        x[self.head] - x[self.tail]
    }
}

/// Adds `w * d/dx` of a function of two edge vectors, given its gradient with respect to the
/// edge vectors, into per-node vectors (chain rule $\partial u/\partial x_{head} = I$,
/// $\partial u/\partial x_{tail} = -I$).
#[inline]
pub fn scatter_gradient<T: Real, const N: usize>(
    out: &mut NodeVecs<T, N>,
    edges: [Edge; 2],
    grads: [T::Vec3; 2],
    w: T,
) {
    for (e, g) in edges.iter().zip(grads) {
        out[e.head] += g * w;
        out[e.tail] -= g * w;
    }
}

/// Adds `w *` the node-space Hessian of a function of two edge vectors into `out`, given its
/// Hessian with respect to the edge vectors, `[[H_uu, H_uv], [H_vu, H_vv]]`.
#[inline]
pub fn scatter_hessian<T: Real, const N: usize>(
    out: &mut Blocks<T, N>,
    edges: [Edge; 2],
    h: [[T::Mat3; 2]; 2],
    w: T,
) {
    for (p, ep) in edges.iter().enumerate() {
        for (q, eq) in edges.iter().enumerate() {
            let m = h[p][q] * w;
            out[ep.head][eq.head] += m;
            out[ep.tail][eq.tail] += m;
            out[ep.head][eq.tail] -= m;
            out[ep.tail][eq.head] -= m;
        }
    }
}

impl<T: Real> EdgeCosine<T> {
    /// The edge-space Hessian `[[H_uu, H_uv], [H_vu, H_vv]]`.
    #[inline(always)]
    #[must_use]
    pub fn hessian_blocks(&self) -> [[T::Mat3; 2]; 2] {
        [[self.h_uu, self.h_uv], [self.h_uv.transposed(), self.h_vv]]
    }
}
