//! Caller buffers: the mesh size query and copy, the page's nodes, the last-error message;
//! NULL and too-small buffers (the sizes needed come back), nothing written on failure.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use core::ffi::c_char;
use core::ptr;
use folio_book::{Book, BookSettings};
use folio_capi::*;
use folio_geometry::mesh::TriMesh;

/// Sentinel for "not written".
const UNTOUCHED: f32 = -12345.0;

fn mesh_size(h: FolioBookHandle) -> (usize, usize) {
    let (mut v, mut t) = (0u32, 0u32);
    // SAFETY: valid out-pointers.
    let status = unsafe { folio_book_mesh_size(h, &mut v, &mut t) };
    assert_eq!(status, FolioStatus::Ok, "{}", last_error());
    (v as usize, t as usize)
}

/// Mesh buffers of the given lengths, filled with sentinels.
struct Buffers {
    positions: Vec<f32>,
    normals: Vec<f32>,
    uvs: Vec<f32>,
    indices: Vec<u32>,
}

impl Buffers {
    fn new(lens: [usize; 4]) -> Self {
        Self {
            positions: vec![UNTOUCHED; lens[0]],
            normals: vec![UNTOUCHED; lens[1]],
            uvs: vec![UNTOUCHED; lens[2]],
            indices: vec![u32::MAX; lens[3]],
        }
    }

    fn copy(&mut self, h: FolioBookHandle) -> FolioStatus {
        // SAFETY: each pointer is valid for its length.
        unsafe {
            folio_book_mesh_copy(
                h,
                self.positions.as_mut_ptr(),
                self.positions.len(),
                self.normals.as_mut_ptr(),
                self.normals.len(),
                self.uvs.as_mut_ptr(),
                self.uvs.len(),
                self.indices.as_mut_ptr(),
                self.indices.len(),
            )
        }
    }

    fn untouched(&self) -> bool {
        self.positions.iter().all(|&x| x == UNTOUCHED)
            && self.normals.iter().all(|&x| x == UNTOUCHED)
            && self.uvs.iter().all(|&x| x == UNTOUCHED)
            && self.indices.iter().all(|&i| i == u32::MAX)
    }
}

#[test]
fn mesh_copy_matches_the_book_and_reports_short_buffers() {
    let h = create(&FolioBookSettings::default());
    assert_eq!(
        folio_book_grab(h, FOLIO_SIDE_RIGHT, 11.0, 5.0, 1),
        FolioStatus::Ok
    );
    let (v, t) = mesh_size(h);
    let exact = [3 * v, 3 * v, 2 * v, 3 * t];

    // The same book built and grabbed directly gives the same mesh.
    let mut book = Book::<f64>::new(BookSettings::default()).unwrap();
    book.grab_at(folio_geometry::BlockSide::Right, [11.0, 5.0], 1)
        .unwrap();
    let mut direct = TriMesh::new();
    book.mesh(&mut direct).unwrap();
    assert_eq!((v, t), (direct.vertex_count(), direct.triangle_count()));

    let mut b = Buffers::new(exact);
    assert_eq!(b.copy(h), FolioStatus::Ok, "{}", last_error());
    assert_eq!(b.positions, direct.positions.as_flattened());
    assert_eq!(b.normals, direct.normals.as_flattened());
    assert_eq!(b.uvs, direct.uvs.as_flattened());
    assert_eq!(b.indices, direct.triangles.as_flattened());

    // Each buffer one element short: BUFFER_TOO_SMALL naming it and the length needed,
    // and no buffer written.
    let names = ["positions", "normals", "uvs", "indices"];
    for k in 0..4 {
        let mut lens = exact;
        lens[k] -= 1;
        let mut b = Buffers::new(lens);
        assert_eq!(b.copy(h), FolioStatus::BufferTooSmall, "{}", names[k]);
        let message = last_error();
        assert!(
            message.contains(&format!("`{}` holds {}", names[k], lens[k]))
                && message.contains(&format!("{} needed", exact[k])),
            "{message}"
        );
        assert!(b.untouched(), "nothing written when {} is short", names[k]);
    }

    // Longer buffers are filled at their start.
    let mut b = Buffers::new(exact.map(|n| n + 5));
    assert_eq!(b.copy(h), FolioStatus::Ok);
    assert_eq!(&b.positions[..exact[0]], direct.positions.as_flattened());
    assert!(b.positions[exact[0]..].iter().all(|&x| x == UNTOUCHED));

    // NULL with length 0 skips a buffer; NULL with a length is refused.
    let mut positions = vec![0.0f32; exact[0]];
    // SAFETY: `positions` is valid for its length; the others are NULL.
    let status = unsafe {
        folio_book_mesh_copy(
            h,
            positions.as_mut_ptr(),
            positions.len(),
            ptr::null_mut(),
            0,
            ptr::null_mut(),
            0,
            ptr::null_mut(),
            0,
        )
    };
    assert_eq!(status, FolioStatus::Ok);
    assert_eq!(positions, direct.positions.as_flattened());
    // SAFETY: NULL with a nonzero length must be refused before any write.
    let status = unsafe {
        folio_book_mesh_copy(
            h,
            ptr::null_mut(),
            exact[0],
            ptr::null_mut(),
            0,
            ptr::null_mut(),
            0,
            ptr::null_mut(),
            0,
        )
    };
    assert_eq!(status, FolioStatus::NullPointer);
    assert!(last_error().contains("`positions` is NULL"));

    // After a step the mesh follows the book.
    let _ = step(h);
    book.step().unwrap();
    direct.clear();
    book.mesh(&mut direct).unwrap();
    let mut b = Buffers::new(exact);
    assert_eq!(b.copy(h), FolioStatus::Ok);
    assert_eq!(b.positions, direct.positions.as_flattened());
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}

#[test]
fn page_positions_need_a_page_and_room() {
    let h = create(&FolioBookSettings::default());
    let (mut columns, mut rows) = (0u32, 0u32);
    // SAFETY: valid out-pointers.
    assert_eq!(
        unsafe { folio_book_page_grid(h, &mut columns, &mut rows) },
        FolioStatus::Ok
    );
    assert_eq!((columns, rows), (9, 12));
    let n = 3 * (columns * rows) as usize;
    let mut xyz = vec![f64::NAN; n];
    // SAFETY: `xyz` is valid for `n` doubles.
    let at_rest = unsafe { folio_book_page_positions(h, xyz.as_mut_ptr(), n) };
    assert_eq!(at_rest, FolioStatus::NoActivePage);

    assert_eq!(
        folio_book_grab(h, FOLIO_SIDE_RIGHT, 11.0, 5.0, 1),
        FolioStatus::Ok
    );
    // SAFETY: as above; the short length is refused before any write.
    let short = unsafe { folio_book_page_positions(h, xyz.as_mut_ptr(), n - 1) };
    assert_eq!(short, FolioStatus::BufferTooSmall);
    assert!(last_error().contains(&format!("{n} needed")));
    assert!(xyz.iter().all(|x| x.is_nan()));
    // SAFETY: NULL is refused even with length 0 (this buffer is not optional).
    let null = unsafe { folio_book_page_positions(h, ptr::null_mut(), 0) };
    assert_eq!(null, FolioStatus::NullPointer);
    // SAFETY: as above.
    let ok = unsafe { folio_book_page_positions(h, xyz.as_mut_ptr(), n) };
    assert_eq!(ok, FolioStatus::Ok);
    assert!(xyz.iter().all(|x| x.is_finite()));
    // The held node is one of the page's nodes.
    let held = held_position(h);
    assert!(xyz.chunks_exact(3).any(|p| p == held));
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}

/// Calls `folio_last_error_message` with a buffer of `len` bytes (`None`: NULL).
fn message_into(len: Option<usize>) -> (FolioStatus, Vec<c_char>, usize) {
    let mut needed = usize::MAX;
    let mut buf = vec![b'#' as c_char; len.unwrap_or(0)];
    let p = if len.is_some() {
        buf.as_mut_ptr()
    } else {
        ptr::null_mut()
    };
    // SAFETY: `p` is NULL or valid for `len` bytes.
    let status = unsafe { folio_last_error_message(p, len.unwrap_or(0), &mut needed) };
    (status, buf, needed)
}

#[test]
fn last_error_message_truncates_and_reports_the_size_needed() {
    assert_eq!(
        folio_book_release(FolioBookHandle::default()),
        FolioStatus::StaleHandle
    );
    let full = last_error();
    assert_eq!(full, "folio_book_release: the zero handle names no book");
    let whole = full.len() + 1;

    let (status, _, needed) = message_into(None);
    assert_eq!((status, needed), (FolioStatus::Ok, whole), "size query");

    let (status, buf, needed) = message_into(Some(6));
    assert_eq!((status, needed), (FolioStatus::BufferTooSmall, whole));
    let text: Vec<u8> = buf.iter().map(|&c| c as u8).collect();
    assert_eq!(&text, b"folio\0", "cut to len - 1 bytes and NUL-terminated");

    let (status, buf, _) = message_into(Some(0));
    assert_eq!(status, FolioStatus::BufferTooSmall);
    assert!(buf.is_empty());

    let (status, buf, _) = message_into(Some(whole));
    assert_eq!(status, FolioStatus::Ok);
    assert_eq!(buf[whole - 1], 0);

    // NULL with a length is refused; `needed` is still written.
    let mut needed = 0usize;
    // SAFETY: NULL buffer (refused), valid `needed`.
    let status = unsafe { folio_last_error_message(ptr::null_mut(), 10, &mut needed) };
    assert_eq!((status, needed), (FolioStatus::NullPointer, whole));
    // `needed` may be NULL.
    let mut buf = vec![0 as c_char; whole];
    // SAFETY: `buf` is valid for `whole` bytes.
    let status = unsafe { folio_last_error_message(buf.as_mut_ptr(), whole, ptr::null_mut()) };
    assert_eq!(status, FolioStatus::Ok);

    // Reading the message does not replace it.
    assert_eq!(last_error(), full);
    // A success clears it.
    let mut s = core::mem::MaybeUninit::<FolioBookSettings>::uninit();
    // SAFETY: `s` is valid for one write.
    assert_eq!(
        unsafe { folio_book_settings_default(s.as_mut_ptr()) },
        FolioStatus::Ok
    );
    assert_eq!(last_error(), "");
    let (_, _, needed) = message_into(None);
    assert_eq!(needed, 1);
}

#[test]
fn status_names_cover_every_code() {
    for code in 0..=12u32 {
        // SAFETY: `folio_status_name` returns a static NUL-terminated string.
        let name = unsafe { core::ffi::CStr::from_ptr(folio_status_name(code)) };
        let name = name.to_str().unwrap();
        assert!(name.starts_with("FOLIO_STATUS_") && name != "FOLIO_STATUS_UNKNOWN");
    }
    // SAFETY: as above.
    let unknown = unsafe { core::ffi::CStr::from_ptr(folio_status_name(9999)) };
    assert_eq!(unknown.to_str().unwrap(), "FOLIO_STATUS_UNKNOWN");
    assert_eq!(folio_api_version(), FOLIO_API_VERSION);
}
