//! The book a DOG scene describes (`[book]`, `[weights]`, `[solver]`): checked by the
//! validation the C API shares ([`crate::limits::book`], which runs the book's own
//! [`BookSettings::validate`]), each refusal reported at the scene key that set it; then
//! whether the scene's first grab can touch the page ([`check_reach`]).

use core::ops::Range;

use folio_book::{Action, Book, BookSettings, GrabOutcome, InputOutcome, Script};
use toml::Spanned;

use crate::fixtures::{self, Kind};
use crate::number::show;
use crate::scene::Scene;
use crate::settings::book_settings;

pub use crate::limits::MAX_PAGES;

type Problem = (Range<usize>, String);

/// The scene keys of [`folio_book::BookParams`] that older scene files spell differently
/// (serde aliases), or whose value another key sets (the page height is
/// `aspect_ratio` x `page_width`), so that an error finds the key the file wrote.
const OTHER_SPELLINGS: [(&str, &str); 3] = [
    ("book.total_pages", "book.pages"),
    ("book.page_thickness", "book.thickness"),
    ("book.page_width", "book.aspect_ratio"),
];

/// Where `key` (or another spelling of it) sits in the scene, else `[book]`.
fn span(scene: &Scene, key: &str) -> Range<usize> {
    let other = OTHER_SPELLINGS
        .iter()
        .find(|(new, _)| *new == key)
        .map(|(_, old)| *old);
    [Some(key), other]
        .into_iter()
        .flatten()
        .find_map(|k| scene.keys.span(k))
        .unwrap_or_else(|| scene.book.as_ref().map_or(0..0, Spanned::span))
}

/// Checks a DOG scene's book: `cover` is an effect, then the shared validation of the book
/// `folio run` builds ([`crate::limits::book`], the one the C API uses), at the key that
/// set the refused value.
///
/// # Errors
/// The span of the refused key and why.
pub fn check(scene: &Scene) -> Result<(), Problem> {
    if let Some(at) = scene.keys.span("book.cover") {
        return Err((
            at,
            "book.cover: a scene writes it as the `cover` effect".into(),
        ));
    }
    let settings: BookSettings<f64> = book_settings(scene);
    crate::limits::book(&settings).map_err(|r| (span(scene, &r.key), r.message))
}

/// Checks that the scene's first grab can touch the page: timed events grab the right
/// block's top page, so that block must hold one; a book fixture's first grab (a camera
/// ray) must hit this book as the run has it at that frame, with as many pages as it takes
/// (a book far thicker, smaller or larger than the one the fixture was recorded on is never
/// touched). Builds and steps the book as `folio run` does until the grab (milliseconds for
/// the blocks alone; a one- or two-page book settles longer at creation).
///
/// # Errors
/// The span of the input (or of `book.left_pages`) and why the grab cannot touch.
pub fn check_reach(scene: &Scene) -> Result<(), Problem> {
    let input = scene.input.get_ref();
    let settings = book_settings::<f64>(scene);
    let p = settings.params;
    if let Some(events) = &input.events {
        if p.left_pages >= p.total_pages {
            let at = scene
                .keys
                .span("book.left_pages")
                .unwrap_or_else(|| events.span());
            return Err((
                at,
                "the first grab takes the right block's top page, but book.left_pages leaves \
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

#[cfg(test)]
mod tests {
    use crate::scene::Scene;

    const DOG: &str = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";

    fn refused(extra: &str) -> (usize, usize, String) {
        let e = Scene::parse(&format!("{DOG}{extra}")).expect_err(extra);
        (e.line, e.column, e.message)
    }

    #[test]
    fn the_book_types_are_the_scene_keys() {
        let scene = Scene::parse(&format!(
            "{DOG}[book]\ntotal_pages = 40\naspect_ratio = 1.5\n[weights]\nglue = 300.0\n"
        ))
        .unwrap();
        let s = crate::settings::book_settings::<f32>(&scene);
        assert_eq!((s.params.total_pages, s.params.left_pages), (40, 20));
        assert_eq!(s.params.aspect_ratio, 1.5);
        assert_eq!(s.weights.glue, 300.0_f32);
        assert_eq!(s.weights.pull, folio_book::Weights::<f32>::default().pull);
        // The older spellings still read.
        let old = Scene::parse(&format!("{DOG}[book]\npages = 10\nthickness = 0.01\n")).unwrap();
        let p = crate::settings::book_settings::<f64>(&old).params;
        assert_eq!(
            (p.total_pages, p.left_pages, p.page_thickness),
            (10, 5, 0.01)
        );
    }

    #[test]
    fn a_refused_book_is_reported_at_its_key() {
        let (line, column, message) = refused("[book]\npage_width = 1e300\n");
        assert_eq!((line, column), (5, 14), "{message}");
        assert!(
            message.starts_with("book.page_width is too large"),
            "{message}"
        );
        let (line, column, message) = refused("[book]\nthickness = -1.0\n");
        assert_eq!((line, column), (5, 13), "{message}");
        assert_eq!(message, "book.page_thickness must be finite and > 0");
        let (line, _, message) = refused("[book]\ncover_overhang = -0.5\n");
        assert_eq!(line, 5, "{message}");
        let (line, column, message) = refused("[book]\ncover = false\n");
        assert_eq!((line, column), (5, 9), "{message}");
        assert!(message.contains("`cover` effect"), "{message}");
        let (line, column, message) = refused("[book]\nmidline_nodes = 2\n");
        assert_eq!((line, column), (5, 17), "{message}");
        assert!(message.contains("midline"), "{message}");
        let (line, column, message) = refused("[weights]\nglue = 2e9\n");
        assert_eq!((line, column), (5, 8), "{message}");
        assert!(
            message.starts_with("weights.glue must be in ["),
            "{message}"
        );
        // Inside [0, 1e9] but outside the range the book holds (issue 20).
        let (line, column, message) = refused("[weights]\npull = 1e9\n");
        assert_eq!((line, column), (5, 8), "{message}");
        assert!(
            message.starts_with("weights.pull must be in ["),
            "{message}"
        );
    }
}
