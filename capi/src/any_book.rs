//! A book of either precision behind one type, so that a handle can name both.

use folio_book::{Book, BookError, DragOutcome, PageCounts};
use folio_geometry::QuadGrid;
use folio_geometry::mesh::{MeshError, TriMesh};
use folio_kernels::{Real, Vec3Ops};

use crate::step_report::FolioStepReport;

/// A [`Book`] in `f32` or `f64` (`FolioBookSettings::precision`).
#[derive(Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "one book per handle, held once; the two precisions differ by the settings' \
              width, and boxing would add an indirection to every call"
)]
pub(crate) enum AnyBook {
    /// Single precision.
    F32(Book<f32>),
    /// Double precision.
    F64(Book<f64>),
}

/// Runs `$body` with `$b` bound to the book of either precision: a [`Book`] method whose
/// signature names no precision is called through this, not wrapped again.
macro_rules! dispatch {
    ($any:expr, $b:ident => $body:expr) => {
        match $any {
            $crate::any_book::AnyBook::F32($b) => $body,
            $crate::any_book::AnyBook::F64($b) => $body,
        }
    };
}
pub(crate) use dispatch;

/// `p` in precision `T`.
fn vec3<T: Real>(p: [f64; 3]) -> T::Vec3 {
    T::Vec3::new(T::from_f64(p[0]), T::from_f64(p[1]), T::from_f64(p[2]))
}

/// `p` in `f64`.
fn xyz<T: Real>(p: T::Vec3) -> [f64; 3] {
    [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()]
}

/// One step and its C report.
fn step<T: Real>(book: &mut Book<T>) -> Result<FolioStepReport, BookError> {
    let r = book.step()?;
    Ok(FolioStepReport::new(book, &r))
}

impl AnyBook {
    /// [`Book::drag_to`] with the target in `f64`.
    pub fn drag_to(&mut self, target: [f64; 3]) -> Result<DragOutcome, BookError> {
        dispatch!(self, b => b.drag_to(vec3_of(b, target)))
    }

    /// [`Book::counts`].
    pub fn counts(&self) -> PageCounts {
        dispatch!(self, b => b.counts())
    }

    /// [`Book::release`].
    pub fn release(&mut self) -> bool {
        dispatch!(self, b => b.release())
    }

    /// [`Book::step`] with its C report.
    pub fn step(&mut self) -> Result<FolioStepReport, BookError> {
        dispatch!(self, b => step(b))
    }

    /// [`Book::mesh`].
    pub fn mesh(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        dispatch!(self, b => b.mesh(out))
    }

    /// The active page's grid (fixed for the book).
    pub fn grid(&self) -> QuadGrid {
        dispatch!(self, b => b.nodes().grid)
    }

    /// The active page's nodes in grid order, in `f64`, into `out` (`3 * grid().len()`
    /// values); `false` (nothing written) when there is no active page.
    pub fn page_positions(&self, out: &mut [f64]) -> bool {
        dispatch!(self, b => match b.page() {
            Some(page) => {
                for (chunk, &p) in out.chunks_exact_mut(3).zip(page) {
                    chunk.copy_from_slice(&xyz_of(b, p));
                }
                true
            }
            None => false,
        })
    }

    /// The held node's position, if a node is held.
    pub fn held_position(&self) -> Option<[f64; 3]> {
        dispatch!(self, b => {
            let node = b.held_node()?;
            let page = b.page()?;
            page.get(node).map(|&p| xyz_of(b, p))
        })
    }
}

/// [`vec3`] with `T` taken from `_book`.
fn vec3_of<T: Real>(_book: &Book<T>, p: [f64; 3]) -> T::Vec3 {
    vec3::<T>(p)
}

/// [`xyz`] with `T` taken from `_book`.
fn xyz_of<T: Real>(_book: &Book<T>, p: T::Vec3) -> [f64; 3] {
    xyz::<T>(p)
}
