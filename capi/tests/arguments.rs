//! Bad arguments: NaN and infinite input, unknown sides, precisions and flags, out-of-range
//! settings; each is refused with a status and a message, and changes nothing.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use folio_capi::*;

/// Settings with one field changed, the status expected and a word the message must hold.
type Case = (&'static str, fn(&mut FolioBookSettings), &'static str);

#[test]
fn out_of_range_settings_are_refused_by_name() {
    let cases: [Case; 22] = [
        (
            "no pages",
            |s| s.total_pages = 0,
            "`total_pages` must be from 1 to 100000, not 0",
        ),
        (
            "left > total",
            |s| s.left_pages = 101,
            "`left_pages` must be at most total_pages, not 101",
        ),
        ("zero width", |s| s.page_width = 0.0, "page_width"),
        ("negative width", |s| s.page_width = -12.0, "page_width"),
        ("NaN width", |s| s.page_width = f64::NAN, "page_width"),
        (
            "infinite width",
            |s| s.page_width = f64::INFINITY,
            "page_width",
        ),
        (
            "huge width",
            |s| s.page_width = 1e300,
            "`page_width` must be at most 1.2e5 page units, not 1e300",
        ),
        (
            "huge height",
            |s| s.aspect_ratio = 1e6,
            "`aspect_ratio` must be such that the page's height",
        ),
        ("NaN aspect", |s| s.aspect_ratio = f64::NAN, "aspect_ratio"),
        (
            "zero thickness",
            |s| s.page_thickness = 0.0,
            "page_thickness",
        ),
        ("zero time step", |s| s.time_step = 0.0, "time_step"),
        ("NaN time step", |s| s.time_step = f64::NAN, "time_step"),
        ("negative time step", |s| s.time_step = -0.1, "time_step"),
        ("one quad across", |s| s.quads_across = 1, "quads_across"),
        ("no quads along", |s| s.quads_along = 0, "quads_along"),
        (
            "too many quads",
            |s| {
                s.quads_across = 300;
                s.quads_along = 300;
            },
            "65536",
        ),
        ("cover 2", |s| s.cover = 2, "`cover`"),
        ("precision 0", |s| s.precision = 0, "`precision`"),
        ("precision 16", |s| s.precision = 16, "`precision`"),
        (
            "unknown effect",
            |s| s.effects |= 1 << 5,
            "`effects` has unknown bits 0x20",
        ),
        (
            "glue without blocks",
            |s| s.effects = FOLIO_EFFECTS_ALL & !FOLIO_EFFECT_BLOCKS,
            "`effects`: glue must be off without blocks",
        ),
        (
            "f32 time step beyond f32",
            |s| {
                s.precision = FOLIO_PRECISION_F32;
                s.time_step = 1e300;
            },
            "time_step",
        ),
    ];
    for (name, change, word) in cases {
        let mut s = FolioBookSettings::default();
        change(&mut s);
        assert_eq!(create_status(&s), FolioStatus::InvalidArgument, "{name}");
        let message = last_error();
        assert!(
            message.starts_with("folio_book_create: ") && message.contains(word),
            "{name}: {message}"
        );
    }
}

#[test]
fn valid_variants_are_accepted() {
    let defaults = FolioBookSettings::default();
    let no_cover = FolioBookSettings {
        cover: 0,
        ..defaults
    };
    let fixed = FolioBookSettings {
        effects: FOLIO_EFFECT_GRAVITY | FOLIO_EFFECT_COLLISIONS,
        ..defaults
    };
    let bare = FolioBookSettings {
        effects: 0,
        ..defaults
    };
    let f32 = settings(FOLIO_PRECISION_F32);
    for s in [no_cover, fixed, bare, f32] {
        assert_eq!(
            create_status(&s),
            FolioStatus::Ok,
            "{s:?}: {}",
            last_error()
        );
    }
    assert_eq!(defaults.precision, FOLIO_PRECISION_F64);
    assert_eq!(defaults.effects, FOLIO_EFFECTS_ALL);
    assert_eq!((defaults.total_pages, defaults.left_pages), (100, 50));
}

#[test]
fn bad_grabs_are_refused_and_change_nothing() {
    let h = create(&FolioBookSettings {
        left_pages: 0,
        ..FolioBookSettings::default()
    });
    let cases = [
        (7, 6.0, 6.0, 1, FolioStatus::InvalidArgument, "side"),
        (
            FOLIO_SIDE_NONE,
            6.0,
            6.0,
            1,
            FolioStatus::InvalidArgument,
            "side",
        ),
        (
            FOLIO_SIDE_RIGHT,
            f64::NAN,
            6.0,
            1,
            FolioStatus::InvalidArgument,
            "not finite",
        ),
        (
            FOLIO_SIDE_RIGHT,
            6.0,
            f64::NEG_INFINITY,
            1,
            FolioStatus::InvalidArgument,
            "not finite",
        ),
        (
            FOLIO_SIDE_RIGHT,
            6.0,
            6.0,
            0,
            FolioStatus::InvalidArgument,
            "pages",
        ),
        (
            FOLIO_SIDE_RIGHT,
            6.0,
            6.0,
            101,
            FolioStatus::NotEnoughPages,
            "the right block holds 100 pages, 101 asked for",
        ),
        (
            FOLIO_SIDE_LEFT,
            6.0,
            6.0,
            1,
            FolioStatus::NotEnoughPages,
            "the left block holds 0 pages, 1 asked for",
        ),
    ];
    for (side, u, v, pages, status, word) in cases {
        assert_eq!(
            folio_book_grab(h, side, u, v, pages),
            status,
            "{side} {u} {v} {pages}"
        );
        let message = last_error();
        assert!(message.contains(word), "{message}");
        let r = step(h);
        assert_eq!(
            (r.phase, r.pages_active),
            (FolioPhase::AtRest, 0),
            "nothing grabbed"
        );
    }
    // A whole block as a stack is fine.
    assert_eq!(
        folio_book_grab(h, FOLIO_SIDE_RIGHT, 11.0, 3.0, 100),
        FolioStatus::Ok
    );
    assert_eq!(step(h).pages_active, 100);
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}

#[test]
fn nan_drags_are_refused_and_keep_the_target() {
    for precision in [FOLIO_PRECISION_F64, FOLIO_PRECISION_F32] {
        let s = settings(precision);
        let [a, b] = [create(&s), create(&s)];
        assert_eq!(folio_book_drag(a, 1.0, 2.0, 3.0), FolioStatus::NotHeld);
        assert_eq!(folio_book_release(a), FolioStatus::NotHeld);
        assert_eq!(last_error(), "folio_book_release: no page is held");
        for h in [a, b] {
            assert_eq!(
                folio_book_grab(h, FOLIO_SIDE_RIGHT, 11.0, 4.0, 1),
                FolioStatus::Ok
            );
            assert_eq!(folio_book_drag(h, 8.0, 3.0, 4.0), FolioStatus::Ok);
        }
        // Book `a` also gets refused drags; it must end exactly where `b` does.
        let bad = [
            [f64::NAN, 0.0, 0.0],
            [0.0, f64::INFINITY, 0.0],
            [0.0, 0.0, f64::NEG_INFINITY],
        ];
        for p in bad {
            assert_eq!(
                folio_book_drag(a, p[0], p[1], p[2]),
                FolioStatus::InvalidArgument
            );
            assert!(last_error().starts_with("folio_book_drag: drag target (x, y, z) = ("));
        }
        if precision == FOLIO_PRECISION_F32 {
            // Finite in f64, infinite in f32: the book refuses it.
            assert_eq!(
                folio_book_drag(a, 1e300, 0.0, 0.0),
                FolioStatus::InvalidArgument
            );
        }
        for _ in 0..10 {
            assert_eq!(step(a), step(b));
        }
        assert_eq!(held_position(a), held_position(b));
        for h in [a, b] {
            assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
        }
    }
}
