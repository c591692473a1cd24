//! The book a DOG scene describes (`[book]`, a [`folio_book::BookSettings`], and `effects`): checked
//! by the book's own [`folio_book::BookSettings::validate`] (the one the C API uses), each refusal
//! reported at the scene key that set it. Whether the scene's first grab can touch the page
//! is `crate::reach` (feature `fixture-reach`).

use core::ops::Range;

use folio_kernels::SettingError;
use toml::Spanned;

use crate::scene::{Scene, SceneError};
use crate::settings::book_settings;

pub use folio_book::MAX_PAGES;

/// A refusal: the span of the scene key at fault, and why.
pub(crate) type Problem = (Range<usize>, String);

/// The book's refusal `e` at the scene key that set the field (`book.` and its path in
/// [`folio_book::BookSettings`]), or at the effect.
fn problem(scene: &Scene, e: &SettingError) -> Problem {
    if e.path.segments().first() == Some(&"effects") {
        let name = e.path.field();
        let list = scene.effects.as_ref();
        let at = list
            .and_then(|l| l.get_ref().iter().find(|n| n.get_ref() == name))
            .map(Spanned::span)
            .or_else(|| list.map(Spanned::span))
            .unwrap_or(0..0);
        return (at, format!("effect `{name}` must be {}", e.requirement));
    }
    crate::settings::refusal(scene, "book", e)
}

/// Checks a DOG scene's book: the book `folio run` builds is held to [`folio_book::BookSettings::validate`] (the one the C API uses), at the key that set the
/// refused value.
///
/// # Errors
/// A key that is no field of [`folio_book::BookSettings`], or a refused value, at its place.
pub fn check(scene: &Scene) -> Result<(), SceneError> {
    // In `f64` whatever the run's precision, as the book was checked before its keys were
    // its settings' fields: the ranges are the same numbers in both (reading the book in
    // `f32` too would link a second reader of every field into the browser build).
    book_settings::<f64>(scene)?.validate().map_err(|e| {
        let (span, message) = problem(scene, &e);
        scene.error(span, message)
    })
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
            "{DOG}[book]\nquads_across = 6\nprojection_iterations = 2\n\
             [book.params]\ntotal_pages = 40\naspect_ratio = 1.5\n\
             [book.weights]\nglue = 300.0\n[book.solver]\ntolerance = 1e-5\n"
        ))
        .unwrap();
        assert!(scene.notices.is_empty(), "{:?}", scene.notices);
        let s = crate::settings::book_settings::<f32>(&scene).unwrap();
        let defaults = folio_book::BookSettings::<f32>::default();
        assert_eq!((s.params.total_pages, s.params.left_pages), (40, 20));
        assert_eq!(s.params.aspect_ratio, 1.5);
        assert_eq!(s.weights.glue, 300.0_f32);
        assert_eq!(s.weights.pull, defaults.weights.pull);
        assert_eq!((s.quads_across, s.projection_iterations), (6, 2));
        // One key of [book.solver] keeps the book's other solver defaults (not the solver's).
        assert_eq!(s.solver.tolerance, 1e-5);
        assert_eq!(s.solver.merit_slack, defaults.solver.merit_slack);
        assert_eq!(
            s.solver.refinement_tolerance,
            defaults.solver.refinement_tolerance
        );
        // The older spellings still read, each with a notice naming its new key.
        let old = Scene::parse(&format!("{DOG}[book]\npages = 10\nthickness = 0.01\n")).unwrap();
        let p = crate::settings::book_settings::<f64>(&old).unwrap().params;
        assert_eq!(
            (p.total_pages, p.left_pages, p.page_thickness),
            (10, 5, 0.01)
        );
        let said: Vec<_> = old
            .notices
            .iter()
            .map(|n| (n.line, n.message.as_str()))
            .collect();
        assert_eq!(said.len(), 2, "{said:?}");
        assert_eq!(said[0].0, 5);
        assert!(said[0].1.contains("`book.params.total_pages`"), "{said:?}");
        assert!(
            said[1].1.contains("`book.params.page_thickness`"),
            "{said:?}"
        );
    }

    #[test]
    fn a_refused_book_is_reported_at_its_key() {
        let (line, column, message) = refused("[book.params]\npage_width = 1e300\n");
        assert_eq!((line, column), (5, 14), "{message}");
        assert_eq!(
            message,
            "`book.params.page_width` must be at most 1.2e5 page units, not 1e300"
        );
        // An older key is refused where the file wrote it, by its new name.
        let (line, column, message) = refused("[book]\nthickness = -1.0\n");
        assert_eq!((line, column), (5, 13), "{message}");
        assert_eq!(
            message,
            "`book.params.page_thickness` must be finite and > 0, not -1"
        );
        let (line, _, message) = refused("[book.params]\ncover_overhang = -0.5\n");
        assert_eq!(line, 5, "{message}");
        let (line, column, message) = refused("[book.params]\ncover = false\n");
        assert_eq!((line, column), (5, 9), "{message}");
        assert!(message.contains("`cover` effect"), "{message}");
        // A table is placed at its header.
        let (line, column, message) = refused("[book.effects]\nglue = false\n");
        assert_eq!((line, column), (4, 1), "{message}");
        assert!(message.contains("`effects` list"), "{message}");
        let (line, column, message) = refused("[book.params]\nmidline_nodes = 2\n");
        assert_eq!((line, column), (5, 17), "{message}");
        assert!(message.contains("midline"), "{message}");
        let (line, column, message) = refused("[book.weights]\nglue = 2e9\n");
        assert_eq!((line, column), (5, 8), "{message}");
        assert!(
            message.starts_with("`book.weights.glue` must be in ["),
            "{message}"
        );
        // Inside [0, 1e9] but outside the range the book holds (issue 20).
        let (line, column, message) = refused("[weights]\npull = 1e9\n");
        assert_eq!((line, column), (5, 8), "{message}");
        assert!(
            message.starts_with("`book.weights.pull` must be in ["),
            "{message}"
        );
        // A field the file does not set, refused for another's sake: at its section.
        let (line, _, message) = refused("[book]\nquads_across = 60000\n");
        assert_eq!(line, 5, "{message}");
        let (line, column, message) = refused("[book]\ncolour = 1\n");
        assert_eq!((line, column), (5, 1), "{message}");
        assert!(message.contains("unknown field `colour`"), "{message}");
    }
}
