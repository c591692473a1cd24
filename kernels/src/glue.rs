//! Binding glue, $V_{\mathrm{glue}}$ of seed `000_…` eq. 11: the pages stand upright at the
//! binding. Nodes `[x_l, x_b1, x_b2, x_r]`: the midline node left of the binding edge, the
//! binding edge $(x_{b_1}, x_{b_2})$ (left to right), the node right of it. In the XY plane
//! (Z is ignored: the midline is planar),
//! $$n = \frac{R\thinspace(x_{b_2} - x_{b_1})}{\lVert\cdot\rVert},\ R(x,y,z) = (-y, x, 0),\quad
//!   d_{left} = \frac{P(x_l - x_{b_1})}{\lVert\cdot\rVert},~
//!   d_{right} = \frac{P(x_r - x_{b_2})}{\lVert\cdot\rVert},\ P = \mathrm{diag}(1,1,0),$$
//! $$V = (\langle n, d_{left}\rangle - 1)^2 + (\langle n, d_{right}\rangle - 1)^2.$$
//! Each $\langle n, d\rangle$ is an [`EdgeCosine`] of the linearly mapped edges, so
//! $\nabla_e = R^T \nabla_u c$, $\nabla^2_{ee} = R^T H_{uu} R$, $\nabla^2_{e e'} = R^T H_{uv} P$, ...;
//! then $\nabla V = 2(g-1)\nabla g$, $\nabla^2 V = 2\nabla g \nabla g^T + 2(g-1)\nabla^2 g$.
//! Unweighted ($w_{\mathrm{glue}}$ = 600 by default); dimensionless. A degenerate edge
//! takes the [`EdgeCosine`] fallback ($g = 0$, no force from that side).

use core::marker::PhantomData;

use crate::edge_cosine::{Edge, EdgeCosine, scatter_gradient, scatter_hessian};
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, zero_blocks, zero_vecs};

/// Glue energy at the binding edge (module docs).
/// Parameter-free; the type parameter fixes the precision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Glue<T>(PhantomData<T>);

impl<T> Glue<T> {
    /// The glue energy.
    #[must_use]
    pub const fn new() -> Self {
        Self(PhantomData)
    }
}

/// The binding edge `b1 -> b2` and the two midline edges leaving it.
const BINDING: Edge = Edge::new(1, 2);
const SIDES: [Edge; 2] = [Edge::new(1, 0), Edge::new(2, 3)];

/// `R` (rotate +90 degrees in XY, drop Z) and `P` (drop Z).
fn maps<T: Real>() -> (T::Mat3, T::Mat3) {
    let [ex, ey, _] = T::Vec3::AXES;
    (
        T::Mat3::outer(ey, ex) - T::Mat3::outer(ex, ey),
        T::Mat3::outer(ex, ex) + T::Mat3::outer(ey, ey),
    )
}

/// $g = \langle n, d\rangle$ for one side, with node-space gradient and (optionally) the
/// edge-space Hessian blocks.
fn side<T: Real>(
    x: &NodeVecs<T, 4>,
    side: Edge,
    hessian: bool,
) -> (T, NodeVecs<T, 4>, [[T::Mat3; 2]; 2]) {
    let (r, p) = maps::<T>();
    let (u, v) = (r * BINDING.vector::<T, 4>(x), p * side.vector::<T, 4>(x));
    let c = if hessian {
        EdgeCosine::<T>::with_hessian(u, v)
    } else {
        EdgeCosine::<T>::with_gradient(u, v)
    };
    let rt = r.transposed();
    let mut grad = zero_vecs::<T, 4>();
    scatter_gradient(
        &mut grad,
        [BINDING, side],
        [rt * c.grad_u, p * c.grad_v],
        T::ONE,
    );
    let h = if hessian {
        [
            [rt * c.h_uu * r, rt * c.h_uv * p],
            [p * c.h_uv.transposed() * r, p * c.h_vv * p],
        ]
    } else {
        [[T::Mat3::ZERO; 2]; 2]
    };
    (c.value, grad, h)
}

impl<T: Real> Potential<T, 4> for Glue<T> {
    fn value(&self, x: &NodeVecs<T, 4>) -> T {
        let (r, p) = maps::<T>();
        let u = r * BINDING.vector::<T, 4>(x);
        SIDES
            .iter()
            .map(|s| EdgeCosine::<T>::value(u, p * s.vector::<T, 4>(x)) - T::ONE)
            .fold(T::ZERO, |acc, d| acc + d * d)
    }

    fn gradient(&self, x: &NodeVecs<T, 4>) -> NodeVecs<T, 4> {
        let mut out = zero_vecs::<T, 4>();
        for s in SIDES {
            let (g, grad, _) = side::<T>(x, s, false);
            let w = T::TWO * (g - T::ONE);
            for (o, gk) in out.iter_mut().zip(grad) {
                *o += gk * w;
            }
        }
        out
    }

    fn hessian(&self, x: &NodeVecs<T, 4>) -> Blocks<T, 4> {
        let mut out = zero_blocks::<T, 4>();
        for s in SIDES {
            let (g, grad, h) = side::<T>(x, s, true);
            scatter_hessian(&mut out, [BINDING, s], h, T::TWO * (g - T::ONE));
            for a in 0..4 {
                for b in 0..4 {
                    out[a][b] += T::Mat3::outer(grad[a], grad[b]) * T::TWO;
                }
            }
        }
        out
    }
}
