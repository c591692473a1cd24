//! Playing the shared page-turn drag on every page model, for the page-model bench and
//! report: the same input, the same render grid, the same metrics, timed per frame.

use std::time::Instant;

use folio_book::BookSettings;
use folio_geometry::QuadGrid;
use folio_kernels::Real;
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::dog::DogPage;
use folio_pages::spring::{Integrator, SpringPage, SpringSettings};
use folio_pages::{PageModel, PageStatus, TouchScript, frame_metrics};

/// The shared page turn (240 frames at 60 fps, `tests/fixtures/page_turn.touch`).
pub const PAGE_TURN: &str = include_str!("../../tests/fixtures/page_turn.touch");

/// The render grid every model is sampled on (24 x 34 quads, half a page unit).
#[must_use]
pub fn render_grid() -> QuadGrid {
    QuadGrid::new(24, 34).expect("grid")
}

/// The models of the comparison, cheapest first, with their report names.
///
/// # Panics
/// On default settings the models refuse (a bench harness).
#[must_use]
pub fn models() -> Vec<(&'static str, Box<dyn PageModel<f64>>)> {
    let implicit = SpringSettings {
        integrator: Integrator::ImplicitEuler,
        // Unconditionally stable: one implicit step per frame, no substeps.
        substeps: 1,
        ..SpringSettings::default()
    };
    vec![
        (
            "cone curl (seed 001)",
            Box::new(ConePage::new(ConeSettings::default()).expect("cone")),
        ),
        (
            "mass-spring, semi-implicit (seed 003)",
            Box::new(SpringPage::new(SpringSettings::default()).expect("spring")),
        ),
        (
            "mass-spring, implicit Euler",
            Box::new(SpringPage::new(implicit).expect("spring")),
        ),
        (
            "DOG page of the book (seed 000)",
            Box::new(DogPage::new(BookSettings::default()).expect("dog")),
        ),
    ]
}

/// What one play measured, per frame.
#[derive(Clone, Debug, Default)]
pub struct ModelPlay {
    /// Wall time of each step (input applied before it), seconds.
    pub step_seconds: Vec<f64>,
    /// Wall time of each sampling of the render grid, seconds.
    pub sample_seconds: Vec<f64>,
    /// Max edge stretch of the render grid per frame.
    pub max_stretch: Vec<f64>,
    /// RMSE edge stretch per frame.
    pub rmse_stretch: Vec<f64>,
    /// Max angle defect per frame (radians).
    pub angle_defect: Vec<f64>,
    /// Frames the model reported the finger unreachable.
    pub unreachable: usize,
    /// Frames the model could not advance.
    pub stalled: usize,
    /// Distance from the held point to the finger on held frames.
    pub finger_gaps: Vec<f64>,
}

/// Plays `script` on `model`, sampling `grid` after every step.
///
/// # Panics
/// On input the fixture should never produce (a bench harness).
#[must_use]
pub fn play(model: &mut dyn PageModel<f64>, script: &TouchScript, grid: QuadGrid) -> ModelPlay {
    let mut out = ModelPlay::default();
    let mut samples = vec![<f64 as Real>::Vec3::ZERO; grid.len()];
    for frame in 0..script.frames {
        script.at(frame).apply(model).expect("input");
        let t = Instant::now();
        let step = model.step().expect("step");
        out.step_seconds.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        model.sample(grid, &mut samples).expect("sample");
        out.sample_seconds.push(t.elapsed().as_secs_f64());
        let m = frame_metrics(grid, model.size(), &samples).expect("metrics");
        out.max_stretch.push(m.max_stretch);
        out.rmse_stretch.push(m.rmse_stretch);
        out.angle_defect.push(m.max_angle_defect);
        match step.status {
            PageStatus::Unreachable => out.unreachable += 1,
            PageStatus::Stalled => out.stalled += 1,
            // `Moved`, or a status this report does not count.
            _ => {}
        }
        out.finger_gaps.extend(step.finger_gap);
    }
    out
}

/// The mean of `v` (0 when empty).
#[must_use]
pub fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}
