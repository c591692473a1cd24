//! The user's hand: grab, drag, release.

use folio_book::{DragOutcome, GrabOutcome};
use folio_geometry::BlockSide;

use crate::any_book::dispatch;
use crate::failure::Failure;
use crate::guard;
use crate::handle::FolioBookHandle;
use crate::registry;
use crate::side::{FolioSide, block_side};
use crate::status::FolioStatus;

/// `Ok` when every value of `values` is finite; else `INVALID_ARGUMENT` naming them.
fn finite(what: &str, names: &str, values: &[f64]) -> Result<(), Failure> {
    if values.iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    let list: alloc::vec::Vec<String> = values.iter().map(|v| format!("{v}")).collect();
    Err(Failure::invalid(format!(
        "{what} {names} = ({}) is not finite",
        list.join(", ")
    )))
}

/// Grabs `pages` pages (1: one page; more: a stack) from the top of the block on `side`
/// (seed `000_…` Sec. 3.3, 4.1) by the material point $(u, v)$ of the page: $u$ across from
/// the binding ($0 \le u \le W$), $v$ along it ($0 \le v \le H$), page units; a point off
/// the page is first clamped onto it. The page node held is the one nearest $(u, v)$ on the
/// ring one cell in from the page's border (the seed lets the user hold only those). The held node starts where it lies; move it
/// with `folio_book_drag`, and read where it is with `folio_book_held_position`.
///
/// With an active page already present (held or falling), its nearest ring node is held
/// instead and `side` and `pages` are ignored.
///
/// Returns `FOLIO_STATUS_INVALID_ARGUMENT` for an unknown side, a non-finite point or
/// `pages` 0, `FOLIO_STATUS_NOT_ENOUGH_PAGES` if the block holds fewer than `pages`,
/// `FOLIO_STATUS_STALE_HANDLE`. On failure the book is unchanged.
#[unsafe(no_mangle)]
pub extern "C" fn folio_book_grab(
    handle: FolioBookHandle,
    side: FolioSide,
    u: f64,
    v: f64,
    pages: u32,
) -> FolioStatus {
    guard::call("folio_book_grab", || {
        let side = block_side(side).ok_or_else(|| {
            Failure::invalid(format!(
                "`side` must be FOLIO_SIDE_LEFT (0) or FOLIO_SIDE_RIGHT (1), not {side}"
            ))
        })?;
        finite("grab point", "(u, v)", &[u, v])?;
        if pages == 0 {
            return Err(Failure::invalid("`pages` must be at least 1"));
        }
        registry::with_entry(handle, |e| {
            let outcome = dispatch!(&mut e.book, b => {
                // Clamped onto the page: far points would overflow the book's squared
                // distances.
                let [w, h] = b.page_size();
                b.grab_at(side, [u.clamp(0.0, w), v.clamp(0.0, h)], pages)
            })
            .map_err(Failure::book)?;
            match outcome {
                GrabOutcome::Grabbed { .. } => {
                    e.touch();
                    Ok(())
                }
                GrabOutcome::NotEnoughPages => {
                    let (name, held) = match side {
                        BlockSide::Left => ("left", e.book.counts().left),
                        BlockSide::Right => ("right", e.book.counts().right),
                    };
                    Err(Failure::new(
                        FolioStatus::NotEnoughPages,
                        format!("the {name} block holds {held} pages, {pages} asked for"),
                    ))
                }
                // `Missed`, or any other outcome that grabbed nothing.
                _ => Err(Failure::invalid("the grab missed the book")),
            }
        })
    })
}

/// Moves the held node's target to $(x, y, z)$ (book frame, page units; see the header's
/// introduction). The page follows at the next steps: each step pulls the node towards the
/// target on a leash of one page unit (seed eq. 14), so a target far ahead is reached over
/// several steps. There is no tent or drag plane here: the caller owns the finger's path.
///
/// Returns `FOLIO_STATUS_INVALID_ARGUMENT` for a NaN or infinite coordinate (or one beyond
/// the precision's range), `FOLIO_STATUS_NOT_HELD` if no page is held,
/// `FOLIO_STATUS_STALE_HANDLE`. On failure the target is unchanged.
#[unsafe(no_mangle)]
pub extern "C" fn folio_book_drag(handle: FolioBookHandle, x: f64, y: f64, z: f64) -> FolioStatus {
    guard::call("folio_book_drag", || {
        finite("drag target", "(x, y, z)", &[x, y, z])?;
        registry::with_entry(handle, |e| {
            match e.book.drag_to([x, y, z]).map_err(Failure::book)? {
                DragOutcome::Moved => Ok(()),
                // `NotHeld` (there is no ray here to miss), or any other outcome.
                _ => Err(not_held()),
            }
        })
    })
}

fn not_held() -> Failure {
    Failure::new(FolioStatus::NotHeld, "no page is held")
}

/// Lets go of the held page: it falls under gravity, settles, and merges into the block it
/// comes to rest on (reported in the `merged` field of `FolioStepReport`).
///
/// Returns `FOLIO_STATUS_NOT_HELD` (and changes nothing) if no page is held,
/// `FOLIO_STATUS_STALE_HANDLE`.
#[unsafe(no_mangle)]
pub extern "C" fn folio_book_release(handle: FolioBookHandle) -> FolioStatus {
    guard::call("folio_book_release", || {
        registry::with_entry(handle, |e| {
            if e.book.release() {
                e.touch();
                Ok(())
            } else {
                Err(not_held())
            }
        })
    })
}
