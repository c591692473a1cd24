//! A seeded random walk through the whole C API with good and bad arguments, by the fuzz
//! target's own driver (`folio_tests::fuzz::capi::walk`, whose module docs list what every
//! call is held to: no panic, a known status, a message naming the function on failure and
//! none on success, finite reports and meshes). The fuzzer explores from the corpus; this
//! test walks a fixed set of random inputs on every run and asserts that the walk reaches
//! success and every kind of refusal a caller can provoke.

use folio_capi::FolioStatus;
use folio_tests::Rng;
use folio_tests::fuzz::capi::{StatusCounts, walk};
use folio_tests::fuzz::sweep_input;

/// Random inputs walked (each up to `fuzz::capi::MAX_CALLS` calls).
const WALKS: usize = 48;

#[test]
fn random_calls_never_panic_and_always_explain() {
    // `FOLIO_FUZZ_SEED=<n>` walks other inputs (a failure prints the seed it ran with).
    let seed = std::env::var("FOLIO_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(0x00f0_110c_a91e_2024);
    eprintln!("seed {seed}");
    let mut rng = Rng::new(seed);
    let mut counts: StatusCounts = [0; 16];
    for k in 0..WALKS {
        let data = sweep_input(&mut rng, 2 * k, &[], 512);
        for (total, n) in counts.iter_mut().zip(walk(&data)) {
            *total += n;
        }
    }
    eprintln!("statuses seen (by code): {counts:?}");
    for status in [
        FolioStatus::Ok,
        FolioStatus::NullPointer,
        FolioStatus::StaleHandle,
        FolioStatus::InvalidArgument,
        FolioStatus::BufferTooSmall,
        FolioStatus::NotHeld,
    ] {
        assert!(
            counts[status as usize] > 0,
            "{status:?} never seen: {counts:?}"
        );
    }
    assert!(counts[FolioStatus::Ok as usize] > 150, "{counts:?}");
}
