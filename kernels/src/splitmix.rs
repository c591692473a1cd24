//! SplitMix64 (Steele, Lea and Flood, *Fast splittable pseudorandom number generators*,
//! OOPSLA 2014): Folio's one seeded random source, for the tearing sheet's fiber texture,
//! the tests' random configurations and the benches' inputs, so that every seeded stream
//! is reproducible on every target. No allocation, no floating-point state.
//!
//! The state advances by the odd constant [`GAMMA`] ($\lfloor 2^{64}/\varphi \rfloor$) and
//! each output is the state through the bijective mix [`mix64`]; [`unit_interval`] maps 64
//! bits to $[0, 1)$.

/// The state increment, $\lfloor 2^{64}/\varphi \rfloor$ rounded to odd (the golden gamma).
pub const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output mix: a bijection of `u64` with good avalanche.
#[inline]
#[must_use]
pub const fn mix64(z: u64) -> u64 {
    let z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    let z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The top 53 bits of `h` as a number in $[0, 1)$: $\lfloor h / 2^{11} \rfloor / 2^{53}$
/// (exact: both steps are exact in `f64`).
#[inline]
#[must_use]
pub fn unit_interval(h: u64) -> f64 {
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// A SplitMix64 stream (module docs).
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The stream of `seed`.
    #[inline]
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(GAMMA);
        mix64(self.0)
    }

    /// Uniform in `[lo, hi)`: $lo + (hi - lo)\thinspace u$, $u$ the next [`unit_interval`].
    #[inline]
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = unit_interval(self.next_u64());
        lo + (hi - lo) * u
    }
}

#[cfg(test)]
mod tests {
    use super::{SplitMix64, unit_interval};

    #[test]
    fn reference_stream() {
        // The reference outputs of SplitMix64 for seed 1234567 (Vigna's splitmix64.c).
        let mut r = SplitMix64::new(1_234_567);
        let want = [
            6_457_827_717_110_365_317,
            3_203_168_211_198_807_973,
            9_817_491_932_198_370_423,
            4_593_380_528_125_082_431,
            16_408_922_859_458_223_821,
        ];
        for w in want {
            assert_eq!(r.next_u64(), w);
        }
    }

    #[test]
    fn unit_interval_bounds() {
        assert_eq!(unit_interval(0), 0.0);
        assert!(unit_interval(u64::MAX) < 1.0);
        let mut r = SplitMix64::new(7);
        for _ in 0..1000 {
            let x = r.uniform(-2.0, 3.0);
            assert!((-2.0..3.0).contains(&x));
        }
    }
}
