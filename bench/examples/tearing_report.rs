//! What a tearing frame costs (seed `002_…`; the paper reports 68-254 ms physics, 4-17 ms
//! remeshing and 2-17 ms tearing per frame on an 8-core laptop; Folio's target is at most
//! 5 ms per whole frame on one core). Plays the asymmetric scenario of
//! [`folio_bench::tearing`] (96 triangles, fingers at $(3, 0)$ and $(7.5, 0)$ pulled apart)
//! for 240 frames with (a) every effect (physics, cones and remesh, tearing), (b) tearing
//! off, (c) cones and tearing off (physics only), timing each `TearingSheet::step` with
//! `Instant`. The sheet keeps being simulated whether or not the tear has separated it.
//!
//! The parts of (a) are timed after each of its frames on copies of the sheet's state
//! (thrown away): the tearing step alone (`Tears::step`: candidates, splits, Griffith, one
//! propagation if one passes), the membrane gradients it reads, and the cone layer's update
//! and remesh. The tearing part of a frame also runs a relaxation physics step (and, after a
//! topology change, a symbolic analysis) after each propagation; that is physics, counted in
//! the frame but not in the part.
//!
//! The simulation is deterministic, so each configuration is played [`PLAYS`] times,
//! interleaved, and every frame keeps its fastest time: a frame the OS preempted (a
//! multiple of the scheduler tick on a loaded machine) is not the simulation's cost. The
//! example checks that the plays did the same thing and prints the spread of one play's p99.
//!
//! Single-threaded, one run, every configuration side by side (after one untimed warm-up
//! play): `cargo run --release -p folio-bench --example tearing_report`.

use core::hint::black_box;
use std::time::Instant;

use folio_bench::book::{quantile, worst};
use folio_bench::tearing::{ASYMMETRIC, ConeInputs, Scene, TearInputs, sized_settings};
use folio_tearing::sheet::{SheetEffects, SheetSettings};

/// Frames played per configuration.
const FRAMES: usize = 240;

/// Plays of each configuration; every frame keeps its fastest.
const PLAYS: usize = 5;

/// A test on a frame's propagations, analyses, refusals and flips.
type FrameKind = fn(&[u32; 4]) -> bool;

/// What one play did and measured, frame by frame.
#[derive(Clone, Default, PartialEq)]
struct Events {
    /// Propagations, symbolic analyses, refused propagations and cone flips of each frame.
    frames: Vec<[u32; 4]>,
    /// Frames the solver refused.
    failed: usize,
    /// Tearing steps on copies that propagated.
    copy_propagations: usize,
    /// The first frame whose first tear reached the boundary (separated the sheet).
    separated: Option<usize>,
    triangles: usize,
    tears: usize,
    /// Length of the first tear, in bits (compared across plays).
    tear_length_bits: u64,
}

/// Wall times, seconds, one per frame.
#[derive(Clone, Default)]
struct Times {
    step: Vec<f64>,
    tear_step: Vec<f64>,
    gradients: Vec<f64>,
    cones: Vec<f64>,
}

impl Times {
    /// Every frame's fastest time of `self` and `other`.
    fn min(&mut self, other: &Self) {
        for (a, b) in [
            (&mut self.step, &other.step),
            (&mut self.tear_step, &other.tear_step),
            (&mut self.gradients, &other.gradients),
            (&mut self.cones, &other.cones),
        ] {
            for (x, y) in a.iter_mut().zip(b) {
                *x = x.min(*y);
            }
        }
    }
}

/// One play of the scenario with `effects`; the parts timed on copies when `parts`.
fn play(effects: SheetEffects, parts: bool) -> (Events, Times) {
    play_with(
        SheetSettings {
            effects,
            ..SheetSettings::default()
        },
        parts,
    )
}

/// One play of the scenario on the sheet of `settings`; the parts timed when `parts`.
fn play_with(settings: SheetSettings<f64>, parts: bool) -> (Events, Times) {
    let mut scene = Scene::notched_with(settings, ASYMMETRIC);
    let (mut ev, mut tm) = (Events::default(), Times::default());
    let mut loads = folio_tearing::LoadBuffers::default();
    for frame in 0..FRAMES {
        scene.move_fingers();
        let t = Instant::now();
        let r = scene.sheet.step();
        tm.step.push(t.elapsed().as_secs_f64());
        scene.frames += 1;
        ev.frames
            .push([r.propagations, r.analyses, r.refused, r.flips]);
        ev.failed += usize::from(!r.status.advanced());
        let first = scene.sheet.tears().tears().first();
        if ev.separated.is_none() && first.is_some_and(|t| t.tip.is_none() && t.path.len() > 1) {
            ev.separated = Some(frame);
        }
        if parts {
            let t = Instant::now();
            scene
                .sheet
                .model()
                .triangle_loads(scene.sheet.mesh().positions(), &mut loads);
            tm.gradients.push(t.elapsed().as_secs_f64());
            black_box(&loads);

            let mut tear = TearInputs::of(&scene.sheet);
            let t = Instant::now();
            let step = tear.step();
            tm.tear_step.push(t.elapsed().as_secs_f64());
            ev.copy_propagations += usize::from(step.propagation.is_some());

            let mut cones = ConeInputs::of(&scene.sheet);
            let t = Instant::now();
            black_box(cones.run());
            tm.cones.push(t.elapsed().as_secs_f64());
        }
    }
    ev.triangles = scene.sheet.mesh().triangle_count();
    ev.tears = scene.sheet.tears().tears().len();
    ev.tear_length_bits = scene.tear_length().to_bits();
    (ev, tm)
}

/// A configuration's plays: what the first did, every frame's fastest time, each play's
/// p99 of the whole frame, and whether every play did the same thing.
struct Config {
    name: &'static str,
    events: Events,
    fastest: Times,
    p99s: Vec<f64>,
    deterministic: bool,
}

impl Config {
    fn new(name: &'static str) -> Self {
        Self {
            name,
            events: Events::default(),
            fastest: Times::default(),
            p99s: Vec::new(),
            deterministic: true,
        }
    }

    fn add(&mut self, (events, times): (Events, Times)) {
        self.p99s.push(quantile(&times.step, 0.99));
        if self.p99s.len() == 1 {
            self.events = events;
            self.fastest = times;
        } else {
            self.deterministic &= events == self.events;
            self.fastest.min(&times);
        }
    }

    fn total(&self, k: usize) -> u32 {
        self.events.frames.iter().map(|f| f[k]).sum()
    }
}

fn ms(samples: &[f64], q: f64) -> f64 {
    quantile(samples, q) * 1e3
}

fn mean_ms(samples: &[f64]) -> f64 {
    samples.iter().sum::<f64>() / samples.len().max(1) as f64 * 1e3
}

fn max_ms(samples: &[f64]) -> f64 {
    samples.iter().copied().fold(0.0, worst) * 1e3
}

/// The CPU model, the cores and the process's thread count, where Linux tells them.
fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".to_owned());
    let threads = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("Threads:"))
                .map(|l| l.trim_start_matches("Threads:").trim().to_owned())
        })
        .unwrap_or_else(|| "?".to_owned());
    let cores = std::thread::available_parallelism().map_or(0, usize::from);
    format!(
        "{cpu}, {cores} logical core(s) available. The example runs single-threaded, on one \
         core ({threads} thread(s) in the process)"
    )
}

fn main() {
    let all = SheetEffects::default();
    let no_tearing = SheetEffects {
        tearing: false,
        ..all
    };
    let physics = SheetEffects {
        cones: false,
        ..no_tearing
    };
    let mut configs = [
        (
            Config::new("(a) physics + cones/remesh + tearing"),
            all,
            true,
        ),
        (
            Config::new("(b) tearing off (physics + cones/remesh)"),
            no_tearing,
            false,
        ),
        (
            Config::new("(c) cones and tearing off (physics only)"),
            physics,
            false,
        ),
    ];
    // Warm up caches and the allocator once.
    let _ = play(all, true);
    for _ in 0..PLAYS {
        for (config, effects, parts) in &mut configs {
            config.add(play(*effects, *parts));
        }
    }
    let configs = configs.map(|c| c.0);
    let baseline = ms(&configs[2].fastest.step, 0.5);

    println!(
        "Tearing sheet, asymmetric pulls (fingers at (3, 0) and (7.5, 0), 0.3 units/s), \
         {FRAMES} frames at 60 fps, 96 triangles at the start; each frame's fastest of \
         {PLAYS} plays."
    );
    println!("Machine: {}.", machine());
    println!();
    println!(
        "| configuration | frames | median ms | p99 ms | mean ms | max ms | propagations | analyses | triangles at end | median / physics only |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for c in &configs {
        let s = &c.fastest.step;
        println!(
            "| {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {} | {} | {} | {:.2} |",
            c.name,
            s.len(),
            ms(s, 0.5),
            ms(s, 0.99),
            mean_ms(s),
            max_ms(s),
            c.total(0),
            c.total(1),
            c.events.triangles,
            ms(s, 0.5) / baseline,
        );
    }
    println!();
    let a = &configs[0];
    println!("Parts of (a), timed after each of its frames on copies of the sheet's state:");
    println!();
    println!("| part | median ms | p99 ms | mean ms | max ms |");
    println!("|---|---|---|---|---|");
    for (name, samples) in [
        (
            "tearing step alone (`Tears::step`: candidates, splits, Griffith, propagation)",
            &a.fastest.tear_step,
        ),
        (
            "membrane gradients and Eshelby tensors the tearing step reads",
            &a.fastest.gradients,
        ),
        (
            "cone layer alone (`ConeLayer::update` + `remesh`)",
            &a.fastest.cones,
        ),
    ] {
        println!(
            "| {name} | {:.4} | {:.4} | {:.4} | {:.4} |",
            ms(samples, 0.5),
            ms(samples, 0.99),
            mean_ms(samples),
            max_ms(samples),
        );
    }
    println!();
    println!("Frames of (a) by what they did:");
    println!();
    println!("| frames | count | median ms | max ms |");
    println!("|---|---|---|---|");
    let kinds: [(&str, FrameKind); 4] = [
        ("no propagation, no analysis", |f| f[0] == 0 && f[1] == 0),
        ("propagation(s), no analysis", |f| f[0] > 0 && f[1] == 0),
        ("one analysis", |f| f[1] == 1),
        ("two analyses", |f| f[1] == 2),
    ];
    for (name, kind) in kinds {
        let s: Vec<f64> = a
            .events
            .frames
            .iter()
            .zip(&a.fastest.step)
            .filter(|(f, _)| kind(f))
            .map(|(_, &t)| t)
            .collect();
        if !s.is_empty() {
            println!(
                "| {name} | {} | {:.3} | {:.3} |",
                s.len(),
                ms(&s, 0.5),
                max_ms(&s)
            );
        }
    }
    println!();
    let first = a.events.frames.iter().position(|f| f[0] > 0);
    let label =
        |f: Option<usize>| f.map_or_else(|| "never".to_owned(), |f| format!("at frame {}", f + 1));
    println!(
        "(a): first propagation {}, the first tear separated the sheet {}; {} tear(s), the \
         first {:.3} units long; {} propagation(s) refused by the mesh; {} of the {} tearing \
         steps timed on copies propagated.",
        label(first),
        label(a.events.separated),
        a.events.tears,
        f64::from_bits(a.events.tear_length_bits),
        a.total(2),
        a.events.copy_propagations,
        FRAMES,
    );
    for c in &configs {
        let p99s: Vec<String> = c.p99s.iter().map(|p| format!("{:.2}", p * 1e3)).collect();
        println!(
            "{}: {} cone flip(s), {} frame(s) the solver refused; the {PLAYS} plays {}; p99 \
             of each play alone (ms): {}.",
            &c.name[..3],
            c.total(3),
            c.events.failed,
            if c.deterministic {
                "did the same thing"
            } else {
                "DIFFERED"
            },
            p99s.join(", "),
        );
    }
    sizes();
}

/// The whole frame (every effect) at three mesh sizes, with the seed's split and with the
/// disk estimator (hinges counting folds), the same scenario.
fn sizes() {
    println!();
    println!(
        "Whole frames (every effect) at three mesh sizes, {FRAMES} frames, each frame's \
         fastest of {PLAYS} plays:"
    );
    println!();
    println!(
        "| quads | triangles at start | estimator | median ms | p99 ms | max ms | propagations | analyses | first tear length | solver refusals |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for n in [8, 16, 32] {
        for disk in [false, true] {
            let settings = sized_settings(n, disk);
            let mut config = Config::new("sizes");
            for _ in 0..PLAYS {
                config.add(play_with(settings, false));
            }
            let s = &config.fastest.step;
            println!(
                "| {n} x {} | {} | {} | {:.3} | {:.3} | {:.3} | {} | {} | {:.3} | {} |",
                3 * n / 4,
                4 * n * (3 * n / 4) / 2,
                if disk { "disk" } else { "split" },
                ms(s, 0.5),
                ms(s, 0.99),
                max_ms(s),
                config.total(0),
                config.total(1),
                f64::from_bits(config.events.tear_length_bits),
                config.events.failed,
            );
            assert!(config.deterministic, "{n}: plays differed");
        }
    }
}
