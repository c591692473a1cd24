//! Running a checked scene: the model steps through its input, every frame is measured, and
//! the run ends in a [`Report`] (`report.json`).

use alloc::collections::BTreeMap;
use std::time::Instant;

use folio_book::{
    Action, Book, BookError, BookStepReport, DragOutcome, GrabOutcome, InputOutcome, Script,
};
use folio_geometry::QuadGrid;
use folio_kernels::{Real, Vec3Ops, real};
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::dog::DogPage;
use folio_pages::spring::SpringPage;
use folio_pages::touch::Touch;
use folio_pages::xpbd::XpbdPage;
use folio_pages::{Gestures, PageError, PageModel, PageStatus, TouchScript, frame_metrics};

use folio_scene::clock;
use folio_scene::events;
use folio_scene::settings::{book_settings, spring_settings, xpbd_settings};
use serde::Serialize;

use folio_scene::fixtures::{self, Kind};
use folio_scene::scene::{ModelKind, Precision, Scene};

use folio_solvers::report::StepStatus;

use crate::health::{self, Bounds, Health};
pub use crate::shape::{PageView, RENDER_QUADS, Shape};
use crate::sheet_run::TearingLog;

/// One frame of a run.
#[derive(Clone, Debug, Serialize)]
pub struct FrameRecord {
    /// Frame index.
    pub frame: u32,
    /// Model steps the frame took (a frame is 1/60 s of model time; [`folio_scene::clock`]):
    /// as many as it was due, or up to the first that failed.
    pub steps: u32,
    /// Wall time of all the frame's steps (milliseconds): the frame's compute time.
    pub step_ms: f64,
    /// Heap allocations (and reallocations) the frame's steps made, counted by the `folio`
    /// binary's allocator on the running thread ([`Meter`]).
    pub allocations: usize,
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
    /// Unknowns of the step's KKT system (DOG book).
    pub dofs: Option<usize>,
    /// Constraint rows of the step's KKT system (DOG book).
    pub constraint_rows: Option<usize>,
    /// Potential and constraint terms of the step (DOG book).
    pub terms: Option<usize>,
    /// Point-obstacle collision tests of the step (DOG book).
    pub contact_tests: Option<usize>,
    /// A finger-bookmarking snapshot was taken (DOG book).
    pub snapshot: Option<bool>,
    /// The book slept through every step of the frame: no solver work (DOG book;
    /// `folio_book::Book::is_asleep`).
    pub asleep: Option<bool>,
    /// Tear propagations in the frame (sheet).
    pub propagations: Option<u32>,
    /// Propagations the Griffith criterion allowed but the mesh refused (sheet).
    pub refused: Option<u32>,
    /// Edge flips of the cone remesh (sheet).
    pub flips: Option<u32>,
    /// Triangles of the sheet after the frame (sheet).
    pub triangles: Option<usize>,
    /// How the step went.
    pub status: String,
    /// Some coordinate of the state is not finite after the step.
    pub nonfinite: bool,
    /// The step refused its input as non-finite (its state was kept).
    pub nonfinite_input: bool,
    /// The step failed or was refused: the model could not advance and kept its state.
    pub failed: bool,
    /// The frame's inputs that did nothing they should have ("grab at frame 30 missed the
    /// page").
    pub inputs: Vec<String>,
    /// Why the frame is bad (empty: it is not), from [`crate::health::judge`].
    pub problems: Vec<String>,
}

impl FrameRecord {
    /// A frame with its steps, time, status and finiteness, and no model-specific figure: each
    /// model fills in its own with struct update syntax.
    #[must_use]
    pub fn new(frame: u32, steps: u32, step_ms: f64, status: String, nonfinite: bool) -> Self {
        Self {
            frame,
            steps,
            step_ms,
            allocations: 0,
            max_stretch: None,
            rmse_stretch: None,
            angle_defect: None,
            dog_residual: None,
            penetration: None,
            dofs: None,
            constraint_rows: None,
            terms: None,
            contact_tests: None,
            snapshot: None,
            asleep: None,
            propagations: None,
            refused: None,
            flips: None,
            triangles: None,
            status,
            nonfinite,
            nonfinite_input: false,
            failed: false,
            inputs: Vec::new(),
            problems: Vec::new(),
        }
    }

    /// The record's step health from a solver status: failed unless it advanced, with
    /// non-finite input flagged.
    #[must_use]
    pub fn solver(self, status: StepStatus) -> Self {
        Self {
            status: format!("{status:?}"),
            nonfinite_input: status == StepStatus::NonFiniteInput,
            failed: !status.advanced(),
            ..self
        }
    }
}

/// The summary of a run (`report.json`'s `summary`).
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Frames run.
    pub frames: u32,
    /// Mean compute time of a frame, all its steps (milliseconds): the run's compute time
    /// over its frames.
    pub step_ms_mean: f64,
    /// Median compute time of a frame, all its steps (milliseconds).
    pub step_ms_median: f64,
    /// 99th-percentile compute time of a frame, all its steps (milliseconds).
    pub step_ms_p99: f64,
    /// Model steps over the run (frames take [`clock::FRAME_SECONDS`] of model time each).
    pub steps_total: u64,
    /// Heap allocations per model step, over the run (DESIGN.md: stepping does not allocate).
    pub allocations_per_step: f64,
    /// Mean over frames with a page of the max edge stretch (null without one).
    pub max_stretch_mean: Option<f64>,
    /// Mean over frames with a page of the RMSE edge stretch (null without one).
    pub rmse_stretch_mean: Option<f64>,
    /// Largest max edge stretch of a frame (null without a page).
    pub max_stretch_max: Option<f64>,
    /// Largest DOG residual (DOG book), else null.
    pub dog_residual_max: Option<f64>,
    /// Deepest penetration (DOG book), else null.
    pub penetration_max: Option<f64>,
    /// Frames with non-finite input or state (`health` tells them apart).
    pub nonfinite_frames: usize,
    /// Every frame held to its bounds: what went wrong, counted, and the first bad frame.
    pub health: Health,
    /// The scene's other expectations the run did not meet.
    pub unmet: Vec<String>,
    /// `"good"`, or `"bad"` when a frame is bad or an expectation is unmet (`folio run`
    /// then exits with 3).
    pub verdict: &'static str,
    /// Frames per step status.
    pub status_counts: BTreeMap<String, usize>,
    /// What the model simulated.
    pub effects: Vec<String>,
    /// Largest KKT system of a step: unknowns (DOG book).
    pub dofs_max: Option<usize>,
    /// Largest KKT system of a step: constraint rows (DOG book).
    pub constraint_rows_max: Option<usize>,
    /// Most terms in a step (DOG book).
    pub terms_max: Option<usize>,
    /// Collision tests over the run (DOG book).
    pub contact_tests_total: Option<usize>,
    /// Finger-bookmarking snapshots over the run (DOG book).
    pub snapshots_total: Option<usize>,
    /// Frames the book slept through, doing no solver work (DOG book).
    pub asleep_frames: Option<usize>,
    /// Fraction of the contact sheet's pixels that show the active page (and any page
    /// model's page), when a sheet was drawn.
    pub page_coverage: Option<f64>,
    /// Fraction of the contact sheet's pixels that show paper (pages and block tops).
    pub paper_coverage: Option<f64>,
    /// Pages in the left block, the right block and the grip at the end (DOG book).
    pub final_pages: Option<[u32; 3]>,
    /// Tear propagations over the run (sheet).
    pub propagations_total: Option<usize>,
    /// The length of every tear in the pattern at the end (sheet units; sheet).
    pub tear_lengths: Option<Vec<f64>>,
    /// The kind of point the first tear started at (sheet; null without a tear).
    pub tear_start: Option<String>,
}

/// A finished run (`report.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The scene's name.
    pub scene: String,
    /// The page model.
    pub model: &'static str,
    /// The precision the model ran in (`"f64"`, `"f32"`).
    pub precision: &'static str,
    /// The summary.
    pub summary: Summary,
    /// Every frame.
    pub frames: Vec<FrameRecord>,
    /// The tears' log (sheet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tearing: Option<TearingLog>,
}

/// Measures a frame's steps: their wall time and the allocations the running thread made
/// (counted by the `folio` binary's global allocator, `folio_counting`).
pub(crate) struct Meter {
    started: Instant,
    allocations: usize,
}

impl Meter {
    /// Starts measuring.
    #[must_use]
    pub(crate) fn start() -> Self {
        Self {
            allocations: folio_counting::allocations(),
            started: Instant::now(),
        }
    }

    /// The milliseconds and allocations since [`Meter::start`].
    #[must_use]
    pub(crate) fn stop(self) -> (f64, usize) {
        let ms = self.started.elapsed().as_secs_f64() * 1e3;
        let allocations = folio_counting::allocations() - self.allocations;
        (ms, allocations)
    }
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

pub(crate) fn fail(e: impl core::fmt::Display) -> RunError {
    RunError(e.to_string())
}

/// The frames to run: the scene's, else the input's.
fn frames(scene: &Scene, input: u32) -> u32 {
    scene.frames.as_ref().map_or(input, |f| *f.get_ref())
}

/// The input of a scene as gestures, when it is not a book fixture: a touch fixture or the
/// scene's timed events.
fn touch_input(scene: &Scene) -> Result<Option<(Gestures, bool)>, RunError> {
    let input = scene.input.get_ref();
    if let Some(events) = &input.events {
        let frames = scene.frames.as_ref().map(|f| *f.get_ref());
        let script = events::touch_script(events.get_ref(), frames).map_err(|e| fail(e.1))?;
        return Ok(Some((script, false)));
    }
    let name = input
        .fixture
        .as_ref()
        .ok_or_else(|| fail("no input"))?
        .get_ref();
    let text = fixtures::text(name).ok_or_else(|| fail("unknown fixture"))?;
    match fixtures::kind(name) {
        Some(Kind::Touch) => Ok(Some((
            TouchScript::parse(text).map_err(fail)?.into(),
            name == "seed003-turn",
        ))),
        _ => Ok(None),
    }
}

/// Runs `scene`, calling `progress(frame, frames)` and `observe(frame, frames, shape)`
/// after every frame. Every frame is measured and held to the scene's bounds
/// ([`crate::health`]); an input that does nothing or a step that fails is recorded in its
/// frame, and the run goes on. A frame is [`clock::FRAME_SECONDS`] of model time: its inputs
/// apply, then the model takes the frame's steps ([`folio_scene::clock`]). The model runs in
/// the scene's precision (`solver.precision`).
///
/// # Errors
/// A model or input the scene describes but that refuses to start (settings the model
/// rejects; the scene's check refuses them first).
pub fn run(
    scene: &Scene,
    progress: impl FnMut(u32, u32),
    observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Report, RunError> {
    let model = *scene.model.get_ref();
    if model == ModelKind::Sheet {
        return crate::sheet_run::run(scene, progress, observe);
    }
    let (records, final_pages) = match (touch_input(scene)?, scene.precision()) {
        (Some(touch), Precision::F64) => run_touch::<f64>(scene, touch, progress, observe)?,
        (Some(touch), Precision::F32) => run_touch::<f32>(scene, touch, progress, observe)?,
        (None, Precision::F64) => run_book::<f64>(scene, progress, observe)?,
        (None, Precision::F32) => run_book::<f32>(scene, progress, observe)?,
    };
    Ok(Report::new(scene, records, final_pages))
}

/// The frames of a run and the final page counts (DOG book).
type Run = (Vec<FrameRecord>, Option<[u32; 3]>);

/// A page model of `scene` in precision `T` for touch input: the DOG page (kept by type: its
/// book measures the page and counts the pages), else another model behind the trait.
enum Page<T: Real> {
    Dog(Box<DogPage<T>>),
    Other(Box<dyn PageModel<T>>),
}

impl<T: Real> Page<T> {
    fn new(scene: &Scene, seed: bool) -> Result<Self, RunError> {
        Ok(match *scene.model.get_ref() {
            ModelKind::Cone => {
                let mut s = ConeSettings::default();
                if seed {
                    (s.width, s.height) = (T::from_f64(25.0), T::from_f64(25.0));
                }
                Self::Other(Box::new(ConePage::new(s).map_err(fail)?))
            }
            ModelKind::MassSpring => {
                let s = spring_settings::<T>(scene, seed);
                Self::Other(Box::new(SpringPage::new(s).map_err(fail)?))
            }
            ModelKind::Xpbd => {
                let s = xpbd_settings::<T>(scene, seed);
                Self::Other(Box::new(XpbdPage::new(s).map_err(fail)?))
            }
            ModelKind::Dog => {
                Self::Dog(Box::new(DogPage::new(book_settings(scene)).map_err(fail)?))
            }
            other => return Err(fail(format!("no touch run for the {} model", other.name()))),
        })
    }

    fn model(&self) -> &dyn PageModel<T> {
        match self {
            Self::Dog(d) => d.as_ref(),
            Self::Other(o) => o.as_ref(),
        }
    }

    fn model_mut(&mut self) -> &mut dyn PageModel<T> {
        match self {
            Self::Dog(d) => d.as_mut(),
            Self::Other(o) => o.as_mut(),
        }
    }
}

/// The model time step $h$ (seconds) of a page model of `scene`; `None` for the cone,
/// which has no step (one per frame).
fn page_time_step(scene: &Scene, seed: bool) -> Option<f64> {
    match *scene.model.get_ref() {
        ModelKind::Dog => Some(book_settings::<f64>(scene).solver.time_step),
        ModelKind::MassSpring => Some(spring_settings::<f64>(scene, seed).time_step),
        ModelKind::Xpbd => Some(xpbd_settings::<f64>(scene, seed).time_step),
        _ => None,
    }
}

/// The steps frame `frame` takes at time step `h` (one per frame without a step).
fn frame_steps(frame: u32, h: Option<f64>) -> u32 {
    h.map_or(1, |h| clock::steps_in_frame(frame, h))
}

/// The collision tests, snapshots and sleep of the steps of a frame (DOG book).
#[derive(Default)]
struct FrameWork {
    contact_tests: usize,
    snapshot: bool,
    /// Steps taken, and those the book slept through.
    steps: u32,
    asleep: u32,
}

impl FrameWork {
    fn add<T: Real>(&mut self, report: Option<&BookStepReport<T>>) {
        if let Some(r) = report {
            self.contact_tests += r.contacts.tested;
            self.snapshot |= r.snapshot;
            self.steps += 1;
            self.asleep += u32::from(r.asleep);
        }
    }

    /// `record` with the frame's totals in place of its last step's.
    fn total(&self, record: FrameRecord) -> FrameRecord {
        FrameRecord {
            contact_tests: record.contact_tests.map(|_| self.contact_tests),
            snapshot: record.snapshot.map(|_| self.snapshot),
            asleep: record
                .asleep
                .map(|_| self.steps > 0 && self.asleep == self.steps),
            ..record
        }
    }
}

/// The name of the function that steps a frame: `folio atlas` counts the instructions of a
/// run inside it only (callgrind's `--toggle-collect`, [`crate::atlas::instructions`]), so
/// its counts hold a frame's steps and nothing of the run's setup, sampling or outputs.
pub(crate) const FRAME_FUNCTION: &str = "advance_frame";

/// Takes the `wanted` steps of one frame with `step`, up to the first one that has not
/// `advanced` (the model keeps its state); returns the last step's result (`none` without
/// a step) and the steps taken. Never inlined: see [`FRAME_FUNCTION`].
#[inline(never)]
fn advance_frame<S>(
    wanted: u32,
    none: S,
    mut step: impl FnMut() -> S,
    advanced: impl Fn(&S) -> bool,
) -> (S, u32) {
    let (mut last, mut steps) = (none, 0);
    while steps < wanted {
        last = step();
        steps += 1;
        if !advanced(&last) {
            break;
        }
    }
    (last, steps)
}

/// Runs a page model in precision `T` through touch input `(script, seed)`.
fn run_touch<T: Real>(
    scene: &Scene,
    (script, seed): (Gestures, bool),
    mut progress: impl FnMut(u32, u32),
    mut observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Run, RunError> {
    let mut page = Page::<T>::new(scene, seed)?;
    let h = page_time_step(scene, seed);
    let grid = QuadGrid::new(RENDER_QUADS.0, RENDER_QUADS.1).ok_or_else(|| fail("grid"))?;
    let mut samples = vec![T::Vec3::ZERO; grid.len()];
    let mut records = Vec::new();
    let n = frames(scene, script.frames);
    for frame in 0..n {
        let inputs: Vec<String> = touch_problem(scene, script.at(frame), frame, page.model_mut())
            .into_iter()
            .collect();
        let mut work = FrameWork::default();
        let meter = Meter::start();
        let (step, steps) = advance_frame(
            frame_steps(frame, h),
            Err(PageError::InvalidInput { what: "no step" }),
            || {
                let step = page.model_mut().step();
                if let Page::Dog(d) = &page {
                    work.add(d.last_report());
                }
                step
            },
            |s| s.as_ref().is_ok_and(|s| s.status != PageStatus::Stalled),
        );
        let (step_ms, allocations) = meter.stop();
        let mut record = match &step {
            Ok(step) => {
                let status = match step.status {
                    PageStatus::Moved => "Moved",
                    PageStatus::Unreachable => "Unreachable",
                    PageStatus::Stalled => "Stalled",
                    _ => "Other",
                };
                FrameRecord {
                    failed: step.status == PageStatus::Stalled,
                    ..FrameRecord::new(frame, steps, step_ms, status.to_string(), false)
                }
            }
            Err(e) => FrameRecord {
                failed: true,
                ..FrameRecord::new(frame, steps, step_ms, format!("Refused ({e})"), false)
            },
        };
        record.inputs = inputs;
        record.allocations = allocations;
        let model = page.model();
        let sampled = model
            .sample(grid, &mut samples)
            .and_then(|()| frame_metrics(grid, model.size(), &samples));
        match sampled {
            Ok(m) => {
                record.max_stretch = Some(m.max_stretch.to_f64());
                record.rmse_stretch = Some(m.rmse_stretch.to_f64());
                record.angle_defect = Some(m.max_angle_defect.to_f64());
                record.nonfinite = !samples.iter().all(|p| real::vec_is_finite::<T>(*p));
            }
            // A page that cannot be sampled or measured is not a finite page.
            Err(_) => record.nonfinite = true,
        }
        if let Page::Dog(d) = &page {
            record = work.total(book_record(record, d.book(), d.last_report(), step.is_ok()));
        }
        records.push(record);
        observe(frame, n, Shape::Page(&PageView(page.model())));
        progress(frame + 1, n);
    }
    let final_pages = match &page {
        Page::Dog(d) => {
            let c = d.book().counts();
            Some([c.left, c.right, c.active])
        }
        Page::Other(_) => None,
    };
    Ok((records, final_pages))
}

/// Runs the DOG book in precision `T` through the scene's book fixture.
fn run_book<T: Real>(
    scene: &Scene,
    mut progress: impl FnMut(u32, u32),
    mut observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Run, RunError> {
    let name = scene
        .input
        .get_ref()
        .fixture
        .as_ref()
        .ok_or_else(|| fail("no input"))?;
    let text = fixtures::text(name.get_ref()).ok_or_else(|| fail("unknown fixture"))?;
    let mut script = Script::parse(text).map_err(fail)?;
    if let Some(k) = &scene.input.get_ref().pages {
        for e in &mut script.events {
            if let Action::Grab { pages, .. } = &mut e.action {
                *pages = *k.get_ref();
            }
        }
    }
    let mut book = Book::<T>::new(book_settings(scene)).map_err(fail)?;
    let h = Some(book.settings().solver.time_step.to_f64());
    let mut records = Vec::new();
    let n = frames(scene, script.frames);
    for frame in 0..n {
        let mut inputs = Vec::new();
        for e in script.events_at(frame) {
            let outcome = book.apply(script.camera, script.forward, e.action);
            inputs.extend(input_problem(frame, outcome));
        }
        let mut work = FrameWork::default();
        let meter = Meter::start();
        let (step, steps) = advance_frame(
            frame_steps(frame, h),
            Err(BookError::InvalidSetting {
                field: "no step",
                requirement: "taken",
            }),
            || {
                let step = book.step();
                work.add(step.as_ref().ok());
                step
            },
            |s| s.as_ref().is_ok_and(|r| r.solver.status.advanced()),
        );
        let (step_ms, allocations) = meter.stop();
        let record = match &step {
            Ok(_) => FrameRecord::new(frame, steps, step_ms, String::new(), false),
            Err(e) => FrameRecord {
                failed: true,
                ..FrameRecord::new(frame, steps, step_ms, format!("Refused ({e})"), false)
            },
        };
        let mut record = work.total(book_record(record, &book, step.as_ref().ok(), step.is_ok()));
        record.inputs = inputs;
        record.allocations = allocations;
        records.push(record);
        observe(frame, n, Shape::Book(&book));
        progress(frame + 1, n);
    }
    let c = book.counts();
    Ok((records, Some([c.left, c.right, c.active])))
}

/// `record` with the book's measures of the frame (after its last step), in `f64`: the
/// active page's stretch, DOG residual and penetration, the state's finiteness, and, from
/// the last step's `report` (when the step `stepped`), its solver status and work.
fn book_record<T: Real>(
    record: FrameRecord,
    book: &Book<T>,
    report: Option<&BookStepReport<T>>,
    stepped: bool,
) -> FrameRecord {
    let stretch = book.stretch();
    let finite = book
        .state()
        .x
        .iter()
        .chain(&book.state().v)
        .all(|p| real::vec_is_finite::<T>(*p));
    let record = FrameRecord {
        max_stretch: stretch.map(|s| s.0.to_f64()),
        rmse_stretch: stretch.map(|s| s.1.to_f64()),
        dog_residual: book.dog_residual().map(Real::to_f64),
        penetration: book.penetration().map(Real::to_f64),
        nonfinite: record.nonfinite || !finite,
        ..record
    };
    match report.filter(|_| stepped) {
        Some(r) => FrameRecord {
            dofs: Some(r.dofs),
            constraint_rows: Some(r.constraint_rows),
            terms: Some(r.census.potentials + r.census.constraints),
            contact_tests: Some(r.contacts.tested),
            snapshot: Some(r.snapshot),
            asleep: Some(r.asleep),
            ..record.solver(r.solver.status)
        },
        None => record,
    }
}

/// What a touch input did wrong, if anything: a grab that missed the page, a refused drag.
fn touch_problem<T: Real>(
    scene: &Scene,
    touch: Touch,
    frame: u32,
    page: &mut dyn PageModel<T>,
) -> Option<String> {
    let e = touch.apply(page).err()?;
    Some(match touch {
        Touch::Grab { .. } | Touch::Take { .. } => format!(
            "grab at frame {frame} missed the page ({})",
            events::refusal(scene, None, frame, &e)
        ),
        Touch::Drag(_) => format!("drag at frame {frame} was refused ({e})"),
        _ => format!("input at frame {frame} was refused ({e})"),
    })
}

/// What a recorded book input did wrong, if anything: a grab whose ray missed the book or
/// found too few pages, a drag whose ray missed the drag plane, a refused input.
fn input_problem(frame: u32, outcome: Result<InputOutcome, BookError>) -> Option<String> {
    match outcome {
        Ok(InputOutcome::Grab(GrabOutcome::Missed)) => {
            Some(format!("grab at frame {frame} missed the page"))
        }
        Ok(InputOutcome::Grab(GrabOutcome::NotEnoughPages)) => Some(format!(
            "grab at frame {frame} found fewer pages than it takes"
        )),
        Ok(InputOutcome::Drag(DragOutcome::Missed)) => {
            Some(format!("drag at frame {frame} missed the drag plane"))
        }
        Ok(_) => None,
        Err(e) => Some(format!("input at frame {frame} was refused ({e})")),
    }
}

/// The `q`-quantile (0..=1) of `v` (0 when empty).
fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(((s.len().max(1) - 1) as f64 * q).round() as usize)
        .copied()
        .unwrap_or(0.0)
}

/// The summary of `records` (the sheet's tear fields are left empty), with their health
/// under `bounds` (each record's `problems` are written).
pub(crate) fn summarize(
    records: &mut [FrameRecord],
    bounds: Bounds,
    effects: Vec<String>,
    final_pages: Option<[u32; 3]>,
) -> Summary {
    let health = health::judge(records, bounds);
    let steps: Vec<f64> = records.iter().map(|r| r.step_ms).collect();
    let with_page: Vec<&FrameRecord> = records.iter().filter(|r| r.max_stretch.is_some()).collect();
    let mean = |f: fn(&FrameRecord) -> Option<f64>| {
        (!with_page.is_empty()).then(|| {
            with_page
                .iter()
                .filter_map(|r| f(r))
                .fold(0.0, |a, b| a + b)
                / with_page.len() as f64
        })
    };
    // NaN-aware: a NaN measure is the largest.
    let max = |f: fn(&FrameRecord) -> Option<f64>| {
        records
            .iter()
            .filter_map(f)
            .reduce(|a, b| if a.is_nan() || a >= b { a } else { b })
    };
    let mut status_counts = BTreeMap::new();
    for r in records.iter() {
        *status_counts.entry(r.status.clone()).or_insert(0) += 1;
    }
    Summary {
        frames: records.len() as u32,
        step_ms_mean: steps.iter().sum::<f64>() / steps.len().max(1) as f64,
        step_ms_median: quantile(&steps, 0.5),
        step_ms_p99: quantile(&steps, 0.99),
        steps_total: records.iter().map(|r| u64::from(r.steps)).sum(),
        allocations_per_step: records.iter().map(|r| r.allocations as f64).sum::<f64>()
            / records
                .iter()
                .map(|r| f64::from(r.steps))
                .sum::<f64>()
                .max(1.0),
        max_stretch_mean: mean(|r| r.max_stretch),
        rmse_stretch_mean: mean(|r| r.rmse_stretch),
        max_stretch_max: max(|r| r.max_stretch),
        dog_residual_max: max(|r| r.dog_residual),
        penetration_max: max(|r| r.penetration),
        nonfinite_frames: records
            .iter()
            .filter(|r| r.nonfinite || r.nonfinite_input)
            .count(),
        verdict: if health.good() { "good" } else { "bad" },
        health,
        unmet: Vec::new(),
        status_counts,
        effects,
        dofs_max: records.iter().filter_map(|r| r.dofs).max(),
        constraint_rows_max: records.iter().filter_map(|r| r.constraint_rows).max(),
        terms_max: records.iter().filter_map(|r| r.terms).max(),
        contact_tests_total: records.iter().map(|r| r.contact_tests).sum(),
        page_coverage: None,
        paper_coverage: None,
        snapshots_total: records.iter().map(|r| r.snapshot.map(usize::from)).sum(),
        asleep_frames: records.iter().map(|r| r.asleep.map(usize::from)).sum(),
        final_pages,
        propagations_total: None,
        tear_lengths: None,
        tear_start: None,
    }
}

impl Report {
    /// The report of `scene`'s run: the summary of `records` held to the scene's bounds
    /// ([`Bounds::of`]), then its expectations (a sheet run adds its tears and judges
    /// again).
    pub(crate) fn new(
        scene: &Scene,
        mut records: Vec<FrameRecord>,
        final_pages: Option<[u32; 3]>,
    ) -> Self {
        let summary = summarize(
            &mut records,
            Bounds::of(scene),
            scene.effect_names(),
            final_pages,
        );
        let mut report = Self {
            scene: scene.name.clone(),
            model: scene.model.get_ref().name(),
            precision: scene.precision().name(),
            summary,
            frames: records,
            tearing: None,
        };
        report.judge(&scene.expect);
        report
    }

    /// Checks the expectations of `expect` beyond the health bounds (pages, mean stretch,
    /// tears) against the summary: writes `unmet` and the verdict (call again after a
    /// summary field changes).
    pub fn judge(&mut self, expect: &folio_scene::scene::Expect) {
        self.summary.unmet = self.unmet(expect);
        let good = self.summary.health.good() && self.summary.unmet.is_empty();
        self.summary.verdict = if good { "good" } else { "bad" };
    }

    /// `true` when every frame is good and every expectation is met.
    #[must_use]
    pub fn good(&self) -> bool {
        self.summary.verdict == "good"
    }

    /// The expectations of `expect` beyond the health bounds this report does not meet, as
    /// messages (empty: all met).
    #[must_use]
    fn unmet(&self, expect: &folio_scene::scene::Expect) -> Vec<String> {
        let s = &self.summary;
        let mut out = Vec::new();
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
                s.max_stretch_mean,
                expect.max_stretch_mean,
            ),
            (
                "rmse_stretch_mean",
                s.rmse_stretch_mean,
                expect.rmse_stretch_mean,
            ),
        ];
        for (name, got, bound) in bounds {
            if let Some(bound) = bound {
                match got {
                    Some(v) if v <= bound => {}
                    _ => out.push(format!("{name} {got:?} above {bound}")),
                }
            }
        }
        if let Some(min) = expect.tear_length_min.as_ref().map(|v| *v.get_ref()) {
            let longest = s
                .tear_lengths
                .as_ref()
                .and_then(|l| l.iter().copied().reduce(f64::max));
            if !longest.is_some_and(|l| l >= min) {
                out.push(format!("longest tear {longest:?}, expected at least {min}"));
            }
        }
        if let Some(start) = expect.tear_start.as_ref().map(|v| *v.get_ref()) {
            if s.tear_start.as_deref() != Some(start.name()) {
                out.push(format!(
                    "the first tear started at {:?}, expected {}",
                    s.tear_start,
                    start.name()
                ));
            }
        }
        out
    }
}

#[cfg(test)]
#[path = "run_tests.rs"]
mod tests;
