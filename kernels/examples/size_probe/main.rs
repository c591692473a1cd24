//! Size probe: a bare-metal program that links every kernel, for measuring `.text` on
//! `thumbv7em-none-eabihf` (CI step "thumbv7em build"). Not a firmware: it never runs.
//!
//! `cargo build -p folio-kernels --example size_probe --features size-probe \
//!   --no-default-features --target thumbv7em-none-eabihf --release`
//! links every kernel in f32 and f64; add `probe-f32-only` for the f32 set alone.
#![no_std]
#![no_main]
#![allow(unsafe_code)] // `no_mangle` on the entry point only.

mod exercise;

/// Entry point the linker keeps; everything reachable from it is what the kernels cost.
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    exercise::exercise::<f32>();
    #[cfg(not(feature = "probe-f32-only"))]
    exercise::exercise::<f64>();
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
