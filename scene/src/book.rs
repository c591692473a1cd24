//! The book a DOG scene describes (`[book]`, `[weights]`, `[solver]`): checked by the
//! validation the C API shares ([`crate::limits::book`], which runs the book's own
//! [`BookSettings::validate`]), each refusal reported at the scene key that set it. Whether
//! the scene's first grab can touch the page is `crate::reach` (feature `fixture-reach`).

use core::ops::Range;

use folio_book::BookSettings;
use toml::Spanned;

use crate::scene::Scene;
use crate::settings::book_settings;

pub use crate::limits::MAX_PAGES;

/// A refusal: the span of the scene key at fault, and why.
pub(crate) type Problem = (Range<usize>, String);

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
