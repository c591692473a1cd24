//! Memory figures read from the linker's section symbols (cortex-m-rt's `link.x`) and the
//! stack high-water mark from cortex-m-rt's stack painting (`paint-stack`: every word
//! between the end of static RAM and the initial stack pointer is set to
//! [`cortex_m_rt::STACK_PAINT_VALUE`] at reset).

use cortex_m_rt::STACK_PAINT_VALUE;

// Declarations only: the addresses are taken (`&raw const`), the contents never read.
#[allow(unsafe_code)]
unsafe extern "C" {
    static __vector_table: u32;
    static __erodata: u32;
    static __sdata: u32;
    static __edata: u32;
    static __sbss: u32;
    static __ebss: u32;
    static _stack_end: u32;
    static _stack_start: u32;
}

/// Sizes of the program's memory (bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint {
    /// What a part keeps in flash: `.vector_table`, `.text` and `.rodata` (the initial
    /// values of `.data` come on top, see `data`).
    pub flash: usize,
    /// Initialized statics (`.data`): in RAM, with a copy in flash.
    pub data: usize,
    /// Zeroed statics (`.bss`), the heap arena included.
    pub bss: usize,
    /// Stack space between the end of the statics and the top of RAM.
    pub stack_space: usize,
}

/// Address of a linker symbol (its contents are never read).
macro_rules! address {
    ($symbol:ident) => {
        (&raw const $symbol) as usize
    };
}

/// The section sizes of this program.
#[must_use]
pub fn footprint() -> Footprint {
    let (vectors, rodata_end) = (address!(__vector_table), address!(__erodata));
    let (data, data_end) = (address!(__sdata), address!(__edata));
    let (bss, bss_end) = (address!(__sbss), address!(__ebss));
    let (stack_end, stack_start) = (address!(_stack_end), address!(_stack_start));
    Footprint {
        flash: rodata_end - vectors,
        data: data_end - data,
        bss: bss_end - bss,
        stack_space: stack_start - stack_end,
    }
}

/// Most stack bytes used since reset: from the top of RAM down to the deepest word that no
/// longer holds the paint value.
#[allow(unsafe_code)]
#[must_use]
pub fn stack_high_water() -> usize {
    // The painted region, word aligned (asserted by `link.x`).
    let (low, high) = (address!(_stack_end), address!(_stack_start));
    let mut at = low;
    while at < high {
        // SAFETY: `at` is a word-aligned address inside the stack region (RAM), below the
        // current stack pointer's deepest use or inside it; a volatile read of RAM has no
        // side effects.
        let word = unsafe { core::ptr::read_volatile(at as *const u32) };
        if word != STACK_PAINT_VALUE {
            break;
        }
        at += 4;
    }
    high - at
}
