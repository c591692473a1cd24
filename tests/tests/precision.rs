//! f32 results agree with f64 (every term, values and all derivatives) within a stated
//! tolerance: the max-norm gap relative to the f64 output's scale (floored at 1) is at most
//! `F32_TOL`.

use folio_tests::terms::{Terms, evaluate_all};
use folio_tests::{INNER_DIRS, Rng, jittered_star, to_f32};

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
                .fold(0.0, f64::max);
            if worst.len() <= k {
                worst.push((name, 0.0));
            }
            worst[k].1 = worst[k].1.max(gap);
        }
    }
    for (name, gap) in &worst {
        println!("{name:<24} f32 vs f64 gap {gap:9.2e}");
    }
    for (name, gap) in &worst {
        assert!(*gap <= F32_TOL, "{name}: f32 gap {gap:e} > {F32_TOL:e}");
    }
}
