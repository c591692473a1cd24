//! Running a checked scene: the model steps through its input, every frame is measured, and
//! the run ends in a [`Report`] (`report.json`).

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
use folio_scene::settings::{SceneReal, book_settings, spring_settings, xpbd_settings};

use folio_scene::fixtures::{self, Kind};
use folio_scene::scene::{ModelKind, Precision, Scene};

use crate::error::{RunError, fail};
use crate::meter::Meter;
use crate::report::{FrameRecord, Report};
use crate::shape::{PageView, RENDER_QUADS, Shape};

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
/// the scene's precision (`precision`).
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
enum Page<T: SceneReal> {
    Dog(Box<DogPage<T>>),
    Other(Box<dyn PageModel<T>>),
}

impl<T: SceneReal> Page<T> {
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
                let s = spring_settings::<T>(scene, seed).map_err(fail)?;
                Self::Other(Box::new(SpringPage::new(s).map_err(fail)?))
            }
            ModelKind::Xpbd => {
                let s = xpbd_settings::<T>(scene, seed).map_err(fail)?;
                Self::Other(Box::new(XpbdPage::new(s).map_err(fail)?))
            }
            ModelKind::Dog => {
                let s = book_settings(scene).map_err(fail)?;
                Self::Dog(Box::new(DogPage::new(s).map_err(fail)?))
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
fn page_time_step(scene: &Scene, seed: bool) -> Result<Option<f64>, RunError> {
    Ok(match *scene.model.get_ref() {
        ModelKind::Dog => Some(book_settings::<f64>(scene).map_err(fail)?.solver.time_step),
        ModelKind::MassSpring => Some(spring_settings::<f64>(scene, seed).map_err(fail)?.time_step),
        ModelKind::Xpbd => Some(xpbd_settings::<f64>(scene, seed).map_err(fail)?.time_step),
        _ => None,
    })
}

/// The steps frame `frame` takes at time step `h` (one per frame without a step).
fn frame_steps(frame: u32, h: Option<f64>) -> u32 {
    h.map_or(1, |h| clock::steps_in_frame(frame, h))
}

/// The collision tests, Newton iterations, snapshots and sleep of the steps of a frame (DOG
/// book).
#[derive(Default)]
struct FrameWork {
    contact_tests: usize,
    iterations: u32,
    snapshot: bool,
    /// Steps taken, and those the book slept through.
    steps: u32,
    asleep: u32,
}

impl FrameWork {
    fn add<T: Real>(&mut self, report: Option<&BookStepReport<T>>) {
        if let Some(r) = report {
            self.contact_tests += r.contacts.tested;
            self.iterations += r.solver.iterations;
            self.snapshot |= r.snapshot;
            self.steps += 1;
            self.asleep += u32::from(r.asleep);
        }
    }

    /// `record` with the frame's totals in place of its last step's.
    fn total(&self, record: FrameRecord) -> FrameRecord {
        FrameRecord {
            contact_tests: record.contact_tests.map(|_| self.contact_tests),
            newton_iterations: record.newton_iterations.map(|_| self.iterations),
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
fn run_touch<T: SceneReal>(
    scene: &Scene,
    (script, seed): (Gestures, bool),
    mut progress: impl FnMut(u32, u32),
    mut observe: impl FnMut(u32, u32, Shape<'_>),
) -> Result<Run, RunError> {
    let mut page = Page::<T>::new(scene, seed)?;
    let h = page_time_step(scene, seed)?;
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
fn run_book<T: SceneReal>(
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
    let mut book = Book::<T>::new(book_settings(scene).map_err(fail)?).map_err(fail)?;
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
            Err(BookError::InvalidInput {
                what: "no step taken",
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
        gutter_failures: Some(book.top_page_failures()),
        nonfinite: record.nonfinite || !finite,
        ..record
    };
    match report.filter(|_| stepped) {
        Some(r) => FrameRecord {
            dofs: Some(r.dofs),
            constraint_rows: Some(r.constraint_rows),
            terms: Some(r.census.potentials + r.census.constraints),
            contact_tests: Some(r.contacts.tested),
            newton_iterations: Some(r.solver.iterations),
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

#[cfg(test)]
#[path = "run_tests.rs"]
mod tests;
