//! Hard cases of the kernels: degenerate and collinear stars, zero-length edges,
//! coordinates at $10^{\pm 8}$, `f32` near overflow and underflow, symmetric and finite
//! Hessians, and the derivative check itself seeing a NaN.

use folio_kernels::dog::{DogBoundaryStar, DogInnerStar, FlatStarRemedy};
use folio_kernels::glue::Glue;
use folio_kernels::hinge::Hinge;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::spring::Spring;
use folio_kernels::term::{Blocks, NodeVecs};
use folio_kernels::{Constraint, Potential, Real, Vec3Ops, curve_laplacian, dog_laplacian};
use folio_tests::{check_potential, flat_blocks, flat_vecs, nan_max, rel_err};
use glam::DVec3;

/// Largest asymmetry of `h` relative to its largest entry (NaN if any entry is).
fn asymmetry<T: Real, const N: usize>(h: &Blocks<T, N>) -> f64 {
    let flat = flat_blocks::<T, N>(h);
    let n = 3 * N;
    let scale = folio_tests::worst(nan_max(flat.iter().map(|v| v.abs())), f64::MIN_POSITIVE);
    let diff = (0..n * n).map(|i| (flat[i] - flat[(i % n) * n + i / n]).abs());
    nan_max(diff) / scale
}

/// Value, gradient and Hessian of `p` at `x` are finite and the Hessian symmetric to
/// `tol`.
fn potential_sound<T: Real, P: Potential<T, N>, const N: usize>(
    p: &P,
    x: &NodeVecs<T, N>,
    tol: f64,
    name: &str,
) {
    let v = p.value(x).to_f64();
    let g = flat_vecs::<T, N>(&p.gradient(x));
    let h = p.hessian(x);
    let hf = flat_blocks::<T, N>(&h);
    assert!(v.is_finite(), "{name}: value {v}");
    assert!(
        g.iter().chain(&hf).all(|c| c.is_finite()),
        "{name}: {g:?} {hf:?}"
    );
    let a = asymmetry::<T, N>(&h);
    assert!(a <= tol, "{name}: Hessian asymmetry {a:e}");
}

/// Value, Jacobian and Hessian (unit multipliers) of `c` at `x` are finite and the Hessian
/// symmetric to `tol`.
fn constraint_sound<T: Real, C: Constraint<T, R, N>, const R: usize, const N: usize>(
    c: &C,
    x: &NodeVecs<T, N>,
    tol: f64,
    name: &str,
) {
    let v: Vec<f64> = c.value(x).iter().map(|v| v.to_f64()).collect();
    let j: Vec<f64> = c.jacobian(x).iter().flat_map(flat_vecs::<T, N>).collect();
    let h = c.hessian(x, &[T::ONE; R]);
    let hf = flat_blocks::<T, N>(&h);
    assert!(
        v.iter().chain(&j).chain(&hf).all(|c| c.is_finite()),
        "{name}: {v:?} {j:?}"
    );
    let a = asymmetry::<T, N>(&h);
    assert!(a <= tol, "{name}: Hessian asymmetry {a:e}");
}

/// `N` points `p(k)` in precision `T`.
fn points<T: Real, const N: usize>(p: impl Fn(usize) -> [f64; 3]) -> NodeVecs<T, N> {
    core::array::from_fn(|k| {
        let [x, y, z] = p(k).map(T::from_f64);
        T::Vec3::new(x, y, z)
    })
}

/// Both DOG stars at `inner` and `boundary` (finite, Hessians symmetric to $10^{-12}$) and
/// the flat-star remedy's Jacobians there (finite).
fn stars_sound<T: Real>(inner: &NodeVecs<T, 5>, boundary: &NodeVecs<T, 4>) {
    constraint_sound(&DogInnerStar::<T>::new(), inner, 1e-12, "inner star");
    constraint_sound(
        &DogBoundaryStar::<T>::new(),
        boundary,
        1e-12,
        "boundary star",
    );
    let remedy = FlatStarRemedy::<T>::default();
    let rows = remedy.inner_jacobian(inner);
    let j: Vec<f64> = rows.iter().flat_map(flat_vecs::<T, 5>).collect();
    let rows = remedy.boundary_jacobian(boundary);
    let jb: Vec<f64> = rows.iter().flat_map(flat_vecs::<T, 4>).collect();
    assert!(
        j.iter().chain(&jb).all(|v| v.is_finite()),
        "remedy {j:?} {jb:?}"
    );
}

/// Every node of a DOG star on one point (all edges of zero length): the stars' DOG
/// constraints, the flat-star remedy and the Laplacians take their finite fallbacks.
/// Asserts finite outputs and Hessians symmetric to $10^{-12}$, in both precisions.
#[test]
fn degenerate_star_with_every_node_on_one_point_is_finite() {
    fn check<T: Real>() {
        let p = [1.0, -2.0, 0.5];
        let inner = points::<T, 5>(|_| p);
        let boundary = points::<T, 4>(|_| p);
        stars_sound::<T>(&inner, &boundary);
        let one = T::ONE;
        let lap = dog_laplacian::inner([one; 4]).expect("unit rest lengths");
        potential_sound(&lap, &inner, 1e-12, "DOG Laplacian");
        let curve = curve_laplacian::new([one; 2]).expect("unit rest lengths");
        potential_sound(&curve, &points::<T, 3>(|_| p), 1e-12, "curve Laplacian");
    }
    check::<f64>();
    check::<f32>();
}

/// A star whose five nodes lie on one line (a collinear, flat-as-can-be star): the DOG
/// rows' normal is undefined there. Asserts finite outputs and symmetric Hessians
/// ($10^{-12}$) for the stars and the remedy's Jacobians, in both precisions.
#[test]
fn collinear_star_is_finite_and_symmetric() {
    fn check<T: Real>() {
        // p0 in the middle, the four neighbours on the X axis at +-1 and +-2.
        let along = [0.0, 1.0, 2.0, -1.0, -2.0];
        let inner = points::<T, 5>(|k| [along[k], 0.0, 0.0]);
        let boundary = points::<T, 4>(|k| [along[k], 0.0, 0.0]);
        stars_sound::<T>(&inner, &boundary);
    }
    check::<f64>();
    check::<f32>();
}

/// Zero-length edges in the two-node terms (both nodes on one point) and in the hinge
/// and glue stencils: the spring, iso3d, iso2d, hinge and glue take their documented
/// fallbacks. Asserts finite outputs and symmetric Hessians ($10^{-12}$), both precisions.
#[test]
fn zero_length_edges_take_finite_fallbacks() {
    fn check<T: Real>() {
        let pair = points::<T, 2>(|_| [3.0, 3.0, 3.0]);
        let one = T::ONE;
        let spring = Spring::new(one, T::from_f64(100.0)).expect("valid");
        potential_sound(&spring, &pair, 1e-12, "spring");
        potential_sound(&Iso3d::new(one).expect("valid"), &pair, 1e-12, "iso3d");
        constraint_sound(&Iso2d::new(one).expect("valid"), &pair, 1e-12, "iso2d");
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].map(|p| p.map(T::from_f64));
        let hinge = Hinge::new([square[0], square[2], square[3], square[1]]).expect("a square");
        let four = points::<T, 4>(|_| [0.0, 1.0, 0.0]);
        potential_sound(&hinge, &four, 1e-12, "hinge");
        potential_sound(&Glue::<T>::new(), &four, 1e-12, "glue");
    }
    check::<f64>();
    check::<f32>();
}

/// A spring and a hinge at coordinates of magnitude $10^8$ and $10^{-8}$, f64, with rest
/// sizes scaled alike: outputs finite, and the exact scaling law of each term holds to
/// $10^{-12}$ relative against the same configuration at scale 1 (the spring's energy
/// scales by $s^2$, its gradient by $s$, its Hessian not at all; the hinge's energy, which
/// is scale-free in the pattern, by $s^2 / s^2 = 1$ with pattern and positions scaled).
#[test]
fn coordinates_at_1e8_and_1e_minus_8_keep_the_scaling_laws() {
    let unit = [DVec3::new(1.0, 0.2, -0.3), DVec3::new(1.9, 0.1, 0.4)];
    let spring = |rest: f64| Spring::new(rest, 1.0).expect("valid");
    let (v1, g1, h1) = (
        spring(1.0).value(&unit),
        flat_vecs::<f64, 2>(&spring(1.0).gradient(&unit)),
        flat_blocks::<f64, 2>(&spring(1.0).hessian(&unit)),
    );
    let square = [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]];
    let bent = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.3),
        DVec3::new(1.0, 0.0, 0.3),
    ];
    let hinge_at = |s: f64| {
        let h = Hinge::new(square.map(|p| p.map(|c| c * s))).expect("valid");
        h.value(&bent.map(|p| p * s))
    };
    let e1 = hinge_at(1.0);
    for s in [1e8, 1e-8] {
        let x = unit.map(|p| p * s);
        let p = spring(s);
        potential_sound(&p, &x, 1e-12, "spring");
        let v = p.value(&x) / (s * s);
        let g: Vec<f64> = flat_vecs::<f64, 2>(&p.gradient(&x))
            .iter()
            .map(|c| c / s)
            .collect();
        let h = flat_blocks::<f64, 2>(&p.hessian(&x));
        assert!(
            (v / v1 - 1.0).abs() <= 1e-12,
            "spring energy at {s:e}: {v} vs {v1}"
        );
        assert!(rel_err(&g, &g1) <= 1e-12, "spring gradient at {s:e}");
        assert!(rel_err(&h, &h1) <= 1e-12, "spring Hessian at {s:e}");
        let hinge = Hinge::new(square.map(|p| p.map(|c| c * s))).expect("valid");
        potential_sound(&hinge, &bent.map(|p| p * s), 1e-10, "hinge");
        let e = hinge_at(s);
        assert!(
            (e / e1 - 1.0).abs() <= 1e-12,
            "hinge energy at {s:e}: {e} vs {e1}"
        );
    }
}

/// f32 at the documented coordinate limit ([`Real::COORD_MAX`] $= 10^6$): the quartic
/// iso3d, the spring, the glue, the DOG stars and the Laplacians on nodes spread over the
/// whole range. Asserts finite outputs and Hessians symmetric to $10^{-5}$.
#[test]
fn f32_near_overflow_stays_finite() {
    let m = f64::from(f32::COORD_MAX);
    let pair = points::<f32, 2>(|k| if k == 0 { [m, -m, m] } else { [-m, m, -m] });
    potential_sound(&Iso3d::new(1e-3f32).expect("valid"), &pair, 1e-5, "iso3d");
    potential_sound(
        &Spring::new(1.0f32, 1e3).expect("valid"),
        &pair,
        1e-5,
        "spring",
    );
    let signs = [
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, -1.0],
        [1.0, -1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [0.5, 0.0, -0.5],
    ];
    let five = points::<f32, 5>(|k| signs[k].map(|s| s * m));
    let four = points::<f32, 4>(|k| signs[k].map(|s| s * m));
    potential_sound(&Glue::<f32>::new(), &four, 1e-5, "glue");
    constraint_sound(&DogInnerStar::<f32>::new(), &five, 1e-5, "inner star");
    constraint_sound(&DogBoundaryStar::<f32>::new(), &four, 1e-5, "boundary star");
    let lap = dog_laplacian::inner([1e-3f32; 4]).expect("valid");
    potential_sound(&lap, &five, 1e-5, "DOG Laplacian");
}

/// f32 on subnormal coordinates ($10^{-40}$ and $10^{-44}$) and with rest sizes at the
/// length floor ($10^{-15}$): no $0/0$. Asserts finite outputs and symmetric Hessians.
#[test]
fn f32_near_underflow_stays_finite() {
    for tiny in [1e-40f64, 1e-44] {
        let pair = points::<f32, 2>(|k| [tiny * (k as f64 + 1.0), tiny, 0.0]);
        let floor = f32::LENGTH_FLOOR;
        potential_sound(
            &Spring::new(floor, 1.0f32).expect("valid"),
            &pair,
            1e-5,
            "spring",
        );
        potential_sound(&Iso3d::new(floor).expect("valid"), &pair, 1e-5, "iso3d");
        let five = points::<f32, 5>(|k| [tiny * k as f64, tiny * (k % 2) as f64, 0.0]);
        constraint_sound(&DogInnerStar::<f32>::new(), &five, 1e-5, "inner star");
        let lap = dog_laplacian::inner([floor; 4]).expect("valid");
        potential_sound(&lap, &five, 1e-5, "DOG Laplacian");
    }
}

/// Issue 20: the derivative checks folded their errors with `f64::max`, which drops NaN,
/// so a NaN component passed every check. Asserts: [`rel_err`] is NaN when a component is
/// NaN (analytic or differenced), and a potential whose gradient has one NaN component
/// fails [`check_potential`] (its first-derivative error is not below any bound).
#[test]
fn derivative_check_fails_on_a_nan_component() {
    assert!(rel_err(&[f64::NAN, 1e-9], &[0.0, 1e-9]).is_nan());
    assert!(rel_err(&[1.0, 2.0], &[1.0, f64::NAN]).is_nan());
    assert!(rel_err(&[1.0, 2.0], &[1.0, 2.0]) == 0.0);
    let x = [DVec3::new(0.1, 0.2, 0.3)];
    let e = check_potential(&NanGradient, &x);
    let passes = matches!(
        e.first.partial_cmp(&1e-6),
        Some(core::cmp::Ordering::Less | core::cmp::Ordering::Equal)
    );
    assert!(
        e.first.is_nan() && !passes,
        "a NaN gradient component passed: {e:?}"
    );
    let folded = e.max(folio_tests::FdErrors::default());
    assert!(
        folded.first.is_nan(),
        "the fold of errors dropped a NaN: {folded:?}"
    );
}

/// $V = \lVert x\rVert^2 / 2$ with its gradient's Y component replaced by NaN.
struct NanGradient;

impl Potential<f64, 1> for NanGradient {
    fn value(&self, x: &NodeVecs<f64, 1>) -> f64 {
        0.5 * x[0].length_squared()
    }
    fn gradient(&self, x: &NodeVecs<f64, 1>) -> NodeVecs<f64, 1> {
        [DVec3::new(x[0].x, f64::NAN, x[0].z)]
    }
    fn hessian(&self, _x: &NodeVecs<f64, 1>) -> Blocks<f64, 1> {
        [[glam::DMat3::IDENTITY]]
    }
}
