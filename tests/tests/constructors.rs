//! Term constructors validate their parameters and name the offending one.

use folio_kernels::KernelError;
use folio_kernels::binding::Binding;
use folio_kernels::contact::ContactPlane;
use folio_kernels::fix::Fix;
use folio_kernels::gravity::Gravity;
use folio_kernels::hinge::Hinge;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::membrane::Membrane;
use folio_kernels::positional::Positional;
use folio_kernels::spring::Spring;
use folio_kernels::{curve_laplacian, dog_laplacian};
use glam::DVec3;

#[test]
fn bad_rest_lengths_name_the_edge() {
    assert_eq!(
        dog_laplacian::inner([1.0, 1.0, 0.0, 1.0]).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 2 }
    );
    assert_eq!(
        dog_laplacian::inner([1.0, -1.0, 1.0, 1.0]).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 1 }
    );
    assert_eq!(
        dog_laplacian::boundary([f64::NAN, 1.0]).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 0 }
    );
    assert_eq!(
        curve_laplacian::new([1.0, f64::INFINITY]).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 1 }
    );
    let coincident = [DVec3::ZERO, DVec3::ZERO, DVec3::X];
    assert_eq!(
        curve_laplacian::from_rest::<f64>(&coincident).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 0 }
    );
    assert!(
        dog_laplacian::inner([1e-200_f64, 1.0, 1.0, 1.0]).is_err(),
        "below the length floor"
    );
    assert_eq!(
        dog_laplacian::inner_area([1.0, 1.0, 1.0, 0.0], 1.0).unwrap_err(),
        KernelError::NonPositiveRestLength { index: 3 }
    );
    assert_eq!(
        dog_laplacian::boundary_area([1.0, 1.0], 0.0).unwrap_err(),
        KernelError::OutOfRange { name: "area" }
    );
    assert_eq!(
        dog_laplacian::inner_area([1.0; 4], f64::NAN).unwrap_err(),
        KernelError::NonFiniteParameter { name: "area" }
    );
}

#[test]
fn bad_parameters_are_typed_errors() {
    assert_eq!(
        Iso2d::new(-1.0).unwrap_err(),
        KernelError::OutOfRange {
            name: "rest_length"
        }
    );
    assert_eq!(
        Iso3d::new(f64::NAN).unwrap_err(),
        KernelError::NonFiniteParameter {
            name: "rest_length"
        }
    );
    assert_eq!(
        Binding::new(1.5).unwrap_err(),
        KernelError::OutOfRange { name: "q" }
    );
    assert_eq!(
        Binding::new(f32::NAN).unwrap_err(),
        KernelError::NonFiniteParameter { name: "q" }
    );
    assert_eq!(
        Gravity::new(9.81, -1.0).unwrap_err(),
        KernelError::OutOfRange { name: "mass" }
    );
    assert_eq!(
        Gravity::new(f64::INFINITY, 1.0).unwrap_err(),
        KernelError::NonFiniteParameter { name: "g" }
    );
    assert_eq!(
        Spring::new(1.0, -2.0).unwrap_err(),
        KernelError::OutOfRange { name: "stiffness" }
    );
    assert_eq!(
        Fix::<f64>::new(DVec3::new(0.0, f64::NAN, 0.0)).unwrap_err(),
        KernelError::NonFiniteParameter { name: "target" }
    );
    assert_eq!(
        Positional::<f64>::new(DVec3::splat(f64::MAX)).map(|p| p.target),
        Ok(DVec3::splat(f64::MAX))
    );
    assert_eq!(
        ContactPlane::<f64>::new(DVec3::ZERO, DVec3::ZERO, 0.0, 1.0).unwrap_err(),
        KernelError::OutOfRange { name: "normal" }
    );
    assert_eq!(
        ContactPlane::<f64>::new(DVec3::ZERO, DVec3::Y, f64::NAN, 1.0).unwrap_err(),
        KernelError::NonFiniteParameter { name: "clearance" }
    );
    assert_eq!(
        ContactPlane::<f64>::new(DVec3::ZERO, DVec3::new(0.0, 3.0, 4.0), 0.1, 1.0)
            .map(|p| p.normal),
        Ok(DVec3::new(0.0, 0.6, 0.8))
    );
    assert_eq!(
        ContactPlane::<f64>::new(DVec3::ZERO, DVec3::Y, 0.1, -1.0).unwrap_err(),
        KernelError::OutOfRange { name: "stiffness" }
    );
    // Messages name the problem.
    assert_eq!(
        KernelError::OutOfRange { name: "q" }.to_string(),
        "parameter `q` is out of its range"
    );
}

const TRIANGLE: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.9]];
/// Edge (u0, u1) along X, u2 above it, u3 below it.
const HINGE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [0.3, 0.8], [0.6, -0.7]];

#[test]
fn membrane_refuses_bad_patterns_and_parameters() {
    let area = |index| KernelError::NonPositiveRestArea { index };
    assert!(Membrane::new(TRIANGLE, 1.0, 0.3).is_ok());
    assert!(Membrane::new(TRIANGLE.map(|p| p.map(|c| c as f32)), 1.0, 0.0).is_ok());
    // Clockwise, collinear, coincident, sliver, below the length floor.
    let [a, b, c] = TRIANGLE;
    assert_eq!(Membrane::new([a, c, b], 1.0, 0.3).unwrap_err(), area(0));
    let collinear = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]];
    assert_eq!(Membrane::new(collinear, 1.0, 0.3).unwrap_err(), area(0));
    assert_eq!(Membrane::new([a, a, a], 1.0, 0.3).unwrap_err(), area(0));
    let sliver = [[0.0, 0.0], [1.0, 0.0], [0.5, 1e-9]];
    assert_eq!(Membrane::new(sliver, 1.0, 0.3).unwrap_err(), area(0));
    assert!(Membrane::new([[0.0, 0.0], [1.0, 0.0], [0.5, 1e-3]], 1.0, 0.3).is_ok());
    // f32's threshold is sqrt(f32::EPSILON) ~ 3.5e-4 relative.
    let sliver32 = [[0.0f32, 0.0], [1.0, 0.0], [0.5, 1e-4]];
    assert_eq!(Membrane::new(sliver32, 1.0, 0.3).unwrap_err(), area(0));
    let tiny = TRIANGLE.map(|p| p.map(|c| c * 1e-160));
    assert_eq!(Membrane::new(tiny, 1.0, 0.3).unwrap_err(), area(0));
    let overflowing = TRIANGLE.map(|p| p.map(|c| c * 1e300));
    assert_eq!(Membrane::new(overflowing, 1.0, 0.3).unwrap_err(), area(0));
    // Non-finite input names its field.
    let mut nan = TRIANGLE;
    nan[2][1] = f64::NAN;
    assert_eq!(
        Membrane::new(nan, 1.0, 0.3).unwrap_err(),
        KernelError::NonFiniteParameter { name: "pattern" }
    );
    assert_eq!(
        Membrane::new(TRIANGLE, f64::INFINITY, 0.3).unwrap_err(),
        KernelError::NonFiniteParameter {
            name: "stretch_modulus"
        }
    );
    assert_eq!(
        Membrane::new(TRIANGLE, 1.0, f64::NAN).unwrap_err(),
        KernelError::NonFiniteParameter { name: "poisson" }
    );
    // Ranges: Y > 0, 0 <= nu < 1/2.
    for y in [0.0, -1.0] {
        assert_eq!(
            Membrane::new(TRIANGLE, y, 0.3).unwrap_err(),
            KernelError::OutOfRange {
                name: "stretch_modulus"
            }
        );
    }
    for nu in [-0.1, 0.5, 0.7] {
        assert_eq!(
            Membrane::new(TRIANGLE, 1.0, nu).unwrap_err(),
            KernelError::OutOfRange { name: "poisson" }
        );
    }
    // Stored constants: rest area, plane-stress Lame parameters, D_m^{-1}.
    let m = Membrane::new(TRIANGLE, 2.6, 0.3).unwrap();
    assert!((m.rest_area - 0.45).abs() < 1e-15);
    assert!((m.mu - 1.0).abs() < 1e-15);
    assert!((m.lambda - 2.6 * 0.3 / 0.91).abs() < 1e-15);
    let dm = [[1.0, 0.2], [0.0, 0.9]];
    for (r, row) in dm.iter().enumerate() {
        for c in 0..2 {
            let prod: f64 = (0..2).map(|k| row[k] * m.dm_inv[k][c]).sum();
            let id = if r == c { 1.0 } else { 0.0 };
            assert!(
                (prod - id).abs() < 1e-15,
                "D_m D_m^-1 = {prod} at ({r},{c})"
            );
        }
    }
    assert_eq!(
        area(3).to_string(),
        "rest triangle 3 is degenerate or not counter-clockwise in the pattern"
    );
}

#[test]
fn hinge_refuses_bad_patterns() {
    let area = |index| KernelError::NonPositiveRestArea { index };
    assert!(Hinge::new(HINGE).is_ok());
    let [u0, u1, u2, u3] = HINGE;
    // Overlapping triangles: u3 on the same side of the edge as u2.
    let above = [0.7, 0.5];
    assert_eq!(Hinge::new([u0, u1, u2, above]).unwrap_err(), area(1));
    // Mirrored (clockwise throughout): triangle 0 is named; swapping u2 and u3 fixes it.
    assert_eq!(Hinge::new([u0, u1, u3, u2]).unwrap_err(), area(0));
    assert_eq!(Hinge::new([u1, u0, u2, u3]).unwrap_err(), area(0));
    // Degenerate triangles: u2 or u3 on the edge line, zero-length edge.
    assert_eq!(Hinge::new([u0, u1, [2.0, 0.0], u3]).unwrap_err(), area(0));
    assert_eq!(Hinge::new([u0, u1, u2, [0.5, 0.0]]).unwrap_err(), area(1));
    assert_eq!(Hinge::new([u0, u0, u2, u3]).unwrap_err(), area(0));
    assert_eq!(
        Hinge::new([u0, u1, u2, [0.5, -1e-10]]).unwrap_err(),
        area(1)
    );
    let mut nan = HINGE;
    nan[3][0] = f64::NEG_INFINITY;
    assert_eq!(
        Hinge::new(nan).unwrap_err(),
        KernelError::NonFiniteParameter { name: "pattern" }
    );
    // Below the length floor; and at it, so thin that 3/(A_a + A_b) overflows.
    let tiny = HINGE.map(|p| p.map(|c| c * 1e-154));
    assert_eq!(Hinge::new(tiny).unwrap_err(), area(0));
    let (l, h) = (1e-150, 1.6e-158);
    let thin = [[0.0, 0.0], [l, 0.0], [l / 2.0, h], [l / 2.0, -h]];
    // The membrane refuses it too since issue 20: its longest edge is far below sqrt(eps).
    assert_eq!(
        Membrane::new([thin[0], thin[1], thin[2]], 1.0, 0.3).unwrap_err(),
        area(0)
    );
    assert_eq!(Hinge::new(thin).unwrap_err(), area(0));
    // A symmetric diamond: K = (cot a1 + cot b1, cot a0 + cot b0, -cot a0 - cot a1, -cot b0 - cot b1).
    let h = Hinge::new([[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, -1.0]]).unwrap();
    assert_eq!(h.stencil, [2.0, 2.0, -2.0, -2.0]);
    assert_eq!(h.scale, 1.5);
}
