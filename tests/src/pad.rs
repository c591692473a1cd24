//! The finger's pad in the tests (`folio_book::pad`): a grab of the fore-edge's middle and
//! the hinge the pad turns about.

use folio_book::{BlockSide, Book, GrabOutcome};
use folio_kernels::Real;

type V = <f64 as Real>::Vec3;

/// A grab by the pad (or the seed's pull) of the right page's fore-edge middle.
pub struct EdgeGrab {
    /// The grab point $(u, v)$, page units.
    pub at: [f64; 2],
    /// Where the held point lay at the grab (the pad's centre).
    pub start: V,
    /// The bound node of the grab point's row: the hinge the pad turns about.
    pub hinge: V,
}

/// Grabs `book`'s right page at the middle of its fore-edge; panics when the grab misses.
///
/// # Panics
/// When the book refuses the grab or takes no page.
#[must_use]
pub fn grab_fore_edge_middle(book: &mut Book<f64>) -> EdgeGrab {
    let [w, h] = book.page_size();
    let at = [w, 0.5 * h];
    let outcome = book.grab_at(BlockSide::Right, at, 1).expect("a grab");
    assert!(
        matches!(outcome, GrabOutcome::Grabbed { .. }),
        "{outcome:?}"
    );
    let row = (0.5 * h / book.grid_spacing()[1]).round() as usize;
    let hinge = book.state().x[book.nodes().page(0, row)];
    let start = book.target().expect("held");
    EdgeGrab { at, start, hinge }
}
