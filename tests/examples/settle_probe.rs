//! How fast a released page settles and merges: the shared page turn
//! (`TouchScript::page_turn`, the fore-edge point carried over the spine) on a book of any
//! page count and thickness, driven through `Book::grab_at` and `Book::drag_to` as the DOG
//! page model drives it.
//!
//! ```text
//! cargo run --release -p folio-tests --example settle_probe -- PAGES THICKNESS [HELD] [FRAMES] [MU]
//! cargo run --release -p folio-tests --example settle_probe -- sweep [MU]
//! ```
//! One book prints the frames from the release to the merge (`None`: no merge), the block
//! and the largest edge stretch; `sweep` does so for 3 to 1000 pages, 0.001 to 0.05 thick.
//! `MU` is `BookSettings::contact_friction` (default 0).

use folio_book::{BlockSide, Book, BookSettings};
use folio_pages::TouchScript;
use folio_tests::turn::turn_page;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |k: usize| args.get(k).map(String::as_str);
    if arg(0) == Some("sweep") {
        let mu: f64 = arg(1).map_or(0.0, |a| a.parse().expect("MU"));
        for pages in [3_u32, 10, 50, 100, 400, 1000] {
            for thickness in [0.001, 0.0075, 0.01, 0.02, 0.05] {
                let (merge, side, stretch) = turn(pages, thickness, mu, 120, 1200);
                println!(
                    "pages {pages:5} thickness {thickness:6} mu {mu}: merged {merge:?} \
                     {side:?} after release, max stretch {stretch:.4}"
                );
            }
        }
        return;
    }
    let number = |k: usize, default: f64| arg(k).map_or(default, |a| a.parse().expect("number"));
    let pages = number(0, 100.0) as u32;
    let held = number(2, 120.0) as u32;
    let r = turn(
        pages,
        number(1, 0.0075),
        number(4, 0.0),
        held,
        number(3, f64::from(held) + 900.0) as u32,
    );
    println!(
        "merged {:?} {:?} after release, max stretch {:.4}",
        r.0, r.1, r.2
    );
}

/// Frames from the release to the merge, the block merged into, and the largest max edge
/// stretch of the turn.
fn turn(
    pages: u32,
    thickness: f64,
    mu: f64,
    held: u32,
    frames: u32,
) -> (Option<u32>, Option<BlockSide>, f64) {
    let mut s = BookSettings::<f64>::default();
    s.params.total_pages = pages;
    s.params.left_pages = pages / 2;
    s.params.page_thickness = thickness;
    s.contact_friction = mu;
    let mut book = Book::new(s).expect("book");
    let [w, h] = book.page_size();
    let script = TouchScript::page_turn(w, h, 10, held, frames);
    let turned = turn_page(&mut book, &script).expect("turn");
    (
        turned.merged.map(|(_, f)| f),
        turned.merged.map(|(side, _)| side),
        turned.max_stretch.0,
    )
}
