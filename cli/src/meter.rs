//! Measuring a frame's steps: wall time and allocations.

use std::time::Instant;

/// Measures a frame's steps: their wall time and the allocations the running thread made
/// (counted by the `folio` binary's global allocator, `folio_counting`).
pub(crate) struct Meter {
    started: Instant,
    allocations: usize,
}

impl Meter {
    /// Starts measuring.
    #[must_use]
    pub(crate) fn start() -> Self {
        Self {
            allocations: folio_counting::allocations(),
            started: Instant::now(),
        }
    }

    /// The milliseconds and allocations since [`Meter::start`].
    #[must_use]
    pub(crate) fn stop(self) -> (f64, usize) {
        let ms = self.started.elapsed().as_secs_f64() * 1e3;
        let allocations = folio_counting::allocations() - self.allocations;
        (ms, allocations)
    }
}
