//! The book a DOG scene describes (`[book]`, `[weights]`, `[solver]`, `effects`): checked
//! by the book's own [`BookSettings::validate`] (the one the C API uses), each refusal
//! reported at the scene key that set it. Whether the scene's first grab can touch the page
//! is `crate::reach` (feature `fixture-reach`).

use core::ops::Range;

use folio_book::BookSettings;
use folio_kernels::{SettingError, Shown};
use toml::Spanned;

use crate::scene::Scene;
use crate::settings::book_settings;

pub use folio_book::MAX_PAGES;

/// A refusal: the span of the scene key at fault, and why.
pub(crate) type Problem = (Range<usize>, String);

/// The fields of [`BookSettings`] a scene sets under another key (`[book]` is the field
/// `params`; `[solver]` also holds the book's own iteration counts and its grid).
const SCENE_KEYS: [(&str, &str); 5] = [
    ("solver.tolerance", "solver.newton_tolerance"),
    ("quads_across", "solver.grid"),
    ("quads_along", "solver.grid"),
    ("collision_rounds", "solver.collision_rounds"),
    ("max_corrections", "solver.max_corrections"),
];

/// The scene keys of [`folio_book::BookParams`] that older scene files spell differently
/// (serde aliases), or whose value another key sets (the page height is
/// `aspect_ratio` x `page_width`), so that an error finds the key the file wrote.
const OTHER_SPELLINGS: [(&str, &str); 3] = [
    ("book.total_pages", "book.pages"),
    ("book.page_thickness", "book.thickness"),
    ("book.aspect_ratio", "book.page_width"),
];

/// The scene key of the field at `e`'s path in [`BookSettings`].
fn scene_key(e: &SettingError) -> String {
    let path = e.path.to_string();
    if let Some((_, key)) = SCENE_KEYS.iter().find(|(field, _)| *field == path) {
        (*key).to_string()
    } else if let Some(field) = path.strip_prefix("params.") {
        format!("book.{field}")
    } else {
        path
    }
}

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

/// The book's refusal `e` at the scene key that set the field, in the scene's words.
fn problem(scene: &Scene, e: &SettingError) -> Problem {
    let not = e
        .value
        .map(|v| format!(", not {}", Shown(v)))
        .unwrap_or_default();
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
    let key = scene_key(e);
    let message = format!("{key} must be {}{not}", e.requirement);
    (span(scene, &key), message)
}

/// Checks a DOG scene's book: `cover` is an effect, then the book `folio run` builds is
/// held to [`BookSettings::validate`] (the one the C API uses), at the key that set the
/// refused value.
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
    settings.validate().map_err(|e| problem(scene, &e))
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
        assert_eq!(
            message,
            "book.page_width must be at most 1.2e5 page units, not 1e300"
        );
        let (line, column, message) = refused("[book]\nthickness = -1.0\n");
        assert_eq!((line, column), (5, 13), "{message}");
        assert_eq!(
            message,
            "book.page_thickness must be finite and > 0, not -1"
        );
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
