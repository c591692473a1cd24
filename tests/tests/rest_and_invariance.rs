//! Zero at rest and invariance under rigid motion, for every term where it holds, and the
//! closed-form energies of the sheet terms (membrane under plane-stress uniaxial tension,
//! hinge under an isometric fold).

use folio_kernels::binding::Binding;
use folio_kernels::dog::{DogBoundaryStar, DogInnerStar};
use folio_kernels::fix::Fix;
use folio_kernels::glue::Glue;
use folio_kernels::hinge::Hinge;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::membrane::{Membrane, MembraneLaw};
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
    folio_tests::worst(folio_tests::worst(value, grad), hess)
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
    folio_tests::worst(folio_tests::worst(value, rel_err(&jy, &jx)), hess)
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
        worst = folio_tests::worst(
            worst,
            constraint_invariance(&DogInnerStar::new(), &s5, q, t),
        );
        worst = folio_tests::worst(
            worst,
            constraint_invariance(&DogBoundaryStar::new(), &s4, q, t),
        );
        worst = folio_tests::worst(
            worst,
            constraint_invariance(&Iso2d::new(1.1).unwrap(), &pair, q, t),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(
                &dog_laplacian::inner([0.9, 1.1, 1.0, 0.8]).unwrap(),
                &s5,
                q,
                t,
            ),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(&dog_laplacian::boundary([0.9, 1.2]).unwrap(), &s3, q, t),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(&curve_laplacian::new([0.7, 1.3]).unwrap(), &s3, q, t),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(&Iso3d::new(1.2).unwrap(), &pair, q, t),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(
                &Spring::new(SpringKind::Shear.rest_length(1.0), 2.0).unwrap(),
                &pair,
                q,
                t,
            ),
        );
        // The glue lives in the XY plane: invariant under rotations about Z and any translation.
        let qz = DQuat::from_rotation_z(rng.uniform(-3.0, 3.0));
        let b1 = rng.vec(1.0);
        let glue_x = [
            b1 + DVec3::new(-0.2, 1.0, 0.3),
            b1,
            b1 + DVec3::new(0.4, 0.1, 0.0),
            b1 + DVec3::new(0.5, 1.2, -0.2),
        ];
        worst = folio_tests::worst(worst, potential_invariance(&Glue::new(), &glue_x, qz, t));
    }
    println!("worst rigid-motion discrepancy {worst:.2e}");
    assert!(worst <= 1e-10, "rigid motion changed a term by {worst:e}");
}

/// A random counter-clockwise pattern triangle with $2A \ge 0.2\thinspace\ell_{\max}^2$.
fn pattern_triangle(r: &mut Rng) -> [[f64; 2]; 3] {
    folio_tests::pattern_triangle(r, 0.2, 0.1)
}

/// A random hinge pattern: the triangle `[u0, u1, u2]` and `u3` on the other side of the
/// edge `(u0, u1)`, both triangles with $2A \ge 0.2\thinspace\ell_{\max}^2$.
fn pattern_hinge(r: &mut Rng) -> [[f64; 2]; 4] {
    loop {
        let [u0, u1, u2] = pattern_triangle(r);
        let u3 = [r.uniform(-3.0, 3.0), r.uniform(-3.0, 3.0)];
        let (area2, longest) = folio_tests::area2_and_longest([u1, u0, u3]);
        if area2 >= 0.2 * longest {
            return [u0, u1, u2, u3];
        }
    }
}

/// The pattern embedded in the plane Z = 0.
fn embed<const N: usize>(u: &[[f64; 2]; N]) -> NodeVecs<f64, N> {
    u.map(|p| DVec3::new(p[0], p[1], 0.0))
}

#[test]
fn membrane_and_hinge_vanish_at_rest() {
    let mut rng = Rng::new(54);
    for _ in 0..200 {
        let (q, t) = (rng.rotation(), rng.vec(3.0));
        let u = pattern_triangle(&mut rng);
        let m = Membrane::new(u, rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.49)).unwrap();
        assert_potential_at_rest("membrane", &m, &rigid(&embed(&u), q, t));
        let h = pattern_hinge(&mut rng);
        assert_potential_at_rest("hinge", &Hinge::new(h).unwrap(), &rigid(&embed(&h), q, t));
    }
}

#[test]
fn hinge_vanishes_on_affine_images_of_the_pattern() {
    // sum K_i = 0 and sum K_i u_i = 0: any x_i = M u_i + t (M 3x2) has zero bending, including
    // in-plane stretches and shears, which bend nothing.
    let mut rng = Rng::new(55);
    for _ in 0..200 {
        let u = pattern_hinge(&mut rng);
        let hinge = Hinge::new(u).unwrap();
        let (c0, c1, t) = (rng.vec(2.0), rng.vec(2.0), rng.vec(3.0));
        let x = u.map(|p| c0 * p[0] + c1 * p[1] + t);
        let s = hinge.apply(&x).length();
        let scale: f64 = hinge
            .stencil
            .iter()
            .zip(&x)
            .map(|(k, p)| k.abs() * p.length())
            .sum();
        assert!(s <= 1e-14 * scale, "hinge stencil {s:e} on an affine image");
    }
}

/// A hinge that takes its normal from the configuration it is evaluated at, as the sheet
/// does at the start of each step ([`Hinge::orient`]).
struct Oriented(Hinge<f64>);

impl Oriented {
    fn at(&self, x: &NodeVecs<f64, 4>) -> Hinge<f64> {
        let mut h = self.0;
        h.orient(x);
        h
    }
}

impl Potential<f64, 4> for Oriented {
    fn value(&self, x: &NodeVecs<f64, 4>) -> f64 {
        self.at(x).value(x)
    }
    fn gradient(&self, x: &NodeVecs<f64, 4>) -> NodeVecs<f64, 4> {
        self.at(x).gradient(x)
    }
    fn hessian(&self, x: &NodeVecs<f64, 4>) -> folio_kernels::term::Blocks<f64, 4> {
        self.at(x).hessian(x)
    }
}

/// With a normal ([`Hinge::orient`]), the sheet's in-plane deformations that are not affine
/// (a smooth bend of the pattern within its own plane) bend nothing: the hinge counts only
/// $s$ along its normal. (The stencil itself, $s$, is not zero there: it is the in-plane
/// cotangent Laplacian, which the paper's energy counts.)
#[test]
fn hinge_ignores_in_plane_deformation() {
    let mut rng = Rng::new(59);
    let mut largest_stencil: f64 = 0.0;
    for _ in 0..200 {
        let u = pattern_hinge(&mut rng);
        let hinge = Oriented(Hinge::new(u).unwrap());
        let (a, b) = (rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05));
        let x = u.map(|p| DVec3::new(p[0] + a * p[1] * p[1], p[1] + b * p[0] * p[0], 0.0));
        let (q, t) = (rng.rotation(), rng.vec(3.0));
        let moved = rigid(&x, q, t);
        largest_stencil = largest_stencil.max(hinge.0.apply(&x).length());
        let v = hinge.value(&moved);
        assert!(
            v.abs() <= 1e-24,
            "in-plane deformation bent the hinge: {v:e}"
        );
        assert!(hinge.0.value(&moved) > 0.0 || hinge.0.apply(&x).length() < 1e-9);
    }
    assert!(
        largest_stencil > 1e-3,
        "the in-plane cases were affine: {largest_stencil}"
    );
}

#[test]
fn hinge_fold_energy_matches_the_dihedral_angle() {
    let mut rng = Rng::new(56);
    for _ in 0..200 {
        let u = pattern_hinge(&mut rng);
        let hinge = Hinge::new(u).unwrap();
        let folds_only = Oriented(hinge);
        let (area_a, _) = folio_tests::area2_and_longest([u[0], u[1], u[2]]);
        let (area_b, _) = folio_tests::area2_and_longest([u[1], u[0], u[3]]);
        let (area_a, area_b) = (area_a / 2.0, area_b / 2.0);
        let flat = embed(&u);
        let edge = flat[1] - flat[0];
        let fold = |theta: f64| {
            // Turn triangle b about the edge: an isometry of the sheet.
            let turn = DQuat::from_axis_angle(edge.normalize(), theta);
            let mut x = flat;
            x[3] = flat[0] + turn * (flat[3] - flat[0]);
            x
        };
        let (q, t) = (rng.rotation(), rng.vec(3.0));
        let theta = rng.uniform(-3.1, 3.1);
        let v = hinge.value(&rigid(&fold(theta), q, t));
        let v_folds = folds_only.value(&rigid(&fold(theta), q, t));
        let expected =
            12.0 * edge.length_squared() * (theta / 2.0).sin().powi(2) / (area_a + area_b);
        assert!(
            (v - expected).abs() <= 1e-12 * expected.max(1e-3),
            "fold by {theta}: energy {v} vs {expected}"
        );
        assert!(v > 0.0, "a fold by {theta} must cost energy");
        assert!(
            (v_folds - expected).abs() <= 1e-12 * expected.max(1e-3),
            "folds only, fold by {theta}: energy {v_folds} vs {expected}"
        );
        // Small angles: quadratic in theta, V / theta^2 -> 3 |e|^2 / (A_a + A_b).
        let small = 1e-4;
        let ratio = hinge.value(&fold(small)) / small.powi(2);
        let limit = 3.0 * edge.length_squared() / (area_a + area_b);
        assert!(
            (ratio / limit - 1.0).abs() <= 1e-6,
            "V/theta^2 = {ratio} vs {limit}"
        );
        let quarter = hinge.value(&fold(small / 2.0)) / hinge.value(&fold(small));
        assert!(
            (quarter - 0.25).abs() <= 1e-6,
            "halving theta scaled V by {quarter}"
        );
    }
}

#[test]
fn membrane_uniaxial_plane_stress() {
    // E = diag(eps, -nu eps) in the pattern frame has plane stress S = diag(Y eps, 0): energy
    // A0 Y eps^2 / 2 and no force across the stretch (this fixes the plane-stress Lame pair).
    let mut rng = Rng::new(57);
    for _ in 0..200 {
        let u = pattern_triangle(&mut rng);
        let (y, nu, eps) = (
            rng.uniform(0.5, 3.0),
            rng.uniform(0.0, 0.49),
            rng.uniform(-0.2, 0.3),
        );
        let m = Membrane::new(u, y, nu).unwrap();
        let (sx, sy) = ((1.0 + 2.0 * eps).sqrt(), (1.0 - 2.0 * nu * eps).sqrt());
        let (q, t) = (rng.rotation(), rng.vec(3.0));
        let x = rigid(&u.map(|p| DVec3::new(sx * p[0], sy * p[1], 0.0)), q, t);
        let area = folio_tests::area2_and_longest(u).0 / 2.0;
        let expected = area * y * eps * eps / 2.0;
        let v = m.value(&x);
        assert!(
            (v - expected).abs() <= 1e-12 * expected.max(1e-6),
            "uniaxial energy {v} vs {expected}"
        );
        // Forces at unit strain are of order Y A0 |D_m^-1|.
        let unit_force = y
            * area
            * m.dm_inv
                .iter()
                .flatten()
                .fold(0.0_f64, |a, b| folio_tests::worst(a, b.abs()));
        let lateral = q * DVec3::Y;
        for g in m.gradient(&x) {
            let across = g.dot(lateral);
            assert!(
                across.abs() <= 1e-13 * unit_force,
                "lateral force {across:e} (force {g:?}, scale {unit_force:e})"
            );
        }
    }
}

/// Wagner's tension field (Mansfield, *The Bending and Stretching of Plates*, 2nd ed. 1989,
/// ch. 9): a membrane in simple shear $\gamma$ that cannot carry compression wrinkles at 45°
/// and carries the shear as a uniaxial tension $Y\gamma/2$ along the other diagonal, so its
/// shear stiffness is $Y/4$, not the elastic $\mu = Y/(2(1+\nu))$: the energy per area is
/// $Y\gamma^2/8$. Checked at a small shear on random triangles in random frames.
#[test]
fn tension_field_membrane_shears_with_wagner_stiffness() {
    let mut rng = Rng::new(58);
    let gamma: f64 = 1e-4;
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let u = pattern_triangle(&mut rng);
        let (y, nu) = (rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.49));
        let m = Membrane::new(u, y, nu)
            .unwrap()
            .with_law(MembraneLaw::TensionField);
        // Simple shear along a random pattern direction d: p -> p + gamma (p . n) d.
        let phi = rng.uniform(-3.2, 3.2);
        let (d, n) = ([phi.cos(), phi.sin()], [-phi.sin(), phi.cos()]);
        let sheared = u.map(|p| {
            let s = gamma * (p[0] * n[0] + p[1] * n[1]);
            DVec3::new(p[0] + s * d[0], p[1] + s * d[1], 0.0)
        });
        let x = rigid(&sheared, rng.rotation(), rng.vec(3.0));
        let area = folio_tests::area2_and_longest(u).0 / 2.0;
        let wagner = area * y * gamma * gamma / 8.0;
        // The Green strain's principal values are +-gamma/2 + gamma^2/4: relative O(gamma).
        worst = worst.max((m.value(&x) - wagner).abs() / wagner);
        let elastic = Membrane::new(u, y, nu).unwrap().value(&x);
        let ratio = m.value(&x) / elastic;
        assert!(
            (ratio - (1.0 + nu) / 2.0).abs() <= 1e-3,
            "tension field / elastic shear energy {ratio} for nu {nu}"
        );
    }
    println!(
        "tension-field shear against Wagner's Y gamma^2 / 8: worst relative error {worst:.2e}"
    );
    assert!(worst <= 1e-3, "{worst}");
}

#[test]
fn membrane_and_hinge_are_invariant_under_rigid_motion() {
    let mut rng = Rng::new(58);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (q, t) = (rng.rotation(), rng.vec(10.0));
        let u = pattern_triangle(&mut rng);
        let m = Membrane::new(u, rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.49)).unwrap();
        let x = rigid(&embed(&u), rng.rotation(), rng.vec(2.0)).map(|p| p * 1.1 + rng.vec(0.3));
        worst = folio_tests::worst(worst, potential_invariance(&m, &x, q, t));
        let h = pattern_hinge(&mut rng);
        let x4 = rigid(&embed(&h), rng.rotation(), rng.vec(2.0)).map(|p| p + rng.vec(0.5));
        worst = folio_tests::worst(
            worst,
            potential_invariance(&Hinge::new(h).unwrap(), &x4, q, t),
        );
        worst = folio_tests::worst(
            worst,
            potential_invariance(&Oriented(Hinge::new(h).unwrap()), &x4, q, t),
        );
    }
    println!("worst rigid-motion discrepancy (sheet terms) {worst:.2e}");
    assert!(
        worst <= 1e-10,
        "rigid motion changed a sheet term by {worst:e}"
    );
}
