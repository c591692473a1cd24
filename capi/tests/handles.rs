//! Handles: the zero handle, destroyed handles, double destroy, never reused values, NULL
//! and misaligned out-pointers, books on several threads.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use core::ptr;
use folio_capi::*;

/// Every function that takes a handle, called on `h`: each status.
fn statuses(h: FolioBookHandle) -> Vec<(&'static str, FolioStatus)> {
    let mut report = core::mem::MaybeUninit::<FolioStepReport>::uninit();
    let (mut a, mut b) = (0u32, 0u32);
    let mut xyz = [0.0f64; 3];
    // SAFETY: every pointer is valid for what the function writes.
    unsafe {
        vec![
            ("grab", folio_book_grab(h, FOLIO_SIDE_RIGHT, 6.0, 6.0, 1)),
            ("drag", folio_book_drag(h, 1.0, 2.0, 3.0)),
            ("release", folio_book_release(h)),
            ("step", folio_book_step(h, report.as_mut_ptr())),
            ("mesh_size", folio_book_mesh_size(h, &mut a, &mut b)),
            (
                "mesh_copy",
                folio_book_mesh_copy(
                    h,
                    ptr::null_mut(),
                    0,
                    ptr::null_mut(),
                    0,
                    ptr::null_mut(),
                    0,
                    ptr::null_mut(),
                    0,
                ),
            ),
            ("page_grid", folio_book_page_grid(h, &mut a, &mut b)),
            (
                "page_positions",
                folio_book_page_positions(h, xyz.as_mut_ptr(), 3),
            ),
            (
                "held_position",
                folio_book_held_position(h, xyz.as_mut_ptr()),
            ),
            ("destroy", folio_book_destroy(h)),
        ]
    }
}

fn assert_all_stale(h: FolioBookHandle) {
    for (name, status) in statuses(h) {
        assert_eq!(status, FolioStatus::StaleHandle, "{name}");
        let message = last_error();
        assert!(
            message.contains("no live book") || message.contains("zero handle"),
            "{message}"
        );
    }
}

#[test]
fn the_zero_handle_and_made_up_handles_are_stale() {
    assert_all_stale(FolioBookHandle::default());
    assert_all_stale(FolioBookHandle { id: u64::MAX });
    assert_all_stale(FolioBookHandle { id: 12345 << 24 });
}

#[test]
fn a_destroyed_handle_is_stale_and_double_destroy_is_refused() {
    let h = create(&FolioBookSettings::default());
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
    assert_eq!(last_error(), "", "success clears the last error");
    assert_eq!(folio_book_destroy(h), FolioStatus::StaleHandle);
    assert!(last_error().starts_with("folio_book_destroy: handle"));
    assert_all_stale(h);
}

#[test]
fn handle_values_are_never_reused() {
    let s = FolioBookSettings::default();
    let first = create(&s);
    assert_eq!(folio_book_destroy(first), FolioStatus::Ok);
    let second = create(&s);
    assert_ne!(first, second);
    assert_eq!(folio_book_destroy(first), FolioStatus::StaleHandle);
    // The second book works and is not disturbed by the stale calls.
    assert_eq!(step(second).pages_left, 50);
    assert_eq!(folio_book_destroy(second), FolioStatus::Ok);
}

#[test]
fn null_out_pointers_are_refused() {
    let s = FolioBookSettings::default();
    let mut h = FolioBookHandle::default();
    // SAFETY: NULL where the test says, valid pointers elsewhere.
    unsafe {
        assert_eq!(
            folio_book_create(ptr::null(), &mut h),
            FolioStatus::NullPointer
        );
        assert_eq!(last_error(), "folio_book_create: `settings` is NULL");
        assert_eq!(
            folio_book_create(&s, ptr::null_mut()),
            FolioStatus::NullPointer
        );
        assert_eq!(last_error(), "folio_book_create: `out` is NULL");
        assert_eq!(h.id, 0);
        assert_eq!(
            folio_book_settings_default(ptr::null_mut()),
            FolioStatus::NullPointer
        );
    }
    let h = create(&s);
    let mut n = 0u32;
    // SAFETY: as above.
    unsafe {
        assert_eq!(
            folio_book_step(h, ptr::null_mut()),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_mesh_size(h, ptr::null_mut(), &mut n),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_mesh_size(h, &mut n, ptr::null_mut()),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_page_grid(h, ptr::null_mut(), &mut n),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_page_grid(h, &mut n, ptr::null_mut()),
            FolioStatus::NullPointer
        );
        assert_eq!(
            folio_book_held_position(h, ptr::null_mut()),
            FolioStatus::NullPointer
        );
        assert_eq!(last_error(), "folio_book_held_position: `xyz` is NULL");
    }
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}

#[test]
fn misaligned_out_pointers_are_refused() {
    let h = create(&FolioBookSettings::default());
    let mut bytes = [0u8; 2 * core::mem::size_of::<FolioStepReport>()];
    let odd = bytes.as_mut_ptr().wrapping_add(1).cast::<FolioStepReport>();
    // SAFETY: the pointer is misaligned and the function must refuse it without a write.
    let status = unsafe { folio_book_step(h, odd) };
    assert_eq!(status, FolioStatus::InvalidArgument);
    assert!(last_error().contains("not aligned"), "{}", last_error());
    assert!(bytes.iter().all(|&b| b == 0), "nothing written");
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
}

#[test]
fn books_on_several_threads_and_one_book_shared() {
    let workers: Vec<_> = (0..4)
        .map(|k| {
            std::thread::spawn(move || {
                let h = create(&FolioBookSettings::default());
                assert_eq!(
                    folio_book_grab(h, FOLIO_SIDE_RIGHT, 11.0, 3.0 + f64::from(k), 1),
                    FolioStatus::Ok
                );
                for _ in 0..5 {
                    assert_eq!(step(h).phase, FolioPhase::Held);
                }
                // The last error is per thread: this thread's failure stays its own.
                assert_eq!(
                    folio_book_drag(h, f64::NAN, 0.0, 0.0),
                    FolioStatus::InvalidArgument
                );
                assert!(last_error().contains("not finite"));
                assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
            })
        })
        .collect();
    for w in workers {
        w.join().unwrap();
    }
    assert_eq!(
        last_error(),
        "",
        "other threads' failures are not this thread's"
    );

    // One book, two threads stepping it, then destroyed while the other may still run.
    let shared = create(&FolioBookSettings::default());
    let stepper = std::thread::spawn(move || {
        let mut report = core::mem::MaybeUninit::<FolioStepReport>::uninit();
        let mut ok = 0;
        for _ in 0..50 {
            // SAFETY: `report` is valid for one write.
            match unsafe { folio_book_step(shared, report.as_mut_ptr()) } {
                FolioStatus::Ok => ok += 1,
                FolioStatus::StaleHandle => break,
                other => panic!("{other:?}"),
            }
        }
        ok
    });
    for _ in 0..3 {
        let _ = step(shared);
    }
    assert_eq!(folio_book_destroy(shared), FolioStatus::Ok);
    let stepped = stepper.join().unwrap();
    assert!(stepped <= 50);
    assert_eq!(folio_book_destroy(shared), FolioStatus::StaleHandle);
}
