//! Every gradient, Hessian, Jacobian and constraint Hessian of `folio-kernels` against
//! central finite differences (f64) on 200 seeded random configurations per term, plus
//! Hessian symmetry. Run with `--nocapture` to see the worst errors per term.

use folio_kernels::binding::Binding;
use folio_kernels::cone::ConeCurl;
use folio_kernels::contact::ContactPlane;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::gravity::Gravity;
use folio_kernels::hinge::Hinge;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::membrane::{Membrane, MembraneLaw};
use folio_kernels::positional::Positional;
use folio_kernels::spring::Spring;
use folio_kernels::term::NodeVecs;
use folio_kernels::{Constraint, Potential, curve_laplacian, dog_laplacian};
use folio_tests::{
    BOUNDARY_DIRS, FdErrors, INNER_DIRS, Rng, check_constraint, check_potential, jittered_star,
    rel_err,
};
use glam::{DQuat, DVec3};

const CONFIGS: usize = 200;
/// Bound on the worst relative FD error of first and second derivatives.
const FD_TOL: f64 = 1e-6;
/// Bound on relative Hessian asymmetry.
const SYM_TOL: f64 = 1e-13;

fn report(name: &str, e: FdErrors) {
    println!(
        "{name:<28} first {:9.2e}   second {:9.2e}   asym {:9.2e}",
        e.first, e.second, e.asymmetry
    );
    assert!(
        e.first <= FD_TOL,
        "{name}: first derivative error {:e}",
        e.first
    );
    assert!(
        e.second <= FD_TOL,
        "{name}: second derivative error {:e}",
        e.second
    );
    assert!(
        e.asymmetry <= SYM_TOL,
        "{name}: Hessian asymmetry {:e}",
        e.asymmetry
    );
}

fn potentials<P: Potential<f64, N>, const N: usize>(
    name: &str,
    seed: u64,
    mut make: impl FnMut(&mut Rng) -> (P, NodeVecs<f64, N>),
) {
    let mut rng = Rng::new(seed);
    let mut worst = FdErrors::default();
    for _ in 0..CONFIGS {
        let (p, x) = make(&mut rng);
        worst = worst.max(check_potential(&p, &x));
    }
    report(name, worst);
}

fn constraints<C: Constraint<f64, R, N>, const R: usize, const N: usize>(
    name: &str,
    seed: u64,
    mut make: impl FnMut(&mut Rng) -> (C, NodeVecs<f64, N>),
) {
    let mut rng = Rng::new(seed);
    let mut worst = FdErrors::default();
    for _ in 0..CONFIGS {
        let (c, x) = make(&mut rng);
        let lambda = [(); R].map(|()| rng.uniform(-2.0, 2.0));
        worst = worst.max(check_constraint(&c, &x, &lambda));
    }
    report(name, worst);
}

fn lengths<const K: usize>(rng: &mut Rng) -> [f64; K] {
    [(); K].map(|()| rng.uniform(0.5, 1.5))
}

#[test]
fn dog_inner_star() {
    constraints("DOG inner star", 1, |r| {
        (DogInnerStar::new(), jittered_star(r, INNER_DIRS, 0.7))
    });
}

#[test]
fn dog_boundary_star() {
    constraints("DOG boundary star", 2, |r| {
        (DogBoundaryStar::new(), jittered_star(r, BOUNDARY_DIRS, 0.7))
    });
}

#[test]
fn dog_laplacian_inner() {
    potentials("DOG Laplacian inner", 3, |r| {
        (
            dog_laplacian::inner(lengths(r)).unwrap(),
            jittered_star(r, INNER_DIRS, 0.7),
        )
    });
}

#[test]
fn dog_laplacian_boundary() {
    potentials("DOG Laplacian boundary", 4, |r| {
        let dirs = [DVec3::ZERO, DVec3::X, DVec3::NEG_X];
        (
            dog_laplacian::boundary(lengths(r)).unwrap(),
            jittered_star(r, dirs, 0.7),
        )
    });
}

#[test]
fn dog_laplacian_inner_area() {
    potentials("DOG Laplacian inner area", 13, |r| {
        let area = r.uniform(0.1, 3.0);
        (
            dog_laplacian::inner_area(lengths(r), area).unwrap(),
            jittered_star(r, INNER_DIRS, 0.7),
        )
    });
}

#[test]
fn dog_laplacian_boundary_area() {
    potentials("DOG Laplacian boundary area", 14, |r| {
        let dirs = [DVec3::ZERO, DVec3::X, DVec3::NEG_X];
        let area = r.uniform(0.1, 3.0);
        (
            dog_laplacian::boundary_area(lengths(r), area).unwrap(),
            jittered_star(r, dirs, 0.7),
        )
    });
}

#[test]
fn curve_laplacian() {
    potentials("curve Laplacian", 5, |r| {
        let dirs = [DVec3::ZERO, DVec3::NEG_X, DVec3::X];
        (
            curve_laplacian::new(lengths(r)).unwrap(),
            jittered_star(r, dirs, 0.7),
        )
    });
}

#[test]
fn iso2d() {
    constraints("iso2D", 6, |r| {
        (
            Iso2d::new(r.uniform(0.5, 1.5)).unwrap(),
            [r.vec(2.0), r.vec(2.0)],
        )
    });
}

#[test]
fn binding() {
    constraints("binding", 7, |r| {
        (
            Binding::new(r.uniform(0.0, 1.0)).unwrap(),
            [r.vec(2.0), r.vec(2.0), r.vec(2.0)],
        )
    });
}

#[test]
fn fix() {
    constraints("fix", 8, |r| {
        (Fix::new(r.vec(1.0)).unwrap(), [r.vec(2.0), r.vec(2.0)])
    });
}

#[test]
fn glue() {
    potentials("glue", 9, |r| {
        let b1 = r.vec(2.0);
        let b2 = b1 + (DVec3::X + r.vec(0.5)) * r.uniform(0.05, 1.0);
        let up = |r: &mut Rng| (DVec3::Y + r.vec(1.0)) * r.uniform(0.5, 1.5);
        (Glue::new(), [b1 + up(r), b1, b2, b2 + up(r)])
    });
}

#[test]
fn gravity() {
    potentials("gravity", 10, |r| {
        (
            Gravity::new(r.uniform(1.0, 20.0), r.uniform(0.0, 1.0)).unwrap(),
            [r.vec(2.0)],
        )
    });
}

#[test]
fn iso3d() {
    potentials("iso3D", 11, |r| {
        (
            Iso3d::new(r.uniform(0.5, 1.5)).unwrap(),
            [r.vec(2.0), r.vec(2.0)],
        )
    });
}

#[test]
fn positional() {
    potentials("positional", 12, |r| {
        (Positional::new(r.vec(3.0)).unwrap(), [r.vec(3.0)])
    });
}

#[test]
fn contact_plane() {
    potentials("contact plane", 14, |r| {
        let plane = ContactPlane::new(
            r.vec(3.0),
            r.vec(1.0),
            r.uniform(0.0, 0.1),
            r.uniform(0.5, 2.0),
        )
        .unwrap();
        (plane, [r.vec(3.0)])
    });
}

#[test]
fn spring() {
    potentials("spring (Provot)", 13, |r| {
        (
            Spring::new(r.uniform(0.5, 2.0), r.uniform(0.1, 3.0)).unwrap(),
            [r.vec(2.0), r.vec(2.0)],
        )
    });
}

#[test]
fn spring_force_and_damping_jacobians() {
    let mut rng = Rng::new(14);
    let mut worst: f64 = 0.0;
    for _ in 0..CONFIGS {
        let s = Spring::new(rng.uniform(0.5, 2.0), rng.uniform(0.1, 3.0)).unwrap();
        let x = [rng.vec(2.0), rng.vec(2.0)];
        let v = [rng.vec(1.0), rng.vec(1.0)];
        let kd = rng.uniform(0.0, 2.0);
        // Force is minus the gradient; its Jacobian minus the Hessian.
        let f: Vec<f64> = s.force(&x).iter().flat_map(|p| p.to_array()).collect();
        let g: Vec<f64> = s
            .gradient(&x)
            .iter()
            .flat_map(|p| (-*p).to_array())
            .collect();
        worst = folio_tests::worst(worst, rel_err(&f, &g));
        // Damping Jacobian against differences of the damping force in the velocities.
        let jd = folio_tests::flat_blocks::<f64, 2>(&s.damping_jacobian(&x, kd));
        let jd_fd = folio_tests::fd_jacobian(&v, |w| {
            s.damping_force(&x, w, kd)
                .iter()
                .flat_map(|p| p.to_array())
                .collect()
        });
        worst = folio_tests::worst(worst, rel_err(&jd, &jd_fd));
        let fj = folio_tests::flat_blocks::<f64, 2>(&s.force_jacobian(&x));
        let fj_fd = folio_tests::fd_jacobian(&x, |y| {
            s.force(y).iter().flat_map(|p| p.to_array()).collect()
        });
        worst = folio_tests::worst(worst, rel_err(&fj, &fj_fd));
    }
    println!("{:<28} first {worst:9.2e}", "spring force / damping");
    assert!(
        worst <= FD_TOL,
        "spring force/damping Jacobian error {worst:e}"
    );
}

#[test]
fn cone_curl_jacobian() {
    let mut rng = Rng::new(15);
    let mut worst: f64 = 0.0;
    for _ in 0..CONFIGS {
        let (theta, apex, rho) = (
            rng.uniform(0.15, 1.5),
            rng.uniform(-12.0, 2.0),
            rng.uniform(-3.0, 3.0),
        );
        let (x, y) = (rng.uniform(0.0, 12.0), rng.uniform(0.0, 16.0));
        let jac = ConeCurl::new(theta, apex, rho).jacobian(x, y);
        let analytic: Vec<f64> = (0..3).flat_map(|row| jac.map(|col| col[row])).collect();
        let params = [theta, apex, rho];
        let mut fd = vec![0.0; 9];
        for k in 0..3 {
            let h = f64::EPSILON.cbrt() * params[k].abs().max(1.0);
            let (mut p, mut m) = (params, params);
            p[k] += h;
            m[k] -= h;
            let tp = ConeCurl::new(p[0], p[1], p[2]).map_point(x, y);
            let tm = ConeCurl::new(m[0], m[1], m[2]).map_point(x, y);
            let d = (tp - tm) / (2.0 * h);
            for row in 0..3 {
                fd[row * 3 + k] = d[row];
            }
        }
        worst = folio_tests::worst(worst, rel_err(&analytic, &fd));
    }
    println!("{:<28} first {worst:9.2e}", "cone curl Jacobian");
    assert!(worst <= FD_TOL, "cone Jacobian error {worst:e}");
}

/// A random counter-clockwise rest triangle of the pattern with $2A \ge 0.05\thinspace\ell_{\max}^2$
/// (angles down to about 3 degrees).
fn pattern_triangle(r: &mut Rng) -> [[f64; 2]; 3] {
    folio_tests::pattern_triangle(r, 0.05, 0.04)
}

/// A random hinge pattern `[u0, u1, u2, u3]`: edge `(u0, u1)`, `u2` left and `u3` right of it,
/// both triangles passing the shape bound of [`pattern_triangle`].
fn pattern_hinge(r: &mut Rng) -> [[f64; 2]; 4] {
    loop {
        let u0 = [r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0)];
        let phi = r.uniform(-3.2, 3.2);
        let len = r.uniform(0.3, 2.0);
        let (t, n) = ([phi.cos(), phi.sin()], [-phi.sin(), phi.cos()]);
        let u1 = [u0[0] + len * t[0], u0[1] + len * t[1]];
        let side = |r: &mut Rng, sign: f64| {
            let (a, h) = (r.uniform(-0.5, 1.5) * len, sign * r.uniform(0.1, 1.5) * len);
            [u0[0] + a * t[0] + h * n[0], u0[1] + a * t[1] + h * n[1]]
        };
        let (u2, u3) = (side(r, 1.0), side(r, -1.0));
        let (aa, la) = folio_tests::area2_and_longest([u0, u1, u2]);
        let (ab, lb) = folio_tests::area2_and_longest([u1, u0, u3]);
        if aa >= 0.05 * la && ab >= 0.05 * lb {
            return [u0, u1, u2, u3];
        }
    }
}

/// Pattern points mapped by an in-plane stretch (principal stretches in `[lo, hi]`, below 1
/// compresses), embedded in 3D, moved rigidly and jittered by up to `noise` per coordinate.
fn deformed<const N: usize>(
    r: &mut Rng,
    u: &[[f64; 2]; N],
    (lo, hi): (f64, f64),
    noise: f64,
) -> NodeVecs<f64, N> {
    let (q, t): (DQuat, DVec3) = (r.rotation(), r.vec(2.0));
    let (s1, s2, phi) = (r.uniform(lo, hi), r.uniform(lo, hi), r.uniform(-3.2, 3.2));
    let (c, s) = (phi.cos(), phi.sin());
    u.map(|p| {
        let (a, b) = ((c * p[0] + s * p[1]) * s1, (-s * p[0] + c * p[1]) * s2);
        q * DVec3::new(c * a - s * b, s * a + c * b, 0.0) + t + r.vec(noise)
    })
}

#[test]
fn membrane() {
    potentials("membrane (StVK)", 16, |r| {
        let u = pattern_triangle(r);
        let m = Membrane::new(u, r.uniform(0.5, 3.0), r.uniform(0.0, 0.49)).unwrap();
        // Mild (stretched or compressed) and wild (possibly inverted) configurations.
        let noise = if r.uniform(0.0, 1.0) < 0.5 { 0.05 } else { 0.6 };
        (m, deformed(r, &u, (0.6, 1.4), noise))
    });
}

#[test]
fn hinge() {
    potentials("hinge (quadratic bending)", 17, |r| {
        let u = pattern_hinge(r);
        (Hinge::new(u).unwrap(), deformed(r, &u, (0.7, 1.3), 0.4))
    });
}

/// Smallest and largest eigenvalue of a symmetric `9 x 9` Hessian.
fn eigen_range(h: &folio_kernels::term::Blocks<f64, 3>) -> (f64, f64) {
    let flat = folio_tests::flat_blocks::<f64, 3>(h);
    let m = nalgebra::DMatrix::from_row_slice(9, 9, &flat);
    let eig = nalgebra::SymmetricEigen::new(m).eigenvalues;
    (eig.min(), eig.max())
}

#[test]
fn membrane_projected_hessian_is_psd_and_exact_under_tension() {
    let mut rng = Rng::new(18);
    let (mut indefinite_exact, mut tension, mut compression) = (0, 0, 0);
    for _ in 0..CONFIGS {
        let u = pattern_triangle(&mut rng);
        let m = Membrane::new(u, rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.49)).unwrap();
        let x = deformed(&mut rng, &u, (0.6, 1.4), 0.05);
        let (f0, f1) = m.deformation_gradient(&x);
        // Principal stresses of S = 2 mu E + lambda tr(E) I, computed here independently.
        let e = [
            (f0.dot(f0) - 1.0) / 2.0,
            f0.dot(f1) / 2.0,
            (f1.dot(f1) - 1.0) / 2.0,
        ];
        let tr = e[0] + e[2];
        let s = [
            2.0 * m.mu * e[0] + m.lambda * tr,
            2.0 * m.mu * e[1],
            2.0 * m.mu * e[2] + m.lambda * tr,
        ];
        let radius = (((s[0] - s[2]) / 2.0).powi(2) + s[1] * s[1]).sqrt();
        let lowest = (s[0] + s[2]) / 2.0 - radius;
        let (exact, projected) = (m.hessian(&x), m.hessian_projected(&x));
        let (pmin, pmax) = eigen_range(&projected);
        assert!(
            pmin >= -1e-12 * pmax.max(1.0),
            "projected Hessian has eigenvalue {pmin:e} (max {pmax:e})"
        );
        let gap = rel_err(
            &folio_tests::flat_blocks::<f64, 3>(&exact),
            &folio_tests::flat_blocks::<f64, 3>(&projected),
        );
        if lowest >= 0.0 {
            tension += 1;
            assert!(
                gap <= 1e-14,
                "under tension the projection changed H by {gap:e}"
            );
        } else {
            compression += 1;
            assert!(
                gap > 0.0,
                "under compression the projection changed nothing"
            );
            let (emin, emax) = eigen_range(&exact);
            if emin < -1e-9 * emax {
                indefinite_exact += 1;
            }
        }
    }
    println!(
        "membrane projection: {tension} under tension, {compression} compressed, \
         {indefinite_exact} with an indefinite exact Hessian"
    );
    assert!(tension > 10 && compression > 10 && indefinite_exact > 10);
}

/// The state of a tension-field triangle (0 taut, 1 wrinkled, 2 slack) and the energy the
/// relaxed law gives it, both from the principal Green strains and the `y`, `nu` the
/// membrane was made with (not from the kernel's Lamé parameters): wrinkled
/// $A_0 Y e_1^2 / 2$, slack 0, taut `None` (the Saint Venant–Kirchhoff value).
fn tension_field_state(
    m: &Membrane<f64>,
    x: &NodeVecs<f64, 3>,
    y: f64,
    nu: f64,
) -> (usize, Option<f64>) {
    let (f0, f1) = m.deformation_gradient(x);
    let e = [
        (f0.dot(f0) - 1.0) / 2.0,
        f0.dot(f1) / 2.0,
        (f1.dot(f1) - 1.0) / 2.0,
    ];
    let radius = (((e[0] - e[2]) / 2.0).powi(2) + e[1] * e[1]).sqrt();
    let (e1, e2) = ((e[0] + e[2]) / 2.0 + radius, (e[0] + e[2]) / 2.0 - radius);
    if e1 <= 0.0 {
        (2, Some(0.0))
    } else if e2 < -nu * e1 {
        (1, Some(m.rest_area * y * e1 * e1 / 2.0))
    } else {
        (0, None)
    }
}

/// A random tension-field membrane in a configuration stretched or compressed up to 40 %
/// each way, with its `y` and `nu`.
fn tension_field_case(r: &mut Rng) -> (Membrane<f64>, NodeVecs<f64, 3>, f64, f64) {
    let u = pattern_triangle(r);
    let (y, nu) = (r.uniform(0.5, 3.0), r.uniform(0.0, 0.49));
    let m = Membrane::new(u, y, nu)
        .unwrap()
        .with_law(MembraneLaw::TensionField);
    let noise = if r.uniform(0.0, 1.0) < 0.5 { 0.05 } else { 0.4 };
    (m, deformed(r, &u, (0.6, 1.4), noise), y, nu)
}

/// The tension-field law against finite differences, in its three states (taut, wrinkled,
/// slack), and its energy against the relaxed energy computed here from the principal
/// strains; its Hessian is positive semi-definite everywhere.
#[test]
fn membrane_tension_field() {
    let mut states = [0usize; 3];
    let mut worst_energy: f64 = 0.0;
    let mut worst_eigen: f64 = 0.0;
    potentials("membrane (tension field)", 21, |r| {
        let (m, x, y, nu) = tension_field_case(r);
        let (state, relaxed) = tension_field_state(&m, &x, y, nu);
        states[state] += 1;
        let value = m.value(&x);
        // Taut: the Saint Venant-Kirchhoff energy, checked on its own in `membrane`.
        let reference =
            relaxed.unwrap_or_else(|| m.with_law(MembraneLaw::StVenantKirchhoff).value(&x));
        worst_energy = worst_energy.max((value - reference).abs() / reference.abs().max(1e-12));
        let (emin, emax) = eigen_range(&m.hessian(&x));
        worst_eigen = worst_eigen.min(emin / emax.max(1e-300));
        (m, x)
    });
    println!(
        "tension field: {} taut, {} wrinkled, {} slack; energy error {worst_energy:.2e}, \
         lowest eigenvalue / highest {worst_eigen:.2e}",
        states[0], states[1], states[2]
    );
    assert!(states.iter().all(|&n| n >= 10), "states {states:?}");
    assert!(
        worst_energy <= 1e-12,
        "relaxed energy off by {worst_energy:e}"
    );
    assert!(worst_eigen >= -1e-12, "indefinite Hessian: {worst_eigen:e}");
}

/// The Eshelby tensor is the energy's derivative with respect to the pattern: moving a
/// rest corner $u_i$ with the 3D positions held changes $V$ by $A_0 \Sigma \nabla N_i$
/// (`Membrane::eshelby`), checked by central differences of the energy rebuilt on the
/// moved pattern; under both laws.
#[test]
fn membrane_eshelby_is_the_pattern_derivative_of_the_energy() {
    let mut rng = Rng::new(19);
    let mut worst: f64 = 0.0;
    for case in 0..2 * CONFIGS {
        let law = [MembraneLaw::StVenantKirchhoff, MembraneLaw::TensionField][case % 2];
        let u = pattern_triangle(&mut rng);
        let (y, nu) = (rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.49));
        let m = Membrane::new(u, y, nu).unwrap().with_law(law);
        let x = deformed(&mut rng, &u, (0.7, 1.3), 0.2);
        let sigma = m.eshelby(&x);
        // grad N_i: the rows of dm_inv give grad N_1, grad N_2; grad N_0 = -(sum).
        let b = m.dm_inv;
        let grads = [
            [-(b[0][0] + b[1][0]), -(b[0][1] + b[1][1])],
            [b[0][0], b[0][1]],
            [b[1][0], b[1][1]],
        ];
        let scale = m.rest_area * (sigma[0].abs() + sigma[1].abs() + sigma[2].abs()) + 1e-12;
        for (i, g) in grads.iter().enumerate() {
            let analytic = [
                m.rest_area * (sigma[0] * g[0] + sigma[1] * g[1]),
                m.rest_area * (sigma[1] * g[0] + sigma[2] * g[1]),
            ];
            for k in 0..2 {
                let h = 1e-6;
                let energy = |d: f64| {
                    let mut v = u;
                    v[i][k] += d;
                    Membrane::new(v, y, nu).unwrap().with_law(law).value(&x)
                };
                let fd = (energy(h) - energy(-h)) / (2.0 * h);
                worst = worst.max((fd - analytic[k]).abs() / scale);
            }
        }
    }
    println!("Eshelby against the pattern derivative: worst relative error {worst:.2e}");
    assert!(worst < 1e-6, "{worst}");
}

/// The hinge that counts only folds (`Hinge::orient` at another configuration: its normal
/// is a parameter within a step).
#[test]
fn hinge_folds_only() {
    potentials("hinge (folds only)", 20, |r| {
        let u = pattern_hinge(r);
        let mut hinge = Hinge::new(u).unwrap();
        hinge.orient(&deformed(r, &u, (0.7, 1.3), 0.4));
        (hinge, deformed(r, &u, (0.7, 1.3), 0.4))
    });
}
