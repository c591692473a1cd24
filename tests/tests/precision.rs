//! f32 results agree with f64 (every term, values and all derivatives) within a stated
//! tolerance: the max-norm gap relative to the f64 output's scale (floored at 1) is at most
//! `F32_TOL`.

use folio_kernels::hinge::Hinge;
use folio_kernels::membrane::Membrane;
use folio_kernels::term::NodeVecs;
use folio_kernels::{Potential, Real};
use folio_tests::terms::{Terms, evaluate_all};
use folio_tests::{INNER_DIRS, Rng, flat_blocks, flat_vecs, jittered_star, precision_gap, to_f32};

/// Stated f32-vs-f64 tolerance (relative to output scale).
const F32_TOL: f64 = 1e-4;

#[test]
fn f32_agrees_with_f64_for_every_term() {
    let mut rng = Rng::new(41);
    let mut worst: Vec<(&str, f64)> = Vec::new();
    for _ in 0..200 {
        let params: Vec<f64> = (0..12).map(|_| rng.uniform(0.5, 1.5)).collect();
        let x = jittered_star(&mut rng, INNER_DIRS, 0.5);
        let lambda: Vec<f64> = (0..3).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let lambda32: Vec<f32> = lambda.iter().map(|&l| l as f32).collect();
        let r64 = evaluate_all(&Terms::<f64>::new(&params), &x, &lambda);
        let r32 = evaluate_all(&Terms::<f32>::new(&params), &to_f32(&x), &lambda32);
        for (k, ((name, o64), (_, o32))) in r64.iter().zip(&r32).enumerate() {
            let gap = o64
                .iter()
                .zip(o32)
                .map(|(a, b)| {
                    let b32: Vec<f32> = b.iter().map(|&v| v as f32).collect();
                    folio_tests::precision_gap(&b32, a)
                })
                .fold(0.0, folio_tests::worst);
            if worst.len() <= k {
                worst.push((name, 0.0));
            }
            worst[k].1 = folio_tests::worst(worst[k].1, gap);
        }
    }
    for (name, gap) in &worst {
        println!("{name:<24} f32 vs f64 gap {gap:9.2e}");
    }
    for (name, gap) in &worst {
        assert!(*gap <= F32_TOL, "{name}: f32 gap {gap:e} > {F32_TOL:e}");
    }
}

/// Value, gradient and Hessian of a potential, flattened into `f64`s.
fn outputs<T: Real, P: Potential<T, N>, const N: usize>(p: &P, x: &NodeVecs<T, N>) -> Vec<f64> {
    [
        vec![p.value(x).to_f64()],
        flat_vecs::<T, N>(&p.gradient(x)),
        flat_blocks::<T, N>(&p.hessian(x)),
    ]
    .concat()
}

fn gap(o32: &[f64], o64: &[f64]) -> f64 {
    let o32: Vec<f32> = o32.iter().map(|&v| v as f32).collect();
    precision_gap(&o32, o64)
}

#[test]
fn membrane_and_hinge_f32_agree_with_f64() {
    let mut rng = Rng::new(42);
    let (mut membrane, mut projected, mut hinge) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..200 {
        // A well-shaped pattern quad: edge (u0, u1) along X, u2 above, u3 below, jittered.
        let mut j = || rng.uniform(-0.15, 0.15);
        let u = [
            [j(), j()],
            [1.0 + j(), j()],
            [0.4 + j(), 0.9 + j()],
            [0.6 + j(), -0.8 + j()],
        ];
        let u32 = u.map(|p| p.map(|c| c as f32));
        let (y, nu) = (rng.uniform(0.5, 2.0), rng.uniform(0.0, 0.45));
        let q = rng.rotation();
        let x: NodeVecs<f64, 4> = u.map(|p| q * glam::DVec3::new(p[0], p[1], 0.0) + rng.vec(0.3));
        let x3: NodeVecs<f64, 3> = [x[0], x[1], x[2]];
        let m64 = Membrane::new([u[0], u[1], u[2]], y, nu).unwrap();
        let m32 = Membrane::new([u32[0], u32[1], u32[2]], y as f32, nu as f32).unwrap();
        membrane = folio_tests::worst(
            membrane,
            gap(&outputs(&m32, &to_f32(&x3)), &outputs(&m64, &x3)),
        );
        projected = folio_tests::worst(
            projected,
            gap(
                &flat_blocks::<f32, 3>(&m32.hessian_projected(&to_f32(&x3))),
                &flat_blocks::<f64, 3>(&m64.hessian_projected(&x3)),
            ),
        );
        let (h64, h32) = (Hinge::new(u).unwrap(), Hinge::new(u32).unwrap());
        hinge = folio_tests::worst(hinge, gap(&outputs(&h32, &to_f32(&x)), &outputs(&h64, &x)));
    }
    for (name, g) in [
        ("membrane", membrane),
        ("membrane projected", projected),
        ("hinge", hinge),
    ] {
        println!("{name:<24} f32 vs f64 gap {g:9.2e}");
        assert!(g <= F32_TOL, "{name}: f32 gap {g:e} > {F32_TOL:e}");
    }
}
