//! `FolioBookSettings`: the book a C caller asks for, and its conversion to the solver's
//! `BookSettings`.

use folio_book::{BookSettings, Effects};
use folio_kernels::{Real, SettingError};

use crate::failure::Failure;
use crate::guard;
use crate::pointer;
use crate::status::FolioStatus;

/// The precision of a book's state and solver: `FOLIO_PRECISION_F32` or
/// `FOLIO_PRECISION_F64`.
pub type FolioPrecision = u32;

/// Single precision: the microcontroller path (a Cortex-M4F FPU is single precision).
pub const FOLIO_PRECISION_F32: FolioPrecision = 32;

/// Double precision: the reference.
pub const FOLIO_PRECISION_F64: FolioPrecision = 64;

/// A set of `FOLIO_EFFECT_*` bits. An effect that is off contributes no term, no KKT row and
/// no work.
pub type FolioEffects = u32;

/// Gravity on blocks, cover and page (seed `000_…` eq. 12).
pub const FOLIO_EFFECT_GRAVITY: FolioEffects = 1 << 0;

/// The binding glue between the two blocks (eq. 11); needs `FOLIO_EFFECT_BLOCKS`.
pub const FOLIO_EFFECT_GLUE: FolioEffects = 1 << 1;

/// Collision handling (Sec. 3.4): the page rests on the blocks instead of passing through.
pub const FOLIO_EFFECT_COLLISIONS: FolioEffects = 1 << 2;

/// The page blocks as simulated midline curves; off, they keep their rest shape.
pub const FOLIO_EFFECT_BLOCKS: FolioEffects = 1 << 3;

/// Finger-bookmarking's history of the held page (Sec. 4.1).
pub const FOLIO_EFFECT_BOOKMARKING: FolioEffects = 1 << 4;

/// Every effect.
pub const FOLIO_EFFECTS_ALL: FolioEffects = FOLIO_EFFECT_GRAVITY
    | FOLIO_EFFECT_GLUE
    | FOLIO_EFFECT_COLLISIONS
    | FOLIO_EFFECT_BLOCKS
    | FOLIO_EFFECT_BOOKMARKING;

/// The book to create. Start from `folio_book_settings_default` and change fields; every
/// field is checked by `folio_book_create` (`FOLIO_STATUS_INVALID_ARGUMENT` names the first
/// bad one) by the book's own rules (`folio_book::BookSettings::validate`), the ones a scene
/// file's `[book]` and `[solver]` are held to. Lengths are page units, times seconds. The
/// fields not listed here (weights, masses, solver tolerances) take the seed's defaults for
/// the chosen precision.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FolioBookSettings {
    /// Pages in the book, from 1 to 100000. Default 100.
    pub total_pages: u32,
    /// Pages in the left block, $\le$ `total_pages`; the rest are in the right block.
    /// Default 50.
    pub left_pages: u32,
    /// Page width $W$, finite, large enough to touch (a grid cell at least 100 times the
    /// constraint tolerance: $W \ge 0.08$ at 8 quads across) and at most $1.2 \cdot 10^5$.
    /// Default 12 (the seed's).
    pub page_width: f64,
    /// Page height over width, $H / W$, finite and $> 0$, with $H \le 1.2 \cdot 10^5$. Default
    /// $\sqrt 2$ (ISO 216).
    pub aspect_ratio: f64,
    /// Thickness of one page, at least $10^{-6} W$, the book (pages x thickness) at most
    /// $1.2 \cdot 10^5$. Default 0.0075 (the seed's).
    pub page_thickness: f64,
    /// Time step $h$ of one `folio_book_step`, in $[10^{-6}, 0.1]$ s (the book's range; a
    /// scene file, whose frames of 1/60 s take whole numbers of steps, also holds it to one
    /// frame). Default $1/60$ s.
    pub time_step: f64,
    /// Quads of the active page's grid across the page (binding to fore-edge), $\ge 2$.
    /// Default 8.
    pub quads_across: u32,
    /// Quads along the binding, $\ge 2$, at most 65536 quads in all. Default 11.
    pub quads_along: u32,
    /// 1: a hard cover (three boards under the blocks); 0: none. Default 1.
    pub cover: u32,
    /// `FOLIO_PRECISION_F32` or `FOLIO_PRECISION_F64`. Default f64.
    pub precision: FolioPrecision,
    /// `FOLIO_EFFECT_*` bits. Default `FOLIO_EFFECTS_ALL`.
    pub effects: FolioEffects,
}

impl Default for FolioBookSettings {
    fn default() -> Self {
        let book = BookSettings::<f64>::default();
        let p = book.params;
        Self {
            total_pages: p.total_pages,
            left_pages: p.left_pages,
            page_width: p.page_width,
            aspect_ratio: p.aspect_ratio,
            page_thickness: p.page_thickness,
            time_step: book.solver.time_step,
            quads_across: u32::try_from(book.quads_across).unwrap_or(u32::MAX),
            quads_along: u32::try_from(book.quads_along).unwrap_or(u32::MAX),
            cover: u32::from(p.cover),
            precision: FOLIO_PRECISION_F64,
            effects: effect_bits(book.effects),
        }
    }
}

/// The `FOLIO_EFFECT_*` bits of `effects`.
fn effect_bits(e: Effects) -> FolioEffects {
    [
        (e.gravity, FOLIO_EFFECT_GRAVITY),
        (e.glue, FOLIO_EFFECT_GLUE),
        (e.collisions, FOLIO_EFFECT_COLLISIONS),
        (e.blocks, FOLIO_EFFECT_BLOCKS),
        (e.bookmarking, FOLIO_EFFECT_BOOKMARKING),
    ]
    .into_iter()
    .filter(|(on, _)| *on)
    .fold(0, |bits, (_, bit)| bits | bit)
}

impl FolioBookSettings {
    /// The solver's settings in precision `T`: the seed's defaults for `T` with these
    /// fields. Checks what only the C API has (the cover flag, the effect bits), then the
    /// book's own validation ([`BookSettings::validate`], on the same fields in `f64`, the
    /// one scene files are held to). The book checks the precision's own limits when it is
    /// built.
    ///
    /// # Errors
    /// `INVALID_ARGUMENT` for a cover flag other than 0 or 1, an unknown effect bit, or a
    /// setting [`BookSettings::validate`] refuses (the message names the C field).
    pub(crate) fn book_settings<T: Real>(&self) -> Result<BookSettings<T>, Failure> {
        if self.cover > 1 {
            return Err(Failure::invalid(format!(
                "`cover` must be 0 or 1, not {}",
                self.cover
            )));
        }
        let unknown = self.effects & !FOLIO_EFFECTS_ALL;
        if unknown != 0 {
            return Err(Failure::invalid(format!(
                "`effects` has unknown bits {unknown:#x} (known: {FOLIO_EFFECTS_ALL:#x})"
            )));
        }
        let wide = self.fill(BookSettings::<f64>::default());
        wide.validate().map_err(|e| Failure::invalid(refusal(&e)))?;
        Ok(self.fill(BookSettings::<T>::default()))
    }

    /// `book` with these fields.
    fn fill<T: Real>(&self, mut book: BookSettings<T>) -> BookSettings<T> {
        let on = |bit: FolioEffects| self.effects & bit != 0;
        book.params.total_pages = self.total_pages;
        book.params.left_pages = self.left_pages;
        book.params.page_width = self.page_width;
        book.params.aspect_ratio = self.aspect_ratio;
        book.params.page_thickness = self.page_thickness;
        book.params.cover = self.cover == 1;
        book.quads_across = self.quads_across as usize;
        book.quads_along = self.quads_along as usize;
        book.solver.time_step = T::from_f64(self.time_step);
        book.effects = Effects {
            gravity: on(FOLIO_EFFECT_GRAVITY),
            glue: on(FOLIO_EFFECT_GLUE),
            collisions: on(FOLIO_EFFECT_COLLISIONS),
            blocks: on(FOLIO_EFFECT_BLOCKS),
            bookmarking: on(FOLIO_EFFECT_BOOKMARKING),
        };
        book
    }
}

/// A refusal of [`BookSettings::validate`] in the C API's words: the field of
/// `FolioBookSettings` (`page_width`, not `params.page_width`), or the effect bit.
fn refusal(e: &SettingError) -> String {
    let path = e.path.to_string();
    if let Some(effect) = path.strip_prefix("effects.") {
        return format!("`effects`: {effect} must be {}", e.requirement);
    }
    let field = ["params.", "solver."]
        .iter()
        .find_map(|section| path.strip_prefix(section))
        .unwrap_or(&path);
    e.named(field).to_string()
}

/// Writes the default settings (each field's docs give its default) to `*out`.
///
/// Returns `FOLIO_STATUS_NULL_POINTER` if `out` is NULL.
///
/// # Safety
/// `out` is NULL or valid for a write of one `FolioBookSettings`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_settings_default(out: *mut FolioBookSettings) -> FolioStatus {
    guard::call("folio_book_settings_default", || {
        // SAFETY: `out` is NULL (refused by `write`) or valid for one write (contract).
        unsafe { pointer::write(out, FolioBookSettings::default(), "out") }
    })
}
