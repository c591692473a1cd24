//! The printed summary: figures next to their targets, the result checks, and the one-line
//! `summary:` that CI can pick up.

use cortex_m_semihosting::hprintln;
use folio_book::Phase;
use folio_geometry::BlockSide;

use crate::memory::Footprint;
use crate::turn::{TurnReport, phase_name};

/// Heap target for the f32 book (bytes).
pub const HEAP_TARGET: u64 = 256 * 1024;
/// Flash target (`.vector_table` + `.text` + `.rodata`, bytes).
pub const FLASH_TARGET: u64 = 256 * 1024;
/// Instructions per active step, target on the Cortex-M4F.
pub const ACTIVE_STEP_TARGET: u64 = 3_000_000;

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
        "active steps: {}, median {} instructions, p99 {}, max {} (frame {}), {}",
        a.steps,
        a.median,
        a.p99,
        a.max,
        a.max_frame,
        verdict(a.max, ACTIVE_STEP_TARGET)
    );
    hprintln!(
        "resting steps: {}, median {} instructions, p99 {}, max {} (frame {})",
        r.steps,
        r.median,
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
        verdict(report.heap.peak as u64, HEAP_TARGET),
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
        verdict(f.flash as u64, FLASH_TARGET),
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
        "(targets: heap and flash <= 256 KiB, <= 3 M instructions per active step, for f32 on the M4F)"
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
    let passed = c.passed();
    hprintln!(
        "summary: {} {} active_median={} active_p99={} active_max={} resting_median={} \
         resting_p99={} resting_max={} setup={} heap_peak={} flash={} stack={} \
         dog_residual_e9={} stretch_ppm={} stretch_mean_ppm={} merge_frame={} instructions_per_tick={} checks={}",
        cx.precision,
        cx.machine,
        report.active.median,
        report.active.p99,
        report.active.max,
        report.resting.median,
        report.resting.p99,
        report.resting.max,
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
