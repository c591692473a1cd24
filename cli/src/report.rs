//! The schema of a run's report (`report.json`): each frame's record, the summary with the
//! frames' health, and a sheet run's tears. Types only: the drivers fill them in
//! ([`crate::run`], [`crate::sheet_run`]), the checkers judge them ([`crate::health`],
//! [`crate::summary`]) and the outputs write them ([`crate::outputs`]).

use alloc::collections::BTreeMap;

use folio_solvers::report::StepStatus;
use serde::Serialize;

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
    /// binary's allocator on the running thread ([`crate::meter::Meter`]).
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
    /// Newton iterations (KKT systems solved) of the frame's steps (DOG book; 0 asleep).
    pub newton_iterations: Option<u32>,
    /// A finger-bookmarking snapshot was taken (DOG book).
    pub snapshot: Option<bool>,
    /// The book slept through every step of the frame: no solver work (DOG book;
    /// `folio_book::Book::is_asleep`).
    pub asleep: Option<bool>,
    /// Blocks' top pages that did not settle so far, each block then meeting the seed's
    /// walls instead (DOG book under `book.gutter = "top-page"`,
    /// `folio_book::Book::top_page_failures`; a frame where it grows is bad).
    pub gutter_failures: Option<u32>,
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
            newton_iterations: None,
            snapshot: None,
            asleep: None,
            gutter_failures: None,
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
    /// Model steps over the run (frames take [`folio_scene::clock::FRAME_SECONDS`] of model time each).
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
    /// How many awake frames took each number of Newton iterations (DOG book: the frames
    /// the book did not sleep through, by their steps' iterations in all).
    pub newton_iterations: Option<BTreeMap<u32, usize>>,
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
    /// The book's paper in physical units (a DOG scene that names a paper other than the
    /// seed's card).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper: Option<PaperRecord>,
}

/// A DOG book's paper (`folio_book::Paper`) and the book's units under it
/// (`folio_book::BookUnits`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PaperRecord {
    /// Page width, binding to fore-edge (m).
    pub width_m: f64,
    /// Page height along the binding (m).
    pub height_m: f64,
    /// Mass per area (g/m²).
    pub grammage: f64,
    /// Sheet thickness (m).
    pub caliper_m: f64,
    /// Plate bending stiffness $D$ (N·m).
    pub bending_stiffness: f64,
    /// $\alpha = \rho g L^3 / D$: the page's weight against its stiffness.
    pub sag_number: f64,
    /// Metres per page unit.
    pub metres_per_unit: f64,
    /// Real seconds per book second $\tau$: one second of the book shows what the real
    /// page does in $\tau$ seconds, so the book plays the real page $1/\tau$ times slower.
    pub real_seconds_per_second: f64,
}

impl PaperRecord {
    /// The record of `paper` under `units`.
    #[must_use]
    pub fn new(paper: &folio_book::Paper, units: &folio_book::BookUnits) -> Self {
        Self {
            width_m: paper.width,
            height_m: paper.height,
            grammage: 1e3 * paper.areal_density,
            caliper_m: paper.thickness,
            bending_stiffness: paper.bending_stiffness,
            sag_number: paper.sag_number(),
            metres_per_unit: units.length,
            real_seconds_per_second: units.time,
        }
    }
}

impl Report {
    /// `true` when every frame is good and every expectation is met.
    #[must_use]
    pub fn good(&self) -> bool {
        self.summary.verdict == "good"
    }
}

/// The bounds every frame is held to (`report.json`'s `summary.health.bounds`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Bounds {
    /// Largest max edge stretch of a frame.
    pub max_stretch: f64,
    /// Largest DOG residual of a frame (page units).
    pub dog_residual: f64,
    /// Deepest penetration into a block (page units); `None` when collisions are not
    /// simulated.
    pub penetration: Option<f64>,
    /// Frames whose step may fail or be refused.
    pub failed_steps: usize,
}

/// The first bad frame and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FirstBad {
    /// Its index.
    pub frame: u32,
    /// Its problems, joined.
    pub why: String,
}

/// What the frames show, counted (`report.json`'s `summary.health`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Health {
    /// The bounds the frames were held to.
    pub bounds: Bounds,
    /// Frames with at least one problem.
    pub bad_frames: usize,
    /// Frames whose step failed or was refused (allowed or not).
    pub failed_steps: usize,
    /// Frames whose step reported non-finite input.
    pub nonfinite_input_frames: usize,
    /// Frames whose state holds a non-finite coordinate.
    pub nonfinite_state_frames: usize,
    /// Inputs that did nothing (a grab that missed the page, a refused drag).
    pub input_problems: usize,
    /// Frames above the stretch bound.
    pub stretch_over: usize,
    /// Frames above the DOG residual bound.
    pub dog_residual_over: usize,
    /// Frames above the penetration bound.
    pub penetration_over: usize,
    /// Blocks' top pages that did not settle ([`FrameRecord::gutter_failures`]).
    pub gutter_failures: u32,
    /// The first bad frame, if any.
    pub first_bad: Option<FirstBad>,
}

impl Health {
    /// `true` when no frame is bad.
    #[must_use]
    pub fn good(&self) -> bool {
        self.bad_frames == 0
    }
}

/// One propagation of a tear (`report.json`'s `tearing.propagations`).
#[derive(Clone, Debug, Serialize)]
pub struct PropagationRecord {
    /// The frame it happened in.
    pub frame: u32,
    /// The tear (index into `tearing.tears`).
    pub tear: usize,
    /// Why its start was a potential tearing point: `tip`, `finger`, `junction`,
    /// `inward-angle`.
    pub kind: &'static str,
    /// The old tip (pattern, sheet units).
    pub from: [f64; 2],
    /// The new tip.
    pub to: [f64; 2],
    /// The release rate $E_r$ (eq. 6).
    pub release_rate: f64,
    /// The fracture energy $E_f$ (eq. 3) it beat.
    pub fracture_energy: f64,
    /// The mesh edit: `moved` (the tip slid), `split` (two lips), `separated` (a piece came
    /// off).
    pub edit: &'static str,
}

/// One tear at the end of the run (`report.json`'s `tearing.tears`).
#[derive(Clone, Debug, Serialize)]
pub struct TearRecord {
    /// The tear it branched from.
    pub parent: Option<usize>,
    /// Still open (it has a tip; a tear that reached the border has none).
    pub open: bool,
    /// Length of its path in the pattern (sheet units).
    pub length: f64,
    /// Its path in the pattern from the start to the tip.
    pub path: Vec<[f64; 2]>,
}

/// The tears' log of a sheet run.
#[derive(Clone, Debug, Serialize)]
pub struct TearingLog {
    /// The alpha textures' size in pixels (width, height).
    pub texture_size: [u32; 2],
    /// Every propagation in order.
    pub propagations: Vec<PropagationRecord>,
    /// Every tear.
    pub tears: Vec<TearRecord>,
}
