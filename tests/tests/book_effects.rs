//! Effect selection (issue 6): an effect the book is not asked to simulate contributes no
//! term, no KKT row and no work. Each effect is switched off alone and the book compared
//! with the full one: its term family is empty, every other family is unchanged, and the
//! step reports show the rows and the work gone. A book at rest simulates only its blocks.

use folio_book::{
    Book, BookError, BookSettings, BookStepReport, BookmarkOutcome, Effects, Family, GrabOutcome,
    Phase, Script,
};
use folio_geometry::BlockSide;

const PAGE_TURN: &str = include_str!("../fixtures/page_turn.input");
const BOOKMARK_FLIP: &str = include_str!("../fixtures/bookmark_flip.input");

const FAMILIES: [Family; 12] = [
    Family::Gravity,
    Family::Glue,
    Family::Contacts,
    Family::BlockBending,
    Family::BlockLinks,
    Family::BindingFix,
    Family::Dog,
    Family::Binding,
    Family::PageBending,
    Family::PageIso,
    Family::Pull,
    Family::Pad,
];

/// The default book with `effects`.
fn book(effects: Effects) -> Book<f64> {
    let settings = BookSettings {
        effects,
        ..BookSettings::default()
    };
    Book::new(settings).expect("book")
}

/// Every effect but the one `off` switches off.
fn all_but(off: fn(&mut Effects)) -> Effects {
    let mut e = Effects::ALL;
    off(&mut e);
    e
}

/// What a run of a fixture did, summed over its steps.
#[derive(Debug, Default)]
struct Work {
    steps: usize,
    /// Largest KKT size of a step: unknowns, rows, potential terms.
    max_dofs: usize,
    max_rows: usize,
    max_potentials: usize,
    /// Unknowns of the steps at rest (before the grab).
    rest_dofs: usize,
    contact_tests: usize,
    snapshots: usize,
    bookmarks_started: usize,
    bookmarks_disabled: usize,
    nonfinite_frames: usize,
}

fn play(book: &mut Book<f64>, text: &str, frames: u32) -> Work {
    let script = Script::parse(text).expect("fixture parses");
    let mut w = Work::default();
    for frame in 0..frames.min(script.frames) {
        for e in script.events_at(frame) {
            let outcome = book
                .apply(script.camera, script.forward, e.action)
                .expect("fixture input is valid");
            match outcome {
                folio_book::InputOutcome::Bookmark(BookmarkOutcome::Started) => {
                    w.bookmarks_started += 1;
                }
                folio_book::InputOutcome::Bookmark(BookmarkOutcome::Disabled) => {
                    w.bookmarks_disabled += 1;
                }
                _ => {}
            }
        }
        let phase = book.phase();
        let r = book.step().expect("step");
        w.steps += 1;
        w.max_dofs = w.max_dofs.max(r.dofs);
        w.max_rows = w.max_rows.max(r.constraint_rows);
        w.max_potentials = w.max_potentials.max(r.census.potentials);
        if phase == Phase::AtRest {
            w.rest_dofs = w.rest_dofs.max(r.dofs);
        }
        w.contact_tests += r.contacts.tested;
        w.snapshots += usize::from(r.snapshot);
        if !book.state().x.iter().all(|p| p.is_finite()) {
            w.nonfinite_frames += 1;
        }
    }
    w
}

/// Frames of the page turn that cover the grab, the drag and the release.
const FRAMES: u32 = 300;

#[test]
fn every_effect_is_on_by_default() {
    assert_eq!(BookSettings::<f64>::default().effects, Effects::ALL);
    assert_eq!(
        Effects::ALL.names().collect::<Vec<_>>(),
        ["gravity", "glue", "collisions", "blocks", "bookmarking"]
    );
    assert_eq!(Effects::NONE.names().count(), 0);
    let mut e = Effects::NONE;
    assert!(e.enable("glue") && e.glue);
    assert!(!e.enable("tearing"));
}

/// Each effect off alone: exactly its families are empty, every other family keeps its
/// size, and the KKT system loses the rows and unknowns it brought.
#[test]
fn an_effect_that_is_off_contributes_no_term() {
    let full = book(Effects::ALL);
    type Switch = fn(&mut Effects);
    let cases: [(&str, Switch, &[Family]); 4] = [
        ("gravity", |e| e.gravity = false, &[Family::Gravity]),
        ("glue", |e| e.glue = false, &[Family::Glue]),
        ("collisions", |e| e.collisions = false, &[Family::Contacts]),
        (
            "blocks",
            |e| (e.blocks, e.glue) = (false, false),
            &[
                Family::Glue,
                Family::BlockBending,
                Family::BlockLinks,
                Family::BindingFix,
            ],
        ),
    ];
    for (name, off, gone) in cases {
        let reduced = book(all_but(off));
        for family in FAMILIES {
            let (with, without) = (full.terms().count(family), reduced.terms().count(family));
            if gone.contains(&family) {
                assert!(with > 0, "{name}: the full book has {family:?} terms");
                assert_eq!(without, 0, "{name} off: no {family:?} term");
            } else if name == "blocks" && matches!(family, Family::Gravity | Family::Contacts) {
                // Only the blocks' share goes: the page keeps its gravity and contacts.
                let page = full.nodes().grid.len();
                assert_eq!(without, page, "{name} off: {family:?} on page nodes only");
            } else {
                assert_eq!(with, without, "{name} off: {family:?} unchanged");
            }
        }
    }
}

/// The step reports of a book with `effects` at rest and with a grabbed page.
fn reports(effects: Effects) -> [BookStepReport<f64>; 2] {
    let mut b = book(effects);
    let rest = b.step().expect("step");
    let grab = b.grab_at(BlockSide::Right, [4.0, 5.0], 1).expect("grab");
    assert!(matches!(grab, GrabOutcome::Grabbed { .. }), "{grab:?}");
    [rest, b.step().expect("step")]
}

/// The KKT size and the terms of each step, with each effect off: the rows, unknowns and
/// potentials it brought are gone, nothing else.
#[test]
fn the_step_reports_show_each_effect_gone() {
    let [full_rest, full] = reports(Effects::ALL);
    let n = book(Effects::ALL).nodes();
    let (blocks, page) = (n.page_offset(), n.grid.len());
    let size = |r: &BookStepReport<f64>| (r.dofs, r.constraint_rows, r.census.potentials);

    let [rest, held] = reports(all_but(|e| e.gravity = false));
    assert_eq!(
        size(&rest),
        (
            full_rest.dofs,
            full_rest.constraint_rows,
            full_rest.census.potentials - blocks
        )
    );
    assert_eq!(
        size(&held),
        (
            full.dofs,
            full.constraint_rows,
            full.census.potentials - blocks - page
        )
    );

    let [rest, held] = reports(all_but(|e| e.glue = false));
    assert_eq!(rest.census.potentials + 1, full_rest.census.potentials);
    assert_eq!(
        size(&held),
        (full.dofs, full.constraint_rows, full.census.potentials - 1)
    );

    let [rest, held] = reports(all_but(|e| e.collisions = false));
    assert_eq!(rest.census.potentials + blocks, full_rest.census.potentials);
    assert_eq!(
        size(&held),
        (
            full.dofs,
            full.constraint_rows,
            full.census.potentials - blocks - page
        )
    );
    assert_eq!(
        rest.contacts.tested + held.contacts.tested,
        0,
        "no collision test"
    );
    assert!(full_rest.contacts.tested > 0 && full.contacts.tested > 0);

    let [rest, held] = reports(all_but(|e| (e.blocks, e.glue) = (false, false)));
    assert_eq!(
        size(&rest),
        (0, 0, 0),
        "fixed blocks at rest: nothing to simulate"
    );
    assert_eq!(
        held.dofs,
        full.dofs - 2 * blocks,
        "every block node eliminated"
    );
    assert_eq!(
        held.constraint_rows,
        full.constraint_rows - full_rest.constraint_rows
    );
    let block_terms = full_rest.census.potentials - 2 * blocks; // bending and glue
    assert_eq!(
        held.census.potentials,
        full.census.potentials - full_rest.census.potentials
    );
    assert!(block_terms > 0);

    let [rest, held] = reports(all_but(|e| e.bookmarking = false));
    assert_eq!(size(&rest), size(&full_rest));
    assert_eq!(size(&held), size(&full));
}

/// The page turn with each effect off: every frame finite, no collision test without
/// collisions and no snapshot without bookmarking. (Without gravity the glue stands the
/// blocks up and the fixture's grab misses them; it still runs.)
#[test]
fn the_page_turn_without_each_effect() {
    let full = play(&mut book(Effects::ALL), PAGE_TURN, FRAMES);
    eprintln!("all effects: {full:?}");
    assert_eq!(full.nonfinite_frames, 0);
    assert!(full.contact_tests > 0 && full.snapshots > 0);
    type Switch = fn(&mut Effects);
    let cases: [(&str, Switch); 5] = [
        ("gravity", |e| e.gravity = false),
        ("glue", |e| e.glue = false),
        ("collisions", |e| e.collisions = false),
        ("blocks", |e| (e.blocks, e.glue) = (false, false)),
        ("bookmarking", |e| e.bookmarking = false),
    ];
    for (name, off) in cases {
        let w = play(&mut book(all_but(off)), PAGE_TURN, FRAMES);
        eprintln!("no {name}: {w:?}");
        assert_eq!(w.nonfinite_frames, 0, "{name} off");
        if name == "collisions" {
            assert_eq!(w.contact_tests, 0, "no collision test ran");
        }
        if name == "bookmarking" {
            assert_eq!(w.snapshots, 0, "no history snapshot");
        }
        if name == "blocks" {
            assert_eq!(w.rest_dofs, 0);
        }
    }
}

/// A book at rest simulates only its blocks; with fixed blocks it simulates nothing and its
/// nodes never move.
#[test]
fn a_book_at_rest_simulates_only_its_blocks() {
    let mut full = book(Effects::ALL);
    let r = full.step().expect("step");
    let n = full.nodes();
    // Two midlines and the two cover ends, X and Y each.
    assert_eq!(r.dofs, 2 * n.page_offset());
    let page_terms = [
        Family::Dog,
        Family::Binding,
        Family::PageBending,
        Family::PageIso,
        Family::Pull,
    ];
    assert!(page_terms.iter().all(|&f| full.terms().count(f) > 0));
    let block_potentials = full.terms().count(Family::BlockBending)
        + full.terms().count(Family::Glue)
        + 2 * n.page_offset(); // gravity and a contact spring per block node
    assert_eq!(r.census.potentials, block_potentials);
    assert_eq!(
        r.census.constraints,
        full.terms().count(Family::BlockLinks) + full.terms().count(Family::BindingFix)
    );

    let mut fixed = book(all_but(|e| (e.blocks, e.glue) = (false, false)));
    let before = fixed.state().x.clone();
    for _ in 0..10 {
        let r = fixed.step().expect("step");
        assert_eq!((r.dofs, r.constraint_rows, r.census.potentials), (0, 0, 0));
        assert_eq!(r.contacts.tested, 0);
    }
    assert_eq!(fixed.state().x, before);
}

/// The hard cover is part of the geometry: without it the two cover nodes, their links and
/// their unknowns are gone.
#[test]
fn a_paperback_has_no_cover_terms() {
    let mut settings = BookSettings::<f64>::default();
    let mut hard = Book::new(settings).expect("book");
    settings.params.cover = false;
    let mut soft = Book::new(settings).expect("book");
    let (h, s) = (hard.step().expect("step"), soft.step().expect("step"));
    assert_eq!(h.dofs, s.dofs + 4, "two cover nodes, X and Y");
    assert_eq!(h.constraint_rows, s.constraint_rows + 2, "two board links");
    assert_eq!(
        hard.terms().count(Family::BlockLinks),
        soft.terms().count(Family::BlockLinks) + 2
    );
}

/// Finger-bookmarking off: the bookmark inputs of the fixture are answered `Disabled` and
/// change nothing; on, they start flights.
#[test]
fn bookmarking_off_refuses_bookmarks() {
    let on = play(&mut book(Effects::ALL), BOOKMARK_FLIP, u32::MAX);
    assert!(on.bookmarks_started > 0 && on.bookmarks_disabled == 0);
    let mut b = book(all_but(|e| e.bookmarking = false));
    let off = play(&mut b, BOOKMARK_FLIP, u32::MAX);
    assert_eq!(off.bookmarks_started, 0);
    assert_eq!(off.bookmarks_disabled, on.bookmarks_started);
    assert_eq!(off.snapshots, 0);
    assert_eq!(off.nonfinite_frames, 0);
    assert!(b.flips().is_empty());
}

#[test]
fn glue_needs_the_blocks() {
    let settings = BookSettings::<f64> {
        effects: all_but(|e| e.blocks = false),
        ..BookSettings::default()
    };
    assert!(matches!(
        Book::new(settings),
        Err(BookError::InvalidSetting(e)) if e.path.is("effects.glue")
    ));
}
