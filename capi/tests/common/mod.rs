//! Shared helpers of the C API tests: calls through the exported functions, as C would.

#![allow(dead_code)] // Each test file uses a part.

use folio_capi::*;

/// The calling thread's last error message, read through `folio_last_error_message`.
pub fn last_error() -> String {
    let mut needed = 0usize;
    // SAFETY: a size query (NULL, 0) with a valid `needed`.
    let status = unsafe { folio_last_error_message(core::ptr::null_mut(), 0, &mut needed) };
    assert_eq!(status, FolioStatus::Ok);
    let mut buf = vec![0 as core::ffi::c_char; needed];
    // SAFETY: `buf` holds `needed` bytes.
    let status = unsafe { folio_last_error_message(buf.as_mut_ptr(), buf.len(), &mut needed) };
    assert_eq!(status, FolioStatus::Ok);
    assert_eq!(buf.last(), Some(&0), "NUL-terminated");
    let bytes: Vec<u8> = buf[..needed - 1].iter().map(|&c| c as u8).collect();
    String::from_utf8(bytes).expect("UTF-8 message")
}

/// Default settings in `precision`.
pub fn settings(precision: FolioPrecision) -> FolioBookSettings {
    FolioBookSettings {
        precision,
        ..FolioBookSettings::default()
    }
}

/// A book from `s`, which must be accepted.
pub fn create(s: &FolioBookSettings) -> FolioBookHandle {
    let mut h = FolioBookHandle::default();
    // SAFETY: both pointers are valid references.
    let status = unsafe { folio_book_create(s, &mut h) };
    assert_eq!(status, FolioStatus::Ok, "{}", last_error());
    assert_ne!(h.id, 0);
    h
}

/// `folio_book_create`'s status for `s` (the book, if any, is destroyed).
pub fn create_status(s: &FolioBookSettings) -> FolioStatus {
    let mut h = FolioBookHandle::default();
    // SAFETY: both pointers are valid references.
    let status = unsafe { folio_book_create(s, &mut h) };
    if status == FolioStatus::Ok {
        assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
    } else {
        assert_eq!(h.id, 0, "a failed create leaves `out` alone");
    }
    status
}

/// One step, which must succeed as a call.
pub fn step(h: FolioBookHandle) -> FolioStepReport {
    let mut r = core::mem::MaybeUninit::<FolioStepReport>::uninit();
    // SAFETY: `r` is valid for one write.
    let status = unsafe { folio_book_step(h, r.as_mut_ptr()) };
    assert_eq!(status, FolioStatus::Ok, "{}", last_error());
    // SAFETY: written by the successful call.
    unsafe { r.assume_init() }
}

/// The held node's position.
pub fn held_position(h: FolioBookHandle) -> [f64; 3] {
    let mut p = [0.0; 3];
    // SAFETY: `p` holds 3 doubles.
    let status = unsafe { folio_book_held_position(h, p.as_mut_ptr()) };
    assert_eq!(status, FolioStatus::Ok, "{}", last_error());
    p
}

/// The page turn's finger path (the C example's): from the held node `start` over the
/// spine to its mirror image, on $\varphi = \pi\thinspace\mathrm{smoothstep}(s)$:
/// $x = x_0 (1 - 0.1\sin\varphi)\cos\varphi$, $y = y_0 + 0.7 x_0 \sin\varphi$,
/// $z = z_0 + 0.12 H \sin\varphi$, for `steps` points.
pub fn turn_path(start: [f64; 3], height: f64, steps: u32) -> Vec<[f64; 3]> {
    (0..steps)
        .map(|k| {
            let s = f64::from(k) / f64::from(steps - 1);
            let phi = core::f64::consts::PI * s * s * (3.0 - 2.0 * s);
            let (sin, cos) = phi.sin_cos();
            [
                start[0] * (1.0 - 0.1 * sin) * cos,
                start[1] + 0.7 * start[0] * sin,
                start[2] + 0.12 * height * sin,
            ]
        })
        .collect()
}
