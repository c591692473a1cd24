//! The run's own guards, below the scene check: scenes changed after they checked (as a
//! caller of `run` could), so that the run must report what the check would refuse.

use folio_scene::scene::Scene;

use super::run;

fn scene(text: &str) -> Scene {
    Scene::parse(text).expect("a scene")
}

/// A time step of 1e-300 gives `NonFiniteInput` on every step: the summary counts every
/// frame as non-finite and the run is bad (it said 0 frames and passed).
#[test]
fn a_run_with_non_finite_input_counts_every_frame() {
    let mut s = scene(
        "name = \"dt\"\nmodel = \"dog\"\nframes = 5\ninput = { fixture = \"page-turn\" }\n\
         [solver]\ntime_step = 0.01\n",
    );
    let h = s
        .solver
        .as_mut()
        .and_then(|s| s.get_mut().time_step.as_mut());
    *h.expect("a time step").get_mut() = 1e-300;
    let report = run(&s, |_, _| {}, |_, _, _| {}).expect("runs");
    let summary = &report.summary;
    assert_eq!(summary.nonfinite_frames, 5);
    assert_eq!(summary.health.nonfinite_input_frames, 5);
    assert_eq!(summary.health.failed_steps, 5);
    assert_eq!(summary.status_counts.get("NonFiniteInput"), Some(&5));
    assert!(!report.good());
    assert_eq!(summary.health.first_bad.as_ref().map(|b| b.frame), Some(0));
}

/// A fixture's grab that misses the book (a book of 100000 pages puts the camera inside
/// it) is an input result of its frame: "grab at frame 30 missed the page", a bad run.
#[test]
fn a_grab_that_misses_is_reported_at_its_frame() {
    let mut s = scene(
        "name = \"miss\"\nmodel = \"dog\"\nframes = 32\ninput = { fixture = \"page-turn\" }\n\
         [book]\ntotal_pages = 100\n",
    );
    let book = s.book.as_mut().expect("a book").get_mut();
    (book.total_pages, book.left_pages) = (100_000, 50_000);
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
