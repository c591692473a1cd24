//! The flat-star remedy of `folio_kernels::dog`: on a flat page the exact DOG Jacobian loses
//! row rank (every row lies in the page plane); the remedied Jacobian has full row rank and
//! differs from the exact one by O(offset); on curved stars the remedy is the identity.

use folio_kernels::Constraint;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_tests::{GridStar, Rng, grid_stars};
use glam::DVec3;
use nalgebra::DMatrix;

/// The seed's default page: 11 x 8 quads (12 x 9 vertices), width 12.
const N: usize = 12;
const M: usize = 9;

/// Global DOG Jacobian of the grid `x`, exact or remedied.
fn dog_jacobian(x: &[DVec3], remedy: Option<&FlatStarRemedy<f64>>) -> DMatrix<f64> {
    let stars = grid_stars(N, M);
    let mut rows: Vec<Vec<(usize, DVec3)>> = Vec::new();
    for star in &stars {
        match *star {
            GridStar::Inner(ix) => {
                let local = ix.map(|k| x[k]);
                let jac = match remedy {
                    Some(r) => r.inner_jacobian(&local),
                    None => DogInnerStar::<f64>::new().jacobian(&local),
                };
                rows.extend(
                    jac.iter()
                        .map(|row| ix.iter().copied().zip(row.iter().copied()).collect()),
                );
            }
            GridStar::Boundary(ix) => {
                let local = ix.map(|k| x[k]);
                let jac = match remedy {
                    Some(r) => r.boundary_jacobian(&local),
                    None => DogBoundaryStar::<f64>::new().jacobian(&local),
                };
                rows.push(ix.iter().copied().zip(jac[0].iter().copied()).collect());
            }
        }
    }
    let mut j = DMatrix::zeros(rows.len(), 3 * x.len());
    for (r, entries) in rows.iter().enumerate() {
        for &(node, g) in entries {
            for a in 0..3 {
                j[(r, 3 * node + a)] += g[a];
            }
        }
    }
    j
}

fn rank_and_conditioning(j: &DMatrix<f64>) -> (usize, f64) {
    let sv = j.singular_values();
    let max = sv.max();
    let rank = sv.iter().filter(|&&s| s > 1e-10 * max).count();
    (rank, sv.min() / max)
}

fn flat_page(rng: &mut Rng) -> Vec<DVec3> {
    let (q, t) = (rng.rotation(), rng.vec(5.0));
    let h = 12.0 / 11.0;
    (0..N * M)
        .map(|k| q * DVec3::new((k % N) as f64 * h, (k / N) as f64 * h, 0.0) + t)
        .collect()
}

#[test]
fn remedy_restores_full_row_rank_on_a_flat_page() {
    let mut rng = Rng::new(61);
    let remedy = FlatStarRemedy::<f64>::default();
    for _ in 0..3 {
        let x = flat_page(&mut rng);
        let exact = dog_jacobian(&x, None);
        let fixed = dog_jacobian(&x, Some(&remedy));
        let rows = exact.nrows();
        let (rank_exact, _) = rank_and_conditioning(&exact);
        let (rank_fixed, cond) = rank_and_conditioning(&fixed);
        println!(
            "flat 12x9 page: {rows} DOG rows, exact rank {rank_exact}, remedied rank {rank_fixed}, sigma_min/sigma_max {cond:.2e}"
        );
        assert!(
            rank_exact < rows,
            "the exact flat Jacobian should be rank deficient"
        );
        assert_eq!(rank_fixed, rows, "remedy must give full row rank");
        let change = (&fixed - &exact).abs().max();
        assert!(
            change <= 10.0 * remedy.relative_offset,
            "remedy changed J by {change:e}"
        );
    }
}

#[test]
fn remedy_leaves_curved_stars_exact() {
    // A cylinder of radius 3 bending the grid's x lines: every inner star is curved, and so
    // is every boundary star whose through-curve is an x line. A boundary star whose
    // through-curve is a straight y line is planar by construction (two of its three edges
    // are collinear) and is remedied: skip those.
    let remedy = FlatStarRemedy::<f64>::default();
    let h = 12.0 / 11.0;
    let x: Vec<DVec3> = (0..N * M)
        .map(|k| {
            let (u, v) = ((k % N) as f64 * h, (k / N) as f64 * h);
            DVec3::new(3.0 * (u / 3.0).sin(), v, 3.0 * (1.0 - (u / 3.0).cos()))
        })
        .collect();
    let (mut inner, mut boundary) = (0, 0);
    for star in grid_stars(N, M) {
        match star {
            GridStar::Inner(ix) => {
                let local = ix.map(|k| x[k]);
                assert_eq!(
                    remedy.inner_jacobian(&local),
                    DogInnerStar::<f64>::new().jacobian(&local)
                );
                inner += 1;
            }
            GridStar::Boundary(ix) => {
                let straight_through = ix[1] % N == ix[3] % N;
                if !straight_through {
                    let local = ix.map(|k| x[k]);
                    assert_eq!(
                        remedy.boundary_jacobian(&local),
                        DogBoundaryStar::<f64>::new().jacobian(&local)
                    );
                    boundary += 1;
                }
            }
        }
    }
    assert_eq!((inner, boundary), (70, 20));
}

#[test]
fn remedy_is_continuous_across_the_flatness_tolerance() {
    // Bend a single star gradually through the tolerance: the Jacobian moves smoothly.
    let remedy = FlatStarRemedy::<f64>::default();
    let jac = |bend: f64| {
        let x = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, bend),
            DVec3::Y,
            DVec3::new(-1.0, 0.0, bend),
            DVec3::NEG_Y,
        ];
        remedy.inner_jacobian(&x)
    };
    let mut prev = jac(0.0);
    let steps = 2000;
    for k in 1..=steps {
        let next = jac(0.02 * k as f64 / steps as f64);
        let jump = prev
            .iter()
            .zip(&next)
            .flat_map(|(a, b)| a.iter().zip(b))
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, folio_tests::worst);
        assert!(jump <= 1e-4, "Jacobian jumped by {jump:e} at step {k}");
        prev = next;
    }
}
