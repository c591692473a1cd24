//! Restarted GMRES with right preconditioning (Saad and Schultz 1986; Saad, "Iterative
//! Methods for Sparse Linear Systems", 2nd ed., Algorithm 9.5), the Krylov refinement of a
//! regularized factor against the true KKT matrix.
//!
//! With $M$ the preconditioner (the factor of $K + E$) it minimizes
//! $\lVert b - K x\rVert_2$ over $x \in x_0 + M^{-1}\mathcal K_m(K M^{-1}, r_0)$: Arnoldi with
//! modified Gram-Schmidt builds $K M^{-1} V_m = V_{m+1}\bar H_m$, Givens rotations reduce
//! $\bar H_m$ to triangular form, and $x = x_0 + M^{-1} V_m y_m$ with
//! $y_m = \arg\min_y \lVert \beta e_1 - \bar H_m y\rVert_2$. Plain iterative refinement is
//! the case $m = 1$ with a fixed step length of 1; GMRES also resolves the preconditioned
//! operator's small eigenvalues $s/(s + \delta)$ (constraint modes with a Schur eigenvalue
//! $s$ below the dual shift $\delta$), where plain refinement stalls at the rate
//! $\delta/(s + \delta)$ per step.

use alloc::vec::Vec;
use folio_kernels::Real;

use crate::room::{Room, refill};
use crate::vector::{dot, norm2};

/// The Krylov basis and the Hessenberg least-squares problem of one GMRES cycle.
///
/// Owns $m + 1$ basis vectors and one work vector of the system order $n$, and
/// $(m + 1)\thinspace m + 4m + 1$ scalars for the Hessenberg matrix, the rotations and the
/// right-hand side, all allocated by [`Gmres::new`].
#[derive(Clone, Debug)]
pub struct Gmres<T> {
    /// Order of the system.
    n: usize,
    /// Restart length $m$.
    restart: usize,
    /// Basis vectors $v_1 \dots v_{m+1}$, $n$ entries each, back to back.
    basis: Vec<T>,
    /// Work vector ($M^{-1} v$, then the update).
    work: Vec<T>,
    /// $\bar H_m$, column $j$ at `j * (m + 1)..`.
    h: Vec<T>,
    /// Givens rotations $(c_j, s_j)$.
    cosine: Vec<T>,
    sine: Vec<T>,
    /// Rotated $\beta e_1$.
    g: Vec<T>,
    /// Least-squares solution $y$.
    y: Vec<T>,
}

/// The operator $K$ and the preconditioner $M^{-1}$ of a [`Gmres::cycle`].
pub trait Operator<T> {
    /// `out = K v`.
    fn product(&mut self, out: &mut [T], v: &[T]);
    /// `out = M^{-1} v`.
    fn precondition(&mut self, out: &mut [T], v: &[T]);
}

/// How one [`Gmres::cycle`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KrylovOutcome<T> {
    /// $\lVert b - Kx\rVert_2$ of the returned $x$ (as the recurrence estimates it).
    pub residual: T,
    /// Krylov iterations (operator applications) done.
    pub iterations: u32,
}

impl<T: Real> Gmres<T> {
    /// Allocates a cycle of length `restart` (at least 1) for systems of order `n`.
    #[must_use]
    pub fn new(n: usize, restart: usize) -> Self {
        let mut gmres = Self {
            n: 0,
            restart: 0,
            basis: Vec::new(),
            work: Vec::new(),
            h: Vec::new(),
            cosine: Vec::new(),
            sine: Vec::new(),
            g: Vec::new(),
            y: Vec::new(),
        };
        gmres.reset(n, restart);
        gmres
    }

    /// Makes this workspace [`Gmres::new`]'s for order `n` and `restart`, in its own
    /// buffers: no allocation when they hold it ([`Gmres::reserve`]).
    pub fn reset(&mut self, n: usize, restart: usize) {
        let m = restart.max(1);
        self.n = n;
        self.restart = m;
        refill(&mut self.basis, (m + 1) * n, T::ZERO);
        refill(&mut self.work, n, T::ZERO);
        refill(&mut self.h, (m + 1) * m, T::ZERO);
        refill(&mut self.cosine, m, T::ZERO);
        refill(&mut self.sine, m, T::ZERO);
        refill(&mut self.g, m + 1, T::ZERO);
        refill(&mut self.y, m, T::ZERO);
    }

    /// Room for order `n` at the current restart length.
    pub fn reserve(&mut self, n: usize) {
        self.basis.room_for((self.restart + 1) * n);
        self.work.room_for(n);
    }

    /// One cycle (at most `restart` iterations) from the residual `r` $= b - K x$ of `x`:
    /// stops early when the estimated $\lVert b - Kx\rVert_2$ is at most `target`.
    /// Returns the estimated residual norm and the
    /// iterations done; `x` is updated, `r` is left undefined.
    pub fn cycle(
        &mut self,
        x: &mut [T],
        r: &[T],
        target: T,
        operator: &mut impl Operator<T>,
    ) -> KrylovOutcome<T> {
        let (n, m) = (self.n, self.restart);
        let beta = norm2(r);
        if !above(beta, target) || !beta.is_finite() {
            return KrylovOutcome {
                residual: beta,
                iterations: 0,
            };
        }
        for (v, &ri) in self.basis[..n].iter_mut().zip(r) {
            *v = ri / beta;
        }
        self.g.iter_mut().for_each(|g| *g = T::ZERO);
        self.g[0] = beta;
        let mut done = 0;
        let mut residual = beta;
        for j in 0..m {
            let (head, tail) = self.basis.split_at_mut((j + 1) * n);
            let w = &mut tail[..n];
            operator.precondition(&mut self.work, &head[j * n..]);
            operator.product(w, &self.work);
            let column = &mut self.h[j * (m + 1)..(j + 1) * (m + 1)];
            for (i, hij) in column.iter_mut().enumerate().take(j + 1) {
                let vi = &head[i * n..(i + 1) * n];
                let dot = dot(w, vi);
                *hij = dot;
                for (wk, &vk) in w.iter_mut().zip(vi) {
                    *wk -= dot * vk;
                }
            }
            let next = norm2(w);
            column[j + 1] = next;
            if next > T::ZERO {
                w.iter_mut().for_each(|wk| *wk /= next);
            }
            // Apply the earlier rotations to the new column, then make its own.
            for i in 0..j {
                let (c, s) = (self.cosine[i], self.sine[i]);
                let (a, b) = (column[i], column[i + 1]);
                column[i] = c * a + s * b;
                column[i + 1] = c * b - s * a;
            }
            let (a, b) = (column[j], column[j + 1]);
            let rho = folio_kernels::math::sqrt(a * a + b * b);
            let (c, s) = if rho > T::ZERO {
                (a / rho, b / rho)
            } else {
                (T::ONE, T::ZERO)
            };
            self.cosine[j] = c;
            self.sine[j] = s;
            column[j] = rho;
            column[j + 1] = T::ZERO;
            self.g[j + 1] = -s * self.g[j];
            self.g[j] *= c;
            done = j + 1;
            residual = abs(self.g[j + 1]);
            if !above(residual, target) || !above(next, T::ZERO) {
                break;
            }
        }
        // Back substitution for y, then x += M^{-1} (V y).
        for i in (0..done).rev() {
            let mut sum = self.g[i];
            for k in i + 1..done {
                sum -= self.h[k * (m + 1) + i] * self.y[k];
            }
            let diagonal = self.h[i * (m + 1) + i];
            self.y[i] = if diagonal == T::ZERO {
                T::ZERO
            } else {
                sum / diagonal
            };
        }
        // The last basis slot is free now: it takes V y.
        let (vectors, combination) = self.basis.split_at_mut(m * n);
        combination.iter_mut().for_each(|c| *c = T::ZERO);
        for (i, &yi) in self.y[..done].iter().enumerate() {
            for (c, &v) in combination.iter_mut().zip(&vectors[i * n..(i + 1) * n]) {
                *c += yi * v;
            }
        }
        operator.precondition(&mut self.work, combination);
        for (xi, &u) in x.iter_mut().zip(&self.work) {
            *xi += u;
        }
        KrylovOutcome {
            residual,
            iterations: done as u32,
        }
    }
}

/// `a > b` (false when either is NaN).
#[inline]
fn above<T: Real>(a: T, b: T) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

/// $|x|$.
#[inline]
fn abs<T: Real>(x: T) -> T {
    if x < T::ZERO { -x } else { x }
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::{Gmres, Operator};
    use crate::chain::{Chain, kkt_values};
    use crate::kkt::Kkt;
    use crate::ordering::Ordering;
    use crate::vector::max_abs;

    /// A dense nonsymmetric matrix with the identity as the preconditioner.
    struct Dense(Vec<Vec<f64>>);

    impl Operator<f64> for Dense {
        fn product(&mut self, out: &mut [f64], v: &[f64]) {
            for (o, row) in out.iter_mut().zip(&self.0) {
                *o = row.iter().zip(v).map(|(a, b)| a * b).sum();
            }
        }

        fn precondition(&mut self, out: &mut [f64], v: &[f64]) {
            out.copy_from_slice(v);
        }
    }

    /// Without restart (m = n) GMRES solves an n x n system in at most n iterations.
    #[test]
    fn solves_a_small_system_in_n_iterations() {
        let a = vec![
            vec![4.0, 1.0, 0.0, 2.0],
            vec![-1.0, 3.0, 1.0, 0.0],
            vec![0.0, 2.0, -5.0, 1.0],
            vec![1.0, 0.0, 1.0, 2.0],
        ];
        let want = [1.0, -2.0, 0.5, 3.0];
        let mut op = Dense(a);
        let mut b = [0.0; 4];
        op.product(&mut b, &want);
        let mut x = [0.0; 4];
        let mut gmres = Gmres::new(4, 4);
        let outcome = gmres.cycle(&mut x, &b, 1e-13, &mut op);
        assert!(outcome.iterations <= 4, "{outcome:?}");
        for (xi, wi) in x.iter().zip(want) {
            assert!((xi - wi).abs() < 1e-12, "{x:?}");
        }
        // A zero residual takes no iteration and leaves x alone.
        let before = x;
        let outcome = gmres.cycle(&mut x, &[0.0; 4], 0.0, &mut op);
        assert_eq!(outcome.iterations, 0);
        assert_eq!(x, before);
    }

    /// The quasi-definite order's first solve is off by the dual shift; the GMRES
    /// refinement brings the chain's KKT solve to the target, in both precisions.
    #[test]
    fn quasi_definite_kkt_refines_to_the_target() {
        let pattern = Chain::new(9).pattern(false);
        let values = kkt_values(&pattern);
        let n = pattern.order();
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (i % 5) as f64).collect();
        let mut kkt = Kkt::<f64>::new(pattern.clone(), Ordering::AmdQuasiDefinite);
        kkt.values_mut().copy_from_slice(&values);
        kkt.factorize(1e-12, 1e-8);
        let mut z = vec![0.0; n];
        let first = kkt.solve_refined(&mut z, &b, 0, 0.0);
        assert!(first.relative_residual > 1e-6, "{first:?}");
        let refined = kkt.solve_refined(&mut z, &b, 40, 1e-12);
        assert!(refined.relative_residual <= 1e-12, "{refined:?}");
        assert!(refined.steps > 0);
        let mut product = vec![0.0; n];
        kkt.multiply(&mut product, &z);
        let error: Vec<f64> = product.iter().zip(&b).map(|(p, q)| p - q).collect();
        assert!(max_abs(&error) <= 1e-12 * max_abs(&b));

        let mut kkt = Kkt::<f32>::new(pattern, Ordering::AmdQuasiDefinite);
        for (v, &w) in kkt.values_mut().iter_mut().zip(&values) {
            *v = w as f32;
        }
        kkt.factorize(1e-4, 3e-4);
        let b32: Vec<f32> = b.iter().map(|&v| v as f32).collect();
        let mut z = vec![0.0f32; n];
        let refined = kkt.solve_refined(&mut z, &b32, 40, 1e-5);
        assert!(refined.relative_residual <= 1e-5, "{refined:?}");
    }
}
