//! The atlas's instruction counts (issue 21): `folio trace` under callgrind, collecting only
//! inside the function that steps a frame (`advance_frame`), gives counts that repeat from
//! run to run and grow with the frames stepped. Valgrind is installed by `.ci/run`; on a
//! machine without it the test says so and passes only outside CI.

use std::path::Path;
use std::process::Command;

mod common;

/// A short DOG page gesture: grab, lift over the spine, let go; `frames` frames.
fn scene(frames: u32) -> String {
    format!(
        "name = \"count-{frames}\"\nmodel = \"dog\"\nframes = {frames}\n\
         [[input.events]]\nframe = 0\ngrab = [11.0, 8.0]\n\
         [[input.events]]\nframe = 20\ndrag = [2.0, 9.0, 8.0]\n"
    )
}

/// The instructions callgrind collected inside the frame functions for the scene file
/// `file` (in `dir`).
fn count(dir: &Path, file: &str) -> u64 {
    let out = dir.join(format!("{file}.callgrind"));
    let run = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg("--toggle-collect=*advance_frame*")
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(env!("CARGO_BIN_EXE_folio"))
        .args(["trace", file])
        .current_dir(dir)
        .output()
        .expect("valgrind runs");
    assert!(run.status.success(), "{}", common::text(&run.stderr));
    assert!(
        common::text(&run.stdout).contains("good"),
        "{}",
        common::text(&run.stdout)
    );
    let text = std::fs::read_to_string(&out).expect("callgrind wrote its output");
    let line = text
        .lines()
        .find(|l| l.starts_with("totals:"))
        .expect("a totals line");
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

#[test]
fn instruction_counts_repeat_and_grow_with_the_frames() {
    let valgrind = Command::new("valgrind").arg("--version").output();
    if !valgrind.is_ok_and(|o| o.status.success()) {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI installs valgrind (.ci/run); it is missing"
        );
        eprintln!("valgrind is not installed: instruction counts not tested");
        return;
    }
    let dir = common::scratch("instructions", "repeat");
    std::fs::write(dir.join("short.toml"), scene(30)).unwrap();
    std::fs::write(dir.join("long.toml"), scene(60)).unwrap();
    let first = count(&dir, "short.toml");
    let second = count(&dir, "short.toml");
    let long = count(&dir, "long.toml");
    println!("30 frames: {first} and {second} instructions; 60 frames: {long}");
    // The steps are single-threaded at this grid and deterministic: the same count (the
    // measured spread is 0; a few instructions in ten million are left to libc's paths).
    let spread = (first as f64 - second as f64).abs() / first as f64;
    assert!(spread < 1e-7, "{first} against {second}");
    // Every frame steps (a held page), so twice the frames is well over the count.
    assert!(
        long as f64 > 1.5 * first as f64,
        "60 frames {long} against 30 frames {first}"
    );
    // A frame of the 8x11 page is some hundred thousand instructions at least: the count
    // holds the steps, not an empty toggle.
    assert!(first > 30 * 100_000, "{first}");
}
