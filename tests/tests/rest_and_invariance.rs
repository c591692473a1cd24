//! Zero at rest and invariance under rigid motion, for every term where it holds.

use folio_kernels::binding::Binding;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::positional::Positional;
use folio_kernels::spring::{Spring, SpringKind};
use folio_kernels::term::{Blocks, NodeVecs};
use folio_kernels::{Constraint, Potential, curve_laplacian, dog_laplacian};
use folio_tests::{BOUNDARY_DIRS, INNER_DIRS, Rng, jittered_star, rel_err, rigid, rotate_blocks};
use glam::{DQuat, DVec3};

const TOL: f64 = 1e-12;

fn flat<const N: usize>(v: &NodeVecs<f64, N>) -> Vec<f64> {
    v.iter().flat_map(|p| p.to_array()).collect()
}

/// A straight cross in a random plane with random arm lengths: the rest state of the
/// bending stencils and an exact flat DOG star.
fn straight_star<const N: usize>(rng: &mut Rng, dirs: [DVec3; N]) -> NodeVecs<f64, N> {
    let (q, p0) = (rng.rotation(), rng.vec(3.0));
    let mut x = [p0; N];
    for k in 1..N {
        x[k] = p0 + q * dirs[k] * rng.uniform(0.5, 1.5);
    }
    x
}

fn assert_potential_at_rest<P: Potential<f64, N>, const N: usize>(
    name: &str,
    p: &P,
    x: &NodeVecs<f64, N>,
) {
    let (v, g) = (p.value(x), flat(&p.gradient(x)));
    assert!(v.abs() <= TOL, "{name}: value {v:e} at rest");
    assert!(
        g.iter().all(|e| e.abs() <= TOL),
        "{name}: gradient {g:?} at rest"
    );
}

fn lengths<const N: usize>(x: &NodeVecs<f64, N>) -> Vec<f64> {
    x[1..].iter().map(|p| (*p - x[0]).length()).collect()
}

#[test]
fn potentials_vanish_at_rest() {
    let mut rng = Rng::new(51);
    for _ in 0..100 {
        let s = straight_star(&mut rng, INNER_DIRS);
        let l = lengths(&s);
        assert_potential_at_rest(
            "DOG Laplacian inner",
            &dog_laplacian::inner([l[0], l[1], l[2], l[3]]).unwrap(),
            &s,
        );
        let b = straight_star(&mut rng, [DVec3::ZERO, DVec3::X, DVec3::NEG_X]);
        assert_potential_at_rest(
            "DOG Laplacian boundary",
            &dog_laplacian::boundary_from_rest(&b).unwrap(),
            &b,
        );
        let c = straight_star(&mut rng, [DVec3::ZERO, DVec3::NEG_X, DVec3::X]);
        assert_potential_at_rest(
            "curve Laplacian",
            &curve_laplacian::from_rest(&c).unwrap(),
            &c,
        );
        let (a, d) = (rng.vec(2.0), rng.vec(2.0));
        let len = (a - d).length();
        assert_potential_at_rest("iso3D", &Iso3d::new(len).unwrap(), &[a, d]);
        assert_potential_at_rest("spring", &Spring::new(len, 1.0).unwrap(), &[a, d]);
        assert_potential_at_rest("positional", &Positional::new(a).unwrap(), &[a]);
        // Glue: both midline edges leave the binding edge along its upward normal.
        let (b1, w) = (rng.vec(2.0), rng.uniform(0.05, 1.0));
        let ang = rng.uniform(-0.5, 0.5);
        let t = DVec3::new(ang.cos(), ang.sin(), 0.0);
        let n = DVec3::new(-t.y, t.x, 0.0);
        let x = [
            b1 + n * rng.uniform(0.5, 2.0),
            b1,
            b1 + t * w,
            b1 + t * w + n * rng.uniform(0.5, 2.0),
        ];
        assert_potential_at_rest("glue", &Glue::new(), &x);
    }
}

fn assert_constraint_at_rest<C: Constraint<f64, R, N>, const R: usize, const N: usize>(
    name: &str,
    c: &C,
    x: &NodeVecs<f64, N>,
) {
    let v = c.value(x);
    assert!(v.iter().all(|e| e.abs() <= TOL), "{name}: {v:?} at rest");
}

#[test]
fn constraints_vanish_at_rest() {
    let mut rng = Rng::new(52);
    for _ in 0..100 {
        assert_constraint_at_rest(
            "DOG inner",
            &DogInnerStar::new(),
            &straight_star(&mut rng, INNER_DIRS),
        );
        assert_constraint_at_rest(
            "DOG boundary",
            &DogBoundaryStar::new(),
            &straight_star(&mut rng, BOUNDARY_DIRS),
        );
        let (a, d) = (rng.vec(2.0), rng.vec(2.0));
        assert_constraint_at_rest("iso2D", &Iso2d::new((a - d).length()).unwrap(), &[a, d]);
        let q = rng.uniform(0.0, 1.0);
        let (b1, b2) = (rng.vec(2.0), rng.vec(2.0));
        let on_edge = b1 * (1.0 - q) + b2 * q + DVec3::Z * rng.uniform(-3.0, 3.0);
        assert_constraint_at_rest("binding", &Binding::new(q).unwrap(), &[on_edge, b1, b2]);
        assert_constraint_at_rest("fix", &Fix::new((b1 + b2) * 0.5).unwrap(), &[b1, b2]);
    }
}

/// Discrepancy between the Hessian at the moved configuration and the rotated Hessian at
/// the original one: $H(Rx + t) = R H(x) R^T$.
fn rotated_hessian_err<const N: usize>(
    moved: &Blocks<f64, N>,
    original: &Blocks<f64, N>,
    q: DQuat,
) -> f64 {
    rel_err(
        &folio_tests::flat_blocks::<f64, N>(moved),
        &folio_tests::flat_blocks::<f64, N>(&rotate_blocks(original, q)),
    )
}

/// Value unchanged, gradient rotated, Hessian rotated blockwise.
fn potential_invariance<P: Potential<f64, N>, const N: usize>(
    p: &P,
    x: &NodeVecs<f64, N>,
    q: DQuat,
    t: DVec3,
) -> f64 {
    let y = rigid(x, q, t);
    let value = rel_err(&[p.value(&y)], &[p.value(x)]);
    let grad = rel_err(&flat(&p.gradient(&y)), &flat(&p.gradient(x).map(|g| q * g)));
    let hess = rotated_hessian_err(&p.hessian(&y), &p.hessian(x), q);
    value.max(grad).max(hess)
}

fn constraint_invariance<C: Constraint<f64, R, N>, const R: usize, const N: usize>(
    c: &C,
    x: &NodeVecs<f64, N>,
    q: DQuat,
    t: DVec3,
) -> f64 {
    let y = rigid(x, q, t);
    let lambda = [0.7; R];
    let value = rel_err(&c.value(&y), &c.value(x));
    let jy: Vec<f64> = c.jacobian(&y).iter().flat_map(flat).collect();
    let jx: Vec<f64> = c
        .jacobian(x)
        .iter()
        .flat_map(|row| flat(&row.map(|g| q * g)))
        .collect();
    let hess = rotated_hessian_err(&c.hessian(&y, &lambda), &c.hessian(x, &lambda), q);
    value.max(rel_err(&jy, &jx)).max(hess)
}

#[test]
fn invariant_terms_are_invariant_under_rigid_motion() {
    let mut rng = Rng::new(53);
    let mut worst: f64 = 0.0;
    for _ in 0..100 {
        let (q, t) = (rng.rotation(), rng.vec(10.0));
        let s5 = jittered_star(&mut rng, INNER_DIRS, 0.6);
        let s4 = jittered_star(&mut rng, BOUNDARY_DIRS, 0.6);
        let s3 = jittered_star(&mut rng, [DVec3::ZERO, DVec3::X, DVec3::NEG_X], 0.6);
        let pair = [rng.vec(2.0), rng.vec(2.0)];
        worst = worst.max(constraint_invariance(&DogInnerStar::new(), &s5, q, t));
        worst = worst.max(constraint_invariance(&DogBoundaryStar::new(), &s4, q, t));
        worst = worst.max(constraint_invariance(
            &Iso2d::new(1.1).unwrap(),
            &pair,
            q,
            t,
        ));
        worst = worst.max(potential_invariance(
            &dog_laplacian::inner([0.9, 1.1, 1.0, 0.8]).unwrap(),
            &s5,
            q,
            t,
        ));
        worst = worst.max(potential_invariance(
            &dog_laplacian::boundary([0.9, 1.2]).unwrap(),
            &s3,
            q,
            t,
        ));
        worst = worst.max(potential_invariance(
            &curve_laplacian::new([0.7, 1.3]).unwrap(),
            &s3,
            q,
            t,
        ));
        worst = worst.max(potential_invariance(&Iso3d::new(1.2).unwrap(), &pair, q, t));
        worst = worst.max(potential_invariance(
            &Spring::new(SpringKind::Shear.rest_length(1.0), 2.0).unwrap(),
            &pair,
            q,
            t,
        ));
        // The glue lives in the XY plane: invariant under rotations about Z and any translation.
        let qz = DQuat::from_rotation_z(rng.uniform(-3.0, 3.0));
        let b1 = rng.vec(1.0);
        let glue_x = [
            b1 + DVec3::new(-0.2, 1.0, 0.3),
            b1,
            b1 + DVec3::new(0.4, 0.1, 0.0),
            b1 + DVec3::new(0.5, 1.2, -0.2),
        ];
        worst = worst.max(potential_invariance(&Glue::new(), &glue_x, qz, t));
    }
    println!("worst rigid-motion discrepancy {worst:.2e}");
    assert!(worst <= 1e-10, "rigid motion changed a term by {worst:e}");
}
