//! The book (seed 000): one frame of the page-turn fixture with the page held, and one frame
//! of a book at rest (blocks only), side by side; then the accuracy-for-time variants (two
//! Newton iterations, constraint Hessian on) on the same held frame. The per-frame median
//! and p99 over the whole fixture come from `cargo run --release -p folio-bench --example
//! book_report`.
#![allow(missing_docs)] // `criterion_group!` generates an undocumented public function.

use core::hint::black_box;
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use folio_bench::book::PAGE_TURN;
use folio_book::{Book, BookSettings, Script};

/// A book after `frames` frames of the page-turn fixture.
fn book_at(settings: BookSettings<f64>, frames: u32) -> Book<f64> {
    let script = Script::parse(PAGE_TURN).expect("fixture");
    let mut book = Book::new(settings).expect("book");
    for frame in 0..frames {
        for e in script.events_at(frame) {
            book.apply(script.camera, script.forward, e.action)
                .expect("input");
        }
        book.step().expect("step");
    }
    book
}

fn frames(c: &mut Criterion) {
    let mut g = c.benchmark_group("book frame");
    let rest = book_at(BookSettings::default(), 0);
    g.bench_function("at rest (blocks only)", |b| {
        b.iter_batched_ref(
            || rest.clone(),
            |book| black_box(book.step()),
            BatchSize::SmallInput,
        );
    });
    for (name, settings) in folio_bench::book::variants() {
        // Frame 80: mid-swipe, the page arched over the spine.
        let held = book_at(settings, 80);
        g.bench_function(format!("held page, {name}"), |b| {
            b.iter_batched_ref(
                || held.clone(),
                |book| black_box(book.step()),
                BatchSize::SmallInput,
            );
        });
    }
    g.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
