//! A full page turn through the C API matches the same turn on `Book` directly: the same
//! page counts at the end, merge step, DOG residuals and final render mesh, bit for bit
//! (the API adds no arithmetic), in both precisions.

#![allow(unsafe_code)] // Calls the C API as C does: through raw pointers.

mod common;

use common::*;
use folio_book::{Book, BookSettings, GrabOutcome};
use folio_capi::*;
use folio_geometry::BlockSide;
use folio_kernels::{Real, Vec3Ops};

/// Drag steps over the spine.
const DRAG_STEPS: u32 = 100;
/// Most steps after the release.
const SETTLE_STEPS: u32 = 600;

/// What a turn ended with.
#[derive(Debug, PartialEq)]
struct Ending {
    /// Steps after the release until the merge.
    merged_after: Option<u32>,
    merged: FolioSide,
    pages: [u32; 3],
    dog_max: f64,
    /// The final render mesh's positions.
    mesh: Vec<f32>,
}

impl Ending {
    /// Nothing merged, nothing measured yet.
    fn unmerged() -> Self {
        Self {
            merged_after: None,
            merged: FOLIO_SIDE_NONE,
            pages: [0; 3],
            dog_max: 0.0,
            mesh: Vec::new(),
        }
    }
}

fn turn_api(precision: FolioPrecision) -> Ending {
    let s = settings(precision);
    let height = s.page_width * s.aspect_ratio;
    let h = create(&s);
    assert_eq!(
        folio_book_grab(h, FOLIO_SIDE_RIGHT, s.page_width, 0.2 * height, 1),
        FolioStatus::Ok,
        "{}",
        last_error()
    );
    let mut dog_max: f64 = 0.0;
    for p in turn_path(held_position(h), height, DRAG_STEPS) {
        assert_eq!(folio_book_drag(h, p[0], p[1], p[2]), FolioStatus::Ok);
        let r = step(h);
        assert_eq!(r.phase, FolioPhase::Held);
        dog_max = dog_max.max(r.dog_residual);
    }
    assert_eq!(folio_book_release(h), FolioStatus::Ok);
    let mut ending = Ending::unmerged();
    for k in 0..SETTLE_STEPS {
        let r = step(h);
        if r.has_active_page == 1 {
            dog_max = dog_max.max(r.dog_residual);
        }
        ending.pages = [r.pages_left, r.pages_right, r.pages_active];
        if r.merged != FOLIO_SIDE_NONE {
            ending.merged_after = Some(k);
            ending.merged = r.merged;
            break;
        }
    }
    ending.dog_max = dog_max;
    let (mut v, mut t) = (0u32, 0u32);
    // SAFETY: valid out-pointers.
    assert_eq!(
        unsafe { folio_book_mesh_size(h, &mut v, &mut t) },
        FolioStatus::Ok
    );
    ending.mesh = vec![0.0; 3 * v as usize];
    // SAFETY: `mesh` holds `3 v` floats; the other buffers are skipped (NULL, 0).
    let status = unsafe {
        folio_book_mesh_copy(
            h,
            ending.mesh.as_mut_ptr(),
            ending.mesh.len(),
            core::ptr::null_mut(),
            0,
            core::ptr::null_mut(),
            0,
            core::ptr::null_mut(),
            0,
        )
    };
    assert_eq!(status, FolioStatus::Ok);
    assert_eq!(folio_book_destroy(h), FolioStatus::Ok);
    ending
}

fn turn_direct<T: Real>() -> Ending {
    let mut book = Book::<T>::new(BookSettings::default()).unwrap();
    let params = book.layout().params;
    let height = params.page_height();
    let grabbed = book
        .grab_at(BlockSide::Right, [params.page_width, 0.2 * height], 1)
        .unwrap();
    let GrabOutcome::Grabbed { node, .. } = grabbed else {
        panic!("{grabbed:?}");
    };
    let p = book.page().unwrap()[node];
    let start = [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let mut dog_max: f64 = 0.0;
    for q in turn_path(start, height, DRAG_STEPS) {
        let v = |c: f64| T::from_f64(c);
        book.drag_to(T::Vec3::new(v(q[0]), v(q[1]), v(q[2])))
            .unwrap();
        book.step().unwrap();
        dog_max = dog_max.max(book.dog_residual().unwrap().to_f64());
    }
    assert!(book.release());
    let mut ending = Ending::unmerged();
    for k in 0..SETTLE_STEPS {
        let r = book.step().unwrap();
        if let Some(d) = book.dog_residual() {
            dog_max = dog_max.max(d.to_f64());
        }
        let c = book.counts();
        ending.pages = [c.left, c.right, c.active];
        if let Some(side) = r.merged {
            ending.merged_after = Some(k);
            ending.merged = match side {
                BlockSide::Left => FOLIO_SIDE_LEFT,
                BlockSide::Right => FOLIO_SIDE_RIGHT,
            };
            break;
        }
    }
    ending.dog_max = dog_max;
    let mut mesh = folio_geometry::mesh::TriMesh::new();
    book.mesh(&mut mesh).unwrap();
    ending.mesh = mesh.positions.as_flattened().to_vec();
    ending
}

fn check(precision: FolioPrecision, api: &Ending, direct: &Ending) {
    eprintln!(
        "f{precision}: merged after {:?} steps into side {}, pages {:?}, max DOG residual {:.2e}",
        api.merged_after, api.merged, api.pages, api.dog_max
    );
    assert_eq!(api, direct, "the API adds nothing to the book");
    assert_eq!(
        api.merged, FOLIO_SIDE_LEFT,
        "the page lands on the left block"
    );
    assert_eq!(api.pages, [51, 49, 0]);
    assert!(api.dog_max < 0.05, "DOG residual {}", api.dog_max);
}

#[test]
fn page_turn_through_the_api_matches_the_book_f64() {
    check(64, &turn_api(FOLIO_PRECISION_F64), &turn_direct::<f64>());
}

#[test]
fn page_turn_through_the_api_matches_the_book_f32() {
    check(32, &turn_api(FOLIO_PRECISION_F32), &turn_direct::<f32>());
}
