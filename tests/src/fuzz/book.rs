//! Fuzz target `book`: sequences of grabs (by ray, and at a material point), drags (by ray,
//! and to a point, up to a flick a step), releases and time steps on a small DOG book
//! ([`Book`], 4x6 quads). Asserts after every event: no panic, a finite state, the pages
//! conserved (left + right + active = total), and the active page's stretch within
//! [`STRETCH_GUARD`].
//!
//! The books are built once per process ([`templates`]) and cloned per input: a book's
//! setup settles it for many steps, which would otherwise dominate every run. An input
//! holds at most [`MAX_STEPS`] time steps.

use std::sync::OnceLock;

use folio_book::{BlockSide, Book, BookSettings, Ray};
use folio_kernels::Vec3Ops;
use glam::DVec3;

use super::Input;

/// Time steps one input may take (each event of kind "step" takes 1 to 4).
pub const MAX_STEPS: u32 = 24;

/// The largest relative stretch of a grid edge of the active page the run guard accepts
/// (issue 20's default bound: 10 %).
pub const STRETCH_GUARD: f64 = 0.10;

/// A coarse book of `total` pages, `left` of them on the left: 4x6 quads, settled for 200
/// steps (the harness's books, and the hard cases of their class).
#[must_use]
pub fn coarse_settings(total: u32, left: u32) -> BookSettings<f64> {
    let mut s = BookSettings::<f64>::default();
    s.params.total_pages = total;
    s.params.left_pages = left;
    s.quads_across = 4;
    s.quads_along = 6;
    s.settle_steps = 200;
    s
}

/// The books an input starts from: [`coarse_settings`] of (total pages, left pages) (1, 0),
/// (2, 1), (12, 6) and (40, 0).
pub fn templates() -> &'static [Book<f64>] {
    static BOOKS: OnceLock<Vec<Book<f64>>> = OnceLock::new();
    BOOKS.get_or_init(|| {
        [(1, 0), (2, 1), (12, 6), (40, 0)]
            .into_iter()
            .filter_map(|(total, left)| Book::new(coarse_settings(total, left)).ok())
            .collect()
    })
}

/// Decodes a book and a sequence of events from `data` and checks the book after each.
///
/// # Panics
/// When a property in the module docs does not hold.
pub fn run(data: &[u8]) {
    let mut input = Input::new(data);
    let books = templates();
    assert!(!books.is_empty(), "the template books build");
    let mut book = books[input.below(books.len())].clone();
    let total = book.settings().params.total_pages;
    let [width, height] = book.page_size();
    let mut steps = 0;
    while !input.is_empty() && steps < MAX_STEPS {
        let event = input.below(6);
        match event {
            0 => {
                let side = if input.flag() {
                    BlockSide::Left
                } else {
                    BlockSide::Right
                };
                let at = [
                    input.uniform(-0.2, 1.2) * width,
                    input.uniform(-0.2, 1.2) * height,
                ];
                let pages = 1 + input.below(3) as u32;
                let _ = book.grab_at(side, at, pages);
            }
            1 | 2 => {
                // A ray from a camera above the book to a point around it.
                let origin = DVec3::new(0.0, 3.0 * width, 0.5 * height);
                let aim = DVec3::new(
                    input.uniform(-1.5, 1.5) * width,
                    input.uniform(-0.5, 1.0) * width,
                    input.uniform(-0.2, 1.2) * height,
                );
                let ray = Ray {
                    origin,
                    direction: aim - origin,
                };
                if event == 1 {
                    let _ = book.grab(&ray, DVec3::new(0.0, -1.0, 0.0), 1 + input.below(2) as u32);
                } else {
                    let _ = book.drag(&ray);
                }
            }
            3 => {
                // Up to a page width from the held target in one go: a flick.
                if let Some(target) = book.target() {
                    let reach = input.uniform(0.0, 1.0) * width;
                    let d = DVec3::new(
                        input.uniform(-1.0, 1.0),
                        input.uniform(-1.0, 1.0),
                        input.uniform(-1.0, 1.0),
                    );
                    let _ = book.drag_to(target + d * reach);
                }
            }
            4 => {
                book.release();
            }
            _ => {
                for _ in 0..1 + input.below(4) {
                    steps += 1;
                    let report = book.step();
                    assert!(
                        report.is_ok(),
                        "a step of an analysed book failed: {report:?}"
                    );
                    check(&book, total);
                }
            }
        }
        check(&book, total);
    }
}

/// The book's state is finite, its pages conserved and its active page within the guard.
fn check(book: &Book<f64>, total: u32) {
    let state = book.state();
    for (k, (x, v)) in state.x.iter().zip(&state.v).enumerate() {
        let finite = [x.x(), x.y(), x.z(), v.x(), v.y(), v.z()]
            .iter()
            .all(|c| c.is_finite());
        assert!(finite, "node {k}: position {x:?}, velocity {v:?}");
    }
    let c = book.counts();
    assert_eq!(
        c.left + c.right + c.active,
        total,
        "pages not conserved: {c:?}"
    );
    if let Some((max, _)) = book.stretch() {
        assert!(
            max <= STRETCH_GUARD,
            "stretch {max} beyond the guard {STRETCH_GUARD} ({:?})",
            book.phase()
        );
    }
}
