//! The small atlas CI runs: a short page turn of the DOG book, six variants against a
//! reference that is cheaper than the command's (16 x 22, two steps a frame, Newton to
//! 1e-10), so that it takes seconds in a test build. No timed assertion: only what the
//! errors must show.

use super::variants::{self, Variant};
use super::*;

/// Grab near the fore-edge, swipe over the spine, let go; 2.5 s.
const SHORT_TURN: &str = r#"
name = "atlas-small"
model = "dog"
frames = 150

[[input.events]]
time = 0.1
grab = [11.0, 8.5]

[[input.events]]
time = 0.9
drag = [-5.0, 6.0, 8.5]

[[input.events]]
time = 1.5
drag = [-11.0, 0.5, 8.5]

[[input.events]]
time = 1.6
release = true
"#;

/// The test's reference: the DOG book in `f64`, 16 x 22, two steps a frame, Newton to a KKT
/// residual of 1e-10.
fn reference() -> Variant {
    let mut v = variants::reference(false);
    for (key, value) in &mut v.solver {
        if *key == "grid" {
            *value = toml::Value::Array(vec![16.into(), 22.into()]);
        }
    }
    v
}

fn error_of(atlas: &Atlas, label: &str) -> f64 {
    let row = atlas
        .variants
        .iter()
        .find(|r| r.label == label)
        .unwrap_or_else(|| panic!("no variant {label}"));
    assert!(row.good, "{label} is not a good run: {row:?}");
    row.errors.expect("measured").rms_mean
}

#[test]
fn the_small_atlas_orders_its_variants_as_accuracy_must() {
    let scene = Scene::parse(SHORT_TURN).expect("the short turn checks");
    let reference = reference();
    // The reference measured against itself (a second run of it) is exactly 0.
    let atlas = measure(
        &scene,
        SHORT_TURN,
        &reference,
        Some(&reference),
        &variants::small(),
        |_, _| {},
    )
    .expect("the atlas runs");
    let itself = atlas.proof.refinement.expect("the second run");
    assert_eq!((itself.rms_worst, itself.max_worst, itself.unmatched), (0.0, 0.0, 0), "{itself:?}");
    assert!(itself.frames > 100, "{itself:?}");
    for row in &atlas.variants {
        assert!(row.refused.is_none(), "{row:?}");
        let e = row.errors.expect("errors");
        assert!(e.rms_mean.is_finite() && e.rms_mean > 0.0, "{row:?}");
    }
    // A finer grid is closer to the reference than a coarser one.
    let coarse = error_of(&atlas, "dog 6x8");
    let default = error_of(&atlas, "dog default");
    let fine = error_of(&atlas, "dog 12x16");
    assert!(fine < default && default < coarse, "6x8 {coarse}, 8x11 {default}, 12x16 {fine}");
    // Two Newton iterations are no worse than one.
    let two = error_of(&atlas, "dog newton 2");
    assert!(two <= default, "newton 2 {two} against newton 1 {default}");
    // The Pareto front holds the default or something that beats it.
    assert!(atlas.variants.iter().any(|r| r.pareto));
}

#[test]
fn the_short_turn_converges_with_the_grid() {
    let scene = Scene::parse(SHORT_TURN).expect("the short turn checks");
    let c = convergence(&scene, SHORT_TURN, &[[6, 8], [12, 16], [24, 32]]).expect("runs");
    let [coarse, fine] = [c.differences[0], c.differences[1]];
    println!(
        "short turn: 6x8 to 12x16 {:.2} %, 12x16 to 24x32 {:.2} % of the page width (mean RMS); observed order {:.2}",
        100.0 * coarse.rms_mean,
        100.0 * fine.rms_mean,
        c.order
    );
    // Converging: each refinement moves the page less than the one before, at better than
    // first order.
    assert!(c.order > 1.0, "{c:?}");
    // The 12 x 16 page is within 3 % of the page width of the finer one, over the turn.
    assert!(fine.rms_mean < 0.03, "{c:?}");
}
