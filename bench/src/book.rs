//! Playing the book's recorded fixtures for benches and reports.

use std::time::Instant;

use folio_book::{Book, BookSettings, BookStepReport, Script};
use folio_kernels::Real;

/// The page-turn fixture (750 frames at 60 fps).
pub const PAGE_TURN: &str = include_str!("../../tests/fixtures/page_turn.input");

/// What one play of a fixture measured.
#[derive(Clone, Debug, Default)]
pub struct Play<T = f64> {
    /// Wall time of every frame's step (input applied before it), seconds.
    pub step_seconds: Vec<f64>,
    /// Mean over frames with an active page of the maximum edge stretch.
    pub max_stretch_mean: f64,
    /// Mean over frames with an active page of the RMS edge stretch.
    pub rms_stretch_mean: f64,
    /// Largest DOG residual after any step (NaN if any was).
    pub dog_max: f64,
    /// DOG residual after every step (0 without an active page).
    pub dog: Vec<f64>,
    /// Frames with an active page.
    pub active_frames: usize,
    /// Pages left, right and held at the end.
    pub final_pages: [u32; 3],
    /// Every step's report.
    pub reports: Vec<BookStepReport<T>>,
}

/// Plays `script` on a new `f64` book with `settings`, timing each step.
///
/// # Panics
/// On a book or input the fixture should never produce (a bench harness).
#[must_use]
pub fn play(settings: BookSettings<f64>, script: &Script) -> Play {
    play_in(settings, script)
}

/// [`play`] in the precision `T`.
///
/// # Panics
/// As [`play`].
#[must_use]
pub fn play_in<T: Real>(settings: BookSettings<T>, script: &Script) -> Play<T> {
    let mut book = Book::new(settings).expect("book");
    let mut out = Play {
        step_seconds: Vec::new(),
        max_stretch_mean: 0.0,
        rms_stretch_mean: 0.0,
        dog_max: 0.0,
        dog: Vec::new(),
        active_frames: 0,
        final_pages: [0; 3],
        reports: Vec::new(),
    };
    let (mut max_sum, mut rms_sum) = (0.0, 0.0);
    for frame in 0..script.frames {
        for e in script.events_at(frame) {
            book.apply(script.camera, script.forward, e.action)
                .expect("input");
        }
        let t = Instant::now();
        let report = book.step().expect("step");
        out.step_seconds.push(t.elapsed().as_secs_f64());
        out.reports.push(report);
        if let Some((max, rms)) = book.stretch() {
            out.active_frames += 1;
            max_sum += max.to_f64();
            rms_sum += rms.to_f64();
            let dog = book.dog_residual().map_or(0.0, Real::to_f64);
            out.dog_max = worst(out.dog_max, dog);
            out.dog.push(dog);
        } else {
            out.dog.push(0.0);
        }
    }
    let c = book.counts();
    out.final_pages = [c.left, c.right, c.active];
    let n = out.active_frames.max(1) as f64;
    out.max_stretch_mean = max_sum / n;
    out.rms_stretch_mean = rms_sum / n;
    out
}

/// The larger of `a` and `b`, NaN if either is: the fold for report maxima, where
/// `f64::max` would drop a NaN and let a broken run look good (shared with the tests).
pub use folio_tests::worst;

/// The `q`-quantile (0..=1) of `samples`.
#[must_use]
pub fn quantile(samples: &[f64], q: f64) -> f64 {
    let mut s = samples.to_vec();
    s.sort_by(f64::total_cmp);
    if s.is_empty() {
        return f64::NAN;
    }
    s[((s.len() - 1) as f64 * q).round() as usize]
}

/// The accuracy-for-time variants on the default book: the default (one Newton iteration,
/// no constraint Hessian, contact springs and the constraint projection on), two Newton
/// iterations and the constraint Hessian on (seed 000 Sec. 5), the projection off, and the
/// seed's plain step (projection and contact springs off).
#[must_use]
pub fn variants() -> [(&'static str, BookSettings<f64>); 5] {
    let mut two = BookSettings::default();
    two.solver.newton_iterations = 2;
    let mut hessian = BookSettings::default();
    hessian.solver.constraint_hessian = true;
    let plain = BookSettings {
        projection_iterations: 0,
        ..BookSettings::default()
    };
    let seed = BookSettings {
        contact_stiffness: 0.0,
        ..plain
    };
    [
        ("1 Newton iteration", BookSettings::default()),
        ("2 Newton iterations", two),
        ("constraint Hessian on", hessian),
        ("no projection", plain),
        ("no projection, no contact springs (seed)", seed),
    ]
}
