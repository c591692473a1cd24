//! A symmetric positive definite banded matrix and its Cholesky factor $A = LL^\top$, in
//! `f64`: the Newton systems of one-dimensional models (a curve's nodes in order couple only
//! their neighbours), where the sparse KKT machinery would be all overhead.
//!
//! With half bandwidth $b$ ($A_{ij} = 0$ for $|i - j| > b$), $L$ keeps the band (no fill)
//! and the factor costs $O(n b^2)$, a solve $O(n b)$, the storage $n(b + 1)$ numbers:
//! $$L_{jj} = \sqrt{A_{jj} - \textstyle\sum_{k} L_{jk}^2},\qquad
//!   L_{ij} = \bigl(A_{ij} - \textstyle\sum_{k} L_{ik}L_{jk}\bigr)/L_{jj},$$
//! the sums over $\max(i, j) - b \le k < j$ (Golub and Van Loan, *Matrix Computations*,
//! 4th ed., Algorithm 4.3.5).

use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use folio_kernels::math;

/// The factorization met a pivot that is not positive and finite: the matrix is not
/// positive definite (or not finite) at that row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotPositiveDefinite {
    /// The row whose pivot failed.
    pub row: usize,
}

impl fmt::Display for NotPositiveDefinite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the banded matrix is not positive definite at row {}",
            self.row
        )
    }
}

impl core::error::Error for NotPositiveDefinite {}

/// A symmetric banded matrix of order `n` and half bandwidth `b`, its lower band stored
/// row by row; after [`Banded::factor`] the same storage holds $L$.
#[derive(Clone, Debug, PartialEq)]
pub struct Banded {
    n: usize,
    b: usize,
    /// Row `i` holds $A_{i, i-b}, \dots, A_{ii}$ (entries left of column 0 stay zero).
    lower: Vec<f64>,
}

impl Banded {
    /// The zero matrix of order `n` and half bandwidth `b`.
    #[must_use]
    pub fn new(n: usize, b: usize) -> Self {
        Self {
            n,
            b,
            lower: vec![0.0; n * (b + 1)],
        }
    }

    /// The order $n$.
    #[must_use]
    pub fn order(&self) -> usize {
        self.n
    }

    /// The half bandwidth $b$.
    #[must_use]
    pub fn half_bandwidth(&self) -> usize {
        self.b
    }

    /// Every entry back to zero (the band kept).
    pub fn clear(&mut self) {
        self.lower.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Where $A_{ij}$ ($j \le i \le j + b$) is stored.
    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        i * (self.b + 1) + self.b + j - i
    }

    /// Adds `value` to $A_{ij}$ (and so to $A_{ji}$).
    ///
    /// # Panics
    /// If $|i - j| > b$ or an index is $\ge n$: the caller's band is wrong, a bug.
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        assert!(
            i < self.n && i - j <= self.b,
            "entry ({i}, {j}) outside the band"
        );
        let k = self.at(i, j);
        self.lower[k] += value;
    }

    /// $A_{ij}$ (zero outside the band).
    #[must_use]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i >= self.n || i - j > self.b {
            0.0
        } else {
            self.lower[self.at(i, j)]
        }
    }

    /// Overwrites the matrix with its Cholesky factor $L$ (module docs).
    ///
    /// # Errors
    /// [`NotPositiveDefinite`] at the first pivot that is not positive and finite; the
    /// storage then holds a partial factor and must be refilled.
    pub fn factor(&mut self) -> Result<(), NotPositiveDefinite> {
        for i in 0..self.n {
            let first = i.saturating_sub(self.b);
            for j in first..=i {
                let mut sum = self.lower[self.at(i, j)];
                for k in first.max(j.saturating_sub(self.b))..j {
                    sum -= self.lower[self.at(i, k)] * self.lower[self.at(j, k)];
                }
                let value = if i == j {
                    if !(sum.is_finite() && sum > 0.0) {
                        return Err(NotPositiveDefinite { row: i });
                    }
                    math::sqrt(sum)
                } else {
                    sum / self.lower[self.at(j, j)]
                };
                let k = self.at(i, j);
                self.lower[k] = value;
            }
        }
        Ok(())
    }

    /// Solves $LL^\top x = r$ in place (`r` becomes $x$) with the factor of
    /// [`Banded::factor`].
    ///
    /// # Panics
    /// If `r`'s length is not the order.
    pub fn solve(&self, r: &mut [f64]) {
        assert_eq!(r.len(), self.n, "right-hand side length");
        for i in 0..self.n {
            let mut sum = r[i];
            for (k, &rk) in r.iter().enumerate().take(i).skip(i.saturating_sub(self.b)) {
                sum -= self.lower[self.at(i, k)] * rk;
            }
            r[i] = sum / self.lower[self.at(i, i)];
        }
        for i in (0..self.n).rev() {
            let mut sum = r[i];
            for (k, &rk) in r
                .iter()
                .enumerate()
                .take((i + self.b + 1).min(self.n))
                .skip(i + 1)
            {
                sum -= self.lower[self.at(k, i)] * rk;
            }
            r[i] = sum / self.lower[self.at(i, i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Banded, NotPositiveDefinite};
    use alloc::vec::Vec;

    /// A diagonally dominant band of order 9, half bandwidth 3, with uneven entries.
    fn matrix() -> Banded {
        let mut a = Banded::new(9, 3);
        for i in 0..9 {
            a.add(i, i, 10.0 + i as f64);
            for d in 1..=3 {
                if i + d < 9 {
                    a.add(i + d, i, 1.0 / (1.0 + (i * d) as f64) - 0.4);
                }
            }
        }
        a
    }

    #[test]
    fn a_solve_reproduces_the_right_hand_side() {
        let a = matrix();
        let x: Vec<f64> = (0..9).map(|i| (i as f64 * 0.7).sin() + 0.1).collect();
        let mut r: Vec<f64> = (0..9)
            .map(|i| (0..9).map(|j| a.get(i, j) * x[j]).sum())
            .collect();
        let mut f = a.clone();
        f.factor().expect("diagonally dominant");
        f.solve(&mut r);
        for (got, want) in r.iter().zip(&x) {
            assert!((got - want).abs() < 1e-14, "{got} {want}");
        }
    }

    #[test]
    fn the_factor_multiplies_back_to_the_matrix() {
        let a = matrix();
        let mut l = a.clone();
        l.factor().unwrap();
        for i in 0..9 {
            for j in 0..=i {
                let lij = |i: usize, j: usize| if j <= i { l.get(i, j) } else { 0.0 };
                let sum: f64 = (0..9).map(|k| lij(i, k) * lij(j, k)).sum();
                assert!((sum - a.get(i, j)).abs() < 1e-13, "({i}, {j})");
            }
        }
    }

    #[test]
    fn an_indefinite_matrix_is_refused_at_its_row() {
        let mut a = Banded::new(3, 1);
        a.add(0, 0, 1.0);
        a.add(1, 0, 2.0);
        a.add(1, 1, 1.0);
        a.add(2, 2, 1.0);
        assert_eq!(a.factor(), Err(NotPositiveDefinite { row: 1 }));
        let mut nan = Banded::new(2, 1);
        nan.add(0, 0, f64::NAN);
        assert_eq!(nan.factor(), Err(NotPositiveDefinite { row: 0 }));
    }

    #[test]
    #[should_panic(expected = "outside the band")]
    fn an_entry_outside_the_band_is_a_bug() {
        Banded::new(5, 1).add(3, 0, 1.0);
    }
}
