//! Size probe: a bare-metal program that links the models and effects of the enabled
//! features in `f32`, for measuring `.text` on `thumbv7em-none-eabihf` (CI step "no_std
//! build"). Not a firmware: it never runs.
//!
//! `cargo build -p folio-size-probe --example size_probe --no-default-features \
//!   --features size-probe,<features> --target thumbv7em-none-eabihf --release`
//!
//! With `book` it builds the default book, grabs, drags, steps and releases a page; with
//! `cone` and `mass-spring` it drives those page models the same way. `collisions` and
//! `bookmarking` compile those effects in or out of the book.
#![no_std]
#![no_main]
#![allow(unsafe_code)] // `no_mangle` on the entry point and the bump allocator only.

extern crate alloc;

mod heap;

use core::hint::black_box;

#[cfg(any(feature = "cone", feature = "mass-spring"))]
use folio_pages::PageModel;

type V3 = <f32 as folio_kernels::Real>::Vec3;

/// A finger path the optimizer cannot see through.
fn finger(k: u32) -> V3 {
    let s = black_box(k as f32) * 0.01;
    V3::new(8.0 - s, 1.0 + s, 3.0)
}

#[cfg(feature = "book")]
fn book() {
    use folio_book::{Book, BookSettings};
    use folio_geometry::BlockSide;
    let Ok(mut book) = Book::<f32>::new(black_box(BookSettings::default())) else {
        return;
    };
    let _ = book.grab_at(BlockSide::Right, black_box([11.0, 3.0]), 1);
    for k in 0..black_box(8) {
        let _ = book.drag_to(finger(k));
        let _ = black_box(book.step());
    }
    let _ = black_box(book.bookmark(true));
    book.release();
    let _ = black_box((book.step(), book.stretch(), book.dog_residual()));
}

#[cfg(any(feature = "cone", feature = "mass-spring"))]
fn page(model: &mut dyn PageModel<f32>) {
    use folio_geometry::QuadGrid;
    let _ = model.grab(black_box([11.0, 3.0]));
    for k in 0..black_box(8) {
        let _ = model.drag(finger(k));
        let _ = black_box(model.step());
    }
    model.release();
    if let Some(grid) = QuadGrid::new(8, 11) {
        let mut out = alloc::vec![V3::ZERO; grid.len()];
        let _ = black_box(model.sample(grid, &mut out));
    }
}

#[cfg(feature = "tearing")]
fn tearing() {
    use folio_tearing::sheet::{SheetSettings, TearingSheet};
    let Ok(mut sheet) = TearingSheet::<f32>::new(black_box(SheetSettings::default())) else {
        return;
    };
    let (Ok(a), Ok(b)) = (
        sheet.grab(black_box([3.0, 0.0])),
        sheet.grab(black_box([7.5, 0.0])),
    ) else {
        return;
    };
    for k in 0..black_box(8) {
        let _ = sheet.move_finger(a, finger(k));
        let _ = sheet.move_finger(b, -finger(k));
        let _ = black_box(sheet.step());
    }
}

/// Entry point the linker keeps; everything reachable from it is what the features cost.
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    #[cfg(feature = "book")]
    book();
    #[cfg(feature = "cone")]
    if let Ok(mut cone) = folio_pages::cone::ConePage::<f32>::new(Default::default()) {
        page(&mut cone);
    }
    #[cfg(feature = "tearing")]
    tearing();
    #[cfg(feature = "mass-spring")]
    if let Ok(mut spring) = folio_pages::spring::SpringPage::<f32>::new(Default::default()) {
        page(&mut spring);
    }
    loop {
        core::hint::spin_loop();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
