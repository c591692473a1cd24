//! A counting global allocator for the no-allocation tests (DESIGN.md: "setup allocates;
//! stepping does not") and for `folio run`, which reports the allocations of every step. A
//! binary installs it with `#[global_allocator] static GLOBAL: Counting = Counting;` and
//! compares [`allocations`] before and after the code it watches. A crate of its own so that
//! the command links no test code (issue 41).
//!
//! It counts per thread: the test harness's own threads (its "has been running for over 60
//! seconds" notice under a slow emulator, output capture) allocate while a test runs, and
//! counted globally they made the book's page turn report 2 allocations under qemu-aarch64
//! and the sheet's frame a few in about one run in thirty.
// A global allocator is an `unsafe impl`; this crate is the only place that needs one.
#![allow(unsafe_code)]

use core::alloc::{GlobalAlloc, Layout};
use core::cell::Cell;
use std::alloc::System;

/// The system allocator, counting the allocations and reallocations of each thread.
pub struct Counting;

thread_local! {
    /// Allocations (and reallocations) made by this thread.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Counts one allocation on the calling thread (`try_with`: a thread being torn down has no
/// counter any more and is not counted).
fn count() {
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

/// Allocations and reallocations made by the calling thread so far.
#[must_use]
pub fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System.alloc` with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: as `realloc`'s contract, forwarded.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
