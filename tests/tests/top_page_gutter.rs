//! The book with its blocks' top pages as the gutter (`Gutter::TopPage`, issue 42).
//!
//! **The grab.** A page grabbed from its block is laid on the block's top page, and the
//! finger holds it where it lies. In the frame of the grab and its first pull a card's page
//! stretches by 0.01 % at most on 8 x 11 and 16 x 22 (the seed's gutter: up to 6.6 %), a
//! book paper's by 0.91 % at most (issue 42's bound: 2 %). Over the rest of the turn a book
//! paper's page at 16 x 22 stretches by up to 10.2 %, over the run guard (an ignored test).
//!
//! **R2 of issue 42, a released page's rest on its block.** The page turned by the shared page
//! turn (`TouchScript::page_turn`) comes to rest on the left block, and in the frame before
//! it merges its chord from the hinge to a quarter of the page out (the middle row) is
//! compared with the one-dimensional reference, the heavy elastica over the same block
//! (`folio_book::gutter::top_page` at 200 segments, solved on that frame's book: an
//! independent model, Newton on a strip's nodes, checked against the shooting cantilever
//! and its Richardson limit in `gutter.rs`).
//!
//! Under the seed's gutter (`Gutter::Seed`) the page rests on what the grid sees of the
//! block's rounded spine edge (`docs/accuracy.md`, "the gutter is a cusp"); under
//! `Gutter::TopPage` the active page is tested against the block's own top page, and its
//! rest is the elastica's.

use folio_book::{BlockSide, Book, BookSettings, Gutter, Stock, gutter};
use folio_pages::TouchScript;
use folio_tests::turn::turn_page_watching;

/// A5's width (ISO 216), m.
const A5_WIDTH: f64 = 0.148;

/// The chord of a curve from `root` to `point` above the table, seen from the hinge
/// towards the left block (degrees).
fn chord(root: [f64; 2], point: [f64; 2]) -> f64 {
    (point[1] - root[1]).atan2(root[0] - point[0]).to_degrees()
}

/// A released page at rest on the left block: its chord to a quarter of the page out, and
/// the 1D reference's over the same block.
struct Rest {
    page: f64,
    reference: f64,
}

/// The default book of `stock` (the seed's card for `None`) with `gutter` on a grid of
/// `quads` (across, along), half its pages on each side.
fn settings(stock: Option<Stock>, gutter: Gutter, quads: [usize; 2]) -> BookSettings<f64> {
    let mut s = BookSettings::<f64>::default();
    s.params.left_pages = s.params.total_pages / 2;
    if let Some(stock) = stock {
        let aspect = s.params.aspect_ratio;
        stock
            .cut(A5_WIDTH, A5_WIDTH * aspect)
            .apply(&mut s)
            .expect("a built-in paper");
    }
    s.gutter = gutter;
    [s.quads_across, s.quads_along] = quads;
    s
}

/// The shared page turn on `settings`' book (across a multiple of 4) to the frame before
/// the released page merges; `None` when it has not merged into the left block by the
/// script's end (the seed's gutter on novel paper at 16 x 22 merges on x86 and not on
/// aarch64: its turn is decided by rounding).
fn rest(stock: Option<Stock>, gutter: Gutter, quads: [usize; 2]) -> Option<Rest> {
    let mut book = Book::new(settings(stock, gutter, quads)).expect("the book");
    let [w, h] = book.page_size();
    let script = TouchScript::page_turn(w, h, 10, 120, 600);
    let mut last = None;
    let turned = turn_page_watching(&mut book, &script, |b| {
        if b.page().is_some() {
            last = Some(b.clone());
        }
    })
    .expect("the turn plays");
    assert_eq!(turned.failed_steps, 0, "{turned:?}");
    if turned.merged.map(|m| m.0) != Some(BlockSide::Left) {
        println!("{gutter:?} {quads:?}: the page did not merge left: {turned:?}");
        return None;
    }
    let at_rest = last.expect("a page before the merge");
    assert_eq!(at_rest.top_page_failures(), 0);
    let page = at_rest.page().expect("the page");
    let grid = at_rest.nodes().grid;
    // Node columns: one more than the quads across.
    assert_eq!((grid.nx - 1) % 4, 0, "a column at a quarter of the page");
    let (hinge, quarter) = (
        page[grid.index(0, grid.nz / 2)],
        page[grid.index((grid.nx - 1) / 4, grid.nz / 2)],
    );
    let top = gutter::top_page(&at_rest, BlockSide::Left, gutter::TOP_PAGE_SEGMENTS)
        .expect("the left block's top page settles");
    let segments = gutter::TOP_PAGE_SEGMENTS;
    Some(Rest {
        page: chord([hinge.x, hinge.y], [quarter.x, quarter.y]),
        reference: chord(top.points[0], top.points[segments / 4]),
    })
}

#[test]
fn a_released_page_rests_on_its_block_as_the_1d_elastica_over_it() {
    // (paper, grid, bound in degrees): R2's 2 at the default grid, 1 at 16 x 22.
    let cases: [(Option<Stock>, [usize; 2], f64); 4] = [
        (Some(Stock::NOVEL), [8, 11], 2.0),
        (Some(Stock::NOVEL), [16, 22], 1.0),
        (None, [8, 11], 2.0),
        (None, [16, 22], 1.0),
    ];
    let mut misses = Vec::new();
    for (stock, quads, bound) in cases {
        let name = stock.map_or("seed card", |_| "novel");
        // The seed's gutter for comparison only (its page need not land).
        let seed = rest(stock, Gutter::Seed, quads).map_or("did not land".to_string(), |r| {
            format!("{:.2} ({:+.2})", r.page, r.page - r.reference)
        });
        let top = rest(stock, Gutter::TopPage, quads).expect("the page lands on the left block");
        println!(
            "{name} {quads:?}: 1D {:.2} deg; top-page gutter {:.2} ({:+.2}); seed's gutter {seed}",
            top.reference,
            top.page,
            top.page - top.reference,
        );
        if (top.page - top.reference).abs() > bound {
            misses.push((name, quads, top.page - top.reference));
        }
    }
    assert!(misses.is_empty(), "{misses:?}");
}

/// The grab frame's largest edge stretch of each paper's page on 8 x 11 and 16 x 22 under
/// `Gutter::TopPage`, over the shared page turn (which must play without a failed step and
/// with both blocks' top pages kept, and, when `guard`, within the run guard's 10 %); the
/// papers whose page stretches by more than 2 % in the grab's frame.
fn grab_misses(papers: &[(&str, Option<Stock>)], guard: bool) -> Vec<(String, [usize; 2], f64)> {
    let mut misses = Vec::new();
    for &(name, stock) in papers {
        for quads in [[8, 11], [16, 22]] {
            let mut book = Book::new(settings(stock, Gutter::TopPage, quads)).expect("the book");
            let [w, h] = book.page_size();
            let script = TouchScript::page_turn(w, h, 10, 120, 600);
            let mut frames = 0;
            let turned = turn_page_watching(&mut book, &script, |b| {
                frames += 1;
                if frames == 12 {
                    // Both blocks keep a top page of TOP_PAGE_WALLS segments from the hinge.
                    for side in [BlockSide::Left, BlockSide::Right] {
                        let walls = b.top_page_walls(side);
                        assert_eq!(walls.len(), gutter::TOP_PAGE_WALLS + 1, "{name} {side:?}");
                        assert!(walls.iter().all(|p| p.is_finite()), "{name} {side:?}");
                    }
                }
            })
            .expect("the turn plays");
            println!(
                "{name} {quads:?}: grab frame {:.4}, max {:.4} at frame {}, merged {:?}",
                turned.grab_stretch, turned.max_stretch.0, turned.max_stretch.1, turned.merged
            );
            assert!(turned.grabbed, "{name} {quads:?}");
            assert_eq!(turned.failed_steps, 0, "{name} {quads:?}: {turned:?}");
            assert!(
                !guard || turned.max_stretch.0 <= 0.10,
                "{name} {quads:?}: {turned:?}"
            );
            assert_eq!(book.top_page_failures(), 0, "{name} {quads:?}");
            if turned.grab_stretch > 0.02 {
                misses.push((name.to_string(), quads, turned.grab_stretch));
            }
        }
    }
    misses
}

/// The book papers of `Stock::BUILT_IN`.
const BOOK_PAPERS: [(&str, Option<Stock>); 3] = [
    ("bible", Some(Stock::BIBLE)),
    ("novel", Some(Stock::NOVEL)),
    ("magazine", Some(Stock::MAGAZINE)),
];

/// Measured 0.00 % (the seed's card) and 0.01 % (card) on 8 x 11 and 16 x 22; under the
/// seed's gutter 0.26 % and 2.3 %, 3.5 % and 6.6 %.
#[test]
fn a_card_page_grabbed_from_its_block_starts_on_its_top_page() {
    let misses = grab_misses(&[("seed card", None), ("card", Some(Stock::CARD))], true);
    assert!(misses.is_empty(), "{misses:?}");
}

/// Issue 42's grab bound, 2 % in the grab's first frame: measured (8 x 11, 16 x 22) bible
/// 0.07 % and 0.58 %, novel 0.08 % and 0.91 %, magazine 0.10 % and 0.90 %. Before the
/// finger held the page where it lay (`folio_pages::dog::finger_frame`), its first pull
/// aimed along the arched page, away from the node, and the same pages stretched by 1.7 %
/// to 6.5 %.
#[test]
fn a_book_paper_page_grabbed_from_its_block_stretches_by_2_percent_at_most() {
    let misses = grab_misses(&BOOK_PAPERS, false);
    assert!(misses.is_empty(), "{misses:?}");
}

/// Issue 42's page-turn bound, the run guard's 10 % over the whole turn, not met by the
/// book papers on the top-page gutter: measured (8 x 11, 16 x 22) bible 2.2 % and 5.6 %,
/// novel 3.0 % and 10.2 %, magazine 4.1 % and 7.2 % (32 x 44: 7.4 %, 10.6 %, 19.3 %). The
/// largest stretch lies at the binding's corner as the page lifts, and in the free page
/// after the release. A weaker pull keeps this turn within the guard (50: 1.8 % at most),
/// but the pull scaled as the square root of the bending left the built-in scenes' pages
/// unturned (`docs/accuracy.md`).
#[test]
#[ignore = "issue 42: a book paper's turn stretches its page over 10 % at 16 x 22"]
fn a_book_paper_page_turns_within_the_run_guard() {
    let misses = grab_misses(&BOOK_PAPERS, true);
    assert!(misses.is_empty(), "{misses:?}");
}

/// The finger holds the page where it touched it: after a grab and a drag to the finger's
/// grab point $(\pm u, 0, v)$ in the page frame, the held node's target is the node where
/// it lies, on either side and either gutter, and on a page arched over its top page (a
/// novel's on `Gutter::TopPage`) that is nearer the binding than $u$.
#[test]
fn the_finger_holds_the_page_where_it_touched_it() {
    use folio_pages::PageModel;
    use folio_pages::dog::DogPage;
    for (stock, gutter) in [
        (Some(Stock::NOVEL), Gutter::TopPage),
        (None, Gutter::TopPage),
        (Some(Stock::NOVEL), Gutter::Seed),
    ] {
        for side in [BlockSide::Right, BlockSide::Left] {
            let mut page = DogPage::new(settings(stock, gutter, [8, 11])).expect("the book");
            let [w, h] = page.size();
            let at = [w - 0.5, 0.3 * h];
            page.grab_page(side, 1, at).expect("the grab");
            let u = if side == BlockSide::Left {
                -at[0]
            } else {
                at[0]
            };
            page.drag(folio_kernels::Vec3Ops::new(u, 0.0, at[1]))
                .expect("the drag");
            let book = page.book();
            let (node, target) = (book.held_node().unwrap(), book.target().unwrap());
            let held = book.page().unwrap()[node];
            let case = format!("{stock:?} {gutter:?} {side:?}");
            assert!((held - target).length() < 1e-12, "{case}: {held} {target}");
            if stock.is_some() && gutter == Gutter::TopPage {
                // The arch: the node lies nearer the binding than its material distance.
                let grid = book.nodes().grid;
                let (i, _) = grid.coords(node);
                let hinge = book.page().unwrap()[0];
                let reach = (held.x - hinge.x).abs();
                let material = i as f64 * book.grid_spacing()[0];
                assert!(reach < material - 0.3, "{case}: {reach} {material}");
            }
        }
    }
}

#[test]
fn the_seeds_gutter_keeps_no_top_page() {
    let mut book = Book::new(settings(None, Gutter::Seed, [8, 11])).expect("the book");
    let [w, h] = book.page_size();
    let script = TouchScript::page_turn(w, h, 10, 120, 600);
    turn_page_watching(&mut book, &script, |b| {
        assert!(b.top_page_walls(BlockSide::Left).is_empty());
        assert!(b.top_page_walls(BlockSide::Right).is_empty());
    })
    .expect("the turn plays");
}
