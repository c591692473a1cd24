//! The older `[solver]` keys (issue 21's resolution, precision, Newton tolerance, constraint
//! Hessian, collision rounds, projection; [`crate::legacy`]) and the frame-time limit on
//! the time step: each still reaches the settings every caller builds at its new key, and
//! each refusal sits at the key the file wrote, in the new key's name.

use folio_book::BookSettings;

use super::{Precision, Scene, SceneError};
use crate::builtin;
use crate::settings::{book_settings, spring_settings, xpbd_settings};

/// The built-in scene `name` with `[solver]` and `line` appended, and the line of `line`.
fn with_solver(name: &str, line: &str) -> (String, usize) {
    let base = builtin::scene(name).expect("a built-in scene");
    let text = format!("{}\n[solver]\n{line}\n", base.trim_end());
    (text, base.trim_end().lines().count() + 2)
}

fn refused(name: &str, line: &str) -> (SceneError, usize) {
    let (text, at) = with_solver(name, line);
    let e = Scene::parse(&text).expect_err(&format!("refused: {line}"));
    (e, at)
}

/// Refused at the value of `line` (`key = value`), with a message that has `says`.
fn refused_at_value(name: &str, line: &str, says: &str) {
    let (e, at) = refused(name, line);
    let column = line.find('=').expect("key = value") + 3;
    assert_eq!((e.line, e.column), (at, column), "{line}: {e}");
    assert!(e.message.contains(says), "{line}: {e}");
}

#[test]
fn every_dog_key_reaches_the_book_settings() {
    let keys = "grid = [10, 14]\nprecision = \"f32\"\nnewton_iterations = 3\n\
                newton_tolerance = 1e-5\nconstraint_hessian = true\ncollision_rounds = 5\n\
                krylov_restart = 4\nprojection = false";
    let (text, _) = with_solver("page-turn", keys);
    let scene = Scene::parse(&text).expect("checks");
    assert_eq!(scene.precision(), Precision::F32);
    let s = book_settings::<f32>(&scene).expect("reads");
    let defaults = BookSettings::<f32>::default();
    assert_eq!((s.quads_across, s.quads_along), (10, 14));
    assert_eq!(s.solver.newton_iterations, 3);
    assert_eq!(s.solver.tolerance, 1e-5);
    assert!(s.solver.constraint_hessian && !defaults.solver.constraint_hessian);
    assert_eq!(s.collision_rounds, 5);
    assert_eq!(s.solver.krylov_restart, 4);
    assert_eq!(
        (s.projection_iterations, defaults.projection_iterations),
        (0, 3)
    );
    // At one step per frame the step counts are the book's own.
    assert_eq!(s.merge_frames, defaults.merge_frames);
    let kept = with_solver("page-turn", "projection = true\nmax_corrections = 7").0;
    let s = book_settings::<f64>(&Scene::parse(&kept).expect("checks")).expect("reads");
    assert_eq!(s.projection_iterations, 7);
}

/// More than one Newton iteration refines the linear solves to eps^(3/4); one keeps the
/// book's sqrt(eps).
#[test]
fn newton_iterations_bring_the_refinement_they_need() {
    let tolerance = |line: &str| {
        let (text, _) = with_solver("page-turn", line);
        book_settings::<f64>(&Scene::parse(&text).expect("checks"))
            .expect("reads")
            .solver
            .refinement_tolerance
    };
    let (many, one) = (
        tolerance("newton_iterations = 4"),
        tolerance("newton_iterations = 1"),
    );
    assert!(
        (many / f64::EPSILON.powf(0.75) - 1.0).abs() < 1e-12,
        "{many}"
    );
    assert!((one / f64::EPSILON.sqrt() - 1.0).abs() < 1e-12, "{one}");
}

#[test]
fn step_counts_of_the_book_keep_their_time() {
    let (text, _) = with_solver("page-turn", "time_step = 0.004166666666666667");
    let s = book_settings::<f64>(&Scene::parse(&text).expect("checks")).expect("reads");
    let d = BookSettings::<f64>::default();
    assert_eq!(s.merge_frames, 4 * d.merge_frames);
    assert_eq!(s.flip_frames, 4 * d.flip_frames);
    assert_eq!(s.history_interval, 4 * d.history_interval);
}

#[test]
fn the_grid_and_precision_reach_the_page_models() {
    let (text, _) = with_solver("mass-spring-turn", "grid = [6, 9]\nprecision = \"f32\"");
    let scene = Scene::parse(&text).expect("checks");
    assert_eq!(scene.precision(), Precision::F32);
    let s = spring_settings::<f32>(&scene, false).expect("reads");
    assert_eq!((s.particles_across, s.particles_along), (7, 10));
    // The same page: its mass shared by 70 particles instead of 108.
    let d = folio_pages::spring::SpringSettings::<f32>::default();
    let mass = |s: &folio_pages::spring::SpringSettings<f32>| {
        s.particle_mass * (s.particles_across * s.particles_along) as f32
    };
    assert!((mass(&s) - mass(&d)).abs() < 1e-6 * mass(&d));
    assert_eq!(s.stretch_stiffness, d.stretch_stiffness);
    let (text, _) = with_solver("mass-spring-turn", "integrator = \"implicit-euler\"");
    let scene = Scene::parse(&text).expect("checks");
    assert_eq!(
        spring_settings::<f64>(&scene, false)
            .expect("reads")
            .integrator,
        folio_pages::spring::Integrator::ImplicitEuler
    );
    let (text, _) = with_solver("xpbd-turn", "grid = [5, 7]");
    let scene = Scene::parse(&text).expect("checks");
    assert_eq!(scene.precision(), Precision::F64);
    let s = xpbd_settings::<f64>(&scene, false).expect("reads");
    assert_eq!((s.quads_across, s.quads_along), (5, 7));
}

#[test]
fn a_key_out_of_range_is_refused_at_its_value() {
    // The model's own range, in the new key's name.
    refused_at_value(
        "page-turn",
        "grid = [1, 10]",
        "`book.quads_across` must be at least 2",
    );
    refused_at_value(
        "page-turn",
        "grid = [10, 1]",
        "`book.quads_along` must be at least 2",
    );
    refused_at_value("xpbd-turn", "grid = [0, 3]", "`xpbd.quads_across` must be");
    // The older key's own range, for the mass-spring page's particles.
    refused_at_value(
        "mass-spring-turn",
        "grid = [6, 65]",
        "each between 2 and 64",
    );
    for t in [
        "newton_tolerance = nan",
        "newton_tolerance = -1e-3",
        "newton_tolerance = inf",
    ] {
        refused_at_value(
            "page-turn",
            t,
            "`book.solver.tolerance` must be finite and >= 0",
        );
    }
    for n in ["collision_rounds = 0", "collision_rounds = 17"] {
        refused_at_value("page-turn", n, "`book.collision_rounds` must be in [1, 16]");
    }
    for n in ["krylov_restart = 0", "krylov_restart = 51"] {
        refused_at_value(
            "page-turn",
            n,
            "`book.solver.krylov_restart` must be in [1, 50]",
        );
    }
    refused_at_value("page-turn", "time_step = 0.02", "at most one frame");
    refused_at_value("mass-spring-turn", "time_step = 0.05", "at most one frame");
    refused_at_value("page-turn", "time_step = 1e308", "at most one frame");
    refused_at_value(
        "page-turn",
        "time_step = nan",
        "`book.solver.time_step` must be in [1e-6, 0.1] seconds, not NaN",
    );
    refused_at_value(
        "page-turn",
        "time_step = 1e-7",
        "`book.solver.time_step` must be in [1e-6, 0.1] seconds, not 1e-7",
    );
    // A precision that does not exist is a serde error at the value.
    let (e, at) = refused("page-turn", "precision = \"f16\"");
    assert_eq!((e.line, e.column), (at, 13), "{e}");
    assert!(
        e.message.contains("f64") && e.message.contains("f32"),
        "{e}"
    );
}

#[test]
fn a_key_for_another_model_is_refused_at_its_value() {
    let dog_only = [
        "newton_tolerance = 1e-6",
        "constraint_hessian = true",
        "collision_rounds = 2",
        "krylov_restart = 3",
        "projection = true",
    ];
    for key in dog_only {
        refused_at_value("xpbd-turn", key, "is for model = \"dog\" only");
        refused_at_value("mass-spring-turn", key, "is for model = \"dog\" only");
    }
    refused_at_value(
        "xpbd-turn",
        "integrator = \"implicit-euler\"",
        "is for model = \"mass-spring\" only",
    );
    refused_at_value("tear-straight", "grid = [8, 6]", "sheet.nx and sheet.ny");
    refused_at_value(
        "tear-straight",
        "precision = \"f32\"",
        "a sheet scene runs in f64",
    );
    let (text, _) = with_solver("tear-straight", "precision = \"f64\"");
    Scene::parse(&text).expect("f64 is the sheet's precision");
    // The cone has no [solver] at all: refused at the table.
    let (e, at) = refused("cone-turn", "grid = [8, 6]");
    assert_eq!((e.line, e.column), (at - 1, 1), "{e}");
    assert!(e.message.contains("[solver] is for"), "{e}");
}

#[test]
fn projection_and_max_corrections_must_agree() {
    let (e, at) = refused("page-turn", "projection = false\nmax_corrections = 2");
    assert_eq!((e.line, e.column), (at, 14), "{e}");
    assert!(e.message.contains("leave out"), "{e}");
    let (e, at) = refused("page-turn", "projection = true\nmax_corrections = 0");
    assert_eq!((e.line, e.column), (at, 14), "{e}");
    assert!(e.message.contains("at least 1"), "{e}");
    let (text, _) = with_solver("page-turn", "projection = false\nmax_corrections = 0");
    Scene::parse(&text).expect("agree");
}
