//! Running a checked scene: the model steps through its input, every frame is measured, and
//! the run ends in a [`Report`] (`report.json`).

use alloc::collections::BTreeMap;
use std::time::Instant;

use folio_book::BookParams;
use folio_book::{
    Action, Book, BookError, BookStepReport, DragOutcome, GrabOutcome, InputOutcome, Script,
};
use folio_geometry::QuadGrid;
use folio_geometry::mesh::TriMesh;
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::dog::DogPage;
use folio_pages::spring::SpringPage;
use folio_pages::touch::Touch;
use folio_pages::xpbd::XpbdPage;
use folio_pages::{Gestures, PageModel, PageStatus, TouchScript, frame_metrics};
use folio_tearing::sheet::TearingSheet;

use folio_scene::events;
use folio_scene::settings::{book_settings, spring_settings, xpbd_settings};
use serde::Serialize;

use folio_scene::fixtures::{self, Kind};
use folio_scene::scene::{ModelKind, Scene};

use folio_solvers::report::StepStatus;

use crate::health::{self, Bounds, Health};
use crate::sheet_run::TearingLog;

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
    /// A frame with its time, status and finiteness, and no model-specific figure: each
    /// model fills in its own with struct update syntax.
    #[must_use]
    pub fn new(frame: u32, step_ms: f64, status: String, nonfinite: bool) -> Self {
        Self {
            frame,
            step_ms,
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
    /// Median step time (milliseconds).
    pub step_ms_median: f64,
    /// 99th-percentile step time (milliseconds).
    pub step_ms_p99: f64,
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
    /// The summary.
    pub summary: Summary,
    /// Every frame.
    pub frames: Vec<FrameRecord>,
    /// The tears' log (sheet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tearing: Option<TearingLog>,
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

/// What a frame shows, for the outputs that draw it.
#[derive(Clone, Copy)]
pub enum Shape<'a> {
    /// The whole book.
    Book(&'a Book<f64>),
    /// A page model's page.
    Page(&'a dyn PageModel<f64>),
    /// The tearing sheet.
    Sheet(&'a TearingSheet<f64>),
}

impl Shape<'_> {
    /// The active page's thickness (page units; 0 without one): a stack of $k$ pages is
    /// $k$ pages thick.
    #[must_use]
    pub fn thickness(&self) -> f64 {
        match self {
            Self::Book(book) => book.active_thickness(),
            Self::Page(_) => BookParams::default().page_thickness,
            Self::Sheet(sheet) => sheet.settings().tearing.thickness,
        }
    }

    /// The page's surface at the material points of `grid` (page models: the page frame of
    /// [`folio_pages`]; the book: the active page in the book's frame), written into `out`;
    /// `false` when there is no page to sample (a book with no active page, a sheet).
    #[must_use]
    pub fn page_points(&self, grid: QuadGrid, out: &mut Vec<[f64; 3]>) -> bool {
        out.clear();
        let point = |p: <f64 as folio_kernels::Real>::Vec3| [p.x, p.y, p.z];
        match self {
            Self::Book(book) => {
                let (Some(nodes), s) = (book.page(), book.settings()) else {
                    return false;
                };
                let Some(page_grid) = QuadGrid::new(s.quads_across, s.quads_along) else {
                    return false;
                };
                let (size, spacing) = (book.page_size(), book.grid_spacing());
                out.extend((0..grid.len()).map(|k| {
                    let at = folio_pages::material_point(grid, size, k);
                    point(page_grid.bilinear::<f64>(nodes, spacing, at))
                }));
                true
            }
            Self::Page(page) => {
                let mut samples = vec![glam_zero(); grid.len()];
                if page.sample(grid, &mut samples).is_err() {
                    return false;
                }
                out.extend(samples.into_iter().map(point));
                true
            }
            Self::Sheet(_) => false,
        }
    }

    /// Appends the frame's render mesh to `out`.
    ///
    /// # Errors
    /// A mesh the mesher refuses (a non-finite or degenerate surface).
    pub fn mesh(&self, out: &mut TriMesh) -> Result<(), RunError> {
        match self {
            Self::Book(book) => book.mesh(out).map_err(fail),
            Self::Page(page) => {
                let grid = QuadGrid::new(RENDER_QUADS.0, RENDER_QUADS.1)
                    .ok_or_else(|| fail("render grid"))?;
                let thickness = BookParams::default().page_thickness;
                folio_pages::mesh(*page, grid, thickness, out).map_err(fail)
            }
            Self::Sheet(sheet) => {
                let s = sheet.settings();
                crate::sheet_view::render_mesh(sheet.mesh(), [s.width, s.height], out);
                Ok(())
            }
        }
    }
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
/// frame, and the run goes on.
///
/// # Errors
/// A model or input the scene describes but that refuses to start (settings the model
/// rejects; the scene's check refuses them first).
pub fn run(
    scene: &Scene,
    mut progress: impl FnMut(u32, u32),
    mut observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Report, RunError> {
    let model = *scene.model.get_ref();
    if model == ModelKind::Sheet {
        return crate::sheet_run::run(scene, progress, observe);
    }
    let mut records = Vec::new();
    let mut final_pages = None;
    if let Some((script, seed)) = touch_input(scene)? {
        // The DOG page is kept by type: its book measures the page and counts the pages.
        let mut dog = None;
        let mut other: Option<Box<dyn PageModel<f64>>> = None;
        match model {
            ModelKind::Cone => {
                let mut s = ConeSettings::default();
                if seed {
                    (s.width, s.height) = (25.0, 25.0);
                }
                other = Some(Box::new(ConePage::new(s).map_err(fail)?));
            }
            ModelKind::MassSpring => {
                let s = spring_settings(scene, seed);
                other = Some(Box::new(SpringPage::new(s).map_err(fail)?));
            }
            ModelKind::Xpbd => {
                let s = xpbd_settings(scene, seed);
                other = Some(Box::new(XpbdPage::new(s).map_err(fail)?));
            }
            ModelKind::Dog => dog = Some(DogPage::new(book_settings(scene)).map_err(fail)?),
            ModelKind::Sheet => return Err(fail("a sheet is held by hands")),
            other => return Err(fail(format!("no touch run for the {} model", other.name()))),
        }
        let grid = QuadGrid::new(RENDER_QUADS.0, RENDER_QUADS.1).ok_or_else(|| fail("grid"))?;
        let mut samples = vec![glam_zero(); grid.len()];
        let n = frames(scene, script.frames);
        for frame in 0..n {
            let page: &mut dyn PageModel<f64> = match (&mut dog, &mut other) {
                (Some(d), _) => d,
                (None, Some(o)) => o.as_mut(),
                (None, None) => return Err(fail("no page model")),
            };
            let inputs: Vec<String> = touch_problem(scene, script.at(frame), frame, page)
                .into_iter()
                .collect();
            let t = Instant::now();
            let step = page.step();
            let step_ms = t.elapsed().as_secs_f64() * 1e3;
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
                        ..FrameRecord::new(frame, step_ms, status.to_string(), false)
                    }
                }
                Err(e) => FrameRecord {
                    failed: true,
                    ..FrameRecord::new(frame, step_ms, format!("Refused ({e})"), false)
                },
            };
            record.inputs = inputs;
            let sampled = page
                .sample(grid, &mut samples)
                .and_then(|()| frame_metrics(grid, page.size(), &samples));
            match sampled {
                Ok(m) => {
                    record.max_stretch = Some(m.max_stretch);
                    record.rmse_stretch = Some(m.rmse_stretch);
                    record.angle_defect = Some(m.max_angle_defect);
                    record.nonfinite = !samples.iter().all(|p| p.is_finite());
                }
                // A page that cannot be sampled or measured is not a finite page.
                Err(_) => record.nonfinite = true,
            }
            if let Some(d) = &dog {
                record = book_record(record, d.book(), d.last_report(), step.is_ok());
            }
            records.push(record);
            let page: &dyn PageModel<f64> = match (&dog, &other) {
                (Some(d), _) => d,
                (None, Some(o)) => o.as_ref(),
                (None, None) => return Err(fail("no page model")),
            };
            observe(frame, n, Shape::Page(page));
            progress(frame + 1, n);
        }
        if let Some(d) = &dog {
            let c = d.book().counts();
            final_pages = Some([c.left, c.right, c.active]);
        }
    } else {
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
        let mut book = Book::<f64>::new(book_settings(scene)).map_err(fail)?;
        let n = frames(scene, script.frames);
        for frame in 0..n {
            let mut inputs = Vec::new();
            for e in script.events_at(frame) {
                let outcome = book.apply(script.camera, script.forward, e.action);
                inputs.extend(input_problem(frame, outcome));
            }
            let t = Instant::now();
            let step = book.step();
            let step_ms = t.elapsed().as_secs_f64() * 1e3;
            let record = match &step {
                Ok(_) => FrameRecord::new(frame, step_ms, String::new(), false),
                Err(e) => FrameRecord {
                    failed: true,
                    ..FrameRecord::new(frame, step_ms, format!("Refused ({e})"), false)
                },
            };
            let mut record = book_record(record, &book, step.as_ref().ok(), step.is_ok());
            record.inputs = inputs;
            records.push(record);
            observe(frame, n, Shape::Book(&book));
            progress(frame + 1, n);
        }
        let c = book.counts();
        final_pages = Some([c.left, c.right, c.active]);
    }
    Ok(Report::new(scene, records, final_pages))
}

/// `record` with the book's measures of the frame: the active page's stretch, DOG residual
/// and penetration, the state's finiteness, and, from the step's `report` (when the step
/// `stepped`), its solver status and work.
fn book_record(
    record: FrameRecord,
    book: &Book<f64>,
    report: Option<&BookStepReport<f64>>,
    stepped: bool,
) -> FrameRecord {
    let stretch = book.stretch();
    let finite = book
        .state()
        .x
        .iter()
        .chain(&book.state().v)
        .all(|p| p.is_finite());
    let record = FrameRecord {
        max_stretch: stretch.map(|s| s.0),
        rmse_stretch: stretch.map(|s| s.1),
        dog_residual: book.dog_residual(),
        penetration: book.penetration(),
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
            ..record.solver(r.solver.status)
        },
        None => record,
    }
}

/// What a touch input did wrong, if anything: a grab that missed the page, a refused drag.
fn touch_problem(
    scene: &Scene,
    touch: Touch,
    frame: u32,
    page: &mut dyn PageModel<f64>,
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
        step_ms_median: quantile(&steps, 0.5),
        step_ms_p99: quantile(&steps, 0.99),
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
