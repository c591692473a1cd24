//! Fuzz target `scene`: the scene parser and its validation ([`Scene::parse`]) on arbitrary
//! text. The seed corpus holds the built-in scenes and a TOML dictionary
//! (`fuzz/scene.dict`) names the keys, so mutations reach the validation of every section.
//! Bytes that are not UTF-8 are read with replacement characters: the byte-level check
//! (the byte offset of bad UTF-8) is the caller's. Asserts: no panic, and every error has
//! a place (a line and a column, both 1-based and within the text).

use folio_scene::scene::Scene;

/// Parses `data` as a scene.
///
/// # Panics
/// When the parser panics or an error has no place in the text.
pub fn run(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Err(e) = Scene::parse(&text) {
        let lines = text.split('\n').count();
        assert!(
            (1..=lines).contains(&e.line) && e.column >= 1,
            "an error without a place: {e:?}"
        );
    }
}
