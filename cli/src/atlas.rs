//! `folio atlas SCENE [--budget MS] [--out DIR]`: what accuracy costs in time.
//!
//! The scene runs as a declared set of variants ([`variants::declared`]: the page model,
//! the grid, Newton iterations, the constraint Hessian, the precision, the time step,
//! collision rounds, the projection), each measured against a reference at the same
//! material points and times ([`errors()`]): the DOG book in `f64` on a fine grid, a short
//! time step and Newton to a KKT residual of 1e-10 ([`variants::reference`]). The
//! reference proves that it is converged: refined once more (a finer grid, half the time
//! step), it must move by less than a tenth of the smallest error the atlas reports
//! (`atlas.json` records both); otherwise the atlas says so and exits with status 3.
//!
//! Each variant's cost is the mean, median and 99th percentile of its frames' compute time,
//! its allocations per step and, where valgrind is installed, the mean instructions of its
//! frames counted by callgrind ([`instructions`]): figures that repeat. Variants are
//! independent and run in parallel (rayon, one variant per core): timings are taken while
//! the other core runs another variant.
//!
//! Outputs in `--out` (default `out/atlas/<scene>/`): `atlas.json` (every variant, its
//! knobs, costs and errors), `atlas.md` (the same as a table), `atlas.svg` (error against
//! mean time per frame, log-log, the Pareto front drawn). With `--budget MS` the most accurate
//! good variant whose p99 frame time fits the budget is written as a scene file,
//! `budget-<MS>ms.toml`, that `folio run` runs.

mod errors;
pub mod instructions;
mod plot;
mod table;
mod trace;
pub mod variants;

use alloc::collections::BTreeMap;
use core::sync::atomic::{AtomicU32, Ordering};
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;

use folio_scene::scene::Scene;

use crate::exit;
use crate::progress::Progress;
pub use errors::{Errors, errors};
use trace::Trace;
pub use variants::Variant;

/// The reference must move by less than this fraction of the smallest reported error when
/// refined once more.
pub const PROOF_FRACTION: f64 = 0.1;

/// A variant's cost per frame of 1/60 s (its steps and what the run does around them).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Costs {
    /// Mean compute time of a frame (milliseconds): the run's compute time over its frames.
    /// The atlas's Pareto front and plot use it: most frames of a page turn hold no active
    /// page (before the grab, after the merge) and cost almost nothing, so the median
    /// tells little of what a turn costs.
    pub frame_ms_mean: f64,
    /// Median compute time of a frame (milliseconds).
    pub frame_ms_median: f64,
    /// 99th percentile (milliseconds).
    pub frame_ms_p99: f64,
    /// Heap allocations per model step.
    pub allocations_per_step: f64,
    /// Mean instructions of a frame's steps, counted by callgrind ([`instructions`]):
    /// `None` where valgrind is not installed (and for the reference, too slow to count).
    pub instructions_per_frame: Option<f64>,
}

/// One measured variant (`atlas.json`'s `variants`).
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Its label.
    pub label: String,
    /// The page model.
    pub model: String,
    /// The scene keys it sets.
    pub knobs: BTreeMap<String, toml::Value>,
    /// Why it could not run (its scene was refused or its model did not start).
    pub refused: Option<String>,
    /// Its costs.
    pub costs: Option<Costs>,
    /// Its errors against the reference.
    pub errors: Option<Errors>,
    /// Largest edge stretch of a frame.
    pub stretch_max: Option<f64>,
    /// Mean over frames of the RMS edge stretch.
    pub stretch_rms_mean: Option<f64>,
    /// Largest DOG residual (DOG book).
    pub dog_residual_max: Option<f64>,
    /// Deepest penetration into a block (DOG book; page units).
    pub penetration_max: Option<f64>,
    /// Frames the health bounds call bad (failed, non-finite, above a bound).
    pub bad_frames: usize,
    /// Pages left, right and held at the end (DOG book).
    pub final_pages: Option<[u32; 3]>,
    /// Every frame good and the scene's expectations met.
    pub good: bool,
    /// On the Pareto front of error against mean frame time (good variants only).
    pub pareto: bool,
}

/// How far the reference is from converged (`atlas.json`'s `reference`).
#[derive(Clone, Debug, Serialize)]
pub struct Proof {
    /// The reference's knobs.
    pub reference: BTreeMap<String, toml::Value>,
    /// The refined reference's knobs.
    pub refined: BTreeMap<String, toml::Value>,
    /// The reference against its refinement (`None`: the refinement was not run).
    pub refinement: Option<Errors>,
    /// The smallest mean RMS error of a variant.
    pub smallest_error: f64,
    /// `refinement.rms_mean < PROOF_FRACTION * smallest_error`.
    pub converged: bool,
    /// The reference's costs.
    pub costs: Costs,
}

/// The atlas of one scene (`atlas.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Atlas {
    /// The scene's name.
    pub scene: String,
    /// Frames run (1/60 s each).
    pub frames: usize,
    /// The page width the errors are fractions of.
    pub page_width: f64,
    /// Material points sampled per frame.
    pub samples: usize,
    /// The reference and its convergence.
    pub proof: Proof,
    /// Every variant.
    pub variants: Vec<Row>,
    /// The scene's model on [`CONVERGENCE_GRIDS`] (`None`: a model without a grid, the cone).
    pub convergence: Option<Convergence>,
}

/// The grids of the atlas's convergence study, each twice as fine as the one before.
pub const CONVERGENCE_GRIDS: [[i64; 2]; 3] = [[6, 8], [12, 16], [24, 32]];

/// The knobs of `variant` as a map.
fn knobs(variant: &Variant) -> BTreeMap<String, toml::Value> {
    variant
        .keys
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect()
}

/// The scene of `variant` on `base` (its text `table`), named after the base and the
/// variant, parsed and checked as `folio run` would.
fn variant_scene(base: &Scene, table: &toml::Table, variant: &Variant) -> Result<Scene, String> {
    let text = variants::scene_text(table, variant, &variant_name(base, variant));
    Scene::parse(&text).map_err(|e| format!("{e}\n{text}"))
}

/// The scene name of `variant` on `base`: the base's name and the variant's slug.
fn variant_name(base: &Scene, variant: &Variant) -> String {
    format!("{}-{}", base.name, variants::slug(&variant.label))
}

/// Measures `variants` of the scene `base` (its file text `text`) against `reference`,
/// and the reference against `refined` when given; `progress(done, total)` counts frames
/// over every run.
///
/// # Errors
/// The reference (or its refinement) could not run: nothing can be measured.
pub fn measure(
    base: &Scene,
    text: &str,
    reference: &Variant,
    refined: Option<&Variant>,
    variants: &[Variant],
    progress: impl Fn(u32, u32) + Sync,
) -> Result<Atlas, String> {
    let table: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    // One run each: the reference, its refinement, the variants.
    let scenes: Vec<Result<Scene, String>> = core::iter::once(reference)
        .chain(refined)
        .chain(variants)
        .map(|v| variant_scene(base, &table, v))
        .collect();
    let runs_count = scenes.len() as u32;
    let done = AtomicU32::new(0);
    let runs: Vec<Result<Trace, String>> = scenes
        .par_iter()
        .with_max_len(1)
        .map(|scene| {
            let scene = scene.as_ref().map_err(Clone::clone)?;
            trace::trace(scene, |frames| {
                let total = frames.saturating_mul(runs_count);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            })
            .map_err(|e| e.to_string())
        })
        .collect();
    let mut runs = runs.into_iter();
    let reference_run = runs
        .next()
        .ok_or("no reference")?
        .map_err(|e| format!("the reference could not run: {e}"))?;
    let refined_run = match refined {
        Some(_) => Some(
            runs.next()
                .ok_or("no refinement")?
                .map_err(|e| format!("the refined reference could not run: {e}"))?,
        ),
        None => None,
    };
    let width = base.page_size()[0];
    let mut rows: Vec<Row> = variants
        .iter()
        .zip(runs)
        .map(|(v, run)| row(v, run, &reference_run, width))
        .collect();
    mark_pareto(&mut rows);
    let smallest_error = rows
        .iter()
        .filter_map(|r| r.errors.map(|e| e.rms_mean))
        .filter(|e| e.is_finite())
        .fold(f64::INFINITY, f64::min);
    let refinement = refined_run.map(|r| errors(&reference_run, &r, width));
    let converged = refinement.is_some_and(|e| e.rms_mean < PROOF_FRACTION * smallest_error);
    Ok(Atlas {
        scene: base.name.clone(),
        frames: reference_run.frames.len(),
        page_width: width,
        samples: trace::sample_grid().len(),
        proof: Proof {
            reference: knobs(reference),
            refined: refined.map(knobs).unwrap_or_default(),
            refinement,
            smallest_error,
            converged,
            costs: costs(&reference_run),
        },
        variants: rows,
        convergence: None,
    })
}

/// The same scene on successively finer grids: the distance between neighbours and the
/// observed order of convergence.
#[derive(Clone, Debug, Serialize)]
pub struct Convergence {
    /// The grids, coarse to fine, each finer by the same ratio.
    pub grids: Vec<[i64; 2]>,
    /// Grid $k$ against grid $k + 1$ (the finer as reference).
    pub differences: Vec<Errors>,
    /// The observed order $p = \ln(e_0 / e_1) / \ln r$ from the first two differences
    /// ($r$ the refinement ratio of the first two grids): the error falls as $h^p$ when
    /// the runs converge.
    pub order: f64,
}

/// Runs the scene `base` (its text `text`) on `grids` (coarse to fine, at least three,
/// refined by one ratio) in parallel and measures each grid against the next.
///
/// # Errors
/// A grid whose run could not start, or fewer than three grids.
pub fn convergence(base: &Scene, text: &str, grids: &[[i64; 2]]) -> Result<Convergence, String> {
    if grids.len() < 3 {
        return Err("the observed order needs three grids".into());
    }
    let table: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    let model = base.model.get_ref().name();
    let runs: Vec<Result<Trace, String>> = grids
        .par_iter()
        .with_max_len(1)
        .map(|&g| {
            let scene = variant_scene(base, &table, &variants::on_grid(model, g))?;
            trace::trace(&scene, |_| {}).map_err(|e| e.to_string())
        })
        .collect();
    let runs: Vec<Trace> = runs.into_iter().collect::<Result<_, _>>()?;
    let width = base.page_size()[0];
    let differences: Vec<Errors> = runs
        .windows(2)
        .map(|w| errors(&w[0], &w[1], width))
        .collect();
    let ratio = grids[1][0] as f64 / grids[0][0] as f64;
    let order = (differences[0].rms_mean / differences[1].rms_mean).ln() / ratio.ln();
    Ok(Convergence {
        grids: grids.to_vec(),
        differences,
        order,
    })
}

/// The costs of a run.
fn costs(run: &Trace) -> Costs {
    let s = &run.report.summary;
    Costs {
        frame_ms_mean: s.step_ms_mean,
        frame_ms_median: s.step_ms_median,
        frame_ms_p99: s.step_ms_p99,
        allocations_per_step: s.allocations_per_step,
        instructions_per_frame: None,
    }
}

/// The row of `variant` from its run against the reference.
fn row(variant: &Variant, run: Result<Trace, String>, reference: &Trace, width: f64) -> Row {
    let mut row = Row {
        label: variant.label.clone(),
        model: variant.model.clone(),
        knobs: knobs(variant),
        refused: None,
        costs: None,
        errors: None,
        stretch_max: None,
        stretch_rms_mean: None,
        dog_residual_max: None,
        penetration_max: None,
        bad_frames: 0,
        final_pages: None,
        good: false,
        pareto: false,
    };
    match run {
        Err(e) => row.refused = Some(e),
        Ok(run) => {
            let s = &run.report.summary;
            row.costs = Some(costs(&run));
            row.errors = Some(errors(&run, reference, width));
            row.stretch_max = s.max_stretch_max;
            row.stretch_rms_mean = s.rmse_stretch_mean;
            row.dog_residual_max = s.dog_residual_max;
            row.penetration_max = s.penetration_max;
            row.bad_frames = s.health.bad_frames;
            row.final_pages = s.final_pages;
            row.good = run.report.good();
        }
    }
    row
}

/// Marks the good variants no other good variant beats in both mean frame time and mean
/// RMS error.
fn mark_pareto(rows: &mut [Row]) {
    let point = |r: &Row| match (r.good, r.costs, r.errors) {
        (true, Some(c), Some(e)) if e.rms_mean.is_finite() => Some((c.frame_ms_mean, e.rms_mean)),
        _ => None,
    };
    let points: Vec<Option<(f64, f64)>> = rows.iter().map(point).collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let Some((t, e)) = points[i] else { continue };
        row.pareto = !points.iter().enumerate().any(|(j, q)| {
            q.is_some_and(|(tq, eq)| j != i && tq <= t && eq <= e && (tq < t || eq < e))
        });
    }
}

/// The most accurate good variant whose p99 frame time is at most `budget_ms`.
#[must_use]
pub fn pick(atlas: &Atlas, budget_ms: f64) -> Option<usize> {
    atlas
        .variants
        .iter()
        .enumerate()
        .filter_map(|(i, r)| match (r.good, r.costs, r.errors) {
            (true, Some(c), Some(e)) if c.frame_ms_p99 <= budget_ms && e.rms_mean.is_finite() => {
                Some((i, e.rms_mean))
            }
            _ => None,
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// `folio atlas`: loads the scene `target` (a built-in name or a file), measures its
/// declared variants, writes the outputs into `out` (default `out/atlas/<scene>`), and,
/// with a budget, the scene of the variant it picks. The exit status: 0, or
/// [`exit::BAD_RUN`] when a variant could not run or the reference is not proven
/// converged, [`exit::BAD_SCENE`] for a scene that does not check, [`exit::OUTPUT`] when
/// the outputs cannot be written.
pub fn command(target: &str, budget_ms: Option<f64>, out: Option<PathBuf>) -> u8 {
    let (scene, text) = match crate::load_scene(target) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return exit::BAD_SCENE;
        }
    };
    if *scene.model.get_ref() == folio_scene::scene::ModelKind::Sheet {
        eprintln!(
            "{target}: the atlas measures page scenes; a tearing sheet has no reference page"
        );
        return exit::BAD_SCENE;
    }
    let out = out.unwrap_or_else(|| Path::new("out").join("atlas").join(&scene.name));
    let model = scene.model.get_ref().name();
    let declared = variants::declared(model);
    let progress = Progress::start(&format!("atlas {}", scene.name));
    let atlas = measure(
        &scene,
        &text,
        &variants::reference(false),
        Some(&variants::reference(true)),
        &declared,
        |done, total| progress.set(done, total),
    );
    progress.finish();
    let mut atlas = match atlas {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{target}: {e}");
            return exit::BAD_RUN;
        }
    };
    if model != "cone" {
        match convergence(&scene, &text, &CONVERGENCE_GRIDS) {
            Ok(c) => atlas.convergence = Some(c),
            Err(e) => {
                eprintln!("{target}: the convergence study could not run: {e}");
                return exit::BAD_RUN;
            }
        }
    }
    let mut status = exit::GOOD;
    if instructions::available() {
        if let Err(e) = count_instructions(&mut atlas, &scene, &text) {
            eprintln!("{target}: {e}");
            status = exit::BAD_RUN;
        }
    } else {
        eprintln!("valgrind is not installed: the atlas has no instruction counts");
    }
    if let Err(e) = write(&atlas, &out) {
        eprintln!("{}: {e}", out.display());
        return exit::OUTPUT;
    }
    print!("{}", table::markdown(&atlas));
    if let Some(budget) = budget_ms {
        match pick(&atlas, budget) {
            Some(i) => {
                let v = &declared[i];
                let name = format!("{}-{budget}ms", scene.name);
                let table: toml::Table = toml::from_str(&text).unwrap_or_default();
                let file = out.join(format!("budget-{budget}ms.toml"));
                let body = format!(
                    "# Picked by `folio atlas {target} --budget {budget}`: {} (p99 {:.3} ms a frame, mean RMS error {:.2} % of the page width).\n{}",
                    v.label,
                    atlas.variants[i].costs.map_or(f64::NAN, |c| c.frame_ms_p99),
                    100.0 * atlas.variants[i].errors.map_or(f64::NAN, |e| e.rms_mean),
                    variants::scene_text(&table, v, &name)
                );
                if let Err(e) = std::fs::write(&file, body) {
                    eprintln!("{}: {e}", file.display());
                    return exit::OUTPUT;
                }
                println!("budget {budget} ms: {} -> {}", v.label, file.display());
            }
            None => {
                eprintln!(
                    "budget {budget} ms: no good variant fits; the cheapest p99 is in atlas.md"
                );
                status = exit::BAD_RUN;
            }
        }
    }
    for row in atlas.variants.iter().filter(|r| r.refused.is_some()) {
        eprintln!(
            "variant {} could not run: {}",
            row.label,
            row.refused.as_deref().unwrap_or("")
        );
        status = exit::BAD_RUN;
    }
    if !atlas.proof.converged {
        eprintln!(
            "the reference is not proven converged: refined once more it moved by {} of the page width, not less than a tenth of the smallest error ({:.3e})",
            atlas
                .proof
                .refinement
                .map_or("?".into(), |e| format!("{:.3e}", e.rms_mean)),
            atlas.proof.smallest_error
        );
        status = exit::BAD_RUN;
    }
    println!("wrote {}", out.display());
    status
}

/// Counts the instructions of every variant that ran ([`instructions`]), two at a time,
/// the scene files and callgrind outputs in a scratch folder removed afterwards.
///
/// # Errors
/// The first variant that could not be counted (the others keep their counts).
fn count_instructions(atlas: &mut Atlas, base: &Scene, text: &str) -> Result<(), String> {
    let folio = std::env::current_exe().map_err(|e| format!("the folio binary: {e}"))?;
    let table: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("folio-atlas-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let declared = variants::declared(base.model.get_ref().name());
    let frames = atlas.frames.max(1) as f64;
    let progress = Progress::start(&format!("atlas {}: callgrind", base.name));
    let done = AtomicU32::new(0);
    let total = atlas.variants.len() as u32;
    let counts: Vec<Option<Result<u64, String>>> = atlas
        .variants
        .par_iter()
        .with_max_len(1)
        .map(|row| {
            let v = declared.iter().find(|v| v.label == row.label)?;
            row.costs?;
            let name = variant_name(base, v);
            let file = dir.join(format!("{name}.toml"));
            let counted = std::fs::write(&file, variants::scene_text(&table, v, &name))
                .map_err(|e| format!("{}: {e}", file.display()))
                .and_then(|()| instructions::count(&folio, &file, &dir));
            progress.set(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            Some(counted.map_err(|e| format!("{}: {e}", row.label)))
        })
        .collect();
    progress.finish();
    let _ = std::fs::remove_dir_all(&dir);
    let mut first_error = None;
    for (row, count) in atlas.variants.iter_mut().zip(counts) {
        match (count, row.costs.as_mut()) {
            (Some(Ok(n)), Some(c)) => c.instructions_per_frame = Some(n as f64 / frames),
            (Some(Err(e)), _) => {
                first_error.get_or_insert(e);
            }
            _ => {}
        }
    }
    first_error.map_or(Ok(()), Err)
}

/// `folio trace SCENE_OR_NAME`: runs the scene's frames with no outputs and prints one line
/// (what [`instructions::count`] runs under callgrind). The exit status is the run's: 0,
/// [`exit::BAD_RUN`] for a bad or failed run, [`exit::BAD_SCENE`] for a scene that does not
/// check.
pub fn trace_command(target: &str) -> u8 {
    let scene = match crate::load_scene(target) {
        Ok((s, _)) => s,
        Err(e) => {
            eprintln!("{e}");
            return exit::BAD_SCENE;
        }
    };
    // No observer: nothing is sampled or drawn around the steps.
    match crate::run::run(&scene, |_, _| {}, |_, _, _| {}) {
        Ok(report) => {
            let s = &report.summary;
            let good = report.good();
            println!(
                "{}: {} frames, {} steps, {}",
                scene.name,
                s.frames,
                s.steps_total,
                if good { "good" } else { "bad run" }
            );
            if good { exit::GOOD } else { exit::BAD_RUN }
        }
        Err(e) => {
            eprintln!("{target}: {e}");
            exit::BAD_RUN
        }
    }
}

/// Writes `atlas.json`, `atlas.md` and `atlas.svg` into `out`.
fn write(atlas: &Atlas, out: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let json = serde_json::to_string_pretty(atlas).map_err(std::io::Error::other)?;
    std::fs::write(out.join("atlas.json"), json)?;
    std::fs::write(out.join("atlas.md"), table::markdown(atlas))?;
    std::fs::write(out.join("atlas.svg"), plot::svg(atlas))
}

#[cfg(test)]
mod tests;
