//! The heavy elastica over a ground: a strip of paper rooted at a point, bending under its own
//! weight and lying one-sidedly on what is under it, settled to rest. It is how a block's top
//! page lies in the gutter (issue 42: the page near the binding as paper lies, a modelling
//! choice of Folio's; the seed's collision test of Sec. 3.4 rests the page on the corner of
//! the block's clearance band instead), and the one-dimensional reference a released page's
//! rest is measured against.
//!
//! **Folio's choice.** The top page is rooted at the hinge, free to turn there, and lies on
//! its block cut square at the binding ([`Band::open_start`]): the pages under it end at the
//! binding as it does. On the default book's settled block (50 pages, its midline rising
//! 37° from the spine) it leans on the cut's upper corner, about 0.33 page units from the
//! hinge, and its chord from the hinge to a quarter of the page out stands at 63.2° (card),
//! 40.8° (novel), 39.6° (magazine) and 24.1° (bible), each paper's book with its own page
//! thickness, at 200 segments ([`top_page`]; `folio-tests`' `gutter.rs` prints them).
//!
//! - [`ground`]: what the strip lies on ([`Ground`]): nothing ([`Air`]), a block
//!   ([`Band`]), a table ([`Level`]), or two of them ([`Both`]).
//! - [`elastica`]: the strip and its rest ([`Elastica::settle`]).

pub mod elastica;
pub mod ground;
mod walls;

pub use elastica::{Elastica, ElasticaError, Root, Settled};
pub use ground::{Air, Band, Both, Ground, Level, Point2};
pub use walls::TOP_PAGE_WALLS;

/// The segments of a block's top page as [`top_page`] settles it: issue 42 asks for at
/// least 200.
pub const TOP_PAGE_SEGMENTS: usize = 200;

/// The top page of `book`'s block on `side` as it lies now, settled at `segments`: rooted
/// where the block's pages end on the binding edge (the binding parameter of the pages
/// before it, [`crate::BookLayout::binding_parameter`]), the page width long, with the
/// book's sag number ([`crate::BookSettings::sag_number`]), over the block cut square at
/// the binding (its midline and thickness) on a table through the midline's lowest point
/// (the cover board or the table under the block).
///
/// # Errors
/// [`ElasticaError::InvalidSetting`] for fewer than 2 segments or a book whose figures are
/// not finite; [`ElasticaError::NoStart`] when no arch from the root clears the block;
/// [`ElasticaError::NotSettled`] when the page finds no rest.
pub fn top_page<T: folio_kernels::Real>(
    book: &crate::Book<T>,
    side: crate::BlockSide,
    segments: usize,
) -> Result<Settled, ElasticaError> {
    use folio_kernels::Vec3Ops;
    let line: alloc::vec::Vec<Point2> = book
        .midline(side)
        .iter()
        .map(|p| [p.x().to_f64(), p.y().to_f64()])
        .collect();
    let (first, last) = (
        book.midline(crate::BlockSide::Left)[0],
        book.midline(crate::BlockSide::Right)[0],
    );
    let counts = book.counts();
    let before = match side {
        crate::BlockSide::Left => counts.left,
        crate::BlockSide::Right => counts.left + counts.active,
    };
    let q = book.layout().binding_parameter(before, 0);
    let at = |a: T, b: T| a.to_f64() + q * (b.to_f64() - a.to_f64());
    let lowest = line.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let finite = line.iter().flatten().all(|c| c.is_finite());
    if !(finite && lowest.is_finite()) {
        return Err(ElasticaError::InvalidSetting(
            folio_kernels::SettingError::new("midline", "finite"),
        ));
    }
    let table = Level { y: lowest };
    let ground = Both(
        Band {
            line: &line,
            clearance: book.block_thickness(side).to_f64(),
            open_start: true,
        },
        table,
    );
    let strip = Elastica {
        root: [at(first.x(), last.x()), at(first.y(), last.y())],
        held: Root::Pinned,
        length: book.layout().params.page_width,
        sag: book.settings().sag_number(),
        segments,
    };
    strip.validate()?;
    let start = strip.arched(&ground, side).ok_or(ElasticaError::NoStart)?;
    strip.settle(&ground, &start)
}
