//! A run's summary: the statistics of its frames, their health under the scene's bounds
//! ([`crate::health`]) and the scene's expectations, which together give the verdict.

use alloc::collections::BTreeMap;

use folio_scene::scene::Scene;

use crate::health;
use crate::report::{Bounds, FrameRecord, PaperRecord, Report, Summary};

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
        newton_iterations: iteration_histogram(records),
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

/// How many awake frames of `records` took each number of Newton iterations (DOG book);
/// `None` for other models.
fn iteration_histogram(records: &[FrameRecord]) -> Option<BTreeMap<u32, usize>> {
    let mut histogram = BTreeMap::new();
    let mut any = false;
    for r in records {
        if let Some(n) = r.newton_iterations {
            any = true;
            if r.asleep != Some(true) {
                *histogram.entry(n).or_insert(0) += 1;
            }
        }
    }
    any.then_some(histogram)
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
            // The scene was checked before its run: its paper reads.
            paper: scene
                .paper
                .as_ref()
                .and_then(|_| folio_scene::settings::book_paper(scene).ok().flatten())
                .map(|(paper, units)| PaperRecord::new(&paper, &units)),
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
