//! The shared page turn (`TouchScript::page_turn`: the fore-edge point carried over the
//! spine and let go) played on a DOG book through `Book::grab_at` and `Book::drag_to`, as
//! the DOG page model drives it, with what the tests and probes read off it.

use folio_book::{BlockSide, Book, BookError, GrabOutcome};
use folio_kernels::Real;
use folio_pages::TouchScript;
use folio_pages::dog::finger_frame;
use folio_pages::touch::Touch;

type V = <f64 as Real>::Vec3;

/// What one page turn did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Turned {
    /// Whether the grab took a page.
    pub grabbed: bool,
    /// The block the released page merged into and the frames from the release to the
    /// merge; `None` when it had not merged by the script's end.
    pub merged: Option<(BlockSide, u32)>,
    /// The largest edge stretch of the page over the turn, and its frame.
    pub max_stretch: (f64, u32),
    /// The largest edge stretch in the first frame after the grab.
    pub grab_stretch: f64,
    /// Steps whose solver did not advance (stalled, failed line search or factorization).
    pub failed_steps: u32,
}

/// Plays `script` on `book`, grabbing on the right block; stops at the merge.
///
/// # Errors
/// A grab, drag or step the book refuses.
pub fn turn_page(book: &mut Book<f64>, script: &TouchScript) -> Result<Turned, BookError> {
    turn_page_watching(book, script, |_| {})
}

/// [`turn_page`], calling `watch` with the book after every step that did not merge the
/// page (the last call sees the page as it came to rest, the frame before its merge).
///
/// # Errors
/// A grab, drag or step the book refuses.
pub fn turn_page_watching(
    book: &mut Book<f64>,
    script: &TouchScript,
    mut watch: impl FnMut(&Book<f64>),
) -> Result<Turned, BookError> {
    let (mut origin, mut offset) = (V::ZERO, V::ZERO);
    let point = |p: [f64; 3]| V::new(p[0], p[1], p[2]);
    let mut out = Turned::default();
    let mut grab_frame = None;
    for f in 0..script.frames {
        match script.at(f) {
            Touch::Grab { at, finger } => {
                let GrabOutcome::Grabbed { node, .. } = book.grab_at(BlockSide::Right, at, 1)?
                else {
                    return Ok(out);
                };
                out.grabbed = true;
                grab_frame = Some(f);
                // The finger's frame: the finger holds the node where it lies.
                if let Some(frame) = finger_frame(book, BlockSide::Right, node, at) {
                    (origin, offset) = frame;
                }
                book.drag_to(point(finger) + offset + origin)?;
            }
            Touch::Drag(finger) => {
                book.drag_to(point(finger) + offset + origin)?;
            }
            Touch::Release => {
                book.release();
            }
            _ => {}
        }
        let report = book.step()?;
        if !report.solver.status.advanced() {
            out.failed_steps += 1;
        }
        if let Some((stretch, _)) = book.stretch() {
            if stretch > out.max_stretch.0 {
                out.max_stretch = (stretch, f);
            }
            if grab_frame == Some(f) {
                out.grab_stretch = stretch;
            }
        }
        if let Some(side) = report.merged {
            out.merged = Some((side, f.saturating_sub(script.release_frame())));
            return Ok(out);
        }
        watch(book);
    }
    Ok(out)
}
