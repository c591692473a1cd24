//! The tearing sheet (seed `002_…`, 96 triangles): one frame of the asymmetric scenario of
//! [`folio_bench::tearing`] with every effect (physics, cones and remesh, tearing) next to
//! the same frame with tearing off, the whole frame on 384 and 1536 triangles (with the
//! seed's split and with the disk estimator), and the tearing step alone (`Tears::step` on copies of
//! the sheet's state), all at the state after [`WARM_FRAMES`] frames. The tear from the
//! notch started at frame 4 and is running then: the measured full frame makes two
//! propagations (each followed by a relaxation step, no symbolic analysis) and the measured
//! tearing step propagates (candidates, splits, Griffith, mesh edit, alpha textures). The
//! per-frame median and p99 over a whole play, and the frames with analyses, come from
//! `cargo run --release -p folio-bench --example tearing_report`.
//!
//! Each iteration steps a fresh clone, made just before it (`BatchSize::PerIteration`):
//! batched clones would leave every timed call starting cold in the cache, unlike the sheet
//! of a running simulation (the tearing step measured 16 µs that way against 7 µs warm).
//!
//! `cargo bench -p folio-bench --bench tearing` (`-- --test` runs each once, as CI does).
#![allow(missing_docs)] // `criterion_group!` generates an undocumented public function.

use core::hint::black_box;
use core::time::Duration;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use folio_bench::tearing::{ASYMMETRIC, Scene, TearInputs, sized_settings};
use folio_tearing::sheet::SheetEffects;

/// Frames played before the measured one.
const WARM_FRAMES: usize = 10;

/// The scenario with `effects` after [`WARM_FRAMES`] frames, its fingers moved for the next.
fn scene_at(effects: SheetEffects) -> Scene {
    warmed(Scene::notched(effects, ASYMMETRIC))
}

/// `scene` after [`WARM_FRAMES`] frames, its fingers moved for the next.
fn warmed(mut scene: Scene) -> Scene {
    for _ in 0..WARM_FRAMES {
        let _ = scene.frame();
    }
    scene.move_fingers();
    scene
}

fn tearing(c: &mut Criterion) {
    let mut g = c.benchmark_group("tearing");
    let all = SheetEffects::default();
    for (name, effects) in [
        ("frame_full", all),
        (
            "frame_no_tearing",
            SheetEffects {
                tearing: false,
                ..all
            },
        ),
    ] {
        let scene = scene_at(effects);
        g.bench_function(name, |b| {
            b.iter_batched_ref(
                || scene.sheet.clone(),
                |sheet| black_box(sheet.step()),
                BatchSize::PerIteration,
            );
        });
    }
    // The whole frame on finer meshes of the same sheet (384 and 1536 triangles), each
    // with the seed's split and with the disk estimator (hinges counting folds).
    for n in [16, 32] {
        for disk in [false, true] {
            let scene = warmed(Scene::notched_with(sized_settings(n, disk), ASYMMETRIC));
            let name = format!(
                "frame_full_{}_triangles_{}",
                2 * n * (3 * n / 4),
                if disk { "disk" } else { "split" }
            );
            g.bench_function(name, |b| {
                b.iter_batched_ref(
                    || scene.sheet.clone(),
                    |sheet| black_box(sheet.step()),
                    BatchSize::PerIteration,
                );
            });
        }
    }
    let inputs = TearInputs::of(&scene_at(all).sheet);
    g.bench_function("tear_step", |b| {
        b.iter_batched_ref(
            || inputs.clone(),
            |inputs| black_box(inputs.step()),
            BatchSize::PerIteration,
        );
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .measurement_time(Duration::from_secs(3))
        .sample_size(30);
    targets = tearing
}
criterion_main!(benches);
