//! The conical page curl (seed 001): isometry, apex and limit parameters, batched map against
//! the per-point map, precision agreement and non-finite input.

use core::f64::consts::{FRAC_PI_2, PI};
use folio_kernels::cone::{ConeCurl, THETA_MIN};
use folio_tests::Rng;
use glam::DVec3;

/// Worst relative change of neighbour distances on a grid of spacing `h` over the page
/// [0, 12] x [0, 16] (seed 000's page size), for edges farther than 1 from the apex (the
/// cone is self-similar about its apex: no sampling resolves it better than another).
fn worst_stretch(curl: &ConeCurl<f64>, h: f64) -> f64 {
    let apex = DVec3::new(0.0, curl.apex(), 0.0);
    let (nx, ny) = ((12.0 / h).round() as usize, (16.0 / h).round() as usize);
    let p = |i: usize, j: usize| curl.map_point(i as f64 * h, j as f64 * h);
    let mut worst: f64 = 0.0;
    for i in 0..=nx {
        for j in 0..=ny {
            for (di, dj) in [(1, 0), (0, 1)] {
                let near_apex = |a: usize, b: usize| {
                    (DVec3::new(a as f64 * h, b as f64 * h, 0.0) - apex).length() < 1.0
                };
                if i + di <= nx && j + dj <= ny && !near_apex(i, j) && !near_apex(i + di, j + dj) {
                    let d = (p(i + di, j + dj) - p(i, j)).length();
                    worst = folio_tests::worst(worst, (d - h).abs() / h);
                }
            }
        }
    }
    worst
}

#[test]
fn cone_map_is_an_isometry_to_second_order() {
    // Apex below the page (the seed's use), inside its height, and a tight cone.
    for (theta, apex, rho) in [(0.7, -6.0, 0.4), (1.2, 4.0, 2.0), (0.3, -20.0, 3.0)] {
        let curl = ConeCurl::new(theta, apex, rho);
        let e: Vec<f64> = [0.2, 0.1, 0.05]
            .iter()
            .map(|&h| worst_stretch(&curl, h))
            .collect();
        println!("theta {theta} apex {apex}: worst relative edge change {e:?}");
        for w in e.windows(2) {
            let ratio = w[0] / w[1];
            assert!(
                (3.0..=5.0).contains(&ratio),
                "edge error ratio {ratio}, expected ~4"
            );
        }
    }
}

#[test]
fn distance_to_the_apex_is_preserved_exactly() {
    let mut rng = Rng::new(30);
    for _ in 0..200 {
        let curl = ConeCurl::new(
            rng.uniform(0.0, 1.6),
            rng.uniform(-10.0, 10.0),
            rng.uniform(-4.0, 4.0),
        );
        let (x, y) = (rng.uniform(0.0, 12.0), rng.uniform(-16.0, 16.0));
        let radius = (x * x + (y - curl.apex()).powi(2)).sqrt();
        let d = (curl.map_point(x, y) - DVec3::new(0.0, curl.apex(), 0.0)).length();
        assert!(
            (d - radius).abs() <= 1e-12 * (1.0 + radius),
            "{d} vs {radius}"
        );
    }
}

#[test]
fn flat_cone_is_the_turned_page() {
    let curl = ConeCurl::new(FRAC_PI_2, -3.0, 0.8);
    let mut rng = Rng::new(31);
    for _ in 0..100 {
        let (x, y) = (rng.uniform(0.0, 12.0), rng.uniform(-5.0, 16.0));
        let expected = DVec3::new(x * 0.8f64.cos(), y, x * 0.8f64.sin());
        assert!((curl.map_point(x, y) - expected).length() <= 1e-12 * (1.0 + x.abs() + y.abs()));
    }
}

#[test]
fn apex_and_limit_parameters_give_finite_output() {
    let thetas = [
        0.0,
        1e-300,
        THETA_MIN / 10.0,
        THETA_MIN,
        1e-3,
        FRAC_PI_2,
        2.0,
        -1.0,
    ];
    for theta in thetas {
        for apex in [-1e6, -5.0, 0.0, 7.5] {
            let curl = ConeCurl::new(theta, apex, 1.0);
            // The apex itself maps to the apex.
            let a = curl.map_point(0.0, apex);
            assert!((a - DVec3::new(0.0, apex, 0.0)).length() <= 1e-9 * (1.0 + apex.abs()));
            for (x, y) in [
                (0.0, apex),
                (0.0, apex - 3.0),
                (-0.0, apex - 3.0),
                (12.0, 16.0),
                (1e-12, apex),
            ] {
                let p = curl.map_point(x, y);
                let j = curl.jacobian(x, y);
                assert!(p.is_finite(), "theta {theta} apex {apex} ({x},{y}) -> {p}");
                assert!(
                    j.iter().all(|c| c.is_finite()),
                    "Jacobian not finite: {j:?}"
                );
            }
        }
    }
}

#[test]
fn thin_cone_winds_onto_the_ray_and_the_clamp_is_continuous() {
    let (apex, rho) = (-4.0, 0.6);
    let at_min = ConeCurl::new(THETA_MIN, apex, rho);
    let below = ConeCurl::new(0.0, apex, rho);
    assert_eq!(at_min.theta(), below.theta());
    for (x, y) in [(3.0, 2.0), (11.0, 15.0), (0.5, -3.9)] {
        let p = below.map_point(x, y);
        assert_eq!(p, at_min.map_point(x, y));
        // Distance from the tangent ruling x = z = 0 at most 2 R sin(theta_min).
        let radius = (x * x + (y - apex) * (y - apex)).sqrt();
        let off_ray = (p.x * p.x + p.z * p.z).sqrt();
        let bound = 2.0 * radius * THETA_MIN.sin() * (1.0 + 1e-9);
        assert!(off_ray <= bound, "{off_ray} > {bound}");
        // Clamped theta has no theta derivative.
        assert_eq!(below.jacobian(x, y)[0], DVec3::ZERO);
    }
}

#[test]
fn negative_zero_x_maps_like_positive_zero() {
    let curl = ConeCurl::new(0.5, 2.0, 0.3);
    assert_eq!(curl.map_point(0.0, -3.0), curl.map_point(-0.0, -3.0));
    let (mut ox, mut oy, mut oz) = ([0.0f64; 2], [0.0f64; 2], [0.0f64; 2]);
    let _ = curl.map_batch(&mut ox, &mut oy, &mut oz, &[0.0, -0.0], &[-3.0, -3.0]);
    assert!((ox[0] - ox[1]).abs() + (oz[0] - oz[1]).abs() <= 1e-12);
}

fn batch_gap<T: folio_kernels::Real>(theta: f64, apex: f64, rho: f64, pts: &[(f64, f64)]) -> f64 {
    let curl = ConeCurl::<T>::new(T::from_f64(theta), T::from_f64(apex), T::from_f64(rho));
    let reference = ConeCurl::<f64>::new(theta, apex, rho);
    let xs: Vec<T> = pts.iter().map(|p| T::from_f64(p.0)).collect();
    let ys: Vec<T> = pts.iter().map(|p| T::from_f64(p.1)).collect();
    let (mut ox, mut oy, mut oz) = (
        vec![T::ZERO; pts.len()],
        vec![T::ZERO; pts.len()],
        vec![T::ZERO; pts.len()],
    );
    assert_eq!(
        curl.map_batch(&mut ox, &mut oy, &mut oz, &xs, &ys),
        pts.len()
    );
    let mut worst: f64 = 0.0;
    for (k, &(x, y)) in pts.iter().enumerate() {
        // Against the f64 per-point map evaluated at the same (rounded) inputs.
        let r = reference.map_point(xs[k].to_f64(), ys[k].to_f64());
        let got = DVec3::new(ox[k].to_f64(), oy[k].to_f64(), oz[k].to_f64());
        worst = folio_tests::worst(worst, (got - r).length() / (1.0 + x.abs() + y.abs()));
    }
    worst
}

#[test]
fn batched_map_matches_the_per_point_map() {
    let mut rng = Rng::new(32);
    let pts: Vec<(f64, f64)> = (0..1001)
        .map(|_| (rng.uniform(0.0, 12.0), rng.uniform(-4.0, 16.0)))
        .collect();
    let (mut w64, mut w32): (f64, f64) = (0.0, 0.0);
    for &(theta, apex, rho) in &[
        (0.7, -6.0, 0.4),
        (0.05, -2.0, 1.0),
        (FRAC_PI_2, 0.0, PI),
        (1e-4, -1.0, 0.0),
    ] {
        w64 = folio_tests::worst(w64, batch_gap::<f64>(theta, apex, rho, &pts));
        w32 = folio_tests::worst(w32, batch_gap::<f32>(theta, apex, rho, &pts));
    }
    println!("batched vs per-point map: f64 {w64:.2e}, f32 {w32:.2e} (relative to page scale)");
    assert!(w64 <= 1e-12, "f64 batch gap {w64:e}");
    assert!(w32 <= 1e-4, "f32 batch gap {w32:e}");
}

#[test]
fn batch_processes_the_shortest_slice() {
    let curl = ConeCurl::new(0.7, -3.0, 0.2);
    let (mut ox, mut oy, mut oz) = ([9.0; 5], [9.0; 4], [9.0; 5]);
    let n = curl.map_batch(&mut ox, &mut oy, &mut oz, &[1.0; 5], &[2.0; 3]);
    assert_eq!(n, 3);
    assert_eq!(ox[3], 9.0, "entries past n are untouched");
}

#[test]
fn f32_map_and_jacobian_agree_with_f64() {
    let mut rng = Rng::new(33);
    let (mut map_gap, mut jac_gap): (f64, f64) = (0.0, 0.0);
    for _ in 0..500 {
        let (t, a, r) = (
            rng.uniform(0.2, 1.5),
            rng.uniform(-10.0, 0.0),
            rng.uniform(-3.0, 3.0),
        );
        let (x, y) = (rng.uniform(0.0, 12.0), rng.uniform(0.0, 16.0));
        let c64 = ConeCurl::new(t, a, r);
        let c32 = ConeCurl::new(t as f32, a as f32, r as f32);
        let p = c32.map_point(x as f32, y as f32);
        let q = c64.map_point(x, y);
        map_gap = folio_tests::worst(
            map_gap,
            (DVec3::new(p.x.into(), p.y.into(), p.z.into()) - q).length() / 16.0,
        );
        let (j32, j64) = (c32.jacobian(x as f32, y as f32), c64.jacobian(x, y));
        for (u, v) in j32.iter().zip(&j64) {
            let u = DVec3::new(u.x.into(), u.y.into(), u.z.into());
            jac_gap = folio_tests::worst(jac_gap, (u - *v).length() / v.length().max(1.0));
        }
    }
    println!("f32 vs f64: map {map_gap:.2e}, Jacobian {jac_gap:.2e}");
    assert!(map_gap <= 1e-5 && jac_gap <= 1e-4);
}

#[test]
fn non_finite_input_gives_nan_never_a_panic() {
    assert!(
        ConeCurl::new(f64::NAN, 0.0, 0.0)
            .map_point(1.0, 1.0)
            .is_nan()
    );
    assert!(
        ConeCurl::new(0.5, f64::NAN, 0.0)
            .map_point(1.0, 1.0)
            .is_nan()
    );
    assert!(
        ConeCurl::new(0.5, 0.0, f64::INFINITY)
            .map_point(1.0, 1.0)
            .is_nan()
    );
    let curl = ConeCurl::new(0.5, -1.0, 0.0);
    assert!(curl.map_point(f64::NAN, 1.0).is_nan());
    assert!(!curl.map_point(1.0, f64::INFINITY).is_finite());
    assert!(curl.jacobian(f64::NAN, 1.0).iter().any(|c| c.is_nan()));
    let (mut ox, mut oy, mut oz) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    let _ = curl.map_batch(&mut ox, &mut oy, &mut oz, &[f64::NAN, 1.0], &[1.0, 1.0]);
    assert!(ox[0].is_nan() && ox[1].is_finite());
}
