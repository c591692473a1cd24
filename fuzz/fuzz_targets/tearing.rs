//! Fuzz target `tearing`: the harness `folio_tests::fuzz::tearing::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::tearing::run(data));
