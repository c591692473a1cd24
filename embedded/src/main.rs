//! # folio-embedded: the Cortex-M proof
//!
//! A `no_std` firmware that builds Folio's default book (seed 000's DOG book) and plays the
//! recorded page turn on an emulated Cortex-M ([`turn`]), in f32 on `mps2-an386`
//! (Cortex-M4F) or, with the `f64` feature, on `mps2-an500` (Cortex-M7, double-precision
//! FPU). It prints over semihosting:
//!
//! 1. the core (CPUID) and the SysTick calibration: instructions per tick ([`clock`]);
//! 2. `Book::new`'s instructions and heap, then one line per step: frame, phase, solver
//!    status, instructions, KKT unknowns and constraint rows, Newton iterations, line-search
//!    halvings;
//! 3. the summary: median and max instructions per active step and per resting step, the
//!    heap (current, peak, allocations inside steps), flash, static RAM and stack
//!    ([`memory`]), each next to its target ([`report`]);
//! 4. the result checks, and a one-line `summary:` for CI;
//!
//! then exits through semihosting with status 0 when every check passed and 1 otherwise
//! (a panic prints its message and exits with 1 too).
#![no_std]
#![no_main]
#![deny(unsafe_code)]

mod clock;
mod fixture;
mod fixture_format;
mod heap;
mod memory;
mod report;
mod stats;
mod turn;

use cortex_m_rt::entry;
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use cortex_m_semihosting::hprintln;

use crate::clock::Clock;
use crate::heap::CountingHeap;

/// The coordinate type of the simulation: f32 (the Cortex-M4F's FPU precision) unless the
/// `f64` feature is on.
#[cfg(not(feature = "f64"))]
pub type Real = f32;
/// The coordinate type of the simulation: f64 (feature `f64`).
#[cfg(feature = "f64")]
pub type Real = f64;

/// The machine this build links for (its `memory.x`).
#[cfg(feature = "an500")]
const MACHINE: &str = "mps2-an500";
/// The machine this build links for (its `memory.x`).
#[cfg(not(feature = "an500"))]
const MACHINE: &str = "mps2-an386";

/// Iterations of the calibration loop (two instructions each).
const CALIBRATION_ITERATIONS: u32 = 4_000_000;

#[global_allocator]
static HEAP: CountingHeap = CountingHeap::empty();

/// Name of the core from CPUID's part number.
fn core_name(cpuid: u32) -> &'static str {
    match (cpuid >> 4) & 0xFFF {
        0xC24 => "Cortex-M4",
        0xC27 => "Cortex-M7",
        _ => "unknown core",
    }
}

/// Runs everything and says whether every check passed.
fn run() -> bool {
    HEAP.init();
    let Some(peripherals) = cortex_m::Peripherals::take() else {
        hprintln!("error: the core peripherals were already taken");
        return false;
    };
    let cpuid = peripherals.CPUID.base.read();
    let clock = Clock::start(peripherals.SYST);
    let calibration = clock.calibrate(CALIBRATION_ITERATIONS);
    let factor = calibration.factor();
    hprintln!(
        "folio-embedded: default book, page turn in {} on {} ({} r{}p{}, CPUID {:#010x})",
        turn::precision(),
        MACHINE,
        core_name(cpuid),
        (cpuid >> 20) & 0xF,
        cpuid & 0xF,
        cpuid
    );
    hprintln!(
        "calibration: {} instructions in {} SysTick ticks = {}.{:03} instructions per tick; using {}",
        calibration.instructions,
        calibration.ticks,
        calibration.factor_milli() / 1000,
        calibration.factor_milli() % 1000,
        factor
    );
    if factor == 0 {
        hprintln!("error: SysTick did not advance (is QEMU running with -icount shift=0?)");
        return false;
    }

    let report = match turn::run(&clock, factor, &HEAP) {
        Ok(report) => report,
        Err(e) => {
            hprintln!("error: {}", e);
            return false;
        }
    };
    let cx = report::Context {
        precision: turn::precision(),
        machine: MACHINE,
        factor,
        footprint: memory::footprint(),
        stack: memory::stack_high_water(),
        arena: heap::ARENA_BYTES,
    };
    report::print_figures(&report, &cx);
    report::print_checks(&report, &cx)
}

#[entry]
fn main() -> ! {
    let status = if run() { EXIT_SUCCESS } else { EXIT_FAILURE };
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
