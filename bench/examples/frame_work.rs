//! What an active frame of the page turn does, for the default book in `f64` and `f32`: per frame with an active page, the step time, the KKT
//! factorizations and refinement steps of the Newton step, and the constraint projection's
//! iterations, normal-equation factorizations and triangular solves (median, p99, max and
//! total), with the merge frame, the largest DOG residual and the frames whose residual
//! exceeds 2e-4, in one run; then `f32` on the delayed-duals order (the `f32` default
//! before [`Ordering::AmdQuasiDefinite`]) for comparison:
//! `cargo run --release -p folio-bench --example frame_work`.

use folio_bench::book::{PAGE_TURN, Play, play_in, quantile, worst};
use folio_book::{BookSettings, Phase, Script};
use folio_kernels::Real;
use folio_solvers::Ordering;

fn row(name: &str, values: &[f64]) {
    println!(
        "| {name} | {:.1} | {:.1} | {:.1} | {:.0} |",
        quantile(values, 0.5),
        quantile(values, 0.99),
        values.iter().copied().fold(0.0, worst),
        values.iter().sum::<f64>()
    );
}

fn table<T: Real>(name: &str, settings: BookSettings<T>, script: &Script) {
    let _ = play_in(settings, script);
    let p: Play<T> = play_in(settings, script);
    let active: Vec<usize> = (0..p.reports.len())
        .filter(|&i| p.reports[i].phase != Phase::AtRest)
        .collect();
    let merged = p.reports.iter().position(|r| r.merged.is_some());
    println!(
        "\n{name}: {} active frames of {}, merged at frame {merged:?}, max DOG residual {:.2e}",
        active.len(),
        p.reports.len(),
        p.dog_max
    );
    println!("| per active frame | median | p99 | max | total |");
    println!("|---|---|---|---|---|");
    let pick = |f: &dyn Fn(usize) -> f64| active.iter().map(|&i| f(i)).collect::<Vec<_>>();
    let r = &p.reports;
    row("step (µs)", &pick(&|i| p.step_seconds[i] * 1e6));
    let counts: [(&str, &dyn Fn(usize) -> u32); 5] = [
        ("KKT factorizations", &|i| r[i].solver.factorizations),
        ("KKT refinement steps", &|i| r[i].solver.refinement_steps),
        ("projection iterations", &|i| r[i].correction.steps),
        ("normal-equation factorizations", &|i| {
            r[i].correction.factorizations
        }),
        ("normal-equation solves", &|i| r[i].correction.solves),
    ];
    for (label, count) in counts {
        row(label, &pick(&|i| f64::from(count(i))));
    }
    let after = pick(&|i| r[i].correction.after.to_f64());
    let tolerance = settings.projection_tolerance.to_f64();
    println!(
        "projection left max|C| above its tolerance {tolerance:.0e} in {} frames (worst {:.1e})",
        after.iter().filter(|&&c| c > tolerance).count(),
        after.iter().copied().fold(0.0, worst)
    );
    for &i in &active {
        if p.dog[i] > 2e-4 {
            println!(
                "  DOG residual {:.2e} at frame {i} ({:?}): {:?}, {} contacts resolved",
                p.dog[i], r[i].phase, r[i].correction, r[i].contacts.resolved
            );
        }
    }
    let linear = pick(&|i| r[i].solver.linear_residual.to_f64());
    println!(
        "KKT relative residual after refinement: median {:.1e}, p99 {:.1e}, max {:.1e}",
        quantile(&linear, 0.5),
        quantile(&linear, 0.99),
        linear.iter().copied().fold(0.0, worst)
    );
}

fn main() {
    let script = Script::parse(PAGE_TURN).expect("fixture");
    table("f64, default", BookSettings::<f64>::default(), &script);
    table("f32, default", BookSettings::<f32>::default(), &script);
    let mut delayed = BookSettings::<f32>::default();
    delayed.solver.ordering = Ordering::AmdDelayedDuals;
    table("f32, AmdDelayedDuals", delayed, &script);
}
