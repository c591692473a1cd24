//! The most accurate page: the active page of the DOG book (seed `000_…`), turned from the
//! right block of a [`Book`] by the finger of a touch script.
//!
//! **Frames.** The book's frame has the binding near $x = 0$ and the blocks on a cover
//! board; the page frame of [`super`] is the book's shifted by the grabbed page's rest
//! corner: $x_0$ of its bound column and $y_0$ of its fore-edge, so that the page lying on
//! its block is near $\lbrace(u, 0, v)\rbrace$ (the block top rises from the binding, so the inner
//! strip of the page sits below $y = 0$).
//!
//! **Gestures.** Any number in sequence ([`super::Gestures`]): each grab takes the top page
//! (or a stack) of the block on its side, or the released page again while it still lies
//! there; the page frame is set anew at each grab, mirrored ($x = -u$) for a page taken on
//! the left.
//!
//! **Input.** The grab holds the grab-ring node nearest the material point (the book lets
//! the user hold only nodes one ring in from the border, seed Sec. 3.3); the finger drives
//! that node's pull target, without the tent, shifted by the offset that puts the finger's
//! grab point, $(\pm u, 0, v)$ in the page frame, on the held node where it lies
//! ([`finger_frame`]): the finger holds the page where it touched it. On a flat page that
//! offset is the node's material offset from the grab point ($\Delta u$ along X, $\Delta v$
//! along Z); on a page that arches from the binding over its block's top page (seed Sec. 3.4
//! does not have one; `book.gutter = "top-page"` does) the fore-edge lies nearer the binding
//! than $u$, and a frame that assumed the page flat aimed the first pull along the page,
//! away from the node: measured on a novel page, 0.9 page units at 8 x 11, a first frame
//! stretched by 2.2 % (bible at 16 x 22: 6.5 %).
//!
//! **Output.** The page's surface at a render node is the bilinear interpolation of the DOG
//! grid at its material point. After the page merges into a block, the page keeps the
//! geometry it came to rest in (the book then simulates only its blocks).

use alloc::vec::Vec;
use folio_geometry::{BlockSide, QuadGrid};
use folio_kernels::{Real, Vec3Ops};

use super::{
    GestureError, PageError, PageModel, PageStatus, PageStep, check_finger, check_grab,
    material_point,
};
use folio_book::{Book, BookSettings, BookStepReport, GrabOutcome};

/// The DOG page (module docs).
#[derive(Clone, Debug)]
pub struct DogPage<T: Real> {
    book: Book<T>,
    /// Page-frame origin in the book frame (set at the grab).
    origin: T::Vec3,
    /// Finger offset of the held node: where it lies minus the finger's grab point (page
    /// frame, [`finger_frame`]).
    offset: T::Vec3,
    /// The page's node positions (page frame), kept after a merge.
    nodes: Vec<T::Vec3>,
    grid: QuadGrid,
    spacing: [f64; 2],
    /// The book's report of the last step (its solver status, KKT size, contacts).
    last: Option<BookStepReport<T>>,
}

impl<T: Real> DogPage<T> {
    /// A book with `settings` whose right block's top page will be turned.
    ///
    /// # Errors
    /// As [`Book::new`].
    pub fn new(settings: BookSettings<T>) -> Result<Self, PageError> {
        let book = Book::new(settings)?;
        let grid = QuadGrid::new(settings.quads_across, settings.quads_along).ok_or(
            PageError::InvalidInput {
                what: "DOG page grid",
            },
        )?;
        let spacing = book.grid_spacing();
        let nodes = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                T::Vec3::new(
                    T::from_f64(i as f64 * spacing[0]),
                    T::ZERO,
                    T::from_f64(j as f64 * spacing[1]),
                )
            })
            .collect();
        Ok(Self {
            book,
            origin: T::Vec3::ZERO,
            offset: T::Vec3::ZERO,
            nodes,
            grid,
            spacing,
            last: None,
        })
    }

    /// The book underneath.
    #[must_use]
    pub fn book(&self) -> &Book<T> {
        &self.book
    }

    /// The book's report of the last [`PageModel::step`] (`None` before the first): what the
    /// page model's [`PageStatus`] sums up (a stalled step's solver status, the KKT size,
    /// the collision tests).
    #[must_use]
    pub fn last_report(&self) -> Option<&BookStepReport<T>> {
        self.last.as_ref()
    }

    /// Copies the active page (page frame) into `nodes`, if there is one.
    fn track(&mut self) {
        if let Some(page) = self.book.page() {
            for (out, &p) in self.nodes.iter_mut().zip(page) {
                *out = p - self.origin;
            }
        }
    }
}

impl<T: Real> PageModel<T> for DogPage<T> {
    fn name(&self) -> &'static str {
        "dog"
    }

    fn size(&self) -> [T; 2] {
        let p = &self.book.layout().params;
        [T::from_f64(p.page_width), T::from_f64(p.page_height())]
    }

    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError> {
        self.grab_page(BlockSide::Right, 1, at)
    }

    /// The top `pages` pages of the block on `side` (or the released page again, if it
    /// still lies there); the page frame's origin is set anew from the page taken, and on
    /// the left its X runs the other way ($x = -u$). A page released before that still moves
    /// on the other side is not left behind: the grab is refused until it merges.
    fn grab_page(&mut self, side: BlockSide, pages: u32, at: [T; 2]) -> Result<(), PageError> {
        check_grab(at, self.size())?;
        if pages == 0 {
            return Err(PageError::InvalidInput {
                what: "pages to grab (zero)",
            });
        }
        if self.book.active_side().is_some_and(|lies| lies != side) {
            return Err(PageError::Gesture(GestureError::Unsettled { side }));
        }
        let at64 = [at[0].to_f64(), at[1].to_f64()];
        let GrabOutcome::Grabbed { node, .. } = self.book.grab_at(side, at64, pages)? else {
            return Err(PageError::Gesture(GestureError::NoPage {
                side,
                model: "dog",
            }));
        };
        if let Some((origin, offset)) = finger_frame(&self.book, side, node, at64) {
            (self.origin, self.offset) = (origin, offset);
        }
        self.track();
        Ok(())
    }

    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError> {
        check_finger::<T>(finger)?;
        self.book.drag_to(finger + self.offset + self.origin)?;
        Ok(())
    }

    fn release(&mut self) {
        self.book.release();
    }

    fn step(&mut self) -> Result<PageStep<T>, PageError> {
        let report = self.book.step()?;
        self.last = Some(report);
        self.track();
        let finger_gap = match (self.book.held_node(), self.book.target()) {
            (Some(node), Some(target)) => self
                .book
                .page()
                .map(|page| folio_kernels::math::length::<T>(page[node] - target)),
            _ => None,
        };
        Ok(PageStep {
            status: if report.solver.status.advanced() {
                PageStatus::Moved
            } else {
                PageStatus::Stalled
            },
            finger_gap,
        })
    }

    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError> {
        super::check_count(grid.len(), out.len())?;
        let size = self.size();
        for (k, p) in out.iter_mut().enumerate() {
            let [u, v] = material_point(grid, size, k);
            *p = self
                .grid
                .bilinear::<T>(&self.nodes, self.spacing, [u.to_f64(), v.to_f64()]);
        }
        Ok(())
    }
}

/// The page frame of a grab (module docs), for callers that drive [`Book::drag_to`] with a
/// finger's path in it: its origin in the book frame, the rest corner of the active page
/// ($x$ of node $(0, 0)$ at the binding, $y$ of the fore-edge's node $(n_x - 1, 0)$, $z = 0$),
/// and the offset from the finger to the held point that puts the finger's grab point
/// $(\pm u, 0, v)$ at `at` $= (u, v)$ (minus on the left) on the held point where it lies:
/// a drag to $f$ aims the held point at $f + \text{offset} + \text{origin}$. The held point
/// is the hold's target at the grab ([`Book::target`]): the held page node `node` (index
/// into the page grid) under the seed's pull, the pad's centre under a pad
/// ([`folio_book::BookSettings::pad_radius`]; aiming a pad at its nearest node instead
/// pulled it 1.5 page units off on 8 x 11). Call it right after the grab. `None` without
/// an active page or for a node off its grid.
#[must_use]
pub fn finger_frame<T: Real>(
    book: &Book<T>,
    side: BlockSide,
    node: usize,
    at: [f64; 2],
) -> Option<(T::Vec3, T::Vec3)> {
    let page = book.page()?;
    let grid = book.nodes().grid;
    let (corner, edge, held) = (
        *page.first()?,
        *page.get(grid.index(grid.nx - 1, 0))?,
        book.target().or_else(|| page.get(node).copied())?,
    );
    let origin = T::Vec3::new(corner.x(), edge.y(), T::ZERO);
    let u = if side == BlockSide::Left {
        -at[0]
    } else {
        at[0]
    };
    let touched = T::Vec3::new(T::from_f64(u), T::ZERO, T::from_f64(at[1]));
    Some((origin, held - origin - touched))
}
