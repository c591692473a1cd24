//! Running a checked scene: the model steps through its input, every frame is measured, and
//! the run ends in a [`Report`] (`report.json`).

use alloc::collections::BTreeMap;
use std::time::Instant;

use folio_geometry::{BookParams, QuadGrid};
use folio_solvers::book::{Action, Book, BookSettings, Script};
use folio_solvers::page::cone::{ConePage, ConeSettings};
use folio_solvers::page::dog::DogPage;
use folio_solvers::page::spring::{SpringPage, SpringSettings};
use folio_solvers::page::{PageModel, PageStatus, TouchScript, frame_metrics};
use serde::Serialize;

use crate::fixtures::{self, Kind};
use crate::scene::{ModelKind, Scene};

/// The render grid page models are measured on (24 x 34 quads, half a page unit).
const RENDER_QUADS: (usize, usize) = (24, 34);

/// One frame of a run.
#[derive(Clone, Debug, Serialize)]
pub struct FrameRecord {
    /// Frame index.
    pub frame: u32,
    /// Wall time of the step (milliseconds).
    pub step_ms: f64,
    /// Max edge stretch of the page (when there is an active page).
    pub max_stretch: Option<f64>,
    /// RMSE edge stretch of the page.
    pub rmse_stretch: Option<f64>,
    /// Max angle defect of the render grid (page models; radians).
    pub angle_defect: Option<f64>,
    /// Max DOG residual of the active page (DOG book).
    pub dog_residual: Option<f64>,
    /// Deepest penetration of the active page into a block (DOG book; page units).
    pub penetration: Option<f64>,
    /// How the step went.
    pub status: String,
    /// Some coordinate is not finite.
    pub nonfinite: bool,
}

/// The summary of a run (`report.json`'s `summary`).
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Frames run.
    pub frames: u32,
    /// Median step time (milliseconds).
    pub step_ms_median: f64,
    /// 99th-percentile step time (milliseconds).
    pub step_ms_p99: f64,
    /// Mean over frames with a page of the max edge stretch.
    pub max_stretch_mean: f64,
    /// Mean over frames with a page of the RMSE edge stretch.
    pub rmse_stretch_mean: f64,
    /// Largest DOG residual (DOG book), else null.
    pub dog_residual_max: Option<f64>,
    /// Deepest penetration (DOG book), else null.
    pub penetration_max: Option<f64>,
    /// Frames with a non-finite coordinate.
    pub nonfinite_frames: usize,
    /// Frames per step status.
    pub status_counts: BTreeMap<String, usize>,
    /// What the model simulated.
    pub effects: Vec<&'static str>,
    /// Pages in the left block, the right block and the grip at the end (DOG book).
    pub final_pages: Option<[u32; 3]>,
}

/// A finished run (`report.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The scene's name.
    pub scene: String,
    /// The page model.
    pub model: &'static str,
    /// The summary.
    pub summary: Summary,
    /// Every frame.
    pub frames: Vec<FrameRecord>,
}

/// Why a checked scene could not run.
#[derive(Debug)]
pub struct RunError(pub String);

impl core::fmt::Display for RunError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.0)
    }
}

impl core::error::Error for RunError {}

fn fail(e: impl core::fmt::Display) -> RunError {
    RunError(e.to_string())
}

/// The book settings of a DOG scene.
fn book_settings(scene: &Scene) -> BookSettings<f64> {
    let mut s = BookSettings::default();
    if let Some(book) = &scene.book {
        let b = book.get_ref();
        let p: &mut BookParams = &mut s.params;
        if let Some(v) = &b.pages {
            p.total_pages = *v.get_ref();
            p.left_pages = p.total_pages / 2;
        }
        if let Some(v) = &b.left_pages {
            p.left_pages = *v.get_ref();
        }
        if let Some(v) = &b.page_width {
            p.page_width = *v.get_ref();
        }
        if let Some(v) = &b.thickness {
            p.page_thickness = *v.get_ref();
        }
        if let Some(v) = b.cover {
            p.cover = v;
        }
    }
    s
}

/// The frames to run: the scene's, else the input's.
fn frames(scene: &Scene, input: u32) -> u32 {
    scene.frames.as_ref().map_or(input, |f| *f.get_ref())
}

/// Runs `scene`, calling `progress(frame, frames)` after every frame.
///
/// # Errors
/// A model or input the scene describes but that refuses to start (settings the model
/// rejects), or a step error.
pub fn run(scene: &Scene, mut progress: impl FnMut(u32, u32)) -> Result<Report, RunError> {
    let name = scene.input.get_ref().fixture.get_ref();
    let text = fixtures::text(name).ok_or_else(|| fail("unknown fixture"))?;
    let model = *scene.model.get_ref();
    let mut records = Vec::new();
    let mut final_pages = None;
    let effects = match (fixtures::kind(name), model) {
        (Some(Kind::Book), _) => {
            let mut script = Script::parse(text).map_err(fail)?;
            if let Some(k) = &scene.input.get_ref().pages {
                for e in &mut script.events {
                    if let Action::Grab { pages, .. } = &mut e.action {
                        *pages = *k.get_ref();
                    }
                }
            }
            let settings = book_settings(scene);
            let mut book = Book::new(settings).map_err(fail)?;
            let n = frames(scene, script.frames);
            for frame in 0..n {
                for e in script.events_at(frame) {
                    book.apply(script.camera, script.forward, e.action)
                        .map_err(fail)?;
                }
                let t = Instant::now();
                let report = book.step().map_err(fail)?;
                let step_ms = t.elapsed().as_secs_f64() * 1e3;
                let stretch = book.stretch();
                let finite = book
                    .state()
                    .x
                    .iter()
                    .chain(&book.state().v)
                    .all(|p| p.is_finite());
                records.push(FrameRecord {
                    frame,
                    step_ms,
                    max_stretch: stretch.map(|s| s.0),
                    rmse_stretch: stretch.map(|s| s.1),
                    angle_defect: None,
                    dog_residual: book.dog_residual(),
                    penetration: book.penetration(),
                    status: format!("{:?}", report.solver.status),
                    nonfinite: !finite,
                });
                progress(frame + 1, n);
            }
            let mut effects = vec![
                "page blocks",
                "gravity",
                "glue",
                "collisions",
                "bookmarking",
            ];
            if settings.params.cover {
                effects.push("cover");
            }
            let c = book.counts();
            final_pages = Some([c.left, c.right, c.active]);
            effects
        }
        (Some(Kind::Touch), _) => {
            let script = TouchScript::parse(text).map_err(fail)?;
            let seed = name == "seed003-turn";
            let mut page: Box<dyn PageModel<f64>> = match model {
                ModelKind::Cone => {
                    let mut s = ConeSettings::default();
                    if seed {
                        (s.width, s.height) = (25.0, 25.0);
                    }
                    Box::new(ConePage::new(s).map_err(fail)?)
                }
                ModelKind::MassSpring => Box::new(
                    SpringPage::new(if seed {
                        SpringSettings::seed_experiment()
                    } else {
                        SpringSettings::default()
                    })
                    .map_err(fail)?,
                ),
                ModelKind::Dog => Box::new(DogPage::new(book_settings(scene)).map_err(fail)?),
            };
            let grid = QuadGrid::new(RENDER_QUADS.0, RENDER_QUADS.1).ok_or_else(|| fail("grid"))?;
            let mut samples = vec![glam_zero(); grid.len()];
            let n = frames(scene, script.frames);
            for frame in 0..n {
                script.at(frame).apply(page.as_mut()).map_err(fail)?;
                let t = Instant::now();
                let step = page.step().map_err(fail)?;
                let step_ms = t.elapsed().as_secs_f64() * 1e3;
                page.sample(grid, &mut samples).map_err(fail)?;
                let m = frame_metrics(grid, page.size(), &samples).map_err(fail)?;
                records.push(FrameRecord {
                    frame,
                    step_ms,
                    max_stretch: Some(m.max_stretch),
                    rmse_stretch: Some(m.rmse_stretch),
                    angle_defect: Some(m.max_angle_defect),
                    dog_residual: None,
                    penetration: None,
                    status: match step.status {
                        PageStatus::Moved => "Moved",
                        PageStatus::Unreachable => "Unreachable",
                        PageStatus::Stalled => "Stalled",
                    }
                    .to_string(),
                    nonfinite: !samples.iter().all(|p| p.is_finite()),
                });
                progress(frame + 1, n);
            }
            match model {
                ModelKind::Cone => vec![],
                ModelKind::MassSpring => vec!["gravity", "table"],
                ModelKind::Dog => vec!["page blocks", "gravity", "glue", "collisions", "cover"],
            }
        }
        (None, _) => return Err(fail("unknown fixture")),
    };
    Ok(Report {
        scene: scene.name.clone(),
        model: model.name(),
        summary: summarize(&records, effects, final_pages),
        frames: records,
    })
}

fn glam_zero() -> <f64 as folio_kernels::Real>::Vec3 {
    <f64 as folio_kernels::Real>::Vec3::ZERO
}

/// The `q`-quantile (0..=1) of `v` (0 when empty).
fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(((s.len().max(1) - 1) as f64 * q).round() as usize)
        .copied()
        .unwrap_or(0.0)
}

fn summarize(
    records: &[FrameRecord],
    effects: Vec<&'static str>,
    final_pages: Option<[u32; 3]>,
) -> Summary {
    let steps: Vec<f64> = records.iter().map(|r| r.step_ms).collect();
    let with_page: Vec<&FrameRecord> = records.iter().filter(|r| r.max_stretch.is_some()).collect();
    let mean = |f: fn(&FrameRecord) -> Option<f64>| {
        with_page.iter().filter_map(|r| f(r)).sum::<f64>() / with_page.len().max(1) as f64
    };
    let max = |f: fn(&FrameRecord) -> Option<f64>| records.iter().filter_map(f).reduce(f64::max);
    let mut status_counts = BTreeMap::new();
    for r in records {
        *status_counts.entry(r.status.clone()).or_insert(0) += 1;
    }
    Summary {
        frames: records.len() as u32,
        step_ms_median: quantile(&steps, 0.5),
        step_ms_p99: quantile(&steps, 0.99),
        max_stretch_mean: mean(|r| r.max_stretch),
        rmse_stretch_mean: mean(|r| r.rmse_stretch),
        dog_residual_max: max(|r| r.dog_residual),
        penetration_max: max(|r| r.penetration),
        nonfinite_frames: records.iter().filter(|r| r.nonfinite).count(),
        status_counts,
        effects,
        final_pages,
    }
}

impl Report {
    /// The expectations of `expect` this report does not meet, as messages (empty: all met).
    /// Non-finite frames always fail.
    #[must_use]
    pub fn unmet(&self, expect: &crate::scene::Expect) -> Vec<String> {
        let s = &self.summary;
        let mut out = Vec::new();
        if s.nonfinite_frames > 0 {
            out.push(format!(
                "{} frames with non-finite values",
                s.nonfinite_frames
            ));
        }
        if let Some(want) = expect.final_pages {
            if s.final_pages != Some(want) {
                out.push(format!(
                    "final pages {:?}, expected {want:?}",
                    s.final_pages
                ));
            }
        }
        let bounds = [
            (
                "max_stretch_mean",
                Some(s.max_stretch_mean),
                expect.max_stretch_mean,
            ),
            (
                "rmse_stretch_mean",
                Some(s.rmse_stretch_mean),
                expect.rmse_stretch_mean,
            ),
            (
                "dog_residual_max",
                s.dog_residual_max,
                expect.dog_residual_max,
            ),
            ("penetration_max", s.penetration_max, expect.penetration_max),
        ];
        for (name, got, bound) in bounds {
            if let Some(bound) = bound {
                match got {
                    Some(v) if v <= bound => {}
                    _ => out.push(format!("{name} {got:?} above {bound}")),
                }
            }
        }
        if let Some(most) = expect.failed_steps {
            let ok = ["Converged", "IterationLimit", "Moved", "Unreachable"];
            let failed: usize = s
                .status_counts
                .iter()
                .filter(|(k, _)| !ok.contains(&k.as_str()))
                .map(|(_, v)| v)
                .sum();
            if failed > most {
                out.push(format!("{failed} failed steps, at most {most} expected"));
            }
        }
        out
    }
}
