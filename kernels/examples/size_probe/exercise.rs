//! Calls every public kernel once in precision `T` with opaque inputs, so the linker keeps
//! exactly the code a firmware using all of them would carry.

use core::hint::black_box;

use folio_kernels::binding::Binding;
use folio_kernels::cone::ConeCurl;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::gravity::Gravity;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::positional::Positional;
use folio_kernels::real::Vec3Ops;
use folio_kernels::spring::Spring;
use folio_kernels::{Constraint, Potential, Real, curve_laplacian, dog_laplacian};

fn potential<T: Real, P: Potential<T, N>, const N: usize>(p: &P, x: &[T::Vec3; N]) {
    black_box((p.value(x), p.gradient(x), p.hessian(x)));
}

fn constraint<T: Real, C: Constraint<T, R, N>, const R: usize, const N: usize>(
    c: &C,
    x: &[T::Vec3; N],
) {
    black_box((c.value(x), c.jacobian(x), c.hessian(x, &[T::ONE; R])));
}

/// Exercises every kernel in precision `T`.
pub fn exercise<T: Real>() {
    let s = black_box(T::ONE);
    let p = [0, 1, 2, 3, 4].map(|k| black_box(T::Vec3::new(s, s * T::from_f64(k as f64), s)));
    let [p0, p1, p2, p3, p4] = p;
    constraint(&DogInnerStar::<T>::new(), &p);
    constraint(&DogBoundaryStar::<T>::new(), &[p0, p1, p2, p3]);
    let remedy = FlatStarRemedy::<T>::default();
    black_box((
        remedy.inner_jacobian(&p),
        remedy.boundary_jacobian(&[p0, p1, p2, p3]),
    ));
    if let Ok(t) = dog_laplacian::inner([s; 4]) {
        potential(&t, &p);
    }
    if let Ok(t) = dog_laplacian::boundary([s; 2]) {
        potential(&t, &[p0, p1, p2]);
    }
    if let Ok(t) = curve_laplacian::new([s; 2]) {
        potential(&t, &[p0, p1, p2]);
    }
    if let Ok(t) = Iso2d::new(s) {
        constraint(&t, &[p0, p1]);
    }
    if let Ok(t) = Binding::new(s) {
        constraint(&t, &[p0, p1, p2]);
    }
    if let Ok(t) = Fix::<T>::new(p4) {
        constraint(&t, &[p0, p1]);
    }
    potential(&Glue::<T>::new(), &[p0, p1, p2, p3]);
    if let Ok(t) = Gravity::new(s, s) {
        potential(&t, &[p0]);
    }
    if let Ok(t) = Iso3d::new(s) {
        potential(&t, &[p0, p1]);
        black_box(t.hessian_projected(&[p0, p1]));
    }
    if let Ok(t) = Positional::<T>::new(p3) {
        potential(&t, &[p0]);
    }
    if let Ok(t) = Spring::new(s, s) {
        potential(&t, &[p0, p1]);
        black_box((
            t.force_jacobian(&[p0, p1]),
            t.damping_force(&[p0, p1], &[p2, p3], s),
        ));
    }
    let curl = ConeCurl::new(s, s, s);
    black_box((curl.map_point(s, s), curl.jacobian(s, s)));
    let mut buf = [[T::ZERO; 16]; 3];
    let xs = black_box([s; 16]);
    let [bx, by, bz] = &mut buf;
    black_box(curl.map_batch(bx, by, bz, &xs, &xs));
    black_box(buf);
}
