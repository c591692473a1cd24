//! The run's own guards, below the scene check: scenes changed after they checked (as a
//! caller of `run` could), so that the run must report what the check would refuse.

use folio_scene::scene::Scene;

use super::run;

fn scene(text: &str) -> Scene {
    Scene::parse(text).expect("a scene")
}

/// A time step of 1e-300 once gave `NonFiniteInput` on every step (and the summary said 0
/// frames and passed, before it counted them; `health.rs` tests the count). The book now
/// holds its step to its own range: a run of a scene changed after it checked is refused
/// before its first frame, naming the field and the value.
#[test]
fn a_run_whose_book_refuses_its_settings_is_an_error() {
    let mut s = scene(
        "name = \"dt\"\nmodel = \"dog\"\nframes = 5\ninput = { fixture = \"page-turn\" }\n\
         [book.solver]\ntime_step = 0.01\n",
    );
    s.source = s.source.replace("time_step = 0.01", "time_step = 1e-300");
    let e = run(&s, |_, _| {}, |_, _, _| {}).expect_err("refused");
    assert!(
        e.0.contains("`solver.time_step` must be in [1e-6, 0.1] seconds, not 1e-300"),
        "{e:?}"
    );
}

/// A fixture's grab that misses the book (a book of 100000 pages puts the camera inside
/// it) is an input result of its frame: "grab at frame 30 missed the page", a bad run.
#[test]
fn a_grab_that_misses_is_reported_at_its_frame() {
    let mut s = scene(
        "name = \"miss\"\nmodel = \"dog\"\nframes = 32\ninput = { fixture = \"page-turn\" }\n\
         [book.params]\ntotal_pages = 100\n",
    );
    s.source = s
        .source
        .replace("total_pages = 100\n", "total_pages = 100000\n");
    let report = run(&s, |_, _| {}, |_, _, _| {}).expect("runs");
    assert_eq!(
        report.frames[30].inputs,
        ["grab at frame 30 missed the page"]
    );
    let h = &report.summary.health;
    assert_eq!(h.input_problems, 1);
    let first = h.first_bad.as_ref().expect("a bad frame");
    assert_eq!(first.frame, 30);
    assert_eq!(first.why, "grab at frame 30 missed the page");
    assert!(!report.good());
}

/// The built-in page turn with `[book.solver]` lines added before its `[expect]`.
fn page_turn_with(solver: &str) -> Scene {
    let base = folio_scene::builtin::scene("page-turn").expect("the page turn");
    let text = base.replace("[expect]", &format!("[book.solver]\n{solver}\n\n[expect]"));
    scene(&text)
}

/// Frames are in time: at `time_step = 1/120` the page turn runs its 750 frames of 1/60 s
/// in two steps each, and the page still lands on the left block (it played the gesture at
/// half speed, one step per frame).
#[test]
fn a_half_time_step_takes_two_steps_a_frame_and_turns_the_page() {
    let s = page_turn_with("time_step = 0.008333333333333333");
    let report = run(&s, |_, _| {}, |_, _, _| {}).expect("runs");
    assert_eq!(report.frames.len(), 750);
    assert!(report.frames.iter().all(|f| f.steps == 2));
    assert_eq!(report.summary.steps_total, 1500);
    assert_eq!(report.summary.final_pages, Some([51, 49, 0]));
    assert!(report.good(), "{:?}", report.summary.health);
    let plain = run(
        &scene(folio_scene::builtin::scene("page-turn").unwrap()),
        |_, _| {},
        |_, _, _| {},
    )
    .expect("runs");
    assert!(plain.frames.iter().all(|f| f.steps == 1));
    assert_eq!(plain.summary.final_pages, report.summary.final_pages);
}

/// `precision = "f32"` runs the book in `f32`: every frame finite, the page turns as in
/// `f64`, and the report names the precision.
#[test]
fn an_f32_page_turn_turns_the_page() {
    let base = folio_scene::builtin::scene("page-turn").expect("the page turn");
    let f32_turn = scene(&base.replace("[expect]", "precision = \"f32\"\n[expect]"));
    let report = run(&f32_turn, |_, _| {}, |_, _, _| {}).expect("runs");
    assert_eq!(report.precision, "f32");
    assert_eq!(report.frames.len(), 750);
    assert!(
        report
            .frames
            .iter()
            .all(|f| !f.nonfinite && !f.nonfinite_input && !f.failed)
    );
    assert_eq!(report.summary.final_pages, Some([51, 49, 0]));
    assert!(report.good(), "{:?}", report.summary.health);
}

/// The page models run in `f32` too, through the same loop: the XPBD page's built-in turn,
/// drawn through [`super::Shape`] (its mesh and its page points in `f64`).
#[test]
fn an_f32_page_model_runs_and_is_drawn() {
    let base = folio_scene::builtin::scene("xpbd-turn").expect("the xpbd turn");
    let text = base.replacen("\n[", "\nprecision = \"f32\"\n\n[", 1);
    let (mut meshes, mut points) = (0, Vec::new());
    let grid = folio_geometry::QuadGrid::new(4, 5).expect("a grid");
    let report = run(
        &scene(&text),
        |_, _| {},
        |_, _, shape| {
            let mut mesh = folio_geometry::mesh::TriMesh::new();
            meshes += usize::from(shape.mesh(&mut mesh).is_ok());
            assert!(shape.page_points(grid, &mut points));
        },
    )
    .expect("runs");
    assert_eq!(report.precision, "f32");
    assert_eq!(meshes, report.frames.len());
    assert_eq!(points.len(), grid.len());
    assert!(points.iter().flatten().all(|c| c.is_finite()));
    assert!(report.good(), "{:?}", report.summary.health);
}
