//! The small atlas CI runs: a short page turn of the DOG book and six variants against the
//! converged implicit-Euler step on the scene's own grid and time step (Newton to a KKT
//! residual of 1e-10), so that it takes seconds in a test build. No timed assertion: only
//! what the errors must show.

use super::variants::{self, Knobs, Variant};
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

/// A DOG variant with `knobs`.
fn dog(knobs: Knobs) -> Variant {
    knobs.variant("dog")
}

/// The converged implicit-Euler step on the scene's grid and time step: Newton with the
/// constraint Hessian to a KKT residual of 1e-10.
fn newton_reference() -> Variant {
    dog(Knobs {
        newton: Some(20),
        tolerance: Some(1e-10),
        hessian: true,
        ..Knobs::default()
    })
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
fn the_small_atlas_measures_newton_against_the_converged_step() {
    let scene = Scene::parse(SHORT_TURN).expect("the short turn checks");
    let reference = newton_reference();
    // Six of the declared variants.
    let wanted = [
        "dog default",
        "dog newton 2",
        "dog hessian",
        "dog f32",
        "dog 6x8",
        "dog 12x16",
    ];
    let variants: Vec<Variant> = variants::declared("dog")
        .into_iter()
        .filter(|v| wanted.contains(&v.label.as_str()))
        .collect();
    assert_eq!(variants.len(), wanted.len());
    // The reference measured against a second run of itself is exactly 0 (a run is
    // deterministic).
    let atlas = measure(
        &scene,
        SHORT_TURN,
        &reference,
        Some(&reference),
        &variants,
        |_, _| {},
    )
    .expect("the atlas runs");
    print!("{}", table::markdown(&atlas));
    let itself = atlas.proof.refinement.expect("the second run");
    assert_eq!(
        (itself.rms_worst, itself.max_worst, itself.unmatched),
        (0.0, 0.0, 0),
        "{itself:?}"
    );
    assert!(
        itself.frames > 140,
        "every frame from the grab on is compared: {itself:?}"
    );
    for row in &atlas.variants {
        assert!(row.refused.is_none(), "{row:?}");
        let e = row.errors.expect("errors");
        assert!(e.rms_mean.is_finite() && e.rms_mean > 0.0, "{row:?}");
    }
    // Two Newton iterations are no worse than one (measured: 3.7 % against 9.9 % of the
    // page width).
    let one = error_of(&atlas, "dog default");
    let two = error_of(&atlas, "dog newton 2");
    assert!(two <= one, "newton 2 {two} against newton 1 {one}");
    assert!(atlas.variants.iter().any(|r| r.pareto));
}

/// A finer grid closer to the reference than a coarser one: what the issue asks of the
/// atlas, and what the DOG book does not do yet (`docs/accuracy.md`, "Resolution"): on
/// this turn, against a 16 x 22 reference at two steps a frame with Newton to 1e-10, the
/// 6 x 8, 8 x 11 and 12 x 16 pages are 11.8, 10.7 and 14.2 % of the page width away, and
/// the grids 6 x 8, 12 x 16, 24 x 32 move by 12.9 % then 10.0 % (observed order 0.37).
#[test]
#[ignore = "fails: the DOG book does not converge with the grid on a page turn (docs/accuracy.md)"]
fn a_finer_grid_is_closer_to_the_reference() {
    let scene = Scene::parse(SHORT_TURN).expect("the short turn checks");
    let mut reference = variants::reference(false);
    for (key, value) in &mut reference.keys {
        match key.as_str() {
            "book.quads_across" => *value = 16.into(),
            "book.quads_along" => *value = 22.into(),
            _ => {}
        }
    }
    let grids = [[6, 8], [8, 11], [12, 16]].map(|g| variants::on_grid("dog", g));
    let atlas =
        measure(&scene, SHORT_TURN, &reference, None, &grids, |_, _| {}).expect("the atlas runs");
    let e: Vec<f64> = grids.iter().map(|v| error_of(&atlas, &v.label)).collect();
    let c = convergence(&scene, SHORT_TURN, &[[6, 8], [12, 16], [24, 32]]).expect("runs");
    println!("errors {e:?}; observed order {:.2}: {c:?}", c.order);
    assert!(e[2] < e[1] && e[1] < e[0], "{e:?}");
    assert!(c.order > 0.5, "{c:?}");
}

/// The `f32` page against the `f64` page over the whole default turn (the built-in
/// `page-turn`, 750 frames), at the same material points and times: 0.74 % of the page
/// width on average over the frames, 8.3 % at the worst frame (tip: 3.7 % RMS).
fn f32_against_f64() -> Errors {
    let text = folio_scene::builtin::scene("page-turn").expect("built in");
    let scene = Scene::parse(text).expect("checks");
    let f64_page = dog(Knobs::default());
    let f32_page = dog(Knobs {
        f32: true,
        ..Knobs::default()
    });
    let atlas = measure(&scene, text, &f64_page, None, &[f32_page], |_, _| {}).expect("runs");
    let e = atlas.variants[0].errors.expect("measured");
    println!(
        "f32 against f64 over the page turn: RMS mean {:.2} %, worst frame {:.2} %, tip RMS {:.2} % of the page width",
        100.0 * e.rms_mean,
        100.0 * e.rms_worst,
        100.0 * e.tip_rms
    );
    assert!(atlas.variants[0].good, "{:?}", atlas.variants[0]);
    e
}

#[test]
fn the_f32_page_stays_near_the_f64_page_on_average() {
    let e = f32_against_f64();
    assert!(e.rms_mean < 0.05, "{e:?}");
}

/// The issue's bound: every frame within 5 % of the page width.
#[test]
#[ignore = "fails: the worst frame of the default turn is 8.3 % of the page width apart (docs/accuracy.md)"]
fn the_f32_page_stays_within_five_percent_of_the_f64_page_at_every_frame() {
    let e = f32_against_f64();
    assert!(e.rms_worst < 0.05, "{e:?}");
}

/// `folio atlas` runs on every built-in page scene: each of its variants, the reference and
/// the refined reference make a scene that checks.
#[test]
fn every_variant_of_every_built_in_page_scene_checks() {
    for (name, text) in folio_scene::builtin::SCENES {
        let scene = Scene::parse(text).expect("a built-in scene checks");
        if *scene.model.get_ref() == folio_scene::scene::ModelKind::Sheet {
            continue;
        }
        let table: toml::Table = toml::from_str(text).expect("TOML");
        let model = scene.model.get_ref().name();
        let all = variants::declared(model)
            .into_iter()
            .chain([variants::reference(false), variants::reference(true)])
            .chain(
                CONVERGENCE_GRIDS
                    .iter()
                    .filter(|_| model != "cone")
                    .map(|&g| variants::on_grid(model, g)),
            );
        for v in all {
            if let Err(e) = variant_scene(&scene, &table, &v) {
                panic!("{name}, {}: {e}", v.label);
            }
        }
    }
}

/// Every model's declared variants have distinct labels (the instruction counts find a
/// variant by its label) and include the DOG page at its defaults, so a page model's scene
/// compares the two at equal knobs.
#[test]
fn declared_variants_are_distinct_and_include_the_default_dog_page() {
    for model in ["dog", "cone", "mass-spring", "xpbd"] {
        let declared = variants::declared(model);
        let mut labels: Vec<&str> = declared.iter().map(|v| v.label.as_str()).collect();
        assert_eq!(labels[0], format!("{model} default"), "{labels:?}");
        assert!(labels.contains(&"dog default"), "{model}: {labels:?}");
        // Issue 42's Newton rows: 1 (the default), 2, 3 and 4 iterations, and Newton to
        // the tolerances 1e-3 and 1e-6.
        for row in [
            "dog newton 2, hessian",
            "dog newton 3, hessian",
            "dog newton 4, hessian",
            "dog newton 20, tol 1e-3, hessian",
            "dog newton 20, tol 1e-6, hessian",
        ] {
            assert!(labels.contains(&row), "{model}: no {row} in {labels:?}");
        }
        labels.sort_unstable();
        let n = labels.len();
        labels.dedup();
        assert_eq!(labels.len(), n, "{model}: a label twice");
    }
}
