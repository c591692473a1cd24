//! The fuzz harnesses: one plain function per target, `fn(&[u8])`, that decodes the bytes
//! into a structured input ([`Input`]) and asserts the target's properties, panicking on a
//! violation.
//!
//! The same functions run under libFuzzer (the cargo-fuzz workspace in `fuzz/`, nightly)
//! and on stable: `tests/tests/fuzz_corpus.rs` replays the committed seed corpora
//! (`fuzz/corpus/<target>/`) and a seeded sweep of random inputs through them, so a
//! regression shows in `cargo test` without a fuzzer. Inputs are decoded by [`Input`]
//! rather than the `arbitrary` crate: the mapping from bytes to inputs is a few lines, has
//! no dependency, and a short or empty input still decodes (missing bytes read as zero).

pub mod book;
pub mod capi;
pub mod kernels;
pub mod ldlt;
pub mod scene;
pub mod tearing;

/// A harness: decodes the bytes and asserts, panicking on a violation.
pub type Harness = fn(&[u8]);

/// The fuzz targets by name (the file names in `fuzz/fuzz_targets/` and the corpus
/// folders) with their harnesses.
pub const TARGETS: [(&str, Harness); 6] = [
    ("kernels", kernels::run),
    ("ldlt", ldlt::run),
    ("scene", scene::run),
    ("book", book::run),
    ("tearing", tearing::run),
    ("capi", capi::run),
];

/// The committed seed corpus of `target` (`fuzz/corpus/<target>/`), its files in name order.
///
/// # Panics
/// When the folder cannot be read.
#[must_use]
pub fn corpus(target: &str) -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/corpus")
        .join(target);
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a corpus entry").path())
        .collect();
    files.sort();
    files
}

/// Input `k` of a seeded sweep: for even `k` (or no seeds) up to `len` random bytes, for odd
/// `k` a seed (in turn) with one to four bytes changed: the stable stand-in for a fuzzer's
/// exploring.
pub fn sweep_input(rng: &mut crate::Rng, k: usize, seeds: &[Vec<u8>], len: usize) -> Vec<u8> {
    if k % 2 == 0 || seeds.is_empty() {
        let n = (rng.next_u64() as usize) % (len + 1);
        return (0..n).map(|_| rng.next_u64() as u8).collect();
    }
    let mut data = seeds[k / 2 % seeds.len()].clone();
    for _ in 0..1 + rng.next_u64() % 4 {
        if !data.is_empty() {
            let at = (rng.next_u64() as usize) % data.len();
            data[at] = rng.next_u64() as u8;
        }
    }
    data
}

/// A reader of structured values from fuzz bytes; past the end every read is zero.
#[derive(Clone, Debug)]
pub struct Input<'a> {
    data: &'a [u8],
}

impl<'a> Input<'a> {
    /// A reader over `data`.
    #[must_use]
    pub fn new(data: &'a [u8]) -> Self {
        Self { data }
    }

    /// Whether every byte was read.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The bytes not read yet, consumed.
    pub fn rest(&mut self) -> &'a [u8] {
        core::mem::take(&mut self.data)
    }

    /// The next byte (0 past the end).
    pub fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    /// The next two bytes, little-endian.
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.byte(), self.byte()])
    }

    /// A choice in `0..n` (`n >= 1`): one byte for `n <= 256`, two beyond.
    pub fn below(&mut self, n: usize) -> usize {
        if n <= 256 {
            usize::from(self.byte()) % n
        } else {
            usize::from(self.u16()) % n
        }
    }

    /// A flag.
    pub fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// Uniform in `[0, 1]` at a resolution of $2^{-16}$.
    pub fn unit(&mut self) -> f64 {
        f64::from(self.u16()) / f64::from(u16::MAX)
    }

    /// Uniform in `[lo, hi]`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Log-uniform in `[lo, hi]` (`0 < lo <= hi`).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }

    /// A signed value of magnitude log-uniform in `[tiny, max]`, or exactly zero (one in
    /// sixteen): every scale from rounding level to the largest allowed.
    pub fn signed(&mut self, tiny: f64, max: f64) -> f64 {
        let head = self.byte();
        if head % 16 == 0 {
            return 0.0;
        }
        let magnitude = self.log_uniform(tiny, max);
        if head & 0x80 == 0 {
            magnitude
        } else {
            -magnitude
        }
    }
}
