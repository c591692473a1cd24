//! The book a DOG scene describes (`[book]`, `[weights]`): checked through the book's own
//! [`BookSettings::validate`], each refusal reported at the scene key that set it.

use core::ops::Range;

use folio_book::{BookError, BookSettings, LayoutError};
use toml::Spanned;

use crate::scene::Scene;
use crate::settings::book_settings;

type Problem = (Range<usize>, String);

/// The most pages a scene's book may have: more only make every frame slower.
pub const MAX_PAGES: u32 = 100_000;

/// The scene keys of [`folio_book::BookParams`] that older scene files spell differently
/// (serde aliases), so that an error finds the key the file wrote.
const OLDER_SPELLINGS: [(&str, &str); 2] = [
    ("book.total_pages", "book.pages"),
    ("book.page_thickness", "book.thickness"),
];

/// Where `key` (or its older spelling) sits in the scene, else `[book]`.
fn span(scene: &Scene, key: &str) -> Range<usize> {
    let older = OLDER_SPELLINGS
        .iter()
        .find(|(new, _)| *new == key)
        .map(|(_, old)| *old);
    [Some(key), older]
        .into_iter()
        .flatten()
        .find_map(|k| scene.keys.span(k))
        .unwrap_or_else(|| scene.book.as_ref().map_or(0..0, Spanned::span))
}

/// Checks a DOG scene's book: `cover` is an effect, at most [`MAX_PAGES`] pages, then
/// everything [`BookSettings::validate`] checks, at the key that set it.
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
    let p = &settings.params;
    if p.total_pages > MAX_PAGES {
        let message = format!("book.total_pages must be between 1 and {MAX_PAGES}");
        return Err((span(scene, "book.total_pages"), message));
    }
    settings.validate().map_err(|e| problem(scene, &e))
}

/// A refusal of [`BookSettings::validate`] at its scene key.
fn problem(scene: &Scene, e: &BookError) -> Problem {
    let (key, message) = match *e {
        BookError::Layout(LayoutError::NoPages) => (
            "book.total_pages",
            format!("book.total_pages must be between 1 and {MAX_PAGES}"),
        ),
        BookError::Layout(LayoutError::LeftPagesExceedTotal { .. }) => (
            "book.left_pages",
            "book.left_pages must be at most total_pages".into(),
        ),
        BookError::Layout(LayoutError::NonPositive { field }) => {
            (field, format!("book.{field} must be finite and > 0"))
        }
        BookError::Layout(LayoutError::TooFewMidlineNodes { .. }) => (
            "midline_nodes",
            "book.midline_nodes must be at least 3".into(),
        ),
        BookError::Layout(LayoutError::TooLarge { field }) => {
            (field, format!("book.{field} is too large: {e}"))
        }
        BookError::InvalidSetting { field, requirement } => {
            (field, format!("{field} must be {requirement}"))
        }
        _ => ("", e.to_string()),
    };
    let key = if key.starts_with("weights.") || key.starts_with("book.") {
        key.to_string()
    } else {
        format!("book.{key}")
    };
    (span(scene, &key), message)
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
