//! `folio`: run a paper scene, check scene files, list the built-in scenes.
//!
//! ```text
//! folio                           run the default scene (the DOG book's page turn)
//! folio run SCENE_OR_NAME [--out DIR]   run a scene file or a built-in scene
//! folio list                      the built-in scenes
//! folio check SCENE...            check scene files without running them
//! ```
//!
//! A run writes `report.json` into `--out` (default `out/<scene>/`) and prints a summary.
//! Exit status: 0 on success, 1 when a scene does not check or a run fails, 2 for bad
//! arguments.

extern crate alloc;

mod export;
mod obj;
mod outputs;
mod render;
mod run;
mod sheet_run;
mod sheet_view;
mod timeline;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use folio_scene::builtin;
use folio_scene::scene::Scene;
use run::Report;

const USAGE: &str = "usage: folio [run SCENE_OR_NAME [--out DIR] | list | check SCENE...]";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let words: Vec<&str> = args.iter().map(String::as_str).collect();
    match words.as_slice() {
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
            ExitCode::SUCCESS
        }
        ["check", files @ ..] if !files.is_empty() => check(files),
        ["help" | "--help" | "-h"] => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        _ => {
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// Checks every file; prints `ok` or the error with its place.
fn check(files: &[&str]) -> ExitCode {
    let mut failed = false;
    for file in files {
        match std::fs::read_to_string(file) {
            Ok(text) => match Scene::parse(&text) {
                Ok(_) => println!("{file}: ok"),
                Err(e) => {
                    eprintln!("{file}: {e}");
                    failed = true;
                }
            },
            Err(e) => {
                eprintln!("{file}: {e}");
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs a scene file or a built-in scene by name.
fn run_named(target: &str, out: Option<PathBuf>) -> ExitCode {
    let (text, origin) = match builtin::scene(target) {
        Some(text) => (text.to_string(), format!("built-in scene {target}")),
        None if Path::new(target).is_file() => match std::fs::read_to_string(target) {
            Ok(text) => (text, target.to_string()),
            Err(e) => {
                eprintln!("{target}: {e}");
                return ExitCode::FAILURE;
            }
        },
        None => {
            let names: Vec<&str> = builtin::SCENES.iter().map(|s| s.0).collect();
            eprintln!(
                "{target}: no such file or built-in scene (built-in: {})",
                names.join(", ")
            );
            return ExitCode::FAILURE;
        }
    };
    let scene = match Scene::parse(&text) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{origin}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let out = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
    let started = Instant::now();
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(scene.name.clone());
    // The bar appears once a run has lasted a second, and only on a terminal.
    let terminal = std::io::stdout().is_terminal();
    let mut shown = false;
    let mut outputs = match outputs::Outputs::new(&scene) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{origin}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let report = run::run(
        &scene,
        |frame, frames| {
            if !shown && terminal && started.elapsed().as_secs_f64() > 1.0 {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                shown = true;
            }
            bar.set_length(u64::from(frames));
            bar.set_position(u64::from(frame));
        },
        |frame, frames, shape| outputs.observe(frame, frames, shape),
    );
    bar.finish_and_clear();
    let report = match report {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{origin}: run failed: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut report = report;
    if let Some(sheet) = outputs.sheet() {
        report.summary.page_coverage = Some(sheet.coverage());
        report.summary.paper_coverage = Some(sheet.paper_coverage());
    }
    if scene.output.report {
        if let Err(e) = write_report(&out, &report) {
            eprintln!("{}: {e}", out.display());
            return ExitCode::FAILURE;
        }
    }
    let written = match outputs.write(&out, &report) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("{}: {e}", out.display());
            return ExitCode::FAILURE;
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
    let unmet = report.unmet(&scene.expect);
    if unmet.is_empty() {
        println!("  expectations     met");
        ExitCode::SUCCESS
    } else {
        for u in &unmet {
            eprintln!("  expectation not met: {u}");
        }
        ExitCode::FAILURE
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
    let statuses: Vec<String> = s
        .status_counts
        .iter()
        .map(|(k, v)| format!("{k} {v}"))
        .collect();
    println!(
        "scene {} (model {}), {} frames in {seconds:.2} s",
        report.scene, report.model, s.frames
    );
    println!(
        "  step time        median {:.3} ms, p99 {:.3} ms",
        s.step_ms_median, s.step_ms_p99
    );
    println!(
        "  edge stretch     mean max {:.4}, mean RMSE {:.4}",
        s.max_stretch_mean, s.rmse_stretch_mean
    );
    println!("  DOG residual     max {}", opt(s.dog_residual_max));
    println!("  penetration      max {}", opt(s.penetration_max));
    println!("  non-finite       {} frames", s.nonfinite_frames);
    println!("  step status      {}", statuses.join(", "));
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
