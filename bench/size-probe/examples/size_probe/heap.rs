//! A bump allocator over a static arena, so that the probe links `alloc` (it never frees;
//! the probe never runs).

use core::alloc::{GlobalAlloc, Layout};
use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicUsize, Ordering};

const ARENA_BYTES: usize = 512 * 1024;

struct Arena(UnsafeCell<[u8; ARENA_BYTES]>);

// SAFETY: disjoint ranges of the arena are handed out through an atomic offset.
unsafe impl Sync for Arena {}

struct Bump {
    next: AtomicUsize,
}

static ARENA: Arena = Arena(UnsafeCell::new([0; ARENA_BYTES]));

#[global_allocator]
static HEAP: Bump = Bump {
    next: AtomicUsize::new(0),
};

// SAFETY: every allocation is a fresh, aligned range inside the arena, or null when full.
unsafe impl GlobalAlloc for Bump {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let base = ARENA.0.get().cast::<u8>();
        let mut start = 0;
        let claimed = self
            .next
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |next| {
                let addr = base as usize + next;
                start = addr.next_multiple_of(layout.align()) - base as usize;
                let end = start.checked_add(layout.size())?;
                (end <= ARENA_BYTES).then_some(end)
            });
        match claimed {
            // SAFETY: `start + size <= ARENA_BYTES`, inside the arena.
            Ok(_) => unsafe { base.add(start) },
            Err(_) => core::ptr::null_mut(),
        }
    }

    unsafe fn dealloc(&self, _ptr: *mut u8, _layout: Layout) {}
}
