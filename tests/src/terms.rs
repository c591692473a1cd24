//! Every kernel term of `folio-kernels` built from one set of parameters in either
//! precision, and a uniform evaluation of all of them on a shared 5-node block, so that
//! precision and degenerate-input tests cover every term with one piece of code.

use folio_kernels::binding::Binding;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::dog_laplacian::{DogLaplacianBoundary, DogLaplacianInner};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::gravity::Gravity;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::positional::Positional;
use folio_kernels::real::Vec3Ops;
use folio_kernels::spring::Spring;
use folio_kernels::term::NodeVecs;
use folio_kernels::{Constraint, Potential, Real, curve_laplacian, dog_laplacian};

use crate::{flat_blocks, flat_vecs};

/// All terms in precision `T`.
#[allow(missing_docs)]
pub struct Terms<T: Real> {
    pub dog_inner: DogInnerStar<T>,
    pub dog_boundary: DogBoundaryStar<T>,
    pub remedy: FlatStarRemedy<T>,
    pub lap_inner: DogLaplacianInner<T>,
    pub lap_boundary: DogLaplacianBoundary<T>,
    pub curve: curve_laplacian::CurveLaplacian<T>,
    pub iso2d: Iso2d<T>,
    pub binding: Binding<T>,
    pub fix: Fix<T>,
    pub glue: Glue<T>,
    pub gravity: Gravity<T>,
    pub iso3d: Iso3d<T>,
    pub positional: Positional<T>,
    pub spring: Spring<T>,
}

impl<T: Real> Terms<T> {
    /// Every term, with parameters drawn from `p` (at least 12 values in `[0.5, 1.5]`).
    ///
    /// # Panics
    /// If `p` is too short or holds unusable parameters (a test-setup error).
    #[must_use]
    pub fn new(p: &[f64]) -> Self {
        let t = |k: usize| T::from_f64(p[k]);
        let v = |k: usize| T::Vec3::new(t(k), t(k + 1), t(k + 2));
        Self {
            dog_inner: DogInnerStar::new(),
            dog_boundary: DogBoundaryStar::new(),
            // The same offset in both precisions, so that the two compute one function.
            remedy: FlatStarRemedy {
                relative_offset: T::from_f64(1e-3),
                ..FlatStarRemedy::default()
            },
            lap_inner: dog_laplacian::inner([t(0), t(1), t(2), t(3)]).unwrap(),
            lap_boundary: dog_laplacian::boundary([t(4), t(5)]).unwrap(),
            curve: curve_laplacian::new([t(6), t(7)]).unwrap(),
            iso2d: Iso2d::new(t(8)).unwrap(),
            binding: Binding::new(t(9) - T::HALF).unwrap(),
            fix: Fix::new(v(0)).unwrap(),
            glue: Glue::new(),
            gravity: Gravity::new(t(10) * T::from_f64(9.81), t(11)).unwrap(),
            iso3d: Iso3d::new(t(3)).unwrap(),
            positional: Positional::new(v(5)).unwrap(),
            spring: Spring::new(t(2), t(7)).unwrap(),
        }
    }
}

fn pot<T: Real, P: Potential<T, N>, const N: usize>(p: &P, x: &NodeVecs<T, N>) -> [Vec<f64>; 3] {
    [
        vec![p.value(x).to_f64()],
        flat_vecs::<T, N>(&p.gradient(x)),
        flat_blocks::<T, N>(&p.hessian(x)),
    ]
}

fn con<T: Real, C: Constraint<T, R, N>, const R: usize, const N: usize>(
    c: &C,
    x: &NodeVecs<T, N>,
    lambda: &[T],
) -> [Vec<f64>; 3] {
    let lam: [T; R] = core::array::from_fn(|k| lambda[k]);
    let jac = c.jacobian(x).iter().flat_map(flat_vecs::<T, N>).collect();
    [
        c.value(x).map(Real::to_f64).to_vec(),
        jac,
        flat_blocks::<T, N>(&c.hessian(x, &lam)),
    ]
}

fn prefix<T: Real, const N: usize>(x: &NodeVecs<T, 5>) -> NodeVecs<T, N> {
    core::array::from_fn(|k| x[k])
}

/// One term's outputs: `[value(s), first derivatives, second derivatives]`, flattened.
pub type Outputs = [Vec<f64>; 3];

/// Evaluates every term on (a prefix of) the 5-node block `x` with multipliers `lambda`
/// (at least 3). Returns `(name, outputs)` per term.
#[must_use]
pub fn evaluate_all<T: Real>(
    t: &Terms<T>,
    x: &NodeVecs<T, 5>,
    lambda: &[T],
) -> Vec<(&'static str, Outputs)> {
    let x4 = prefix::<T, 4>(x);
    let (x3, x2, x1) = (prefix::<T, 3>(x), prefix::<T, 2>(x), prefix::<T, 1>(x));
    let remedied_inner: Vec<f64> = t
        .remedy
        .inner_jacobian(x)
        .iter()
        .flat_map(flat_vecs::<T, 5>)
        .collect();
    let remedied_boundary: Vec<f64> = t
        .remedy
        .boundary_jacobian(&x4)
        .iter()
        .flat_map(flat_vecs::<T, 4>)
        .collect();
    vec![
        ("DOG inner star", con(&t.dog_inner, x, lambda)),
        ("DOG boundary star", con(&t.dog_boundary, &x4, lambda)),
        (
            "DOG flat-star remedy",
            [vec![], [remedied_inner, remedied_boundary].concat(), vec![]],
        ),
        ("DOG Laplacian inner", pot(&t.lap_inner, x)),
        ("DOG Laplacian boundary", pot(&t.lap_boundary, &x3)),
        ("curve Laplacian", pot(&t.curve, &x3)),
        ("iso2D", con(&t.iso2d, &x2, lambda)),
        ("binding", con(&t.binding, &x3, lambda)),
        ("fix", con(&t.fix, &x2, lambda)),
        ("glue", pot(&t.glue, &x4)),
        ("gravity", pot(&t.gravity, &x1)),
        ("iso3D", pot(&t.iso3d, &x2)),
        ("positional", pot(&t.positional, &x1)),
        ("spring", pot(&t.spring, &x2)),
    ]
}
