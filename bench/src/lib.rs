//! Shared inputs for Folio's criterion benches (see `benches/`), and the baselines they are
//! measured against.

pub mod book;
pub mod kkt;
pub mod pages;
pub mod tearing;

use folio_kernels::Real;
use folio_kernels::real::Vec3Ops;
use folio_kernels::splitmix::SplitMix64;

/// A deterministic generator ([`SplitMix64`]) so every bench run sees the same inputs.
pub struct Inputs(SplitMix64);

impl Inputs {
    /// A generator with the given seed.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(SplitMix64::new(seed))
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.uniform(lo, hi)
    }

    /// `count` gently curved stars of `N` nodes (`N` = 5 inner, 4 boundary, 3 curve, 2 edge):
    /// neighbours around the centre at unit-ish distance with a small out-of-plane bend.
    pub fn stars<T: Real, const N: usize>(&mut self, count: usize) -> Vec<[T::Vec3; N]> {
        let dirs = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
        (0..count)
            .map(|_| {
                let c = [
                    self.uniform(-5.0, 5.0),
                    self.uniform(-5.0, 5.0),
                    self.uniform(-1.0, 1.0),
                ];
                core::array::from_fn(|k| {
                    let (dx, dy) = if k == 0 {
                        (0.0, 0.0)
                    } else {
                        dirs[(k - 1) % 4]
                    };
                    let z = if k == 0 { 0.0 } else { self.uniform(-0.2, 0.2) };
                    let v = |a: f64| T::from_f64(a);
                    T::Vec3::new(
                        v(c[0] + dx * self.uniform(0.9, 1.1)),
                        v(c[1] + dy * self.uniform(0.9, 1.1)),
                        v(c[2] + z),
                    )
                })
            })
            .collect()
    }
}

/// Page points of an `n x n` grid over seed 000's page (12 x 16), as structure of arrays.
#[must_use]
pub fn page_grid<T: Real>(n: usize) -> (Vec<T>, Vec<T>) {
    let mut xs = Vec::with_capacity(n * n);
    let mut ys = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            xs.push(T::from_f64(12.0 * i as f64 / (n - 1) as f64));
            ys.push(T::from_f64(16.0 * j as f64 / (n - 1) as f64));
        }
    }
    (xs, ys)
}

macro_rules! seed_cone_loop {
    ($name:ident, $t:ty) => {
        /// The baseline: seed `001_…`'s per-vertex loop as the article writes it (each vertex
        /// recomputes `sin(theta)`, uses `pow` and `asin`, and rotates by `rho` with fresh
        /// trigonometry), array-of-structures output.
        pub fn $name(out: &mut [[$t; 3]], xs: &[$t], ys: &[$t], theta: $t, a: $t, rho: $t) {
            for ((o, &x), &y) in out.iter_mut().zip(xs).zip(ys) {
                let big_r = (x * x + (y - a).powi(2)).sqrt();
                let r = big_r * theta.sin();
                let beta = (x / big_r).asin() / theta.sin();
                let v1 = [
                    r * beta.sin(),
                    big_r + a - r * (1.0 - beta.cos()) * theta.sin(),
                    r * (1.0 - beta.cos()) * theta.cos(),
                ];
                *o = [
                    v1[0] * rho.cos() - v1[2] * rho.sin(),
                    v1[1],
                    v1[0] * rho.sin() + v1[2] * rho.cos(),
                ];
            }
        }
    };
}

seed_cone_loop!(seed_cone_loop_f32, f32);
seed_cone_loop!(seed_cone_loop_f64, f64);
