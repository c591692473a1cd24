//! Page models side by side (seeds 000, 001, 003): one frame of each model in the middle of
//! the shared page-turn drag (frame 70, the page arched over the spine), the render-grid
//! sampling of each, and the mass-spring key-frame replay against its simulation. The
//! per-frame median / p99 over the whole drag and the metrics come from `cargo run --release
//! -p folio-bench --example page_report`.
#![allow(missing_docs)] // `criterion_group!` generates an undocumented public function.

use core::hint::black_box;
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use folio_bench::pages::{PAGE_TURN, render_grid};
use folio_book::BookSettings;
use folio_kernels::Real;
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::dog::DogPage;
use folio_pages::spring::{Integrator, SpringPage, SpringSettings};
use folio_pages::{PageModel, TouchScript};

/// The frame the models are measured at.
const FRAME: u32 = 70;

/// `model` after the drag's first `frames` frames.
fn at_frame<M: PageModel<f64>>(mut model: M, frames: u32) -> M {
    let script = TouchScript::parse(PAGE_TURN).expect("fixture");
    for frame in 0..frames {
        script.at(frame).apply(&mut model).expect("input");
        model.step().expect("step");
    }
    model
}

fn bench_model<M: PageModel<f64> + Clone>(c: &mut Criterion, name: &str, model: M) {
    let script = TouchScript::parse(PAGE_TURN).expect("fixture");
    let held = at_frame(model, FRAME);
    let next = script.at(FRAME);
    c.benchmark_group("page model frame")
        .bench_function(name, |b| {
            b.iter_batched_ref(
                || held.clone(),
                |m| {
                    next.apply(m).expect("input");
                    black_box(m.step())
                },
                BatchSize::SmallInput,
            );
        });
    let grid = render_grid();
    let mut samples = vec![<f64 as Real>::Vec3::ZERO; grid.len()];
    c.benchmark_group("page model sample (24 x 34 quads)")
        .bench_function(name, |b| {
            b.iter(|| black_box(held.sample(grid, &mut samples)));
        });
}

fn frames(c: &mut Criterion) {
    bench_model(
        c,
        "cone curl",
        ConePage::new(ConeSettings::default()).expect("cone"),
    );
    bench_model(
        c,
        "mass-spring semi-implicit",
        SpringPage::new(SpringSettings::default()).expect("spring"),
    );
    let implicit = SpringSettings {
        integrator: Integrator::ImplicitEuler,
        // Unconditionally stable: one implicit step per frame, no substeps.
        substeps: 1,
        ..SpringSettings::default()
    };
    bench_model(
        c,
        "mass-spring implicit",
        SpringPage::new(implicit).expect("spring"),
    );
    bench_model(
        c,
        "DOG page",
        DogPage::new(BookSettings::default()).expect("dog"),
    );
}

fn key_frames(c: &mut Criterion) {
    let script = TouchScript::parse(PAGE_TURN).expect("fixture");
    let page = at_frame(
        SpringPage::<f64>::new(SpringSettings::default()).expect("spring"),
        script.frames,
    );
    let replay = page.replay().expect("replay");
    let mut g = c.benchmark_group("mass-spring key frames");
    let fresh = SpringPage::<f64>::new(SpringSettings::default()).expect("spring");
    let mid = at_frame(fresh, FRAME);
    g.bench_function("simulated frame", |b| {
        b.iter_batched_ref(
            || mid.clone(),
            |m| black_box(m.step()),
            BatchSize::SmallInput,
        );
    });
    g.bench_function("replayed frame", |b| {
        b.iter_batched_ref(
            || replay.clone(),
            |r| black_box(r.step()),
            BatchSize::SmallInput,
        );
    });
    g.finish();
}

criterion_group!(benches, frames, key_frames);
criterion_main!(benches);
