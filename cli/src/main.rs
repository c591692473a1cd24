//! `folio`: run a paper scene, check scene files, list the built-in scenes.
//!
//! ```text
//! folio                           run the default scene (the DOG book's page turn)
//! folio run SCENE_OR_NAME [--out DIR]   run a scene file or a built-in scene
//! folio list                      the built-in scenes
//! folio check SCENE...            check scene files without running them
//! folio atlas SCENE_OR_NAME [--budget MS] [--out DIR]   what accuracy costs in time
//! folio trace SCENE_OR_NAME       run a scene's frames with no outputs (what the atlas
//!                                 counts instructions of, under callgrind)
//! ```
//!
//! A run writes `report.json` into `--out` (default `out/<scene>/`; a scene's name is one
//! file-name component, so nothing is written elsewhere) and prints a summary. Every frame
//! is held to health bounds ([`health`]); the exit status ([`exit`]) tells a good run (0)
//! from a scene that does not check (1), bad arguments (2), a bad run (3) and outputs that
//! could not be written (4).

extern crate alloc;

mod atlas;
mod error;
mod exit;
mod export;
mod health;
mod meter;
mod obj;
mod outputs;
mod progress;
mod render;
mod report;
mod run;
mod shape;
mod sheet_run;
mod sheet_view;
mod summary;
mod timeline;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use folio_scene::builtin;
use folio_scene::number::show;
use folio_scene::scene::Scene;
use report::Report;

/// Counts each thread's allocations, so that a run can report the allocations of its steps
/// ([`report::FrameRecord::allocations`]).
#[global_allocator]
static ALLOCATOR: folio_counting::Counting = folio_counting::Counting;

const USAGE: &str = "usage: folio [run SCENE_OR_NAME [--out DIR] | list | check SCENE... | atlas SCENE_OR_NAME [--budget MS] [--out DIR] | trace SCENE_OR_NAME]";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let words: Vec<&str> = args.iter().map(String::as_str).collect();
    ExitCode::from(match words.as_slice() {
        [] => run_named(builtin::SCENES[0].0, None),
        ["run", target] => run_named(target, None),
        ["run", target, "--out", dir] => run_named(target, Some(PathBuf::from(dir))),
        ["list"] => {
            for (name, text) in builtin::SCENES {
                let description = Scene::parse(text)
                    .map(|s| s.description)
                    .unwrap_or_default();
                println!("{name:<18} {description}");
            }
            exit::GOOD
        }
        ["check", files @ ..] if !files.is_empty() => check(files),
        ["atlas", target, options @ ..] => match atlas_options(options) {
            Some((budget, out)) => atlas::command(target, budget, out),
            None => {
                eprintln!("{USAGE}");
                exit::USAGE
            }
        },
        ["trace", target] => atlas::trace_command(target),
        ["help" | "--help" | "-h"] => {
            println!("{USAGE}\n\n{}", exit::HELP);
            exit::GOOD
        }
        _ => {
            eprintln!("{USAGE}");
            exit::USAGE
        }
    })
}

/// Reads and checks the scene file `file`, as `check` and `run` both do.
///
/// # Errors
/// The message, with the error's place.
/// Its older keys ([`folio_scene::legacy`]) are read, each with a warning on stderr that
/// names the new key.
fn read_scene(file: &str) -> Result<Scene, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("{file}: {e}"))?;
    let scene = Scene::parse_bytes(&bytes).map_err(|e| format!("{file}: {e}"))?;
    for notice in &scene.notices {
        eprintln!("{file}: warning: {notice}");
    }
    Ok(scene)
}

/// Checks every file; prints `ok` or the error with its place.
fn check(files: &[&str]) -> u8 {
    let mut failed = false;
    for file in files {
        match read_scene(file) {
            Ok(_) => println!("{file}: ok"),
            Err(e) => {
                eprintln!("{e}");
                failed = true;
            }
        }
    }
    if failed { exit::BAD_SCENE } else { exit::GOOD }
}

/// The options of `folio atlas`: `--budget MS` (finite, > 0) and `--out DIR`, each at
/// most once, in any order; `None` for anything else.
fn atlas_options(options: &[&str]) -> Option<(Option<f64>, Option<PathBuf>)> {
    let (mut budget, mut out) = (None, None);
    for pair in options.chunks(2) {
        match pair {
            ["--budget", ms] if budget.is_none() => {
                let ms: f64 = ms.parse().ok()?;
                budget = Some(ms).filter(|v| v.is_finite() && *v > 0.0);
                budget?;
            }
            ["--out", dir] if out.is_none() => out = Some(PathBuf::from(dir)),
            _ => return None,
        }
    }
    Some((budget, out))
}

/// The scene a command names: a built-in scene by name, else a scene file; checked, with
/// its text.
///
/// # Errors
/// The message: no such scene, or where the scene does not check.
pub(crate) fn load_scene(target: &str) -> Result<(Scene, String), String> {
    if let Some(text) = builtin::scene(target) {
        return Scene::parse(text)
            .map(|s| (s, text.to_string()))
            .map_err(|e| format!("built-in scene {target}: {e}"));
    }
    if Path::new(target).is_file() {
        let scene = read_scene(target)?;
        let text = std::fs::read_to_string(target).map_err(|e| format!("{target}: {e}"))?;
        return Ok((scene, text));
    }
    let names: Vec<&str> = builtin::SCENES.iter().map(|s| s.0).collect();
    Err(format!(
        "{target}: no such file or built-in scene (built-in: {})",
        names.join(", ")
    ))
}

/// Runs a scene file or a built-in scene by name.
fn run_named(target: &str, out: Option<PathBuf>) -> u8 {
    let scene = match load_scene(target) {
        Ok((s, _)) => s,
        Err(e) => {
            eprintln!("{e}");
            return exit::BAD_SCENE;
        }
    };
    // The name is one file-name component (checked with the scene).
    let out = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
    let started = Instant::now();
    let mut outputs = match outputs::Outputs::new(&scene) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{target}: {e}");
            return exit::BAD_SCENE;
        }
    };
    let progress = progress::Progress::start(&scene.name);
    let report = run::run(
        &scene,
        |frame, frames| progress.set(frame, frames),
        |frame, frames, shape| outputs.observe(frame, frames, shape),
    );
    progress.finish();
    let mut report = match report {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{target}: the run could not start: {e}");
            return exit::BAD_SCENE;
        }
    };
    if let Some(sheet) = outputs.sheet() {
        report.summary.page_coverage = Some(sheet.coverage());
        report.summary.paper_coverage = Some(sheet.paper_coverage());
    }
    if scene.output.report {
        if let Err(e) = write_report(&out, &report) {
            eprintln!("{}: {e}", out.display());
            return exit::OUTPUT;
        }
    }
    let written = match outputs.write(&out, &report) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("{}: {e}", out.display());
            return exit::OUTPUT;
        }
    };
    print_summary(&report, &out, started.elapsed().as_secs_f64());
    if let (Some(page), Some(paper)) = (report.summary.page_coverage, report.summary.paper_coverage)
    {
        println!(
            "  contact sheet    {:.1} % page, {:.1} % paper",
            100.0 * page,
            100.0 * paper
        );
    }
    for (file, what) in written {
        println!("  wrote            {} ({what})", file.display());
    }
    print_verdict(&report)
}

/// Prints the health, the expectations and the verdict; the exit status.
fn print_verdict(report: &Report) -> u8 {
    let s = &report.summary;
    let h = &s.health;
    if h.good() {
        println!("  health           every frame within its bounds");
    } else {
        let over = h.stretch_over + h.dog_residual_over + h.penetration_over;
        println!(
            "  health           {} bad frames: {} failed steps, {} inputs that did nothing, {over} above a bound",
            h.bad_frames, h.failed_steps, h.input_problems
        );
        if let Some(first) = &h.first_bad {
            println!("  first bad frame  {}: {}", first.frame, first.why);
            eprintln!("frame {} is bad: {}", first.frame, first.why);
        }
    }
    if s.unmet.is_empty() {
        println!("  expectations     met");
    } else {
        for u in &s.unmet {
            println!("  expectation      not met: {u}");
            eprintln!("expectation not met: {u}");
        }
    }
    if report.good() {
        exit::GOOD
    } else {
        println!("  verdict          bad run (exit status {})", exit::BAD_RUN);
        exit::BAD_RUN
    }
}

fn write_report(out: &Path, report: &Report) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let json = serde_json::to_string_pretty(report).map_err(std::io::Error::other)?;
    std::fs::write(out.join("report.json"), json)
}

fn print_summary(report: &Report, out: &Path, seconds: f64) {
    let s = &report.summary;
    let opt = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.2e}"));
    let fixed = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.4}"));
    let statuses: Vec<String> = s
        .status_counts
        .iter()
        .map(|(k, v)| format!("{k} {v}"))
        .collect();
    println!(
        "scene {} (model {}, {}), {} frames ({} steps) in {seconds:.2} s",
        report.scene, report.model, report.precision, s.frames, s.steps_total
    );
    println!(
        "  frame compute    median {:.3} ms, p99 {:.3} ms (all of a frame's steps)",
        s.step_ms_median, s.step_ms_p99
    );
    let b = &s.health.bounds;
    println!(
        "  edge stretch     mean max {}, mean RMSE {}, max {} (bound {})",
        fixed(s.max_stretch_mean),
        fixed(s.rmse_stretch_mean),
        fixed(s.max_stretch_max),
        show(b.max_stretch)
    );
    println!(
        "  DOG residual     max {} (bound {})",
        opt(s.dog_residual_max),
        show(b.dog_residual)
    );
    println!(
        "  penetration      max {} (bound {})",
        opt(s.penetration_max),
        b.penetration
            .map_or_else(|| "none without collisions".into(), show)
    );
    println!(
        "  non-finite       {} frames ({} with non-finite input, {} with a non-finite state)",
        s.nonfinite_frames, s.health.nonfinite_input_frames, s.health.nonfinite_state_frames
    );
    println!("  step status      {}", statuses.join(", "));
    if let Some(p) = &report.paper {
        println!(
            "  paper            {:.0} x {:.0} mm, {:.0} g/m², {:.0} µm, D = {:.3e} N·m, sag number {:.3}; a book second is {:.3} real s",
            1e3 * p.width_m,
            1e3 * p.height_m,
            p.grammage,
            1e6 * p.caliper_m,
            p.bending_stiffness,
            p.sag_number,
            p.real_seconds_per_second
        );
    }
    println!(
        "  effects          {}",
        if s.effects.is_empty() {
            "none".to_string()
        } else {
            s.effects.join(", ")
        }
    );
    if let (Some(dofs), Some(rows), Some(terms), Some(tests)) = (
        s.dofs_max,
        s.constraint_rows_max,
        s.terms_max,
        s.contact_tests_total,
    ) {
        println!(
            "  work             at most {dofs} unknowns, {rows} rows, {terms} terms; {tests} collision tests"
        );
    }
    if let Some(histogram) = &s.newton_iterations {
        let cells: Vec<String> = histogram
            .iter()
            .map(|(n, frames)| format!("{n}: {frames}"))
            .collect();
        println!(
            "  Newton           iterations per awake frame (iterations: frames) {}",
            cells.join(", ")
        );
    }
    if let Some(asleep) = s.asleep_frames {
        println!("  asleep           {asleep} frames (no solver work: the book at rest, still)");
    }
    if let Some([left, right, held]) = s.final_pages {
        println!("  pages at the end left {left}, right {right}, held {held}");
    }
    if let Some(lengths) = &s.tear_lengths {
        let list: Vec<String> = lengths.iter().map(|l| format!("{l:.2}")).collect();
        println!(
            "  tears            {} ({} long), {} propagations, first from {}",
            lengths.len(),
            if list.is_empty() {
                "-".to_string()
            } else {
                list.join(", ")
            },
            s.propagations_total.unwrap_or(0),
            s.tear_start.as_deref().unwrap_or("-")
        );
    }
    println!("  report           {}", out.join("report.json").display());
}
