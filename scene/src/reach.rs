//! Whether a DOG scene's first grab can touch the page (feature `fixture-reach`): timed
//! events need a page on the right block; a book fixture's recorded camera ray must hit this
//! book, which takes a short replay of the book until that grab.

use folio_book::{Action, Book, GrabOutcome, InputOutcome, Script};
use toml::Spanned;

use crate::book::Problem;
use crate::fixtures::{self, Kind};
use crate::number::show;
use crate::scene::Scene;
use crate::settings::book_settings;

/// Checks that the scene's first grab can touch the page: timed events grab the right
/// block's top page, so that block must hold one; a book fixture's first grab (a camera
/// ray) must hit this book as the run has it at that frame, with as many pages as it takes
/// (a book far thicker, smaller or larger than the one the fixture was recorded on is never
/// touched). Builds and steps the book as `folio run` does until the grab (milliseconds for
/// the blocks alone; a one- or two-page book settles longer at creation).
///
/// # Errors
/// The span of the input (or of `book.params.left_pages`) and why the grab cannot touch.
pub fn check_reach(scene: &Scene) -> Result<(), Problem> {
    let input = scene.input.get_ref();
    let settings = book_settings::<f64>(scene).map_err(|e| (scene.input.span(), e.message))?;
    let p = settings.params;
    if let Some(events) = &input.events {
        if p.left_pages >= p.total_pages {
            let at = scene
                .keys
                .span("book.params.left_pages")
                .unwrap_or_else(|| events.span());
            return Err((
                at,
                "the first grab takes the right block's top page, but book.params.left_pages leaves \
                 that block empty"
                    .into(),
            ));
        }
        return Ok(());
    }
    let Some(fixture) = &input.fixture else {
        return Ok(());
    };
    let name = fixture.get_ref();
    let (Some(Kind::Book), Some(text)) = (fixtures::kind(name), fixtures::text(name)) else {
        return Ok(());
    };
    let script = Script::parse(text).map_err(|e| (fixture.span(), e.to_string()))?;
    let Some((frame, mut action)) = script.events.iter().find_map(|e| match e.action {
        Action::Grab { .. } => Some((e.frame, e.action)),
        _ => None,
    }) else {
        return Ok(());
    };
    if let (Some(k), Action::Grab { pages, .. }) = (&input.pages, &mut action) {
        *pages = *k.get_ref();
    }
    let mut book = Book::<f64>::new(settings).map_err(|e| (fixture.span(), e.to_string()))?;
    // The run steps the book until the grab (a book at rest simulates only its blocks).
    for _ in 0..frame {
        book.step().map_err(|e| (fixture.span(), e.to_string()))?;
    }
    let outcome = book
        .apply(script.camera, script.forward, action)
        .map_err(|e| (fixture.span(), e.to_string()))?;
    let thick = f64::from(p.total_pages) * p.page_thickness;
    let why = match outcome {
        InputOutcome::Grab(GrabOutcome::Grabbed { .. }) => return Ok(()),
        InputOutcome::Grab(GrabOutcome::NotEnoughPages) => {
            let at = input.pages.as_ref().map_or(fixture.span(), Spanned::span);
            return Err((
                at,
                format!(
                    "the fixture's grab at frame {frame} takes more pages than the block it \
                     hits holds"
                ),
            ));
        }
        _ => format!(
            "the fixture's grab at frame {frame} misses the page: its camera ray was recorded \
             on a 12 x 17 book 0.75 thick; this book's pages are {} x {} and it is {} thick",
            show(p.page_width),
            crate::number::short(p.page_height()),
            crate::number::short(thick)
        ),
    };
    Err((fixture.span(), why))
}
