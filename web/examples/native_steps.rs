//! The browser's step measured natively: plays the default scene's recorded page turn (750
//! frames) through the same [`folio_web::replay::Replay`] the page's `?bench` mode plays in
//! WebAssembly, `--runs N` times (default 5), and prints the mean step time of each run and
//! their median as `native_step_ms=...`, the line `web/test.py` reads.

use std::time::Instant;

use folio_web::replay::Replay;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|k| args.get(k + 1))
        .and_then(|n| n.parse::<usize>().ok())
        .unwrap_or(5)
        .max(1);
    let mut means = Vec::with_capacity(runs);
    for run in 0..runs {
        let mut replay = match Replay::new() {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
        };
        let start = Instant::now();
        while replay.frame() {}
        let ms = start.elapsed().as_secs_f64() * 1e3;
        if replay.failed() > 0 || replay.counts() != [51, 49, 0] {
            eprintln!(
                "error: run {run}: {} failures, counts {:?} (expected [51, 49, 0])",
                replay.failed(),
                replay.counts()
            );
            std::process::exit(1);
        }
        let mean = ms / replay.steps() as f64;
        println!(
            "run {run}: {} steps in {ms:.1} ms, {mean:.4} ms per step",
            replay.steps()
        );
        means.push(mean);
    }
    means.sort_by(f64::total_cmp);
    println!("native_step_ms={:.4}", means[means.len() / 2]);
}
