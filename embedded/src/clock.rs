//! Instruction counting with SysTick.
//!
//! SysTick runs from the core clock (`CLKSOURCE = 1`) with the largest reload, $2^{24}$ ticks,
//! and its exception counts the wraps, so [`Clock::now`] is a 64-bit tick count (ticks).
//! Under `qemu-system-arm -icount shift=0` virtual time advances $2^0 = 1$ ns per executed
//! instruction, and QEMU's MPS2 boards clock the core (and so SysTick) at 25 MHz: one tick is
//! 40 ns, that is 40 instructions. [`Clock::calibrate`] measures that factor on a loop of a
//! known instruction count instead of assuming it.
//!
//! Without `-icount` the same ticks follow host time and mean nothing.

use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{SCB, SYST};
use cortex_m_rt::exception;

/// SysTick reload: the counter runs from this down to 0, `RELOAD + 1` ticks per wrap.
const RELOAD: u32 = 0x00FF_FFFF;

/// Wraps of the SysTick counter since [`Clock::start`].
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    WRAPS.fetch_add(1, Ordering::Relaxed);
}

/// A free-running 64-bit tick counter on SysTick (module docs).
pub struct Clock {
    /// Owned so that nothing else reconfigures SysTick.
    _syst: SYST,
}

/// The result of [`Clock::calibrate`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Calibration {
    /// Instructions the loop executed.
    pub instructions: u64,
    /// Ticks it took.
    pub ticks: u64,
}

impl Calibration {
    /// Instructions per tick, rounded to the nearest whole number (0 if no tick passed).
    #[must_use]
    pub fn factor(&self) -> u64 {
        (self.instructions + self.ticks / 2)
            .checked_div(self.ticks)
            .unwrap_or(0)
    }

    /// Instructions per tick in thousandths (for printing the measured ratio).
    #[must_use]
    pub fn factor_milli(&self) -> u64 {
        (self.instructions * 1000)
            .checked_div(self.ticks)
            .unwrap_or(0)
    }
}

impl Clock {
    /// Starts SysTick from the core clock with its wrap exception enabled.
    #[must_use]
    pub fn start(mut syst: SYST) -> Self {
        syst.disable_counter();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        WRAPS.store(0, Ordering::Relaxed);
        syst.enable_interrupt();
        syst.enable_counter();
        // The counter reads 0 until its first reload, one tick after the enable; reading it
        // as a count then would start the clock a whole period early.
        while SYST::get_current() == 0 {}
        Self { _syst: syst }
    }

    /// Ticks since [`Clock::start`].
    #[must_use]
    pub fn now(&self) -> u64 {
        loop {
            let before = WRAPS.load(Ordering::Relaxed);
            let value = SYST::get_current();
            // A wrap whose exception has not run yet: the counter restarted near RELOAD.
            let pending = SCB::is_pendst_pending() && value > RELOAD / 2;
            if WRAPS.load(Ordering::Relaxed) != before {
                continue;
            }
            let wraps = u64::from(before) + u64::from(pending);
            return wraps * (u64::from(RELOAD) + 1) + u64::from(RELOAD - value);
        }
    }

    /// Measures instructions per tick on a loop of `2 * iterations` instructions
    /// (`subs` + `bne` per iteration). The two clock reads around it add a few dozen
    /// instructions, under one tick.
    #[must_use]
    pub fn calibrate(&self, iterations: u32) -> Calibration {
        let iterations = iterations.max(1);
        let start = self.now();
        spin(iterations);
        let ticks = self.now() - start;
        Calibration {
            instructions: 2 * u64::from(iterations),
            ticks,
        }
    }
}

/// Executes exactly `2 * iterations` instructions (`iterations >= 1`).
#[allow(unsafe_code)]
fn spin(iterations: u32) {
    // SAFETY: a register-only countdown loop; it touches no memory and no stack, and leaves
    // only the flags changed (which `asm!` assumes by default).
    unsafe {
        core::arch::asm!(
            "2:",
            "subs {n}, {n}, #1",
            "bne 2b",
            n = inout(reg) iterations => _,
            options(nomem, nostack),
        );
    }
}
