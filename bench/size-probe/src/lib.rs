//! # folio-size-probe
//!
//! Holds `examples/size_probe`, a bare-metal program that links the `f32` models and effects
//! of the enabled features so that CI can print their `.text` on `thumbv7em-none-eabihf`:
//!
//! `cargo build -p folio-size-probe --example size_probe --no-default-features \
//!   --features size-probe,<features> --target thumbv7em-none-eabihf --release`
//!
//! with `<features>` any of `book`, `collisions`, `bookmarking`, `cone`, `mass-spring`,
//! `tearing` or `full`. The library itself is empty.
#![no_std]
