//! Fuzz target `ldlt`: the harness `folio_tests::fuzz::ldlt::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::ldlt::run(data));
