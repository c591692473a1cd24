//! Test support shared by Folio's integration tests: a seeded random source, finite-difference
//! checks that serve every [`Potential`] and [`Constraint`], and small geometry helpers.
//!
//! Finite differences are central, with step $h = \varepsilon^{1/3}\max(1, |x|)$ per
//! coordinate (DESIGN.md, testing habits). An error is reported as
//! $\lVert a - f\rVert_\infty / \max(\lVert a\rVert_\infty, \lVert f\rVert_\infty, 10^{-2})$:
//! relative for derivatives of ordinary size, absolute below $10^{-2}$ (so that exactly-zero
//! blocks of linear terms do not divide rounding noise by zero).

pub mod dense_kkt;
pub mod elastica;
pub mod fuzz;
pub mod models;
pub mod pad;
pub mod paths;
pub mod terms;
pub mod turn;

use folio_kernels::real::{Mat3Ops, Vec3Ops};
use folio_kernels::splitmix::SplitMix64;
use folio_kernels::term::{Blocks, NodeVecs};
use folio_kernels::{Constraint, Potential, Real};
use glam::{DMat3, DQuat, DVec3};

/// A tiny seeded generator ([`SplitMix64`]), so every "random" test is reproducible.
#[derive(Clone, Debug)]
pub struct Rng(SplitMix64);

impl Rng {
    /// A generator with the given seed.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(SplitMix64::new(seed))
    }

    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.uniform(lo, hi)
    }

    /// A vector with components uniform in `[-r, r)`.
    pub fn vec(&mut self, r: f64) -> DVec3 {
        DVec3::new(
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        )
    }

    /// A uniformly random unit vector.
    pub fn unit(&mut self) -> DVec3 {
        loop {
            let v = self.vec(1.0);
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }

    /// A uniformly random rotation.
    pub fn rotation(&mut self) -> DQuat {
        let axis = self.unit();
        DQuat::from_axis_angle(
            axis,
            self.uniform(-core::f64::consts::PI, core::f64::consts::PI),
        )
    }
}

/// The larger of `a` and `b`, NaN if either is: the fold for every maximum a test asserts
/// on, where `f64::max` would drop a NaN (`NaN.max(1e-9)` is `1e-9`) and let a broken
/// result pass.
#[inline]
#[must_use]
pub fn worst<T: PartialOrd + Copy + core::ops::Add<Output = T>>(a: T, b: T) -> T {
    match a.partial_cmp(&b) {
        // Unordered: one is NaN, and so is the sum.
        None => a + b,
        Some(core::cmp::Ordering::Less) => b,
        Some(_) => a,
    }
}

/// The smaller of `a` and `b`, NaN if either is ([`worst`]'s counterpart for minima).
#[inline]
#[must_use]
pub fn least<T: PartialOrd + Copy + core::ops::Add<Output = T>>(a: T, b: T) -> T {
    match a.partial_cmp(&b) {
        None => a + b,
        Some(core::cmp::Ordering::Greater) => b,
        Some(_) => a,
    }
}

/// The largest of `values` and 0 ([`worst`] folded from 0): NaN if any value is NaN.
#[must_use]
pub fn nan_max(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, worst)
}

/// Relative error as described in the crate docs; NaN when any component is NaN.
#[must_use]
pub fn rel_err(analytic: &[f64], fd: &[f64]) -> f64 {
    let diff = nan_max(analytic.iter().zip(fd).map(|(a, f)| (a - f).abs()));
    let scale = analytic.iter().chain(fd).map(|v| v.abs()).fold(1e-2, worst);
    diff / scale
}

/// Step for coordinate value `x`.
fn step(x: f64) -> f64 {
    f64::EPSILON.cbrt() * x.abs().max(1.0)
}

/// Central differences of a node-space function `f` (returning a flat vector) with respect to
/// every coordinate of `x`: column `3a + i` is $\partial f / \partial x_{a,i}$, returned
/// row-major as `out[row * 3N + col]`.
pub fn fd_jacobian<const N: usize>(
    x: &NodeVecs<f64, N>,
    f: impl Fn(&NodeVecs<f64, N>) -> Vec<f64>,
) -> Vec<f64> {
    let rows = f(x).len();
    let cols = 3 * N;
    let mut out = vec![0.0; rows * cols];
    for a in 0..N {
        for i in 0..3 {
            let h = step(x[a].to_array()[i]);
            let (mut xp, mut xm) = (*x, *x);
            xp[a][i] += h;
            xm[a][i] -= h;
            let (fp, fm) = (f(&xp), f(&xm));
            for r in 0..rows {
                out[r * cols + 3 * a + i] = (fp[r] - fm[r]) / (2.0 * h);
            }
        }
    }
    out
}

/// Worst relative errors of one evaluation: `(gradient or Jacobian, Hessian)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FdErrors {
    /// Gradient (potentials) or Jacobian (constraints) against differences of the value.
    pub first: f64,
    /// Hessian (or constraint Hessian) against differences of the analytic gradient.
    pub second: f64,
    /// $\lVert H - H^T\rVert_\infty / \max(\lVert H\rVert_\infty, 10^{-2})$.
    pub asymmetry: f64,
}

impl FdErrors {
    /// Component-wise maximum, NaN where either is ([`worst`]).
    #[must_use]
    pub fn max(self, o: Self) -> Self {
        Self {
            first: worst(self.first, o.first),
            second: worst(self.second, o.second),
            asymmetry: worst(self.asymmetry, o.asymmetry),
        }
    }
}

fn asymmetry<const N: usize>(h: &Blocks<f64, N>) -> f64 {
    let flat = flat_blocks::<f64, N>(h);
    let n = 3 * N;
    let mut t = vec![0.0; n * n];
    for r in 0..n {
        for c in 0..n {
            t[c * n + r] = flat[r * n + c];
        }
    }
    rel_err(&flat, &t)
}

/// Finite-difference check of a potential at `x`.
pub fn check_potential<P: Potential<f64, N>, const N: usize>(
    p: &P,
    x: &NodeVecs<f64, N>,
) -> FdErrors {
    let g = flat_vecs::<f64, N>(&p.gradient(x));
    let g_fd = fd_jacobian(x, |y| vec![p.value(y)]);
    let h = p.hessian(x);
    let h_fd = fd_jacobian(x, |y| flat_vecs::<f64, N>(&p.gradient(y)));
    FdErrors {
        first: rel_err(&g, &g_fd),
        second: rel_err(&flat_blocks::<f64, N>(&h), &h_fd),
        asymmetry: asymmetry(&h),
    }
}

/// Finite-difference check of a constraint at `x` with multipliers `lambda`.
pub fn check_constraint<C: Constraint<f64, R, N>, const R: usize, const N: usize>(
    c: &C,
    x: &NodeVecs<f64, N>,
    lambda: &[f64; R],
) -> FdErrors {
    let jac: Vec<f64> = c.jacobian(x).iter().flat_map(flat_vecs::<f64, N>).collect();
    let jac_fd = fd_jacobian(x, |y| c.value(y).to_vec());
    let weighted_grad = |y: &NodeVecs<f64, N>| {
        let j = c.jacobian(y);
        let mut g = [DVec3::ZERO; N];
        for (row, l) in j.iter().zip(lambda) {
            for (gk, jk) in g.iter_mut().zip(row) {
                *gk += *jk * *l;
            }
        }
        flat_vecs::<f64, N>(&g)
    };
    let h = c.hessian(x, lambda);
    let h_fd = fd_jacobian(x, weighted_grad);
    FdErrors {
        first: rel_err(&jac, &jac_fd),
        second: rel_err(&flat_blocks::<f64, N>(&h), &h_fd),
        asymmetry: asymmetry(&h),
    }
}

/// Converts an `f64` local block to `f32`.
#[must_use]
pub fn to_f32<const N: usize>(x: &NodeVecs<f64, N>) -> NodeVecs<f32, N> {
    x.map(|p| <f32 as Real>::Vec3::new(p.x as f32, p.y as f32, p.z as f32))
}

/// Max-norm of an `f32` result's difference to an `f64` one, relative to the `f64` scale
/// (floored at 1).
#[must_use]
pub fn precision_gap(f32s: &[f32], f64s: &[f64]) -> f64 {
    let as64: Vec<f64> = f32s.iter().map(|&v| f64::from(v)).collect();
    let diff = nan_max(as64.iter().zip(f64s).map(|(a, b)| (a - b).abs()));
    diff / f64s.iter().map(|v| v.abs()).fold(1.0, worst)
}

/// Flattens node vectors of either precision into `f64`s.
#[must_use]
pub fn flat_vecs<T: Real, const N: usize>(v: &NodeVecs<T, N>) -> Vec<f64> {
    v.iter()
        .flat_map(|p| [p.x(), p.y(), p.z()].map(Real::to_f64))
        .collect()
}

/// Flattens Hessian blocks of either precision into `f64`s (row-major over `3N x 3N`).
#[must_use]
pub fn flat_blocks<T: Real, const N: usize>(h: &Blocks<T, N>) -> Vec<f64> {
    let mut out = Vec::with_capacity(9 * N * N);
    for row in h {
        for i in 0..3 {
            for block in row {
                out.extend((0..3).map(|j| block.entry(i, j).to_f64()));
            }
        }
    }
    out
}

/// Applies `q` and then the translation `t` to every node.
#[must_use]
pub fn rigid<const N: usize>(x: &NodeVecs<f64, N>, q: DQuat, t: DVec3) -> NodeVecs<f64, N> {
    x.map(|p| q * p + t)
}

/// `R H R^T` blockwise: how a Hessian of a rigidly invariant term transforms.
#[must_use]
pub fn rotate_blocks<const N: usize>(h: &Blocks<f64, N>, q: DQuat) -> Blocks<f64, N> {
    let r = DMat3::from_quat(q);
    h.map(|row| row.map(|b| r * b * r.transpose()))
}

/// A perturbed star around `p0`: neighbours at `p0 + len * dir` with the given directions,
/// lengths uniform in `[0.5, 1.5]` and directions jittered by `jitter`.
#[must_use]
pub fn jittered_star<const N: usize>(
    rng: &mut Rng,
    dirs: [DVec3; N],
    jitter: f64,
) -> NodeVecs<f64, N> {
    let p0 = rng.vec(2.0);
    let mut x = [p0; N];
    for (k, d) in dirs.iter().enumerate().skip(1) {
        let dir = (*d + rng.vec(jitter)).normalize();
        x[k] = p0 + dir * rng.uniform(0.5, 1.5);
    }
    x
}

/// The grid directions of an inner star `[p0, xf, yf, xb, yb]` in the XY plane (entry 0 unused).
pub const INNER_DIRS: [DVec3; 5] = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::NEG_X, DVec3::NEG_Y];

/// The grid directions of a boundary star `[p0, xf, yf, xb]` (entry 0 unused).
pub const BOUNDARY_DIRS: [DVec3; 4] = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::NEG_X];

/// A DOG star of an `n x m` vertex grid (vertex `(i, j)` has index `i + n j`), with its node
/// indices in the kernels' order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridStar {
    /// `[p0, xf, yf, xb, yb]`.
    Inner([usize; 5]),
    /// `[p0, a, b, c]`: three consecutive neighbours counter-clockwise.
    Boundary([usize; 4]),
}

/// Every inner and 3-neighbour boundary star of an `n x m` vertex grid (corners have none).
#[must_use]
pub fn grid_stars(n: usize, m: usize) -> Vec<GridStar> {
    let mut out = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let nb = |di: isize, dj: isize| {
                let (a, b) = (i as isize + di, j as isize + dj);
                (a >= 0 && b >= 0 && (a as usize) < n && (b as usize) < m)
                    .then(|| a as usize + n * b as usize)
            };
            let ring = [nb(1, 0), nb(0, 1), nb(-1, 0), nb(0, -1)];
            let c = i + n * j;
            match ring.iter().filter(|q| q.is_some()).count() {
                4 => out.push(GridStar::Inner([
                    c,
                    ring[0].unwrap(),
                    ring[1].unwrap(),
                    ring[2].unwrap(),
                    ring[3].unwrap(),
                ])),
                3 => {
                    // Rotate the ring so that the missing neighbour comes last.
                    let k = (ring.iter().position(Option::is_none).unwrap() + 1) % 4;
                    out.push(GridStar::Boundary([
                        c,
                        ring[k].unwrap(),
                        ring[(k + 1) % 4].unwrap(),
                        ring[(k + 2) % 4].unwrap(),
                    ]));
                }
                _ => {}
            }
        }
    }
    out
}

/// Twice the signed area and the longest squared edge of a pattern triangle.
#[must_use]
pub fn area2_and_longest(u: [[f64; 2]; 3]) -> (f64, f64) {
    let d = |a: [f64; 2], b: [f64; 2]| [b[0] - a[0], b[1] - a[1]];
    let (e1, e2, e3) = (d(u[0], u[1]), d(u[0], u[2]), d(u[1], u[2]));
    let sq = |e: [f64; 2]| e[0] * e[0] + e[1] * e[1];
    (
        e1[0] * e2[1] - e1[1] * e2[0],
        sq(e1).max(sq(e2)).max(sq(e3)),
    )
}

/// A random counter-clockwise pattern triangle in $[-2, 2]^2$ with
/// $2A \ge$ `shape` $\cdot\thinspace\ell_{\max}^2$ and $\ell_{\max}^2 \ge$ `min_longest_sq`.
pub fn pattern_triangle(r: &mut Rng, shape: f64, min_longest_sq: f64) -> [[f64; 2]; 3] {
    loop {
        let u = [(); 3].map(|()| [r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0)]);
        let (area2, longest) = area2_and_longest(u);
        if area2.abs() >= shape * longest && longest >= min_longest_sq {
            return if area2 > 0.0 { u } else { [u[0], u[2], u[1]] };
        }
    }
}
