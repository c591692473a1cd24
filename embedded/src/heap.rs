//! The global allocator: embedded-alloc's first-fit heap over a static arena, wrapped in a
//! counter of the bytes the program holds (current and peak, as requested by the layouts,
//! without the allocator's own overhead) and of the allocation calls.

use core::alloc::{GlobalAlloc, Layout};
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicUsize, Ordering};

use embedded_alloc::LlffHeap;

/// Size of the heap arena (bytes). A statically allocated `.bss` array in SSRAM2&3; the
/// targets ask for at most 256 KiB of heap in f32, the arena leaves room for f64 and for a
/// book that does not fit.
pub const ARENA_BYTES: usize = 2 * 1024 * 1024;

/// What the program holds on the heap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HeapStats {
    /// Bytes held now.
    pub current: usize,
    /// Most bytes held at once since the start.
    pub peak: usize,
    /// Allocation calls so far (`alloc`, `alloc_zeroed` and `realloc`).
    pub allocations: usize,
    /// Failed allocation calls so far.
    pub failures: usize,
}

/// A [`GlobalAlloc`] that counts what passes through it to [`LlffHeap`] (module docs).
pub struct CountingHeap {
    inner: LlffHeap,
    current: AtomicUsize,
    peak: AtomicUsize,
    allocations: AtomicUsize,
    failures: AtomicUsize,
}

impl CountingHeap {
    /// An allocator with no memory until [`CountingHeap::init`].
    #[must_use]
    pub const fn empty() -> Self {
        Self {
            inner: LlffHeap::empty(),
            current: AtomicUsize::new(0),
            peak: AtomicUsize::new(0),
            allocations: AtomicUsize::new(0),
            failures: AtomicUsize::new(0),
        }
    }

    /// Hands the static arena ([`ARENA_BYTES`]) to the heap. Call once, first thing in
    /// `main`; a second call does nothing.
    #[allow(unsafe_code)]
    pub fn init(&self) {
        static mut ARENA: [MaybeUninit<u8>; ARENA_BYTES] = [MaybeUninit::uninit(); ARENA_BYTES];
        static DONE: AtomicUsize = AtomicUsize::new(0);
        if DONE.swap(1, Ordering::AcqRel) != 0 {
            return;
        }
        // SAFETY: the swap above lets exactly one caller through, so the arena is handed to
        // the heap once and never touched by anything else.
        unsafe {
            let start = (&raw mut ARENA).cast::<u8>() as usize;
            self.inner.init(start, ARENA_BYTES);
        }
    }

    /// The counts so far.
    #[must_use]
    pub fn stats(&self) -> HeapStats {
        HeapStats {
            current: self.current.load(Ordering::Relaxed),
            peak: self.peak.load(Ordering::Relaxed),
            allocations: self.allocations.load(Ordering::Relaxed),
            failures: self.failures.load(Ordering::Relaxed),
        }
    }

    fn grew(&self, bytes: usize) {
        let now = self.current.fetch_add(bytes, Ordering::Relaxed) + bytes;
        self.peak.fetch_max(now, Ordering::Relaxed);
    }

    fn counted(&self, ptr: *mut u8, bytes: usize) -> *mut u8 {
        self.allocations.fetch_add(1, Ordering::Relaxed);
        if ptr.is_null() {
            self.failures.fetch_add(1, Ordering::Relaxed);
        } else {
            self.grew(bytes);
        }
        ptr
    }
}

impl Default for CountingHeap {
    fn default() -> Self {
        Self::empty()
    }
}

// SAFETY: every call is forwarded unchanged to `LlffHeap`, a correct `GlobalAlloc`; the
// wrapper only updates atomic counters.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for CountingHeap {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is passed on.
        let ptr = unsafe { self.inner.alloc(layout) };
        self.counted(ptr, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is passed on.
        let ptr = unsafe { self.inner.alloc_zeroed(layout) };
        self.counted(ptr, layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { self.inner.dealloc(ptr, layout) };
        self.current.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's contract is passed on.
        let moved = unsafe { self.inner.realloc(ptr, layout, new_size) };
        self.allocations.fetch_add(1, Ordering::Relaxed);
        if moved.is_null() {
            // The old block is still held.
            self.failures.fetch_add(1, Ordering::Relaxed);
        } else {
            // The default `realloc` of the heap allocates the new block before it frees the
            // old one: both are held for a moment.
            self.grew(new_size);
            self.current.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        moved
    }
}
