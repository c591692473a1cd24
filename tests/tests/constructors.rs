//! Term constructors validate their parameters and name the offending one.

use folio_kernels::KernelError;
use folio_kernels::binding::Binding;
use folio_kernels::contact::ContactPlane;
use folio_kernels::fix::Fix;
use folio_kernels::gravity::Gravity;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
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
