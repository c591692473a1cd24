//! Hard cases of the scene files and the C API (issue 20, "a bad run says so"): what a
//! scene or a C caller may ask for is checked once, in one place, with the key and a
//! short number; a gesture that can never touch the page and a name that leaves the output
//! folder are refused before anything runs. (The `folio` command's own cases, run through
//! the binary, are in `cli/tests/guards.rs`.)

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

use folio_capi::{
    FolioBookHandle, FolioBookSettings, FolioStatus, folio_book_create, folio_book_destroy,
    folio_last_error_message,
};
use folio_scene::scene::{Scene, SceneError};

/// A DOG scene on the page-turn fixture with `extra` appended (line 4 on).
fn dog(extra: &str) -> String {
    format!("name = \"x\"\nmodel = \"dog\"\ninput = {{ fixture = \"page-turn\" }}\n{extra}")
}

/// A DOG scene driven by timed events (a grab at `grab`, a drag over the spine) with
/// `book` as its `[book]` (line 4 on).
fn events(book: &str, grab: &str) -> String {
    format!(
        "name = \"x\"\nmodel = \"dog\"\n[book]\n{book}\n[[input.events]]\nframe = 0\ngrab = {grab}\n\
         [[input.events]]\nframe = 30\ndrag = [-11.0, 1.0, 8.0]\n"
    )
}

fn refused(text: &str) -> SceneError {
    Scene::parse(text).expect_err(text)
}

/// The calling thread's last C API error message.
fn last_error() -> String {
    let mut buf = vec![0 as core::ffi::c_char; 4096];
    let mut needed = 0usize;
    // SAFETY: `buf` holds 4096 bytes and `needed` is a valid reference.
    let status = unsafe { folio_last_error_message(buf.as_mut_ptr(), buf.len(), &mut needed) };
    assert_eq!(status, FolioStatus::Ok);
    let bytes: Vec<u8> = buf[..needed.saturating_sub(1)]
        .iter()
        .map(|&c| c as u8)
        .collect();
    String::from_utf8(bytes).expect("UTF-8")
}

/// `folio_book_create`'s status and message for `s` (an accepted book is destroyed).
fn create(s: &FolioBookSettings) -> (FolioStatus, String) {
    let mut h = FolioBookHandle::default();
    // SAFETY: both pointers are valid references.
    let status = unsafe { folio_book_create(s, &mut h) };
    if status == FolioStatus::Ok {
        assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
        (status, String::new())
    } else {
        assert_eq!(h.id, 0, "a refused create leaves `out` alone");
        (status, last_error())
    }
}

/// A time step of 1e-300 overflows the step's 1/h² terms (every step reported non-finite
/// input, and the run passed): refused at its key, line 5 column 13, with the value short.
#[test]
fn a_time_step_of_1e_minus_300_is_refused_at_its_key() {
    let e = refused(&dog("[solver]\ntime_step = 1e-300\n"));
    assert_eq!((e.line, e.column), (5, 13), "{e}");
    assert!(
        e.message.contains("time_step") && e.message.contains("1e-300"),
        "{e}"
    );
}

/// Subnormal values (4e-320) pass a `> 0` check yet are no time step and no paper: both
/// are refused at their key, and the message prints them in 6 characters, not 320 digits.
#[test]
fn a_subnormal_time_step_or_thickness_is_refused_in_short_notation() {
    for (extra, key, column) in [
        ("[solver]\ntime_step = 4e-320\n", "time_step", 13),
        ("[book]\npage_thickness = 4e-320\n", "page_thickness", 18),
    ] {
        let e = refused(&dog(extra));
        assert_eq!((e.line, e.column), (5, column), "{e}");
        assert!(
            e.message.contains(key) && e.message.contains("4e-320"),
            "{e}"
        );
        assert!(e.message.len() < 150, "{e}");
    }
}

/// A page width of 1e300 with a grab off the page: the grab check formats the page size,
/// which printed 309 digits; the message names the grab's place and stays short.
#[test]
fn a_page_width_of_1e300_is_refused_in_scientific_notation() {
    let e = refused(&events("page_width = 1e300", "[2e300, 1.0]"));
    assert_eq!((e.line, e.column), (7, 8), "{e}");
    assert!(e.message.contains("1e300") && e.message.len() < 120, "{e}");
    let e = refused(&events("page_width = 1e300", "[11.0, 1.0]"));
    assert_eq!((e.line, e.column), (4, 14), "{e}");
    assert!(
        e.message
            .contains("must be at most 1.2e5 page units, not 1e300")
            && e.message.len() < 120,
        "{e}"
    );
}

/// A scene name is a file-name component: `../../escape`, `a/b`, `..` or a backslash
/// would make `folio run` write outside `out/`; each is refused at the name (line 1,
/// column 8).
#[test]
fn a_scene_name_that_leaves_the_output_folder_is_refused_at_the_name() {
    for name in ["../../escape", "a/b", "..", "a\\\\b", "c:x"] {
        let text = dog("").replace("name = \"x\"", &format!("name = \"{name}\""));
        let e = refused(&text);
        assert_eq!((e.line, e.column), (1, 8), "{name}: {e}");
        assert!(e.message.contains("file-name component"), "{name}: {e}");
    }
    assert!(Scene::parse(&dog("").replace("\"x\"", "\"my-turn_2\"")).is_ok());
}

/// Bytes that are not UTF-8 had no place ("stream did not contain valid UTF-8"): the
/// error gives the line, the column and the byte offset of the first bad byte.
#[test]
fn bad_utf8_is_refused_at_its_byte_offset() {
    let mut bytes = b"name = \"x\"\nmodel = \"".to_vec();
    bytes.extend_from_slice(&[0xC3, 0x28]);
    bytes.extend_from_slice(b"\"\n");
    let e = Scene::parse_bytes(&bytes).expect_err("not UTF-8");
    assert_eq!((e.line, e.column), (2, 10), "{e}");
    assert!(e.message.contains("byte 20"), "{e}");
    assert_eq!(bytes[20], 0xC3);
}

/// A book of 100000 pages (750 thick) or of pages 5 thick puts the fixture's camera inside
/// or under the book: its grab missed and the run passed. Refused at the fixture, saying
/// why.
#[test]
fn a_book_too_thick_for_the_fixture_camera_is_refused_with_the_reason() {
    for (book, thick) in [
        ("total_pages = 100000", "750 thick"),
        ("page_thickness = 5.0", "500 thick"),
    ] {
        let e = refused(&dog(&format!("[book]\n{book}\n")));
        assert_eq!((e.line, e.column), (3, 21), "{e}");
        assert!(
            e.message.contains("misses the page") && e.message.contains(thick),
            "{e}"
        );
    }
    // The same books driven by timed events grab by material point and are touched.
    for book in ["total_pages = 100000", "page_thickness = 5.0"] {
        let text = events(book, "[11.0, 8.0]");
        assert!(Scene::parse(&text).is_ok(), "{book}");
    }
}

/// A page 1e-9 wide has grid cells far below the constraint tolerance: no gesture moves
/// it measurably (the run printed "-0.0000" stretch and passed). Refused at its key, with
/// the smallest width that works.
#[test]
fn a_page_too_small_to_touch_is_refused_at_its_key() {
    for text in [
        dog("[book]\npage_width = 1e-9\n"),
        events("page_width = 1e-9", "[0.0, 0.0]"),
    ] {
        let e = refused(&text);
        assert_eq!(e.column, 14, "{e}");
        assert!(
            e.message.contains("too small to touch") && e.message.contains("0.08"),
            "{e}"
        );
    }
}

/// Timed events grab the right block's top page; with `left_pages = total_pages` that
/// block is empty and the run failed mid-way. Refused at `book.left_pages`.
#[test]
fn timed_events_on_an_empty_right_block_are_refused() {
    let e = refused(&events("total_pages = 10\nleft_pages = 10", "[11.0, 8.0]"));
    assert_eq!((e.line, e.column), (5, 14), "{e}");
    assert!(e.message.contains("empty"), "{e}");
}

/// The C API accepted time steps of 1e308 and 4e-320 that scene files refuse. Both now
/// run the same validation: every step a scene refuses, `folio_book_create` refuses by
/// name with the value short; every step a scene accepts, it accepts.
#[test]
fn the_c_api_refuses_every_time_step_a_scene_refuses() {
    for h in [1e308, 4e-320, 1e-300, 1e-7, 0.2, -0.01] {
        let e = refused(&dog(&format!("[solver]\ntime_step = {h:e}\n")));
        assert!(e.message.contains("time_step"), "{h}: {e}");
        let s = FolioBookSettings {
            time_step: h,
            ..FolioBookSettings::default()
        };
        let (status, message) = create(&s);
        assert_eq!(status, FolioStatus::InvalidArgument, "{h:e}");
        assert!(
            message.contains("`time_step` must be in [1e-6, 0.1] seconds") && message.len() < 150,
            "{h:e}: {message}"
        );
    }
    for h in [1e-6, 1.0 / 60.0, 0.1] {
        // A scene's step is at most one frame (frames are 1/60 s each); the C API, which
        // has no frames, takes the book's whole range.
        let scene = Scene::parse(&dog(&format!("[solver]\ntime_step = {h:e}\n")));
        assert_eq!(scene.is_ok(), h <= 1.0 / 60.0, "{h:e}");
        let s = FolioBookSettings {
            time_step: h,
            ..FolioBookSettings::default()
        };
        assert_eq!(create(&s).0, FolioStatus::Ok, "{h:e}");
    }
}

/// A subnormal page thickness, a 1e-9 page and a 1e300 page: the C API refuses each as
/// a scene does, naming the field, with no number longer than a few characters.
#[test]
fn the_c_api_refuses_the_page_sizes_a_scene_refuses() {
    let d = FolioBookSettings::default();
    let cases = [
        (
            "page_thickness = 4e-320",
            FolioBookSettings {
                page_thickness: 4e-320,
                ..d
            },
            "`page_thickness` must be at least 1.2e-5 (1e-6 of the page width",
        ),
        (
            "page_width = 1e-9",
            FolioBookSettings {
                page_width: 1e-9,
                ..d
            },
            "too small to touch",
        ),
        (
            "page_width = 1e300",
            FolioBookSettings {
                page_width: 1e300,
                ..d
            },
            "`page_width` must be at most 1.2e5 page units, not 1e300",
        ),
        (
            "total_pages = 100001",
            FolioBookSettings {
                total_pages: 100_001,
                left_pages: 0,
                ..d
            },
            "`total_pages` must be from 1 to 100000, not 100001",
        ),
    ];
    for (key, s, word) in cases {
        assert!(
            Scene::parse(&dog(&format!("[book]\n{key}\n"))).is_err(),
            "{key}"
        );
        let (status, message) = create(&s);
        assert_eq!(status, FolioStatus::InvalidArgument, "{key}");
        assert!(
            message.contains(word) && message.len() < 200,
            "{key}: {message}"
        );
    }
}

/// A mass-spring scene whose time step (1/60 s, one substep) is within the scene's range
/// but past the explicit integrator's stability limit, $h\,\omega_{max} \le 2$, is refused
/// when the scene is read, at its `substeps` (more substeps are the cure), naming the
/// limit; the stable 1/60 s
/// with the default substeps is accepted.
#[test]
fn a_spring_time_step_past_the_explicit_limit_is_refused() {
    let scene = |solver: &str| {
        format!(
            "name = \"x\"\nmodel = \"mass-spring\"\ninput = {{ fixture = \"page-turn-touch\" }}\n\
             [solver]\n{solver}\n"
        )
    };
    let e = refused(&scene("time_step = 0.016666666666666666\nsubsteps = 1"));
    assert_eq!((e.line, e.column), (6, 12), "{e}");
    assert!(
        e.message.contains("explicit integrator's springs") && e.message.contains("<= 2"),
        "{e}"
    );
    Scene::parse(&scene("time_step = 0.016666666666666666")).expect("the default step");
}
