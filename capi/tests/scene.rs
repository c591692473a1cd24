//! `folio_book_create_from_scene`: the repository's scenes build books; bad text, another
//! model and NULL arguments are refused with a place in the file.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use core::ffi::c_char;
use core::ptr;
use folio_capi::*;

/// `folio_book_create_from_scene` on `text` (NUL appended); the handle on success.
fn from_scene(text: &[u8]) -> Result<FolioBookHandle, FolioStatus> {
    let mut bytes = text.to_vec();
    bytes.push(0);
    let mut h = FolioBookHandle::default();
    // SAFETY: `bytes` is NUL-terminated; `h` is valid for a write.
    let status = unsafe { folio_book_create_from_scene(bytes.as_ptr().cast::<c_char>(), &mut h) };
    if status == FolioStatus::Ok {
        Ok(h)
    } else {
        assert_eq!(h.id, 0, "a failed create leaves `out` alone");
        Err(status)
    }
}

#[test]
fn repository_scenes_build_their_books() {
    for (text, cover, pages) in [
        (include_str!("../../scenes/page-turn.toml"), true, [50, 50]),
        (
            include_str!("../../scenes/paperback.toml"),
            false,
            [120, 120],
        ),
        (include_str!("../../scenes/stack.toml"), true, [0, 80]),
    ] {
        let h = from_scene(text.as_bytes()).unwrap_or_else(|s| panic!("{s:?}: {}", last_error()));
        let r = step(h);
        assert_eq!([r.pages_left, r.pages_right], pages);
        // The same mesh as the book of the same settings (cover boards only with `cover`).
        let (mut v, mut t) = (0u32, 0u32);
        // SAFETY: valid out-pointers.
        assert_eq!(
            unsafe { folio_book_mesh_size(h, &mut v, &mut t) },
            FolioStatus::Ok
        );
        let direct = create(&FolioBookSettings {
            total_pages: pages[0] + pages[1],
            left_pages: pages[0],
            cover: u32::from(cover),
            ..FolioBookSettings::default()
        });
        let (mut v2, mut t2) = (0u32, 0u32);
        // SAFETY: valid out-pointers.
        assert_eq!(
            unsafe { folio_book_mesh_size(direct, &mut v2, &mut t2) },
            FolioStatus::Ok
        );
        assert_eq!((v, t), (v2, t2), "same book as the same settings");
        for b in [h, direct] {
            assert_eq!(folio_book_destroy(b), FolioStatus::Ok);
        }
    }
}

#[test]
fn bad_scenes_are_refused_with_their_place() {
    const HEAD: &str = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
    let cone: &[u8] = include_bytes!("../../scenes/cone-turn.toml");
    let cases: [(Vec<u8>, &str); 5] = [
        (
            format!("{HEAD}frames = -3\n").into_bytes(),
            "line 4, column",
        ),
        (
            b"name = \"x\"\nmodel = \"dog\"\nmodle = 3\n".to_vec(),
            "line 3, column 1",
        ),
        (cone.to_vec(), "DOG book"),
        (format!("{HEAD}[book]\npages = 0\n").into_bytes(), "line 5"),
        (
            b"name = \"\xff\"\n".to_vec(),
            "line 1, column 9: the file is not UTF-8: byte 8",
        ),
    ];
    for (text, word) in cases {
        assert_eq!(
            from_scene(&text),
            Err(FolioStatus::InvalidScene),
            "{text:?}"
        );
        let message = last_error();
        assert!(
            message.starts_with("folio_book_create_from_scene: ") && message.contains(word),
            "{message}"
        );
    }
}

#[test]
fn null_scene_arguments_are_refused() {
    let text = c"name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
    let mut h = FolioBookHandle::default();
    // SAFETY: NULL arguments are refused before any read or write.
    unsafe {
        assert_eq!(
            folio_book_create_from_scene(ptr::null(), &mut h),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_create_from_scene(text.as_ptr(), ptr::null_mut()),
            FolioStatus::NullPointer
        );
    }
    assert_eq!(h.id, 0);
    let h = from_scene(text.to_bytes()).unwrap();
    assert_eq!(step(h).pages_left, 50);
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}
