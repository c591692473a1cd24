//! The page turn: the default book (`BookSettings::default()`, seed 000's DOG book, with the
//! solver's diagnostics off: [`settings`]) plays
//! the recorded page turn of the integration tests (`tests/fixtures/page_turn.input`: camera
//! rays for a grab near the right page's outer edge at frame 30, 100 frames of drag over the
//! spine, the release at frame 131, then the page falls and settles; 750 frames), the same
//! input that `tests/tests/book.rs` (`page_turn_runs_in_f32`) plays on the host, compiled to
//! binary at build time ([`crate::fixture`]).
//!
//! Each step is timed alone (the inputs before it are timed apart); every step's line is
//! printed, then the summary and the result checks: one merge, into the left block; the
//! page counts after it; every node coordinate and velocity finite after every step; no
//! step that failed to advance the state; the book at rest, and asleep, at the end.

use cortex_m_semihosting::hprintln;
use folio_book::{Book, BookSettings, PageCounts, Phase};
use folio_geometry::BlockSide;
use folio_kernels::Vec3Ops;
use folio_solvers::StepStatus;

use crate::Real;
use crate::clock::Clock;
use crate::fixture::Fixture;
use crate::heap::{CountingHeap, HeapStats};
use crate::stats::{StepCounts, Summary};

/// What the run measured (instructions are SysTick ticks times the calibrated factor).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TurnReport {
    /// The page grid the book ran (quads across, along).
    pub grid: [usize; 2],
    /// `Book::new`: instructions, including the settling of the blocks.
    pub setup_instructions: u64,
    /// Steps `Book::new` took to settle the blocks.
    pub settle_steps: u32,
    /// Heap held after `Book::new` (bytes).
    pub setup_heap: usize,
    /// Steps with an active page (held or released).
    pub active: Summary,
    /// Steps of the book at rest.
    pub resting: Summary,
    /// Resting steps the book slept through ([`folio_book::Book::is_asleep`]).
    pub asleep_steps: u32,
    /// Most instructions of the inputs (grab, drag, release) before one step.
    pub input_max: u64,
    /// Allocation calls made inside `Book::step` (setup allocates; stepping should not).
    pub step_allocations: usize,
    /// Allocation calls made by the inputs (a grab lays a new page).
    pub input_allocations: usize,
    /// Heap counts at the end.
    pub heap: HeapStats,
    /// The page turn's accuracy over its active steps.
    pub accuracy: Accuracy,
    /// The result checks.
    pub checks: Checks,
}

/// The page turn's accuracy over its active steps, in whole numbers (the firmware prints no
/// floats): the largest DOG residual $\max\lvert C_{DOG}\rvert$ after any active step, in
/// units of $10^{-9}$, and the relative edge stretch $\max\lvert\ell/\ell_0 - 1\rvert$ of
/// each step, its largest and its mean over the active steps (the figure `book_report`
/// calls "mean max stretch"), in parts per million, all rounded up. A non-finite value reads
/// as `u64::MAX`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Accuracy {
    /// Largest DOG residual, $10^{-9}$.
    pub dog_residual_e9: u64,
    /// Largest edge stretch, parts per million.
    pub stretch_ppm: u64,
    /// Sum over the active steps of each one's largest edge stretch, parts per million.
    stretch_sum_ppm: u64,
    /// Active steps recorded.
    steps: u64,
}

impl Accuracy {
    /// Takes in the active page of `book` after a step.
    fn record(&mut self, book: &Book<Real>) {
        let whole = |value: Real, unit: f64| {
            let v = folio_kernels::Real::to_f64(value) * unit;
            if v.is_finite() && v >= 0.0 {
                // Rounded up: a bound read off this never flatters.
                let whole = v as u64;
                whole + u64::from((whole as f64) < v)
            } else {
                u64::MAX
            }
        };
        if let Some(dog) = book.dog_residual() {
            self.dog_residual_e9 = self.dog_residual_e9.max(whole(dog, 1e9));
        }
        if let Some((max, _)) = book.stretch() {
            let ppm = whole(max, 1e6);
            self.stretch_ppm = self.stretch_ppm.max(ppm);
            self.stretch_sum_ppm = self.stretch_sum_ppm.saturating_add(ppm);
            self.steps += 1;
        }
    }

    /// Mean over the active steps of each one's largest edge stretch, parts per million,
    /// rounded up (0 with no step).
    #[must_use]
    pub fn stretch_mean_ppm(&self) -> u64 {
        self.stretch_sum_ppm.div_ceil(self.steps.max(1))
    }
}

/// The result checks (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Checks {
    /// Merges, and the frame and block of the first.
    pub merges: u32,
    /// Frame and block of the first merge.
    pub first_merge: Option<(u32, BlockSide)>,
    /// Page counts at the start and at the end.
    pub counts: [PageCounts; 2],
    /// Steps after which some coordinate or velocity was not finite.
    pub nonfinite_steps: u32,
    /// Steps that did not advance the state.
    pub stalled_steps: u32,
    /// The phase after the last step.
    pub final_phase: Phase,
    /// The book was asleep after the last step ([`folio_book::Book::is_asleep`]).
    pub final_asleep: bool,
}

impl Checks {
    /// The page merged once, into the left block.
    #[must_use]
    pub fn merged_left(&self) -> bool {
        self.merges == 1 && matches!(self.first_merge, Some((_, BlockSide::Left)))
    }

    /// The left block gained the page the right block lost, and none is held.
    #[must_use]
    pub fn counts_moved(&self) -> bool {
        let [before, after] = self.counts;
        after.left == before.left + 1 && after.right + 1 == before.right && after.active == 0
    }

    /// Every check passed.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.merged_left()
            && self.counts_moved()
            && self.nonfinite_steps == 0
            && self.stalled_steps == 0
            && self.final_phase == Phase::AtRest
            && self.final_asleep
    }
}

/// Why the run could not finish.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TurnError {
    /// The binary fixture is malformed at this byte ([`crate::fixture::FixtureError`]).
    Fixture {
        /// Byte offset in the binary fixture.
        offset: usize,
    },
    /// `Book::new` refused the default settings.
    Setup,
    /// An input was refused at this frame.
    Input {
        /// Frame.
        frame: u32,
    },
    /// `Book::step` returned an error at this frame.
    Step {
        /// Frame.
        frame: u32,
    },
    /// The fixture has more frames than [`crate::stats::MAX_STEPS`].
    TooManyFrames {
        /// Frames in the fixture.
        frames: u32,
    },
    /// The static buffers (step counts, the book) were taken already
    /// ([`StepCounts::take`], [`open_book`]).
    Buffers,
}

impl core::fmt::Display for TurnError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Fixture { offset } => {
                write!(
                    f,
                    "the binary page-turn fixture is malformed at byte {offset}"
                )
            }
            Self::Setup => write!(f, "Book::new refused the default settings"),
            Self::Input { frame } => write!(f, "an input was refused at frame {frame}"),
            Self::Step { frame } => write!(f, "Book::step failed at frame {frame}"),
            Self::TooManyFrames { frames } => {
                write!(f, "the fixture has {frames} frames, too many")
            }
            Self::Buffers => write!(f, "the static buffers were taken already"),
        }
    }
}

/// Lowercase name of a phase.
#[must_use]
pub fn phase_name(phase: Phase) -> &'static str {
    match phase {
        Phase::AtRest => "rest",
        Phase::Held => "held",
        Phase::Released => "released",
        _ => "other",
    }
}

/// Lowercase name of a step status.
fn status_name(status: StepStatus) -> &'static str {
    match status {
        StepStatus::Converged => "converged",
        StepStatus::IterationLimit => "iteration-limit",
        StepStatus::LineSearchFailed => "line-search-failed",
        StepStatus::NumericalFailure => "numerical-failure",
        StepStatus::NonFiniteInput => "non-finite-input",
        _ => "other",
    }
}

/// Every node position and velocity of `book` is finite.
fn all_finite(book: &Book<Real>) -> bool {
    let state = book.state();
    state
        .x
        .iter()
        .chain(&state.v)
        .all(|p| p.x().is_finite() && p.y().is_finite() && p.z().is_finite())
}

/// The book the firmware plays: `BookSettings::default()` (with the `mcu` feature,
/// [`BookSettings::microcontroller`], the built-in scene `page-turn-mcu`) with the solver's
/// diagnostics off. `check_final_residual` evaluates the gradient and the Jacobian once more after the
/// last Newton iteration only so that the status can say `Converged`; it changes nothing in
/// the state, and the firmware reads no such status: it checks its results itself (module
/// docs). Measured with it on: 1.1 M instructions of a median active M4F step (issue 40).
#[must_use]
pub fn settings() -> BookSettings<Real> {
    let mut settings = if cfg!(feature = "mcu") {
        BookSettings::microcontroller()
    } else {
        BookSettings::default()
    };
    settings.solver.check_final_residual = false;
    settings
}

/// Builds the book into a static buffer (`.bss`), not on the stack: `Book::new` inlined into
/// [`run`] gave it a 14,208-byte frame that every step's calls stacked on (high-water
/// 27,308 bytes on the M4F); built here, out of line, the book's bytes are on the stack only
/// while it is built.
///
/// # Errors
/// [`TurnError::Setup`] when `Book::new` refuses the settings, [`TurnError::Buffers`] when
/// the static was taken already.
#[inline(never)]
fn open_book() -> Result<&'static mut Book<Real>, TurnError> {
    let slot = cortex_m::singleton!(: Option<Book<Real>> = None).ok_or(TurnError::Buffers)?;
    let book = Book::<Real>::new(settings()).map_err(|_| TurnError::Setup)?;
    Ok(slot.insert(book))
}

/// Plays the page turn, printing one line per step; `factor` is instructions per SysTick
/// tick ([`crate::clock::Calibration::factor`]).
///
/// # Errors
/// [`TurnError`] when the fixture, the setup, an input or a step is refused.
pub fn run(clock: &Clock, factor: u64, heap: &CountingHeap) -> Result<TurnReport, TurnError> {
    let fixture_error = |e: crate::fixture::FixtureError| TurnError::Fixture { offset: e.offset };
    let mut fixture = Fixture::page_turn().map_err(fixture_error)?;
    if fixture.frames as usize > crate::stats::MAX_STEPS {
        return Err(TurnError::TooManyFrames {
            frames: fixture.frames,
        });
    }

    let t0 = clock.now();
    let book = open_book()?;
    let setup_instructions = (clock.now() - t0) * factor;
    let setup_heap = heap.stats().current;
    hprintln!(
        "book: {} x {} page grid, built in {} instructions ({} settling steps), {} heap bytes held",
        book.settings().quads_across,
        book.settings().quads_along,
        setup_instructions,
        book.settle_steps(),
        setup_heap
    );
    hprintln!(
        "step frame phase status instructions dofs rows iterations halvings corrections collision-rounds"
    );

    let (active, resting) = StepCounts::take().ok_or(TurnError::Buffers)?;
    let mut accuracy = Accuracy::default();
    let mut checks = Checks {
        merges: 0,
        first_merge: None,
        counts: [book.counts(); 2],
        nonfinite_steps: 0,
        stalled_steps: 0,
        final_phase: book.phase(),
        final_asleep: false,
    };
    let (mut input_max, mut step_allocations, mut input_allocations) = (0, 0, 0);
    let mut asleep_steps = 0;
    for frame in 0..fixture.frames {
        let before_input = heap.stats().allocations;
        let t_input = clock.now();
        while let Some(action) = fixture.next_at(frame).map_err(fixture_error)? {
            book.apply(fixture.camera, fixture.forward, action)
                .map_err(|_| TurnError::Input { frame })?;
        }
        input_max = input_max.max((clock.now() - t_input) * factor);
        let before_step = heap.stats().allocations;
        input_allocations += before_step - before_input;

        let t_step = clock.now();
        let report = book.step();
        let instructions = (clock.now() - t_step) * factor;
        step_allocations += heap.stats().allocations - before_step;
        let report = report.map_err(|_| TurnError::Step { frame })?;

        asleep_steps += u32::from(report.asleep);
        if report.phase == Phase::AtRest {
            resting.push(frame, instructions);
        } else {
            active.push(frame, instructions);
            accuracy.record(book);
        }
        if !report.solver.status.advanced() {
            checks.stalled_steps += 1;
        }
        if !all_finite(book) {
            checks.nonfinite_steps += 1;
        }
        if let Some(side) = report.merged {
            checks.merges += 1;
            checks.first_merge.get_or_insert((frame, side));
        }
        hprintln!(
            "step {} {} {} {} {} {} {} {} {} {}{}",
            frame,
            phase_name(report.phase),
            status_name(report.solver.status),
            instructions,
            report.dofs,
            report.constraint_rows,
            report.solver.iterations,
            report.solver.halvings,
            report.correction.steps,
            report.collision_rounds,
            match report.merged {
                Some(BlockSide::Left) => " merged-left",
                Some(BlockSide::Right) => " merged-right",
                None => "",
            }
        );
    }
    checks.counts[1] = book.counts();
    checks.final_phase = book.phase();
    checks.final_asleep = book.is_asleep();
    let settings = book.settings();
    Ok(TurnReport {
        grid: [settings.quads_across, settings.quads_along],
        setup_instructions,
        settle_steps: book.settle_steps(),
        setup_heap,
        active: active.summary(),
        resting: resting.summary(),
        asleep_steps,
        input_max,
        step_allocations,
        input_allocations,
        heap: heap.stats(),
        accuracy,
        checks,
    })
}

/// The coordinate type's name, for the output.
#[must_use]
pub fn precision() -> &'static str {
    core::any::type_name::<Real>()
}
