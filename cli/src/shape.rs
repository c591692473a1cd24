//! What a frame shows, for the outputs that draw it and the measures that sample it, in
//! either precision: a run in `f32` shows its `Book<f32>` or its `f32` page model through
//! the same [`Shape`] as one in `f64` (every figure leaves as `f64`).

use folio_book::{Book, BookParams};
use folio_geometry::QuadGrid;
use folio_geometry::mesh::TriMesh;
use folio_kernels::{Real, Vec3Ops};
use folio_pages::PageModel;
use folio_tearing::sheet::TearingSheet;

use crate::error::{RunError, fail};

/// The render grid page models are measured on (24 x 34 quads, half a page unit).
pub const RENDER_QUADS: (usize, usize) = (24, 34);

/// A simulated surface a frame shows, in any precision: what the outputs and measures ask
/// of a book or a page model.
pub trait View {
    /// The active page's thickness (page units; 0 without one).
    fn thickness(&self) -> f64;

    /// The page's surface at the material points of `grid`, in `f64`, written into `out`
    /// ([`Shape::page_points`]); `false` when there is no page to sample.
    fn page_points(&self, grid: QuadGrid, out: &mut Vec<[f64; 3]>) -> bool;

    /// Appends the frame's render mesh to `out`.
    ///
    /// # Errors
    /// A mesh the mesher refuses (a non-finite or degenerate surface).
    fn mesh(&self, out: &mut TriMesh) -> Result<(), RunError>;
}

/// A point in `f64`.
fn point<T: Real>(p: T::Vec3) -> [f64; 3] {
    [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()]
}

impl<T: Real> View for Book<T> {
    /// A stack of $k$ pages is $k$ pages thick.
    fn thickness(&self) -> f64 {
        self.active_thickness().to_f64()
    }

    /// The active page in the book's frame (`false` without one).
    fn page_points(&self, grid: QuadGrid, out: &mut Vec<[f64; 3]>) -> bool {
        out.clear();
        let (Some(nodes), s) = (self.page(), self.settings()) else {
            return false;
        };
        let Some(page_grid) = QuadGrid::new(s.quads_across, s.quads_along) else {
            return false;
        };
        let (size, spacing) = (self.page_size(), self.grid_spacing());
        out.extend((0..grid.len()).map(|k| {
            let at = folio_pages::material_point(grid, size, k);
            point::<T>(page_grid.bilinear::<T>(nodes, spacing, at))
        }));
        true
    }

    fn mesh(&self, out: &mut TriMesh) -> Result<(), RunError> {
        Book::mesh(self, out).map_err(fail)
    }
}

/// A page model seen as a [`View`] (the page models' trait objects are per precision).
pub struct PageView<'a, T: Real>(pub &'a dyn PageModel<T>);

impl<T: Real> View for PageView<'_, T> {
    /// The book's paper (the cone's page has no thickness of its own).
    fn thickness(&self) -> f64 {
        BookParams::default().page_thickness
    }

    /// The page in the page frame of [`folio_pages`] (`false` when it cannot be sampled).
    fn page_points(&self, grid: QuadGrid, out: &mut Vec<[f64; 3]>) -> bool {
        out.clear();
        let mut samples = vec![T::Vec3::ZERO; grid.len()];
        if self.0.sample(grid, &mut samples).is_err() {
            return false;
        }
        out.extend(samples.into_iter().map(point::<T>));
        true
    }

    /// The page on the render grid ([`RENDER_QUADS`]), the book's paper thick.
    fn mesh(&self, out: &mut TriMesh) -> Result<(), RunError> {
        let grid =
            QuadGrid::new(RENDER_QUADS.0, RENDER_QUADS.1).ok_or_else(|| fail("render grid"))?;
        folio_pages::mesh(self.0, grid, self.thickness(), out).map_err(fail)
    }
}

/// What a frame shows, for the outputs that draw it.
#[derive(Clone, Copy)]
pub enum Shape<'a> {
    /// The whole book (a `Book<f64>` or `Book<f32>`).
    Book(&'a dyn View),
    /// A page model's page (a [`PageView`] of either precision).
    Page(&'a dyn View),
    /// The tearing sheet.
    Sheet(&'a TearingSheet<f64>),
}

impl Shape<'_> {
    /// The active page's thickness (page units; 0 without one): a stack of $k$ pages is
    /// $k$ pages thick.
    #[must_use]
    pub fn thickness(&self) -> f64 {
        match self {
            Self::Book(view) | Self::Page(view) => view.thickness(),
            Self::Sheet(sheet) => sheet.settings().tearing.thickness,
        }
    }

    /// The page's surface at the material points of `grid` (page models: the page frame of
    /// [`folio_pages`]; the book: the active page in the book's frame), converted to `f64`
    /// and written into `out`; `false` when there is no page to sample (a book with no
    /// active page, a sheet).
    #[must_use]
    pub fn page_points(&self, grid: QuadGrid, out: &mut Vec<[f64; 3]>) -> bool {
        match self {
            Self::Book(view) | Self::Page(view) => view.page_points(grid, out),
            Self::Sheet(_) => {
                out.clear();
                false
            }
        }
    }

    /// Appends the frame's render mesh to `out`.
    ///
    /// # Errors
    /// A mesh the mesher refuses (a non-finite or degenerate surface).
    pub fn mesh(&self, out: &mut TriMesh) -> Result<(), RunError> {
        match self {
            Self::Book(view) | Self::Page(view) => view.mesh(out),
            Self::Sheet(sheet) => {
                let s = sheet.settings();
                crate::sheet_view::render_mesh(sheet.mesh(), [s.width, s.height], out);
                Ok(())
            }
        }
    }
}
