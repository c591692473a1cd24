//! The printed summary: figures next to their targets, the result checks, and the one-line
//! `summary:` that CI can pick up.

use cortex_m_semihosting::hprintln;
use folio_book::Phase;
use folio_geometry::BlockSide;

use crate::memory::Footprint;
use crate::turn::{TurnReport, phase_name};

/// Issue 40's bounds for this build ("done when"): the M4F's in `f32`, the M7's in `f64`.
struct Targets {
    /// Instructions per active step: median and 99th percentile.
    active_median: u64,
    active_p99: u64,
    /// Instructions per resting step (the book asleep), median.
    resting_median: u64,
    /// Instructions of `Book::new`.
    setup: u64,
    /// Heap peak (bytes).
    heap: u64,
    /// Flash: `.vector_table` + `.text` + `.rodata` (bytes).
    flash: u64,
    /// Stack high-water mark (bytes).
    stack: u64,
}

/// Issue 40's bounds for the default book in `f32` on the Cortex-M4F (the other builds
/// change some of them).
const F32_TARGETS: Targets = Targets {
    active_median: 6_000_000,
    active_p99: 9_000_000,
    resting_median: 20_000,
    setup: 25_000_000,
    heap: 256 * 1024,
    flash: 192 * 1024,
    stack: 24 * 1024,
};
/// The bounds of issue 40 for this build's precision.
#[cfg(not(any(feature = "f64", feature = "mcu")))]
const TARGETS: Targets = F32_TARGETS;
/// Issue 40's bounds for `page-turn-mcu` (the `mcu` feature, `f32`): a median active step
/// of at most 1.5 M instructions and 128 KiB of heap; the others are the default book's.
#[cfg(all(feature = "mcu", not(feature = "f64")))]
const TARGETS: Targets = Targets {
    active_median: 1_500_000,
    heap: 128 * 1024,
    ..F32_TARGETS
};
/// Issue 40's bounds for the default book in `f64` on the Cortex-M7.
#[cfg(feature = "f64")]
const TARGETS: Targets = Targets {
    active_median: 4_000_000,
    active_p99: 8_000_000,
    heap: 384 * 1024,
    ..F32_TARGETS
};

/// A figure and its target; prints `within` or `OVER by N (x.xx times the target)`.
struct Verdict {
    value: u64,
    target: u64,
}

impl core::fmt::Display for Verdict {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.value <= self.target {
            return write!(f, "within");
        }
        let hundredths = self.value * 100 / self.target.max(1);
        write!(
            f,
            "OVER by {} ({}.{:02} times the target)",
            self.value - self.target,
            hundredths / 100,
            hundredths % 100
        )
    }
}

fn verdict(value: u64, target: u64) -> Verdict {
    Verdict { value, target }
}

/// `pass` or `FAIL`.
fn mark(ok: bool) -> &'static str {
    if ok { "pass" } else { "FAIL" }
}

/// Everything the summary prints besides the run itself.
pub struct Context {
    /// `f32` or `f64`.
    pub precision: &'static str,
    /// The QEMU machine.
    pub machine: &'static str,
    /// Instructions per SysTick tick.
    pub factor: u64,
    /// Section sizes.
    pub footprint: Footprint,
    /// Stack high-water mark (bytes).
    pub stack: usize,
    /// Size of the heap arena inside `.bss` (bytes).
    pub arena: usize,
}

/// Prints the figures of `report` next to their targets.
pub fn print_figures(report: &TurnReport, cx: &Context) {
    let (a, r, f) = (report.active, report.resting, cx.footprint);
    hprintln!("== summary ({} on {}) ==", cx.precision, cx.machine);
    hprintln!(
        "active steps: {}, median {} instructions ({}), p99 {} ({}), max {} (frame {})",
        a.steps,
        a.median,
        verdict(a.median, TARGETS.active_median),
        a.p99,
        verdict(a.p99, TARGETS.active_p99),
        a.max,
        a.max_frame
    );
    hprintln!(
        "resting steps: {} ({} asleep), median {} instructions ({}), p99 {}, max {} (frame {})",
        r.steps,
        report.asleep_steps,
        r.median,
        verdict(r.median, TARGETS.resting_median),
        r.p99,
        r.max,
        r.max_frame
    );
    hprintln!(
        "accuracy over the active steps: max DOG residual {} e-9, edge stretch max {} ppm, mean of each step's max {} ppm",
        report.accuracy.dog_residual_e9,
        report.accuracy.stretch_ppm,
        report.accuracy.stretch_mean_ppm()
    );
    hprintln!(
        "setup: Book::new {} instructions ({} settling steps); inputs: at most {} instructions before one step",
        report.setup_instructions,
        report.settle_steps,
        report.input_max
    );
    hprintln!(
        "heap: peak {} bytes ({}), {} after setup, {} at the end; \
         {} allocation calls, {} inside steps, {} by inputs, {} failed",
        report.heap.peak,
        verdict(report.heap.peak as u64, TARGETS.heap),
        report.setup_heap,
        report.heap.current,
        report.heap.allocations,
        report.step_allocations,
        report.input_allocations,
        report.heap.failures
    );
    hprintln!(
        "flash: {} bytes (.vector_table + .text + .rodata; {}), plus {} bytes of .data initial values",
        f.flash,
        verdict(f.flash as u64, TARGETS.flash),
        f.data
    );
    hprintln!(
        "ram: .data {} + .bss {} bytes ({} of them the heap arena); stack high-water {} of {} bytes",
        f.data,
        f.bss,
        cx.arena,
        cx.stack,
        f.stack_space
    );
    hprintln!(
        "ram in use: {} bytes (statics without the arena + heap peak + stack high-water)",
        f.data + f.bss - cx.arena + report.heap.peak + cx.stack
    );
    hprintln!(
        "(targets: issue 40's bounds for {} on {}; Book::new within {} instructions: {}; stack within {} bytes: {})",
        cx.precision,
        cx.machine,
        TARGETS.setup,
        verdict(report.setup_instructions, TARGETS.setup),
        TARGETS.stack,
        verdict(cx.stack as u64, TARGETS.stack)
    );
}

/// Prints the result checks and the `summary:` line; returns whether every check passed.
pub fn print_checks(report: &TurnReport, cx: &Context) -> bool {
    let c = report.checks;
    let [before, after] = c.counts;
    hprintln!("== checks ==");
    let (merge_frame, merge_side) = match c.first_merge {
        Some((frame, BlockSide::Left)) => (frame, "left"),
        Some((frame, BlockSide::Right)) => (frame, "right"),
        None => (0, "none"),
    };
    hprintln!(
        "{}: the page merged once, into the left block (merges {}, first at frame {} into {})",
        mark(c.merged_left()),
        c.merges,
        merge_frame,
        merge_side
    );
    hprintln!(
        "{}: page counts left/right/active {}/{}/{} -> {}/{}/{}",
        mark(c.counts_moved()),
        before.left,
        before.right,
        before.active,
        after.left,
        after.right,
        after.active
    );
    hprintln!(
        "{}: every coordinate and velocity finite after every step ({} steps were not)",
        mark(c.nonfinite_steps == 0),
        c.nonfinite_steps
    );
    hprintln!(
        "{}: every step advanced the state ({} did not)",
        mark(c.stalled_steps == 0),
        c.stalled_steps
    );
    hprintln!(
        "{}: the book is at rest at the end ({})",
        mark(c.final_phase == Phase::AtRest),
        phase_name(c.final_phase)
    );
    hprintln!(
        "{}: the book is asleep at the end ({} of the resting steps were)",
        mark(c.final_asleep),
        report.asleep_steps
    );
    let passed = c.passed();
    hprintln!(
        "summary: {} {} grid={}x{} active_median={} active_p99={} active_max={} resting_median={} \
         resting_p99={} resting_max={} asleep_steps={} setup={} heap_peak={} flash={} stack={} \
         dog_residual_e9={} stretch_ppm={} stretch_mean_ppm={} merge_frame={} instructions_per_tick={} checks={}",
        cx.precision,
        cx.machine,
        report.grid[0],
        report.grid[1],
        report.active.median,
        report.active.p99,
        report.active.max,
        report.resting.median,
        report.resting.p99,
        report.resting.max,
        report.asleep_steps,
        report.setup_instructions,
        report.heap.peak,
        cx.footprint.flash,
        cx.stack,
        report.accuracy.dog_residual_e9,
        report.accuracy.stretch_ppm,
        report.accuracy.stretch_mean_ppm(),
        merge_frame,
        cx.factor,
        mark(passed)
    );
    passed
}
