//! Per-frame step time over the page-turn fixture (median, p99) for the default book and a
//! resting book, and the accuracy-for-time variants of seed 000 Sec. 5 (one vs two Newton
//! iterations, constraint Hessian off vs on) with the stretch and DOG residual each reaches.
//! All in one run: `cargo run --release -p folio-bench --example book_report`.

use folio_bench::book::{PAGE_TURN, Play, play, quantile};
use folio_book::{BookSettings, Script};

fn row(name: &str, p: &Play, baseline: f64) {
    let median = quantile(&p.step_seconds, 0.5) * 1e6;
    let p99 = quantile(&p.step_seconds, 0.99) * 1e6;
    let total: f64 = p.step_seconds.iter().sum::<f64>() * 1e3;
    println!(
        "| {name} | {median:.0} | {p99:.0} | {total:.1} | {:.2} | {:.4} | {:.4} | {:.2e} |",
        total / baseline,
        p.max_stretch_mean,
        p.rms_stretch_mean,
        p.dog_max
    );
}

fn main() {
    let script = Script::parse(PAGE_TURN).expect("fixture");
    let mut rest_script = script.clone();
    rest_script.events.clear();
    // Warm up caches and the allocator once.
    let _ = play(BookSettings::default(), &script);
    let default = play(BookSettings::default(), &script);
    let baseline: f64 = default.step_seconds.iter().sum::<f64>() * 1e3;
    println!(
        "| run | median step (µs) | p99 step (µs) | fixture total (ms) | total / default | mean max stretch | mean RMSE stretch | max DOG residual |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    row(
        "page turn, default (1 Newton iteration, no constraint Hessian)",
        &default,
        baseline,
    );
    for (name, settings) in folio_bench::book::variants().into_iter().skip(1) {
        row(
            &format!("page turn, {name}"),
            &play(settings, &script),
            baseline,
        );
    }
    row(
        "book at rest, 750 frames",
        &play(BookSettings::default(), &rest_script),
        baseline,
    );
    let active: Vec<f64> = default.step_seconds[30..].to_vec();
    println!(
        "active frames {} of {}; median active step {:.0} µs",
        default.active_frames,
        script.frames,
        quantile(&active[..default.active_frames.min(active.len())], 0.5) * 1e6
    );
}
