//! Fuzz target `capi`: sequences of C API calls (`folio-capi`, called as C calls them,
//! through raw pointers) with good and bad arguments: live, stale, destroyed and made-up
//! handles, NULL out-pointers, short and long buffers, NaN, infinite and huge coordinates,
//! invalid settings. Asserts: every call returns a known status, never
//! `FOLIO_STATUS_PANIC` or `FOLIO_STATUS_POISONED` (a panic caught at the boundary); every
//! failure leaves a message naming its function, every success an empty one; a successful
//! step's report and a copied mesh are finite, its indices in range.
//!
//! Creating a book settles it, the slow part of a run, so an input creates at most
//! [`MAX_BOOKS`] books and steps at most [`MAX_STEPS`] times; the books left are destroyed
//! at the end (a leak would show under the sanitizers).
#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

use core::ptr;

use folio_capi::{
    FOLIO_PRECISION_F32, FolioBookHandle, FolioBookSettings, FolioStatus, FolioStepReport,
    folio_book_create, folio_book_destroy, folio_book_drag, folio_book_grab,
    folio_book_held_position, folio_book_mesh_copy, folio_book_mesh_size,
    folio_book_page_positions, folio_book_release, folio_book_settings_default, folio_book_step,
    folio_last_error_message, folio_status_name,
};

use super::Input;

/// Books one input may create.
pub const MAX_BOOKS: usize = 2;

/// Steps one input may take.
pub const MAX_STEPS: usize = 12;

/// Calls one input may make.
pub const MAX_CALLS: usize = 64;

/// How many calls returned each status, by its code (`FolioStatus as usize`).
pub type StatusCounts = [usize; 16];

/// The harness: [`walk`].
///
/// # Panics
/// As [`walk`].
pub fn run(data: &[u8]) {
    walk(data);
}

/// Decodes a sequence of calls from `data` and makes them; how many calls returned each
/// status (the seeded test `tests/tests/capi_random_calls.rs` asserts that its walks reach
/// every kind of failure).
///
/// # Panics
/// When a property in the module docs does not hold.
pub fn walk(data: &[u8]) -> StatusCounts {
    let mut counts = [0; 16];
    let mut input = Input::new(data);
    let mut live: Vec<FolioBookHandle> = Vec::new();
    let mut dead: Vec<FolioBookHandle> = vec![FolioBookHandle::default()];
    let (mut created, mut steps) = (0, 0);
    for _ in 0..MAX_CALLS {
        if input.is_empty() {
            break;
        }
        let h = match input.below(8) {
            0 | 1 if !dead.is_empty() => dead[input.below(dead.len())],
            2 => FolioBookHandle {
                id: u64::from(input.u16()) << 8 | u64::from(input.byte()),
            },
            _ if !live.is_empty() => live[input.below(live.len())],
            _ => FolioBookHandle::default(),
        };
        let status = match input.below(12) {
            0 if created < MAX_BOOKS => {
                created += 1;
                let s = settings(&mut input);
                let mut out = FolioBookHandle::default();
                let out_ptr = if input.byte() == 0 {
                    ptr::null_mut()
                } else {
                    &raw mut out
                };
                // SAFETY: `s` is readable; `out_ptr` is NULL or valid.
                let status = checked("create", unsafe { folio_book_create(&s, out_ptr) });
                if status == FolioStatus::Ok && !out_ptr.is_null() {
                    live.push(out);
                }
                status
            }
            1 => {
                let status = checked("destroy", folio_book_destroy(h));
                if status == FolioStatus::Ok {
                    live.retain(|&x| x != h);
                    dead.push(h);
                }
                status
            }
            2 => {
                let side = input.below(4) as u32;
                let (u, v) = (coordinate(&mut input).abs(), coordinate(&mut input).abs());
                let pages = input.below(4) as u32;
                checked("grab", folio_book_grab(h, side, u, v, pages))
            }
            3 | 4 => {
                let p = [(); 3].map(|()| coordinate(&mut input));
                checked("drag", folio_book_drag(h, p[0], p[1], p[2]))
            }
            5 => checked("release", folio_book_release(h)),
            6 | 7 if steps < MAX_STEPS => {
                steps += 1;
                step(h, input.byte() == 0)
            }
            8 => mesh(h, &mut input),
            9 => {
                let n = length(&mut input, 3 * 12 * 13);
                let mut xyz = vec![0.0f64; n];
                // SAFETY: `xyz` is valid for `n` doubles.
                let status = checked("page_positions", unsafe {
                    folio_book_page_positions(h, xyz.as_mut_ptr(), n)
                });
                if status == FolioStatus::Ok {
                    assert!(xyz.iter().all(|x| x.is_finite()), "page positions {xyz:?}");
                }
                status
            }
            10 => {
                let mut xyz = [0.0f64; 3];
                // SAFETY: `xyz` holds 3 doubles.
                checked("held_position", unsafe {
                    folio_book_held_position(h, xyz.as_mut_ptr())
                })
            }
            _ => messages(&mut input),
        };
        if let Some(count) = counts.get_mut(status as usize) {
            *count += 1;
        }
    }
    for h in live {
        assert_eq!(
            folio_book_destroy(h),
            FolioStatus::Ok,
            "destroying a live book"
        );
    }
    counts
}

/// Checks a call's status and the thread's message (module docs).
fn checked(call: &str, status: FolioStatus) -> FolioStatus {
    let message = last_error();
    assert!(
        !matches!(status, FolioStatus::Panic | FolioStatus::Poisoned),
        "{call}: {status:?}: {message}"
    );
    if status == FolioStatus::Ok {
        assert_eq!(message, "", "{call} succeeded with a message");
    } else {
        assert!(
            message.starts_with("folio_"),
            "{call}: {status:?}: {message:?}"
        );
    }
    status
}

/// The calling thread's last error message.
fn last_error() -> String {
    let mut needed = 0usize;
    // SAFETY: a size query (NULL, 0) with a valid `needed`.
    let status = unsafe { folio_last_error_message(ptr::null_mut(), 0, &raw mut needed) };
    assert_eq!(status, FolioStatus::Ok, "size query of the last error");
    let mut buf = vec![0 as core::ffi::c_char; needed.max(1)];
    // SAFETY: `buf` holds `buf.len()` bytes.
    let status = unsafe { folio_last_error_message(buf.as_mut_ptr(), buf.len(), &raw mut needed) };
    assert_eq!(status, FolioStatus::Ok, "reading the last error");
    let end = buf.iter().position(|&c| c == 0).expect("NUL-terminated");
    String::from_utf8(buf[..end].iter().map(|&c| c as u8).collect()).expect("UTF-8 message")
}

/// Settings for a small book, mostly valid: 10 to 40 pages (fewer settle slowly at
/// creation), 4 to 6 quads a side, sometimes f32, sometimes one field broken.
fn settings(input: &mut Input<'_>) -> FolioBookSettings {
    let mut s = FolioBookSettings::default();
    if input.byte() == 0 {
        // The defaults through the API, or a NULL out-pointer.
        let out = if input.flag() {
            ptr::null_mut()
        } else {
            &raw mut s
        };
        // SAFETY: `out` is NULL or valid for one write.
        checked("settings_default", unsafe {
            folio_book_settings_default(out)
        });
    }
    s.total_pages = 10 + input.below(31) as u32;
    s.left_pages = input.below(s.total_pages as usize + 2) as u32;
    s.quads_across = 4 + input.below(3) as u32;
    s.quads_along = 4 + input.below(3) as u32;
    s.cover = input.below(2) as u32;
    if input.flag() {
        s.precision = FOLIO_PRECISION_F32;
    }
    match input.below(10) {
        0 => s.page_width = coordinate(input),
        1 => s.time_step = coordinate(input),
        2 => s.precision = input.byte().into(),
        3 => s.cover = input.below(4) as u32,
        4 => s.quads_across = input.below(3) as u32,
        5 => s.effects = input.byte().into(),
        _ => {}
    }
    s
}

/// A coordinate: mostly of the book's size, sometimes NaN, infinite, huge or subnormal.
fn coordinate(input: &mut Input<'_>) -> f64 {
    match input.below(20) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => 1e300,
        4 => -1e-310,
        _ => input.uniform(-20.0, 20.0),
    }
}

/// A buffer length around `needed`: zero, short, long or exact.
fn length(input: &mut Input<'_>, needed: usize) -> usize {
    match input.below(5) {
        0 => 0,
        1 => needed.saturating_sub(1 + input.below(5)),
        2 => needed + input.below(4),
        _ => needed,
    }
}

/// One step of `h` (a NULL report when `null`); a successful step's report is finite.
fn step(h: FolioBookHandle, null: bool) -> FolioStatus {
    let mut r = core::mem::MaybeUninit::<FolioStepReport>::uninit();
    let out = if null {
        ptr::null_mut()
    } else {
        r.as_mut_ptr()
    };
    // SAFETY: `out` is NULL or valid for one write.
    let status = checked("step", unsafe { folio_book_step(h, out) });
    if status == FolioStatus::Ok && !null {
        // SAFETY: written by the successful call.
        let r = unsafe { r.assume_init() };
        let values = [
            r.dog_residual,
            r.stretch_max,
            r.stretch_rms,
            r.penetration,
            r.constraint_residual,
        ];
        assert!(values.iter().all(|v| v.is_finite()), "step report {r:?}");
    }
    status
}

/// The mesh of `h` through `mesh_size` and `mesh_copy`, one buffer of the four (positions,
/// normals, texture coordinates, indices) at a length around the needed one and the rest
/// exact: a copied mesh is finite and its indices in range.
fn mesh(h: FolioBookHandle, input: &mut Input<'_>) -> FolioStatus {
    let (mut vertices, mut triangles) = (0u32, 0u32);
    // SAFETY: valid out-pointers.
    let sized = checked("mesh_size", unsafe {
        folio_book_mesh_size(h, &raw mut vertices, &raw mut triangles)
    });
    let (v, t) = (vertices as usize, triangles as usize);
    let mut lens = [3 * v, 3 * v, 2 * v, 3 * t];
    let odd = input.below(4);
    lens[odd] = length(input, lens[odd]);
    let mut floats: [Vec<f32>; 3] = core::array::from_fn(|k| vec![0.0; lens[k]]);
    let mut indices = vec![0u32; lens[3]];
    let [positions, normals, uvs] = &mut floats;
    // SAFETY: every pointer is valid for its length.
    let copied = checked("mesh_copy", unsafe {
        folio_book_mesh_copy(
            h,
            positions.as_mut_ptr(),
            lens[0],
            normals.as_mut_ptr(),
            lens[1],
            uvs.as_mut_ptr(),
            lens[2],
            indices.as_mut_ptr(),
            lens[3],
        )
    });
    if copied == FolioStatus::Ok && sized == FolioStatus::Ok {
        let finite = floats.iter().flatten().all(|x| x.is_finite());
        assert!(finite, "a copied mesh is finite");
        let in_range = indices.iter().take(3 * t).all(|&i| i < vertices);
        assert!(in_range, "indices in range");
    }
    copied
}

/// The last-error message into a buffer of any length (always NUL-terminated when not
/// empty), and the name of any status code (never NULL).
fn messages(input: &mut Input<'_>) -> FolioStatus {
    let len = input.below(40);
    let mut buf = vec![0 as core::ffi::c_char; len];
    let mut needed = 0usize;
    // SAFETY: `buf` is valid for `len` bytes.
    let status = unsafe { folio_last_error_message(buf.as_mut_ptr(), len, &raw mut needed) };
    assert!(
        matches!(status, FolioStatus::Ok | FolioStatus::BufferTooSmall),
        "last_error_message: {status:?}"
    );
    if len > 0 {
        assert!(buf.contains(&0), "always NUL-terminated");
    }
    let name = folio_status_name(input.byte().into());
    assert!(!name.is_null(), "every code has a name");
    status
}
