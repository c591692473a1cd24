//! The recorded inputs a scene can name (the files in `tests/fixtures/`, embedded).

/// What a fixture drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Kind {
    /// Camera rays on the whole book (`folio_book::Script`): DOG scenes.
    Book,
    /// A finger on one page (`folio_pages::TouchScript`): every page model.
    Touch,
}

/// The fixtures: name, kind, text.
const FIXTURES: [(&str, Kind, &str); 5] = [
    (
        "page-turn",
        Kind::Book,
        include_str!("../../tests/fixtures/page_turn.input"),
    ),
    (
        "peek",
        Kind::Book,
        include_str!("../../tests/fixtures/peek.input"),
    ),
    (
        "bookmark-flip",
        Kind::Book,
        include_str!("../../tests/fixtures/bookmark_flip.input"),
    ),
    (
        "page-turn-touch",
        Kind::Touch,
        include_str!("../../tests/fixtures/page_turn.touch"),
    ),
    (
        "seed003-turn",
        Kind::Touch,
        include_str!("../../tests/fixtures/seed003_turn.touch"),
    ),
];

/// Every fixture name.
pub const NAMES: [&str; 5] = [
    FIXTURES[0].0,
    FIXTURES[1].0,
    FIXTURES[2].0,
    FIXTURES[3].0,
    FIXTURES[4].0,
];

/// The kind of fixture `name`, if there is one.
#[must_use]
pub fn kind(name: &str) -> Option<Kind> {
    FIXTURES.iter().find(|f| f.0 == name).map(|f| f.1)
}

/// The text of fixture `name`, if there is one.
#[must_use]
pub fn text(name: &str) -> Option<&'static str> {
    FIXTURES.iter().find(|f| f.0 == name).map(|f| f.2)
}
