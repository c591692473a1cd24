//! Fuzz target `ldlt`: the $LDL^\top$ factorization and refined solve ([`Kkt`],
//! [`folio_solvers::ldlt::Ldlt`]) of arbitrary small symmetric quasi-definite matrices
//! $K = [[H, J^\top], [J, -C]]$ in `f32` and `f64`, in every ordering, with and without
//! equilibration.
//!
//! $H$ ($1$ to $6$ unknowns) is strictly diagonally dominant with a positive diagonal (so
//! positive definite), $C$ diagonal and $\ge 0$ (zero rows are the usual hard constraints),
//! $J$ sparse with up to [`ROW_COUPLINGS`] entries a row (including empty rows and repeated
//! rows: redundant constraints). Entries span $10^{-6}$ to $10^6$. Some inputs plant a NaN
//! or an infinity.
//!
//! Asserts: no panic; on a well-posed matrix (finite, its [`condition`] number at most
//! $10^{-3} / \varepsilon$), factorized as it is (no dual shift of
//! [`Ordering::AmdQuasiDefinite`], no static $-\delta$ on a structurally zero pivot: those
//! factor another matrix and leave the difference to a refinement with a fixed budget), a
//! factor with no regularized pivot solves
//! to a normwise backward error $\lVert Kz - b\rVert_\infty / (\lVert K\rVert_\infty
//! \lVert z\rVert_\infty + \lVert b\rVert_\infty) \le 10^3 \varepsilon g + 10\tau$ after
//! refinement ($\tau$ the refinement's target, [`Settings::refinement_tolerance`], $g$
//! the growth bound of [`Case`]'s `growth`);
//! on any matrix a solve whose refinement reports its target met has a true relative
//! residual within ten times that target; any other outcome is a [`FactorOutcome`]
//! (regularized pivots counted, or the non-finite pivot named) or a reported residual; a
//! factor handed another analysis refuses it with [`SolverError::SymbolicMismatch`]. Singular
//! and nearly singular matrices (redundant rows, an empty row) are decoded too: there the
//! solver must not claim a residual it did not reach.

use folio_kernels::Real;
use folio_solvers::ldlt::FactorOutcome;
use folio_solvers::{Kkt, Ordering, Settings, SolverError};

use super::Input;
use crate::dense_kkt::{ROW_COUPLINGS, dense_kkt, dense_residual};
use crate::nan_max;

/// Decodes a matrix and a right-hand side from `data`, factorizes and solves.
///
/// # Panics
/// When a property in the module docs does not hold.
pub fn run(data: &[u8]) {
    let mut input = Input::new(data);
    let single = input.flag();
    let case = Case::decode(&mut input);
    if single {
        case.check::<f32>();
    } else {
        case.check::<f64>();
    }
}

/// One decoded matrix, right-hand side and solver choice.
#[derive(Clone, Debug)]
pub struct Case {
    /// Primal unknowns.
    pub dofs: usize,
    /// The dense row-major matrix, `order x order`.
    pub k: Vec<f64>,
    /// The right-hand side.
    pub b: Vec<f64>,
    /// The ordering of the analysis.
    pub ordering: Ordering,
    /// Whether Ruiz equilibration is on.
    pub equilibrate: bool,
}

impl Case {
    /// A matrix as in the module docs, decoded from `input`.
    pub fn decode(input: &mut Input<'_>) -> Self {
        let dofs = 1 + input.below(6);
        let rows = input.below(5);
        let n = dofs + rows;
        let ordering = [
            Ordering::Natural,
            Ordering::Amd,
            Ordering::AmdDelayedDuals,
            Ordering::AmdQuasiDefinite,
        ][input.below(4)];
        let equilibrate = input.flag();
        let mut k = vec![0.0; n * n];
        let scale = input.log_uniform(1e-6, 1e6);
        let density = input.byte();
        for a in 0..dofs {
            for b in a + 1..dofs {
                if input.byte() < density {
                    let v = scale * input.signed(1e-6, 1.0);
                    k[a * n + b] = v;
                    k[b * n + a] = v;
                }
            }
        }
        for a in 0..dofs {
            let off: f64 = (0..dofs)
                .filter(|&b| b != a)
                .map(|b| k[a * n + b].abs())
                .sum();
            k[a * n + a] = off + scale * input.log_uniform(1e-6, 1.0);
        }
        let j_scale = input.log_uniform(1e-6, 1e6);
        for r in dofs..n {
            if r > dofs && input.byte() < 32 {
                // A copy of the previous row: redundant constraints.
                for a in 0..dofs {
                    k[r * n + a] = k[(r - 1) * n + a];
                    k[a * n + r] = k[a * n + r - 1];
                }
            } else {
                let mut count = 0;
                for a in 0..dofs {
                    if count < ROW_COUPLINGS && input.byte() < density {
                        let v = j_scale * input.signed(1e-6, 1.0);
                        k[r * n + a] = v;
                        k[a * n + r] = v;
                        count += 1;
                    }
                }
            }
            if input.byte() < 64 {
                k[r * n + r] = -input.log_uniform(1e-6, 1e6);
            }
        }
        if input.byte() == 255 {
            // On a stored entry, so that the structure stays a KKT pattern.
            let stored: Vec<usize> = (0..n * n)
                .filter(|&i| k[i] != 0.0 || i % (n + 1) == 0)
                .collect();
            let at = stored[input.below(stored.len())];
            let bad = if input.flag() {
                f64::NAN
            } else {
                f64::INFINITY
            };
            let (r, c) = (at / n, at % n);
            k[r * n + c] = bad;
            k[c * n + r] = bad;
        }
        let b = (0..n).map(|_| input.signed(1e-6, 1e6)).collect();
        Self {
            dofs,
            k,
            b,
            ordering,
            equilibrate,
        }
    }

    /// Factorizes and solves in precision `T` and asserts the module docs' properties;
    /// returns the outcome and the backward error of a clean factor.
    ///
    /// # Panics
    /// When a property does not hold.
    pub fn check<T: Real>(&self) -> (FactorOutcome, Option<f64>) {
        let Some(mut kkt) = dense_kkt::<T>(self.dofs, &self.k, self.ordering) else {
            panic!("every decoded row couples to at most {ROW_COUPLINGS} unknowns");
        };
        kkt.set_equilibration(self.equilibrate);
        let s = Settings::<T>::default();
        let outcome = kkt.factorize(s.pivot_epsilon, s.regularization);
        let b: Vec<T> = self.b.iter().map(|&v| T::from_f64(v)).collect();
        let mut z = vec![T::ZERO; b.len()];
        let finite = self.k.iter().all(|v| v.is_finite());
        let refinement = kkt.solve_refined(&mut z, &b, s.refinement_steps, s.refinement_tolerance);
        mismatch_is_refused(&kkt);
        let clean = matches!(outcome, FactorOutcome::Factored { regularized: 0, .. });
        if !finite {
            return (outcome, None);
        }
        let stored: Vec<f64> = self.k.iter().map(|&v| T::from_f64(v).to_f64()).collect();
        let b64: Vec<f64> = b.iter().map(|v| v.to_f64()).collect();
        if refinement.relative_residual <= s.refinement_tolerance {
            // The claim is made in working precision: the product K z is rounded to about
            // n eps |K| |z|, which a relative residual cannot see below.
            let true_residual = dense_residual(&stored, &z, &b64);
            let n = b.len() as f64;
            let (k_norm, z_norm) = (
                norm(&stored, b.len()),
                nan_max(z.iter().map(|v| v.to_f64().abs())),
            );
            let b_norm = nan_max(b64.iter().map(|v| v.abs()));
            let rounding = if b_norm > 0.0 {
                4.0 * n * T::EPSILON.to_f64() * k_norm * z_norm / b_norm
            } else {
                0.0
            };
            let claimed = 10.0 * s.refinement_tolerance.to_f64() + rounding;
            assert!(
                true_residual <= claimed.max(1e2 * T::EPSILON.to_f64()),
                "claimed {:e}, true residual {true_residual:e} for {self:?}",
                refinement.relative_residual.to_f64()
            );
        }
        // The dual shift of `AmdQuasiDefinite` factorizes another matrix and leaves the
        // rest to a Krylov refinement with a fixed budget, which says when it falls short
        // (the claim above) but need not reach the bound below.
        // Likewise a constraint row eliminated before the unknowns it couples to, with a
        // zero diagonal: its pivot is a static -delta, and the factor another matrix's.
        let shifted = self.ordering == Ordering::AmdQuasiDefinite;
        let n = b.len();
        let symbolic = kkt.symbolic();
        let perturbed = (0..n).any(|k| {
            let old = symbolic.perm()[k] as usize;
            symbolic.structural_zero()[k] && stored[old * n + old] == 0.0
        });
        let exact = !shifted && !perturbed;
        let well_posed = exact && condition(&stored) * T::EPSILON.to_f64() <= 1e-3;
        if !(well_posed && clean) {
            return (outcome, None);
        }
        let eta = self.backward_error(&kkt, &z, &b);
        // The refinement stops once the relative residual meets its target (eps^(3/4) by
        // default), which bounds the backward error too.
        let bound =
            1e3 * T::EPSILON.to_f64() * self.growth() + 10.0 * s.refinement_tolerance.to_f64();
        assert!(
            eta <= bound,
            "backward error {eta:e} > {bound:e} ({outcome:?}) for {self:?}"
        );
        (outcome, Some(eta))
    }

    /// A bound on the growth of a quasi-definite factor in any order (Gill, Saunders and
    /// Shinnerl 1996): $g = 1 + \max_r \lVert J_r\rVert_2^2 / (\mu_H \lVert K\rVert_\infty)$
    /// with $\mu_H$ Gershgorin's lower bound on $H$'s eigenvalues: eliminating an unknown of
    /// a small pivot first updates the constraint rows by $\lVert J\rVert^2 / \mu_H$.
    fn growth(&self) -> f64 {
        let (dofs, n) = (self.dofs, self.b.len());
        let k = &self.k;
        let mu = (0..dofs)
            .map(|a| {
                k[a * n + a]
                    - (0..dofs)
                        .filter(|&b| b != a)
                        .map(|b| k[a * n + b].abs())
                        .sum::<f64>()
            })
            .fold(f64::INFINITY, f64::min);
        let j = (dofs..n).map(|r| (0..dofs).map(|a| k[r * n + a] * k[r * n + a]).sum::<f64>());
        let j = nan_max(j);
        1.0 + j / (mu * norm(k, n))
    }

    /// $\lVert Kz - b\rVert_\infty / (\lVert K\rVert_\infty \lVert z\rVert_\infty +
    /// \lVert b\rVert_\infty)$ in f64 with $K$ as stored in precision `T`.
    fn backward_error<T: Real>(&self, kkt: &Kkt<T>, z: &[T], b: &[T]) -> f64 {
        let n = b.len();
        debug_assert_eq!(kkt.pattern().order(), n);
        let stored: Vec<f64> = self.k.iter().map(|&v| T::from_f64(v).to_f64()).collect();
        let residual = (0..n).map(|r| {
            let kz: f64 = (0..n).map(|c| stored[r * n + c] * z[c].to_f64()).sum();
            (b[r].to_f64() - kz).abs()
        });
        let residual = nan_max(residual);
        let k_norm = norm(&stored, n);
        let z_norm = nan_max(z.iter().map(|v| v.to_f64().abs()));
        let b_norm = nan_max(b.iter().map(|v| v.to_f64().abs()));
        let denominator = k_norm * z_norm + b_norm;
        if denominator == 0.0 {
            residual
        } else {
            residual / denominator
        }
    }
}

/// The factor of `kkt` refuses an analysis of another pattern with a typed error.
fn mismatch_is_refused<T: Real>(kkt: &Kkt<T>) {
    let other = dense_kkt::<T>(1, &[1.0], Ordering::Natural).expect("a 1x1 matrix");
    if other.symbolic().fingerprint() == kkt.symbolic().fingerprint() {
        return;
    }
    let mut x = vec![T::ZERO; other.pattern().order()];
    let refused = kkt.factor().solve_permuted(other.symbolic(), &mut x);
    assert!(
        matches!(refused, Err(SolverError::SymbolicMismatch { .. })),
        "a foreign analysis was accepted: {refused:?}"
    );
}

/// The condition number $\kappa_\infty = \lVert K\rVert_\infty \lVert K^{-1}\rVert_\infty$
/// of the dense row-major `k`, the inverse by Gaussian elimination with partial pivoting in
/// f64; infinite when a pivot is zero or the inverse is not finite.
#[must_use]
pub fn condition(k: &[f64]) -> f64 {
    let n = (k.len() as f64).sqrt() as usize;
    let mut a = k.to_vec();
    // The inverse, built from the identity alongside.
    let mut inv: Vec<f64> = (0..n * n)
        .map(|i| f64::from(u8::from(i / n == i % n)))
        .collect();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))
            .unwrap_or(c);
        for j in 0..n {
            a.swap(c * n + j, p * n + j);
            inv.swap(c * n + j, p * n + j);
        }
        let pivot = a[c * n + c];
        if pivot == 0.0 {
            return f64::INFINITY;
        }
        for i in 0..n {
            if i != c {
                let f = a[i * n + c] / pivot;
                for j in 0..n {
                    a[i * n + j] -= f * a[c * n + j];
                    inv[i * n + j] -= f * inv[c * n + j];
                }
            }
        }
        for j in 0..n {
            a[c * n + j] /= pivot;
            inv[c * n + j] /= pivot;
        }
    }
    let kappa = norm(k, n) * norm(&inv, n);
    if kappa.is_finite() {
        kappa
    } else {
        f64::INFINITY
    }
}

/// $\lVert K\rVert_\infty$ of the dense row-major `k` of order `n`.
fn norm(k: &[f64], n: usize) -> f64 {
    nan_max((0..n).map(|r| (0..n).map(|c| k[r * n + c].abs()).sum()))
}
