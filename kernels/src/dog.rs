//! Discrete orthogonal geodesic net (DOG) angle constraints, $C_{\mathrm{DOG}}$ of seed
//! `000_…` eq. 5 (Sec. 3.2, after Rabinovich, Hoffmann and Sorkine-Hornung 2018).
//!
//! A star is a vertex $p_0$ with its grid neighbours. With $e_k = p_k - p_0$ and
//! $c(u, v) = \hat u\cdot\hat v$ ([`EdgeCosine`]):
//!
//! * [`DogInnerStar`], nodes `[p0, xf, yf, xb, yb]` (x-forward, y-forward, x-back, y-back,
//!   counter-clockwise), three rows, all four angles equal:
//!   $$\varphi_1 = c(e_{xf},e_{yf}) - c(e_{yf},e_{xb}),\thickspace
//!   \varphi_2 = c(e_{yf},e_{xb}) - c(e_{xb},e_{yb}),\thickspace
//!   \varphi_3 = c(e_{xb},e_{yb}) - c(e_{xf},e_{yb}).$$
//! * [`DogBoundaryStar`], nodes `[p0, xf, yf, xb]` (three consecutive neighbours), one row
//!   $\varphi = c(e_{xf},e_{yf}) - c(e_{yf},e_{xb})$.
//!
//! Values, Jacobians and constraint Hessians are of this same normalized function.
//! Dimensionless; positions in page units; Jacobian entries in 1/length.
//!
//! **Flat stars.** Where a star is planar (in particular where both grid curves through
//! $p_0$ are straight, as on a page lying flat) every Jacobian row lies in the star's plane:
//! out-of-plane motion changes the angles only to second order. Over a flat grid the rows
//! then outnumber the in-plane unknowns and $\nabla C_{\mathrm{DOG}}$ loses row rank, which
//! makes the KKT matrix singular. [`FlatStarRemedy`] evaluates the Jacobian of a (near-)flat
//! star at $p_0$ displaced along the star normal by a tiny relative offset (the remedy of
//! RHS19), which restores full row rank at an $O(\text{offset})$ change of the rows.
//! A boundary star whose through-curve is straight is planar whatever the page does (two of
//! its three edges are collinear), so the remedy always applies to it.

use core::marker::PhantomData;

use crate::edge_cosine::{Edge, EdgeCosine, scatter_gradient, scatter_hessian};
use crate::math;
use crate::real::{Real, Vec3Ops};
use crate::term::{Blocks, Constraint, NodeVecs, zero_blocks, zero_vecs};

/// The angle layout of a star: which edge pairs form its angles and how rows combine them.
struct StarLayout<const A: usize, const R: usize> {
    /// Angle `a` is between edges `p0 -> pairs[a][0]` and `p0 -> pairs[a][1]`.
    pairs: [[usize; 2]; A],
    /// Row `l` is `sum_a rows[l][a] * c_a`.
    rows: [[i8; A]; R],
}

const INNER: StarLayout<4, 3> = StarLayout {
    pairs: [[1, 2], [2, 3], [3, 4], [1, 4]],
    rows: [[1, -1, 0, 0], [0, 1, -1, 0], [0, 0, 1, -1]],
};

const BOUNDARY: StarLayout<2, 1> = StarLayout {
    pairs: [[1, 2], [2, 3]],
    rows: [[1, -1]],
};

impl<const A: usize, const R: usize> StarLayout<A, R> {
    fn edges(&self, a: usize) -> [Edge; 2] {
        [
            Edge::new(0, self.pairs[a][0]),
            Edge::new(0, self.pairs[a][1]),
        ]
    }

    fn value<T: Real, const N: usize>(&self, x: &NodeVecs<T, N>) -> [T; R] {
        let mut c = [T::ZERO; A];
        for (a, ca) in c.iter_mut().enumerate() {
            let [u, v] = self.edges(a);
            *ca = EdgeCosine::<T>::value(u.vector::<T, N>(x), v.vector::<T, N>(x));
        }
        let mut out = [T::ZERO; R];
        for (o, row) in out.iter_mut().zip(&self.rows) {
            for (&k, &ca) in row.iter().zip(&c) {
                *o += T::from_f64(f64::from(k)) * ca;
            }
        }
        out
    }

    fn jacobian<T: Real, const N: usize>(&self, x: &NodeVecs<T, N>) -> [NodeVecs<T, N>; R] {
        let mut out = [zero_vecs::<T, N>(); R];
        for a in 0..A {
            let edges = self.edges(a);
            let c = EdgeCosine::<T>::with_gradient(
                edges[0].vector::<T, N>(x),
                edges[1].vector::<T, N>(x),
            );
            for (row_out, row) in out.iter_mut().zip(&self.rows) {
                if row[a] != 0 {
                    let w = T::from_f64(f64::from(row[a]));
                    scatter_gradient(row_out, edges, [c.grad_u, c.grad_v], w);
                }
            }
        }
        out
    }

    fn hessian<T: Real, const N: usize>(
        &self,
        x: &NodeVecs<T, N>,
        lambda: &[T; R],
    ) -> Blocks<T, N> {
        let mut out = zero_blocks::<T, N>();
        for a in 0..A {
            // Weight of angle a in sum_l lambda_l phi_l.
            let mut mu = T::ZERO;
            for (row, &l) in self.rows.iter().zip(lambda) {
                mu += T::from_f64(f64::from(row[a])) * l;
            }
            if mu == T::ZERO {
                continue;
            }
            let edges = self.edges(a);
            let c = EdgeCosine::<T>::with_hessian(
                edges[0].vector::<T, N>(x),
                edges[1].vector::<T, N>(x),
            );
            scatter_hessian(&mut out, edges, c.hessian_blocks(), mu);
        }
        out
    }
}

/// DOG constraint of an inner vertex: nodes `[p0, xf, yf, xb, yb]`, three rows (module docs).
/// Parameter-free; the type parameter fixes the precision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DogInnerStar<T>(PhantomData<T>);

/// DOG constraint of a boundary vertex with three neighbours: nodes `[p0, xf, yf, xb]`,
/// one row (module docs). Parameter-free; the type parameter fixes the precision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DogBoundaryStar<T>(PhantomData<T>);

impl<T> DogInnerStar<T> {
    /// The inner-star constraint.
    #[must_use]
    pub const fn new() -> Self {
        Self(PhantomData)
    }
}

impl<T> DogBoundaryStar<T> {
    /// The boundary-star constraint.
    #[must_use]
    pub const fn new() -> Self {
        Self(PhantomData)
    }
}

impl<T: Real> Constraint<T, 3, 5> for DogInnerStar<T> {
    fn value(&self, x: &NodeVecs<T, 5>) -> [T; 3] {
        INNER.value::<T, 5>(x)
    }
    fn jacobian(&self, x: &NodeVecs<T, 5>) -> [NodeVecs<T, 5>; 3] {
        INNER.jacobian::<T, 5>(x)
    }
    fn hessian(&self, x: &NodeVecs<T, 5>, lambda: &[T; 3]) -> Blocks<T, 5> {
        INNER.hessian::<T, 5>(x, lambda)
    }
}

impl<T: Real> Constraint<T, 1, 4> for DogBoundaryStar<T> {
    fn value(&self, x: &NodeVecs<T, 4>) -> [T; 1] {
        BOUNDARY.value::<T, 4>(x)
    }
    fn jacobian(&self, x: &NodeVecs<T, 4>) -> [NodeVecs<T, 4>; 1] {
        BOUNDARY.jacobian::<T, 4>(x)
    }
    fn hessian(&self, x: &NodeVecs<T, 4>, lambda: &[T; 1]) -> Blocks<T, 4> {
        BOUNDARY.hessian::<T, 4>(x, lambda)
    }
}

/// The flat-star remedy (module docs): evaluate the Jacobian of a star whose flatness
/// $s = \max_k \lvert \hat e_k \cdot \hat n\rvert$ is below `flatness_tolerance` at
/// $p_0 + \delta\thinspace\hat n$, with $\delta = $ `relative_offset` $\cdot\thinspace\bar L\thinspace(1 - s/\tau)$,
/// $\bar L$ the mean edge length and $\hat n$ the star normal
/// ($(e_{xf}-e_{xb})\times(e_{yf}-e_{yb})$ inner, $(e_{xf}-e_{xb})\times e_{yf}$ boundary).
/// The blend $(1 - s/\tau)$ keeps the Jacobian continuous; stars with $s \ge \tau$ get the
/// exact Jacobian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatStarRemedy<T> {
    /// $\tau$, dimensionless (sine of the largest out-of-plane edge angle still treated as flat).
    pub flatness_tolerance: T,
    /// Offset relative to the mean edge length: `1e-6` for `f64`, `1e-3` for `f32` by default
    /// (an `f32` offset of `1e-6` would drown in rounding).
    pub relative_offset: T,
}

impl<T: Real> Default for FlatStarRemedy<T> {
    fn default() -> Self {
        let offset = if T::EPSILON.to_f64() < 1e-10 {
            1e-6
        } else {
            1e-3
        };
        Self {
            flatness_tolerance: T::from_f64(1e-2),
            relative_offset: T::from_f64(offset),
        }
    }
}

impl<T: Real> FlatStarRemedy<T> {
    /// The displacement of $p_0$ this remedy applies to a star with the given normal
    /// direction `n` (unnormalized) and edges; zero for curved or degenerate stars.
    fn offset<const N: usize>(&self, x: &NodeVecs<T, N>, n: T::Vec3) -> T::Vec3 {
        let n_len = math::length::<T>(n);
        let usable = n_len >= T::LENGTH_FLOOR;
        if !usable {
            return T::Vec3::ZERO;
        }
        let n_hat = n / n_len;
        let mut flatness = T::ZERO;
        let mut mean_len = T::ZERO;
        for p in &x[1..] {
            let e = *p - x[0];
            let len = math::length::<T>(e);
            mean_len += len / T::from_f64((N - 1) as f64);
            if len >= T::LENGTH_FLOOR {
                let s = math::abs(e.dot(n_hat)) / len;
                if s > flatness {
                    flatness = s;
                }
            }
        }
        let blend = T::ONE - flatness / self.flatness_tolerance;
        if blend > T::ZERO {
            n_hat * (self.relative_offset * mean_len * blend)
        } else {
            T::Vec3::ZERO
        }
    }

    /// Jacobian of an inner star with the remedy applied.
    #[must_use]
    pub fn inner_jacobian(&self, x: &NodeVecs<T, 5>) -> [NodeVecs<T, 5>; 3] {
        let n = (x[1] - x[3]).cross(x[2] - x[4]);
        let mut moved = *x;
        moved[0] += self.offset(x, n);
        INNER.jacobian::<T, 5>(&moved)
    }

    /// Jacobian of a boundary star with the remedy applied.
    #[must_use]
    pub fn boundary_jacobian(&self, x: &NodeVecs<T, 4>) -> [NodeVecs<T, 4>; 1] {
        let n = (x[1] - x[3]).cross(x[2] - x[0]);
        let mut moved = *x;
        moved[0] += self.offset(x, n);
        BOUNDARY.jacobian::<T, 4>(&moved)
    }
}
