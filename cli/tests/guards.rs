//! The `folio` command's guards (issue 20, "a bad run says so"), run through the binary:
//! exit codes that tell a bad scene from a bad run, a summary and `report.json` that name
//! the first bad frame, every metric measured on timed events, nothing written outside the
//! output folder, bad UTF-8 placed, and progress on a run longer than a second.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;

use common::{folio, text};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    common::scratch("guards", name)
}

/// Writes `scene` to `dir/file` and runs it into `dir/out`.
fn run(dir: &Path, file: &str, scene: &[u8]) -> Output {
    std::fs::write(dir.join(file), scene).unwrap();
    folio(dir, &["run", file, "--out", "out"])
}

fn report(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("out/report.json")).unwrap()).unwrap()
}

/// One gesture on the DOG book by timed events: grab, carry over the spine, let go.
const EVENTS: &str = "[[input.events]]\nframe = 0\ngrab = [11.0, 8.0]\n[[input.events]]\n\
    frame = 30\ndrag = [0.0, 8.0, 8.0]\n[[input.events]]\nframe = 60\ndrag = [-11.0, 0.5, 8.0]\n\
    [[input.events]]\nframe = 70\nrelease = true\n";

const QUIET: &str = "[output]\ncontact_sheet = false\nanimation = false\ntimeline = false\n";

/// A bad scene file (1), bad arguments (2) and a bad run (3) have distinct exit codes; a
/// good run exits 0. The help lists them.
#[test]
fn exit_codes_tell_a_bad_scene_from_a_bad_run() {
    let dir = scratch("codes");
    let good = format!(
        "name = \"g\"\nmodel = \"cone\"\nframes = 20\ninput = {{ fixture = \"page-turn-touch\" }}\n{QUIET}"
    );
    assert_eq!(
        run(&dir, "good.toml", good.as_bytes()).status.code(),
        Some(0)
    );
    let bad_scene = good.replace("frames = 20", "frames = 0");
    assert_eq!(
        run(&dir, "bad.toml", bad_scene.as_bytes()).status.code(),
        Some(1)
    );
    assert_eq!(folio(&dir, &["run"]).status.code(), Some(2));
    // Every frame of the cone stretches a little: a bound of zero makes every frame bad.
    let bad_run = format!("{good}[expect]\nmax_stretch = 0.0\n");
    let out = run(&dir, "strict.toml", bad_run.as_bytes());
    assert_eq!(out.status.code(), Some(3), "{}", text(&out.stderr));
    let help = text(&folio(&dir, &["--help"]).stdout);
    for code in ["  0  ", "  1  ", "  2  ", "  3  ", "  4  "] {
        assert!(help.contains(code), "{help}");
    }
}

/// A run that crosses a bound is bad: the summary names the first bad frame and why, and
/// `report.json` says so in its verdict, its counts and the frame's problems.
#[test]
fn a_bad_run_names_its_first_bad_frame() {
    let dir = scratch("first");
    let scene = format!(
        "name = \"b\"\nmodel = \"dog\"\nframes = 45\ninput = {{ fixture = \"page-turn\" }}\n{QUIET}\
         [expect]\nmax_stretch = 1e-6\n"
    );
    let out = run(&dir, "b.toml", scene.as_bytes());
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(3), "{stdout}");
    // The grab is at frame 30: the first frame with a page.
    assert!(
        stdout.contains("first bad frame  30: max edge stretch"),
        "{stdout}"
    );
    let r = report(&dir);
    let s = &r["summary"];
    assert_eq!(s["verdict"], "bad");
    assert_eq!(s["health"]["first_bad"]["frame"], 30);
    assert_eq!(s["health"]["bad_frames"], 15);
    assert_eq!(s["health"]["stretch_over"], 15);
    let problems = r["frames"][30]["problems"].as_array().unwrap();
    assert!(
        problems[0]
            .as_str()
            .unwrap()
            .contains("above the bound 1e-6")
    );
    assert!(r["frames"][29]["problems"].as_array().unwrap().is_empty());
}

/// A DOG scene driven by timed events reported `null` for its DOG residual and
/// penetration: both are measured on every frame with a page, as on a fixture, with the
/// KKT work.
#[test]
fn timed_events_on_the_dog_book_measure_every_metric() {
    let dir = scratch("events");
    let scene = format!("name = \"e\"\nmodel = \"dog\"\nframes = 80\n{QUIET}{EVENTS}");
    let out = run(&dir, "e.toml", scene.as_bytes());
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let s = &report(&dir)["summary"];
    let dog = s["dog_residual_max"].as_f64().expect("a DOG residual");
    let depth = s["penetration_max"].as_f64().expect("a penetration");
    assert!(dog > 0.0 && dog <= 1e-2, "{dog}");
    assert!((0.0..=0.0075).contains(&depth), "{depth}");
    assert!(s["dofs_max"].as_u64().unwrap() > 0);
    assert_eq!(s["nonfinite_frames"], 0);
}

/// Whatever the scene's name says, nothing is written outside the output folder: a name
/// that climbs out is refused (exit 1) before any folder is made.
#[test]
fn nothing_is_written_outside_the_output_folder() {
    let dir = scratch("escape");
    let inner = dir.join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    for name in ["../escape", "../../escape", "a/b"] {
        let scene = format!(
            "name = \"{name}\"\nmodel = \"cone\"\nframes = 5\ninput = {{ fixture = \"page-turn-touch\" }}\n"
        );
        std::fs::write(inner.join("s.toml"), scene).unwrap();
        let out = folio(&inner, &["run", "s.toml"]);
        assert_eq!(out.status.code(), Some(1), "{name}");
        assert!(text(&out.stderr).contains("line 1, column 8"), "{name}");
        assert!(
            !dir.join("escape").exists() && !inner.join("out").exists(),
            "{name}"
        );
    }
}

/// Bytes that are not UTF-8: `check` and `run` both give the line, column and byte
/// offset, and exit 1.
#[test]
fn check_and_run_place_bad_utf8() {
    let dir = scratch("utf8");
    std::fs::write(dir.join("u.toml"), b"name = \"\xff\"\nmodel = \"cone\"\n").unwrap();
    for args in [&["check", "u.toml"][..], &["run", "u.toml", "--out", "o"]] {
        let out = folio(&dir, args);
        assert_eq!(out.status.code(), Some(1));
        let stderr = text(&out.stderr);
        assert!(
            stderr.contains("u.toml: line 1, column 9: the file is not UTF-8: byte 8"),
            "{stderr}"
        );
    }
}

/// A run shows its progress even when stdout is not a terminal (a line per second on
/// stderr, after `FOLIO_PROGRESS_AFTER` seconds, 1 by default); a tearing sheet's run too.
/// The test sets 0: a run that had to outlast the default second passed or failed with the
/// machine's speed (`tear-twist` took under a second on a quiet machine).
#[test]
fn a_long_run_shows_progress_on_a_pipe() {
    let dir = scratch("progress");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_folio"))
        .args(["run", "tear-twist", "--out", "out"])
        .env("FOLIO_PROGRESS_AFTER", "0")
        .current_dir(&dir)
        .output()
        .expect("folio runs");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stderr = text(&out.stderr);
    let lines = stderr
        .lines()
        .filter(|l| l.starts_with("tear-twist: frame "))
        .count();
    assert!(lines >= 1, "{stderr}");
}
