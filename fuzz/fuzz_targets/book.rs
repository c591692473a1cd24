//! Fuzz target `book`: the harness `folio_tests::fuzz::book::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::book::run(data));
