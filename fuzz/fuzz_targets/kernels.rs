//! Fuzz target `kernels`: the harness `folio_tests::fuzz::kernels::run` under libFuzzer.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| folio_tests::fuzz::kernels::run(data));
