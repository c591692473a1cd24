//! Analytic DOGs (DESIGN.md, testing habits): generalized cylinders whose rulings follow one
//! grid direction are exact DOGs; smooth developables sampled from a square grid on their
//! development (a cone through the cone-curl kernel, a cylinder at an angle to the grid) are
//! DOGs to second order (|phi| falls ~4x per halving of the spacing); a sphere sampled from a
//! square grid through its exponential map is not a DOG at any spacing.

use folio_kernels::Constraint;
use folio_kernels::cone::ConeCurl;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar};
use folio_tests::{GridStar, Rng, grid_stars};
use glam::DVec3;

/// Largest |phi| over every inner and 3-neighbour boundary star of the `n x m` vertex grid
/// `p(i, j)`.
fn max_dog_residual(n: usize, m: usize, p: impl Fn(usize, usize) -> DVec3) -> f64 {
    let at = |k: usize| p(k % n, k / n);
    let mut worst: f64 = 0.0;
    for star in grid_stars(n, m) {
        let phi = match star {
            GridStar::Inner(ix) => DogInnerStar::<f64>::new().value(&ix.map(at)).to_vec(),
            GridStar::Boundary(ix) => DogBoundaryStar::<f64>::new().value(&ix.map(at)).to_vec(),
        };
        worst = phi
            .iter()
            .fold(worst, |w, v| folio_tests::worst(w, v.abs()));
    }
    worst
}

#[test]
fn generalized_cylinder_along_the_grid_is_an_exact_dog() {
    let mut rng = Rng::new(21);
    for _ in 0..20 {
        // Cross-section: an equal-edge polyline in the XZ plane with random turning angles.
        let (n, m) = (12, 9);
        let edge = rng.uniform(0.3, 1.5);
        let step = rng.uniform(0.3, 1.5);
        let mut section = vec![DVec3::ZERO];
        let mut heading: f64 = rng.uniform(-1.0, 1.0);
        for _ in 1..n {
            heading += rng.uniform(-0.6, 0.6);
            let last = *section.last().unwrap();
            section.push(last + DVec3::new(heading.cos(), 0.0, heading.sin()) * edge);
        }
        // Extruded in equal steps along Y, then placed rigidly anywhere.
        let q = rng.rotation();
        let t = rng.vec(5.0);
        let phi = max_dog_residual(n, m, |i, j| {
            q * (section[i] + DVec3::Y * (step * j as f64)) + t
        });
        assert!(phi <= 1e-12, "cylinder |phi| = {phi:e}");
    }
}

/// max |phi| of a surface sampled at spacing `h` over the development patch [0.5, 2.5]^2.
fn residual_at(h: f64, surface: &impl Fn(f64, f64) -> DVec3) -> f64 {
    let n = (2.0 / h).round() as usize + 1;
    max_dog_residual(n, n, |i, j| surface(0.5 + i as f64 * h, 0.5 + j as f64 * h))
}

fn residuals(surface: impl Fn(f64, f64) -> DVec3) -> Vec<f64> {
    [0.2, 0.1, 0.05, 0.025]
        .iter()
        .map(|&h| residual_at(h, &surface))
        .collect()
}

fn assert_second_order(name: &str, r: &[f64]) {
    println!("{name}: max|phi| at h = 0.2, 0.1, 0.05, 0.025: {r:?}");
    for w in r.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (3.0..=5.0).contains(&ratio),
            "{name}: ratio {ratio} per halving, expected ~4"
        );
    }
}

#[test]
fn cone_from_its_development_is_a_dog_to_second_order() {
    for (theta, apex, rho) in [(0.6, -5.0, 0.3), (0.9, -2.0, 1.2), (0.4, -8.0, 2.5)] {
        let cone = ConeCurl::new(theta, apex, rho);
        assert_second_order("cone", &residuals(|x, y| cone.map_point(x, y)));
    }
}

#[test]
fn cylinder_at_an_angle_to_the_grid_is_a_dog_to_second_order() {
    // Development coordinates rotated by 0.5 rad against the rulings, wrapped on radius 1.5.
    let (c, s, radius) = (0.5f64.cos(), 0.5f64.sin(), 1.5);
    let r = residuals(|x, y| {
        let (u, v) = (c * x - s * y, s * x + c * y);
        DVec3::new(
            radius * (u / radius).sin(),
            v,
            radius * (1.0 - (u / radius).cos()),
        )
    });
    assert_second_order("oblique cylinder", &r);
}

#[test]
fn sphere_is_not_a_dog_at_any_spacing() {
    // A square grid on the tangent plane at the north pole, wrapped by the exponential map.
    let radius = 2.0;
    let r = residuals(|x, y| {
        let (u, v) = (x - 1.5, y - 1.5);
        let d = (u * u + v * v).sqrt();
        let (az, t) = (v.atan2(u), d / radius);
        DVec3::new(
            radius * t.sin() * az.cos(),
            radius * t.sin() * az.sin(),
            radius * t.cos(),
        )
    });
    println!("sphere: max|phi| at h = 0.2, 0.1, 0.05, 0.025: {r:?}");
    for (k, &phi) in r.iter().enumerate() {
        assert!(phi >= 1e-2, "sphere |phi| {phi:e} too small");
        if k > 0 {
            assert!(phi >= 0.5 * r[k - 1], "sphere residual fell: {r:?}");
        }
    }
}
