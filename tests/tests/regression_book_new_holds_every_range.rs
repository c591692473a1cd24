//! Regression (issue 41): `Book::new` accepted a step of 1e-300 s, 100,001 pages, a page
//! 1e-9 wide, paper 4e-320 thick and 51 projection iterations, which scene files and the C
//! API refused: those ranges lived in the scene crate, and a library caller met them only
//! as non-finite steps. The book's own `BookSettings::validate` now holds every range, and
//! the three ways in (the library, a scene file, the C API) refuse the same settings at the
//! same field.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

use folio_book::{Book, BookError, BookSettings};
use folio_capi::{FolioBookHandle, FolioBookSettings, FolioStatus, folio_book_create};
use folio_scene::scene::Scene;

/// One setting set out of range three ways: on the book's settings, as a scene line, and
/// on the C API's settings (where it has the field).
struct Case {
    /// The field's path in `BookSettings`.
    path: &'static str,
    set: fn(&mut BookSettings<f64>),
    /// `[section]\nkey = value` for a scene file (the section is `[book]` or its table
    /// holding the field).
    scene: &'static str,
    /// The C field set the same way, if the C API has it.
    c: Option<fn(&mut FolioBookSettings)>,
}

const CASES: [Case; 8] = [
    Case {
        path: "pad_radius",
        set: |s| s.pad_radius = 7.0,
        scene: "[book]\npad_radius = 7.0",
        c: None,
    },
    Case {
        path: "pad_radius",
        set: |s| s.pad_radius = f64::NAN,
        scene: "[book]\npad_radius = nan",
        c: None,
    },
    Case {
        path: "solver.time_step",
        set: |s| s.solver.time_step = 1e-300,
        scene: "[book.solver]\ntime_step = 1e-300",
        c: Some(|s| s.time_step = 1e-300),
    },
    Case {
        path: "params.total_pages",
        set: |s| s.params.total_pages = 100_001,
        scene: "[book.params]\ntotal_pages = 100001",
        c: Some(|s| s.total_pages = 100_001),
    },
    Case {
        path: "params.page_width",
        set: |s| s.params.page_width = 1e-9,
        scene: "[book.params]\npage_width = 1e-9",
        c: Some(|s| s.page_width = 1e-9),
    },
    Case {
        path: "params.page_thickness",
        set: |s| s.params.page_thickness = 4e-320,
        scene: "[book.params]\npage_thickness = 4e-320",
        c: Some(|s| s.page_thickness = 4e-320),
    },
    Case {
        path: "projection_iterations",
        set: |s| s.projection_iterations = 51,
        scene: "[book]\nprojection_iterations = 51",
        c: None,
    },
    Case {
        path: "weights.pull",
        set: |s| s.weights.pull = 1e9,
        scene: "[book.weights]\npull = 1e9",
        c: None,
    },
];

#[test]
fn the_library_the_scene_and_the_c_api_refuse_the_same_settings() {
    for case in CASES {
        let mut settings = BookSettings::<f64>::default();
        (case.set)(&mut settings);
        match Book::new(settings) {
            Err(BookError::InvalidSetting(e)) => assert!(e.path.is(case.path), "{e}"),
            other => panic!("{}: {:?}", case.path, other.map(|_| ())),
        }
        let text = format!(
            "name = \"x\"\nmodel = \"dog\"\ninput = {{ fixture = \"page-turn\" }}\n{}\n",
            case.scene
        );
        // The scene key is the field's path under `[book]`.
        let e = Scene::parse(&text).expect_err(case.scene);
        assert_eq!(e.line, 5, "{}: {e}", case.path);
        let key = format!("`book.{}`", case.path);
        assert!(e.message.contains(&key), "{}: {e}", case.path);
        if let Some(set) = case.c {
            let mut c = FolioBookSettings::default();
            set(&mut c);
            let mut handle = FolioBookHandle::default();
            // SAFETY: both pointers are valid references.
            let status = unsafe { folio_book_create(&c, &mut handle) };
            assert_eq!(status, FolioStatus::InvalidArgument, "{}", case.path);
        }
    }
}

#[test]
fn the_defaults_pass_everywhere() {
    assert_eq!(BookSettings::<f64>::default().validate(), Ok(()));
    assert_eq!(BookSettings::<f32>::default().validate(), Ok(()));
    assert_eq!(BookSettings::<f32>::microcontroller().validate(), Ok(()));
}
