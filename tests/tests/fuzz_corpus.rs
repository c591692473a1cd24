//! The fuzz harnesses on stable (`folio_tests::fuzz`, the same functions the cargo-fuzz
//! targets in `fuzz/` call): every file of the committed seed corpora
//! (`fuzz/corpus/<target>/`), then a seeded sweep of random inputs per target. A crash the
//! fuzzer finds is fixed and kept as a named case in `tests/tests/hard_cases/`; this test
//! keeps the corpora and the harnesses building and passing without nightly.

use folio_tests::Rng;
use folio_tests::fuzz::{TARGETS, corpus, sweep_input};

/// The harness of `target`.
fn harness(target: &str) -> folio_tests::fuzz::Harness {
    TARGETS
        .iter()
        .find(|(name, _)| *name == target)
        .map(|&(_, run)| run)
        .expect("a fuzz target")
}

/// Runs every corpus file of `target`, then `random` inputs of up to `len` random bytes,
/// each also as a mutation (a few bytes changed) of a corpus file; returns the inputs run.
fn replay(target: &str, random: usize, len: usize) -> usize {
    let run = harness(target);
    let files = corpus(target);
    assert!(files.len() >= 3, "{target}: a seed corpus of a few files");
    let seeds: Vec<Vec<u8>> = files
        .iter()
        .map(|f| std::fs::read(f).expect("readable"))
        .collect();
    for (file, data) in files.iter().zip(&seeds) {
        eprintln!("{target}: {}", file.display());
        run(data);
    }
    let mut rng = Rng::new(0x00f0_220f_0220);
    for k in 0..random {
        let data = sweep_input(&mut rng, k, &seeds, len);
        run(&data);
    }
    seeds.len() + random
}

#[test]
fn kernels_corpus_and_random_inputs() {
    assert!(replay("kernels", 20_000, 96) > 20_000);
}

#[test]
fn ldlt_corpus_and_random_inputs() {
    assert!(replay("ldlt", 3_000, 160) > 3_000);
}

#[test]
fn scene_corpus_and_random_inputs() {
    assert!(replay("scene", 400, 256) > 400);
}

#[test]
fn book_corpus_and_random_inputs() {
    assert!(replay("book", 12, 64) > 12);
}

#[test]
fn tearing_corpus_and_random_inputs() {
    assert!(replay("tearing", 600, 128) > 600);
}

#[test]
fn capi_corpus_and_random_inputs() {
    assert!(replay("capi", 12, 96) > 12);
}

/// Every harness accepts the empty input and a short one (missing bytes read as zero).
#[test]
fn every_harness_takes_short_inputs() {
    for (_, run) in TARGETS {
        run(&[]);
        run(&[7]);
    }
}
