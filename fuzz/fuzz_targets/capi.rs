//! Fuzz target `capi`: the harness `folio_tests::fuzz::capi::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::capi::run(data));
