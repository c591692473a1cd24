//! What each effect costs (issue 6: simulate only the effects a scene calls for): the
//! page-turn fixture with every effect, then with effects left out, and the book at rest
//! with and without simulated blocks. Per-step time (median, p99), fixture total and its
//! ratio to the full book, the largest KKT system, and where the page ends.
//! All in one run: `cargo run --release -p folio-bench --example effects_report`.

use folio_bench::book::{PAGE_TURN, Play, play, quantile};
use folio_book::{Book, BookSettings, Effects, Script};

/// The book with `effects`.
fn with(effects: Effects) -> BookSettings<f64> {
    BookSettings {
        effects,
        ..BookSettings::default()
    }
}

/// The largest KKT system (unknowns, rows) of a grabbed page with `effects`.
fn kkt_size(effects: Effects) -> (usize, usize) {
    let mut book = Book::new(with(effects)).expect("book");
    let _ = book
        .grab_at(folio_geometry::BlockSide::Right, [11.0, 3.0], 1)
        .expect("grab");
    let r = book.step().expect("step");
    (r.dofs, r.constraint_rows)
}

fn row(name: &str, effects: Effects, p: &Play, baseline: f64) {
    let median = quantile(&p.step_seconds, 0.5) * 1e6;
    let p99 = quantile(&p.step_seconds, 0.99) * 1e6;
    let total: f64 = p.step_seconds.iter().sum::<f64>() * 1e3;
    let (dofs, rows) = kkt_size(effects);
    println!(
        "| {name} | {median:.0} | {p99:.0} | {total:.1} | {:.2} | {dofs} / {rows} | {:?} | {:.2e} |",
        total / baseline,
        p.final_pages,
        p.dog_max
    );
}

fn main() {
    let script = Script::parse(PAGE_TURN).expect("fixture");
    let mut rest = script.clone();
    rest.events.clear();
    let all = Effects::ALL;
    let fixed = Effects {
        blocks: false,
        glue: false,
        ..all
    };
    let variants = [
        ("every effect", all),
        (
            "no bookmarking",
            Effects {
                bookmarking: false,
                ..all
            },
        ),
        ("no glue", Effects { glue: false, ..all }),
        ("fixed blocks (no blocks, no glue)", fixed),
        (
            "fixed blocks, no collisions",
            Effects {
                collisions: false,
                ..fixed
            },
        ),
        (
            "the page alone (fixed blocks, no collisions, no gravity)",
            Effects {
                collisions: false,
                gravity: false,
                ..fixed
            },
        ),
    ];
    // Warm up caches and the allocator once.
    let _ = play(with(all), &script);
    let full = play(with(all), &script);
    let baseline: f64 = full.step_seconds.iter().sum::<f64>() * 1e3;
    println!(
        "| page turn (750 frames) | median step (µs) | p99 step (µs) | total (ms) | total / every effect | KKT unknowns / rows (held) | pages at the end | max DOG residual |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, effects) in variants {
        row(name, effects, &play(with(effects), &script), baseline);
    }
    for (name, effects) in [
        ("book at rest, every effect", all),
        ("book at rest, fixed blocks", fixed),
    ] {
        row(name, effects, &play(with(effects), &rest), baseline);
    }
}
