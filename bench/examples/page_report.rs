//! What accuracy costs in time, across page models: the shared page-turn drag
//! (`tests/fixtures/page_turn.touch`) on the cone curl, the mass-spring page (semi-implicit
//! and implicit) and the DOG page, in one run: per-frame step and sampling time (median,
//! p99, total), the render-grid metrics (mean max stretch, mean RMSE stretch, mean and worst
//! angle defect) and the finger tracking; then the mass-spring key-frame replay against
//! simulation. `cargo run --release -p folio-bench --example page_report`.

use std::time::Instant;

use folio_bench::book::{quantile, worst};
use folio_bench::pages::{PAGE_TURN, mean, models, play, render_grid};
use folio_kernels::Real;
use folio_pages::spring::{SpringPage, SpringSettings};
use folio_pages::{PageModel, TouchScript};

fn main() {
    let script = TouchScript::parse(PAGE_TURN).expect("fixture");
    let grid = render_grid();
    println!(
        "| model | median step (µs) | p99 step (µs) | total steps (ms) | vs cone | sample (µs) | mean max stretch | mean RMSE stretch | mean / worst angle defect | unreachable frames | mean finger gap |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut baseline = None;
    for (name, mut model) in models() {
        // One warm-up play, then the measured one.
        let _ = play(model.as_mut(), &script, grid);
        let (_, mut model) = models()
            .into_iter()
            .find(|(n, _)| *n == name)
            .expect("model");
        let p = play(model.as_mut(), &script, grid);
        let total: f64 = p.step_seconds.iter().sum::<f64>() * 1e3;
        let base = *baseline.get_or_insert(total);
        println!(
            "| {name} | {:.1} | {:.1} | {total:.2} | {:.1}x | {:.1} | {:.4} | {:.4} | {:.1e} / {:.1e} | {} | {:.3} |",
            quantile(&p.step_seconds, 0.5) * 1e6,
            quantile(&p.step_seconds, 0.99) * 1e6,
            total / base,
            quantile(&p.sample_seconds, 0.5) * 1e6,
            mean(&p.max_stretch),
            mean(&p.rmse_stretch),
            mean(&p.angle_defect),
            p.angle_defect.iter().copied().fold(0.0, worst),
            p.unreachable,
            mean(&p.finger_gaps),
        );
    }
    key_frames(&script);
}

/// The seed's key-frame saving (Sec. 2.2.3, 18 % there): a recorded turn played back from
/// its key frames against simulating it, with and without sampling the render grid.
fn key_frames(script: &TouchScript) {
    let grid = render_grid();
    let mut samples = vec![<f64 as Real>::Vec3::ZERO; grid.len()];
    let mut page = SpringPage::<f64>::new(SpringSettings::default()).expect("spring");
    let (mut simulate, mut simulate_sampled) = (0.0, 0.0);
    for frame in 0..script.frames {
        script.at(frame).apply(&mut page).expect("input");
        let t = Instant::now();
        page.step().expect("step");
        simulate += t.elapsed().as_secs_f64();
        page.sample(grid, &mut samples).expect("sample");
        simulate_sampled += t.elapsed().as_secs_f64();
    }
    let mut replay = page.replay().expect("replay");
    let (mut replayed, mut replayed_sampled) = (0.0, 0.0);
    for _ in 0..script.frames {
        let t = Instant::now();
        replay.step().expect("replay step");
        replayed += t.elapsed().as_secs_f64();
        replay.sample(grid, &mut samples).expect("sample");
        replayed_sampled += t.elapsed().as_secs_f64();
    }
    let saving = |sim: f64, rep: f64| 100.0 * (1.0 - rep / sim);
    println!(
        "mass-spring key frames over {} frames: simulate {:.2} ms, replay {:.2} ms ({:.0} % saved); with the render sampling {:.2} ms vs {:.2} ms ({:.0} % saved; the seed reports 18 %)",
        script.frames,
        simulate * 1e3,
        replayed * 1e3,
        saving(simulate, replayed),
        simulate_sampled * 1e3,
        replayed_sampled * 1e3,
        saving(simulate_sampled, replayed_sampled),
    );
}
