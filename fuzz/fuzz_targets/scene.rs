//! Fuzz target `scene`: the harness `folio_tests::fuzz::scene::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::scene::run(data));
