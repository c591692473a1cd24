//! [`FiberTexture`]: the paper's fiber texture $T_{\text{fibers}}(u, v) \in [0, 1]$ of
//! seed `002_…` Sec. 4.2, the resistance of the fiber network that scales the fracture energy
//! (eq. 3, $E_f(p) = c\thinspace T_{\text{fibers}}(u, v)\thinspace d_p$) and drives the detail path (eq. 7).
//!
//! The seed uses "a Perlin noise"; this one is Folio's own seeded gradient noise:
//!
//! - **Lattice gradients** from a hash: corner $(i, j)$ of octave $k$ takes one of 16 unit
//!   vectors at angles $m\pi/8$, $m$ the top four bits of the SplitMix64 mix ([`mix64`]) of
//!   $(\text{seed}_k, i, j)$. No permutation table.
//! - **Gradient noise** $n(x, y) = \mathrm{lerp}\_{f(y_f)}\big(\mathrm{lerp}\_{f(x_f)}(g_{00}
//!   \cdot r_{00}, g_{10} \cdot r_{10}), \mathrm{lerp}\_{f(x_f)}(g_{01} \cdot r_{01}, g_{11}
//!   \cdot r_{11})\big)$ with $r_{ab}$ the offset from corner $ab$ of the cell and the quintic
//!   fade $f(t) = 6t^5 - 15t^4 + 10t^3$, so $n$ is $C^2$ and $|n| \le \sqrt{2}/2$.
//! - **Anisotropy**: pattern coordinates are rotated into the fiber frame ($s$ along the
//!   fibers at angle `direction` from the $u$ axis, $t$ across) and scaled,
//!   $x = s / (\text{scale} \cdot \text{aspect})$, $y = t / \text{scale}$: lattice cells are
//!   `scale` sheet units across the fibers and `aspect` times longer along them.
//! - **fBm**: $N(x, y) = \sum_{k<K} g^k\thinspace n_k(\ell^k x + o_k, \ell^k y + o_k') \thinspace/\thinspace \sum_{k<K}
//!   g^k$ with gain $g$, lacunarity $\ell$ and per-octave seeds and offsets $o_k, o_k' \in
//!   [0, 1)$, so $|N| \le \sqrt{2}/2$.
//! - **Mapping to $[0, 1]$**: $T = \tfrac12 + \tfrac12\thinspace \mathrm{clamp}(c \sqrt{2}\thinspace N, -1,
//!   1)$ with the contrast $c$. At $c = 1$ the map is affine and never clamps; larger $c$
//!   spreads the values and saturates the tails at 0 and 1.
//!
//! Units: $u, v$ and `scale` in sheet units (Folio's page units). Deterministic: the same
//! settings give the same bits on every target.

use folio_kernels::math;
use folio_kernels::splitmix::{GAMMA, mix64, unit_interval};

use folio_kernels::setting::{SettingError, require_range};

/// Most octaves [`FiberSettings::octaves`] accepts.
pub const MAX_OCTAVES: u32 = 12;

/// What [`FiberTexture::value`] returns for a non-finite coordinate: 1, the strongest fibers
/// (a point nowhere on the sheet never starts a tear and the detail path avoids it).
pub const NON_FINITE_VALUE: f64 = 1.0;

/// Settings of [`FiberTexture`] (module docs for the formulas).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FiberSettings {
    /// Seed of the lattice gradients; any value.
    pub seed: u64,
    /// Lattice cell size of the first octave across the fibers, sheet units, in
    /// $[10^{-6}, 10^6]$. Default 0.05 (about 0.9 mm on a 21 cm page 12 units wide).
    pub scale: f64,
    /// Number of octaves $K$, in `1..=`[`MAX_OCTAVES`]. Default 4.
    pub octaves: u32,
    /// Cell length along the fibers over cell length across, in $[1, 64]$; 1 is isotropic.
    /// Default 4.
    pub aspect: f64,
    /// Fiber direction, radians counter-clockwise from the pattern's $u$ axis, $|\cdot| \le
    /// 10^3$. Default 0 (fibers along $u$).
    pub direction: f64,
    /// Frequency ratio $\ell$ of successive octaves, in $[1.5, 4]$. Default 2.
    pub lacunarity: f64,
    /// Amplitude ratio $g$ of successive octaves, in $[0.05, 1]$. Default 0.5.
    pub gain: f64,
    /// Contrast $c$ of the map to $[0, 1]$, in $[0.1, 16]$. Default 2.
    pub contrast: f64,
}

impl Default for FiberSettings {
    fn default() -> Self {
        Self {
            seed: 0x5EED_F1BE,
            scale: 0.05,
            octaves: 4,
            aspect: 4.0,
            direction: 0.0,
            lacunarity: 2.0,
            gain: 0.5,
            contrast: 2.0,
        }
    }
}

impl FiberSettings {
    /// Checks every field against its documented range.
    ///
    /// # Errors
    /// The first field out of its range (`scale`, ...), the range and the value.
    pub fn validate(&self) -> Result<(), SettingError> {
        require_range("scale", self.scale, 1e-6, 1e6)?;
        require_range(
            "octaves",
            f64::from(self.octaves),
            1.0,
            f64::from(MAX_OCTAVES),
        )?;
        require_range("aspect", self.aspect, 1.0, 64.0)?;
        require_range("direction", self.direction, -1e3, 1e3)?;
        require_range("lacunarity", self.lacunarity, 1.5, 4.0)?;
        require_range("gain", self.gain, 0.05, 1.0)?;
        require_range("contrast", self.contrast, 0.1, 16.0)
    }
}

/// The fiber texture $T_{\text{fibers}}(u, v) \in [0, 1]$ (seed `002_…` Sec. 4.2, eq. 3),
/// built once from validated [`FiberSettings`]; evaluation is allocation-free and total.
#[derive(Clone, Debug, PartialEq)]
pub struct FiberTexture {
    settings: FiberSettings,
    /// $\cos$ and $\sin$ of the fiber direction.
    along: [f64; 2],
    /// $1 / (\text{scale} \cdot \text{aspect})$ and $1 / \text{scale}$, lattice cells per
    /// sheet unit along and across the fibers.
    inv_cell: [f64; 2],
    /// $1 / \sum_k g^k$.
    inv_amplitude_sum: f64,
    /// Per-octave seed and lattice offsets $(o_k, o'_k)$.
    octaves: [Octave; MAX_OCTAVES as usize],
}

/// One octave's seed and lattice offset.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
struct Octave {
    seed: u64,
    offset: [f64; 2],
}

impl FiberTexture {
    /// The texture of `settings`.
    ///
    /// # Errors
    /// As [`FiberSettings::validate`].
    pub fn new(settings: FiberSettings) -> Result<Self, SettingError> {
        settings.validate()?;
        let mut octaves = [Octave::default(); MAX_OCTAVES as usize];
        let mut amplitude = 1.0;
        let mut amplitude_sum = 0.0;
        let mut state = settings.seed;
        for (k, octave) in octaves.iter_mut().enumerate() {
            state = mix64(state ^ mix64(k as u64 + 1));
            let ox = unit_interval(mix64(state ^ 0x0FF5_E7A0));
            let oy = unit_interval(mix64(state ^ 0x0FF5_E7A1));
            *octave = Octave {
                seed: state,
                offset: [ox, oy],
            };
            if (k as u32) < settings.octaves {
                amplitude_sum += amplitude;
                amplitude *= settings.gain;
            }
        }
        Ok(Self {
            settings,
            along: [math::cos(settings.direction), math::sin(settings.direction)],
            inv_cell: [
                1.0 / (settings.scale * settings.aspect),
                1.0 / settings.scale,
            ],
            inv_amplitude_sum: 1.0 / amplitude_sum,
            octaves,
        })
    }

    /// The settings this texture was built from.
    #[inline]
    #[must_use]
    pub fn settings(&self) -> &FiberSettings {
        &self.settings
    }

    /// $T_{\text{fibers}}(u, v) \in [0, 1]$ at pattern point $(u, v)$ (sheet units): finite
    /// and in $[0, 1]$ for every finite input; [`NON_FINITE_VALUE`] if $u$ or $v$ is not
    /// finite. Continuous ($C^2$ where the contrast does not clamp).
    #[must_use]
    pub fn value(&self, u: f64, v: f64) -> f64 {
        if !(u.is_finite() && v.is_finite()) {
            return NON_FINITE_VALUE;
        }
        let n = self.noise(u, v);
        let t = 0.5
            + 0.5
                * clamp(
                    self.settings.contrast * core::f64::consts::SQRT_2 * n,
                    -1.0,
                    1.0,
                );
        if t.is_finite() { t } else { NON_FINITE_VALUE }
    }

    /// The fBm $N(u, v) \in [-\sqrt{2}/2, \sqrt{2}/2]$ before the map to $[0, 1]$. An octave
    /// whose lattice coordinate is not finite or exceeds $2^{52}$ contributes 0, so
    /// non-finite input gives 0.
    #[must_use]
    pub fn noise(&self, u: f64, v: f64) -> f64 {
        let [c, s] = self.along;
        let x = (c * u + s * v) * self.inv_cell[0];
        let y = (-s * u + c * v) * self.inv_cell[1];
        let mut sum = 0.0;
        let mut amplitude = 1.0;
        let mut frequency = 1.0;
        for octave in self.octaves.iter().take(self.settings.octaves as usize) {
            sum += amplitude
                * gradient_noise(
                    octave.seed,
                    x * frequency + octave.offset[0],
                    y * frequency + octave.offset[1],
                );
            amplitude *= self.settings.gain;
            frequency *= self.settings.lacunarity;
        }
        sum * self.inv_amplitude_sum
    }
}

/// `lo` if `x < lo`, `hi` if `x > hi`, else `x` (NaN gives `lo`).
#[inline]
#[must_use]
fn clamp(x: f64, lo: f64, hi: f64) -> f64 {
    if x > hi {
        hi
    } else if x >= lo {
        x
    } else {
        lo
    }
}

/// Hash of lattice corner $(i, j)$ under `seed`.
#[inline]
#[must_use]
fn corner_hash(seed: u64, i: i64, j: i64) -> u64 {
    mix64(seed ^ mix64((i as u64).wrapping_mul(GAMMA) ^ mix64((j as u64).wrapping_add(GAMMA))))
}

/// $\cos(\pi/8)$ and $\sin(\pi/8)$.
const C8: f64 = 0.923_879_532_511_286_7;
const S8: f64 = 0.382_683_432_365_089_8;
const H2: f64 = core::f64::consts::FRAC_1_SQRT_2;

/// The 16 unit gradients $(\cos m\pi/8, \sin m\pi/8)$, $m = 0, \dots, 15$.
const GRADIENTS: [[f64; 2]; 16] = [
    [1.0, 0.0],
    [C8, S8],
    [H2, H2],
    [S8, C8],
    [0.0, 1.0],
    [-S8, C8],
    [-H2, H2],
    [-C8, S8],
    [-1.0, 0.0],
    [-C8, -S8],
    [-H2, -H2],
    [-S8, -C8],
    [0.0, -1.0],
    [S8, -C8],
    [H2, -H2],
    [C8, -S8],
];

/// $g \cdot (d_x, d_y)$ for the gradient picked by the top four bits of `hash`.
#[inline]
#[must_use]
fn corner_dot(hash: u64, dx: f64, dy: f64) -> f64 {
    // `hash >> 60` is in 0..16, so the lookup always succeeds.
    let [gx, gy] = GRADIENTS
        .get((hash >> 60) as usize)
        .copied()
        .unwrap_or([1.0, 0.0]);
    gx * dx + gy * dy
}

/// Quintic fade $f(t) = 6t^5 - 15t^4 + 10t^3$: $f(0) = 0$, $f(1) = 1$, $f' = f'' = 0$ at both.
#[inline]
#[must_use]
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Single-octave gradient noise $n(x, y) \in [-\sqrt{2}/2, \sqrt{2}/2]$ (lattice units); 0
/// where $|x|$ or $|y|$ is not below $2^{52}$ (or not finite), where the lattice has no
/// fractional part left.
#[must_use]
fn gradient_noise(seed: u64, x: f64, y: f64) -> f64 {
    const LIMIT: f64 = 4_503_599_627_370_496.0; // 2^52
    if !(math::abs(x) < LIMIT && math::abs(y) < LIMIT) {
        return 0.0;
    }
    let x0 = math::floor(x);
    let y0 = math::floor(y);
    let (dx, dy) = (x - x0, y - y0);
    let (i, j) = (x0 as i64, y0 as i64);
    let (i1, j1) = (i.wrapping_add(1), j.wrapping_add(1));
    let n00 = corner_dot(corner_hash(seed, i, j), dx, dy);
    let n10 = corner_dot(corner_hash(seed, i1, j), dx - 1.0, dy);
    let n01 = corner_dot(corner_hash(seed, i, j1), dx, dy - 1.0);
    let n11 = corner_dot(corner_hash(seed, i1, j1), dx - 1.0, dy - 1.0);
    let (sx, sy) = (fade(dx), fade(dy));
    let bottom = n00 + sx * (n10 - n00);
    let top = n01 + sx * (n11 - n01);
    bottom + sy * (top - bottom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    fn texture(seed: u64) -> FiberTexture {
        FiberTexture::new(FiberSettings {
            seed,
            ..FiberSettings::default()
        })
        .unwrap()
    }

    /// A deterministic dense sample of the unit square (and beyond) in sheet units.
    fn grid(n: usize, extent: f64) -> impl Iterator<Item = (f64, f64)> {
        (0..n).flat_map(move |i| {
            (0..n).map(move |j| {
                (
                    extent * (i as f64 + 0.37) / n as f64,
                    extent * (j as f64 + 0.61) / n as f64,
                )
            })
        })
    }

    #[test]
    fn same_seed_same_bits_and_seeds_differ() {
        let (a, b, c) = (texture(7), texture(7), texture(8));
        let mut differ = 0;
        for (u, v) in grid(64, 3.0) {
            assert_eq!(a.value(u, v).to_bits(), b.value(u, v).to_bits());
            if (a.value(u, v) - c.value(u, v)).abs() > 1e-3 {
                differ += 1;
            }
        }
        // Measured: seeds 7 and 8 differ by more than 1e-3 at 4074 of 4096 points.
        std::println!("seeds 7 and 8 differ at {differ} of 4096 points");
        assert!(differ > 3500, "only {differ} of 4096 points differ");
    }

    #[test]
    fn range_and_mean() {
        for seed in [0, 1, 0xDEAD_BEEF] {
            let t = texture(seed);
            let values: Vec<f64> = grid(200, 12.0).map(|(u, v)| t.value(u, v)).collect();
            assert!(values.iter().all(|x| (0.0..=1.0).contains(x)));
            let n = values.len() as f64;
            let mean = values.iter().sum::<f64>() / n;
            let var = values.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
            let std = var.sqrt();
            // Measured (seeds 0, 1, 0xDEADBEEF; 40 000 points on 12 x 12): mean 0.4984,
            // 0.5007, 0.4996; standard deviation 0.186 for all three.
            std::println!("seed {seed}: mean {mean:.4} std {std:.4}");
            assert!((mean - 0.5).abs() < 0.03, "mean {mean}");
            assert!(std > 0.12 && std < 0.3, "std {std}");
        }
    }

    #[test]
    fn contrast_one_never_clamps() {
        let t = FiberTexture::new(FiberSettings {
            contrast: 1.0,
            octaves: 1,
            ..FiberSettings::default()
        })
        .unwrap();
        let (lo, hi) = grid(300, 12.0).fold((1.0f64, 0.0f64), |(lo, hi), (u, v)| {
            let x = t.value(u, v);
            (lo.min(x), hi.max(x))
        });
        // Measured (one octave, 90 000 points): [0.030, 0.977].
        std::println!("contrast 1: range [{lo:.4}, {hi:.4}]");
        assert!(lo > 0.0 && hi < 1.0);
    }

    #[test]
    fn continuity() {
        let t = texture(3);
        let mut worst = [0.0f64; 2];
        for (u, v) in grid(60, 12.0) {
            for (k, h) in [1e-6, 0.5e-6].into_iter().enumerate() {
                let d = (t.value(u + h, v) - t.value(u, v))
                    .abs()
                    .max((t.value(u, v + h) - t.value(u, v)).abs());
                worst[k] = worst[k].max(d);
            }
        }
        // Measured: 6.0e-5 at h = 1e-6 and 3.0e-5 at h = 5e-7 (Lipschitz, slope ~60 per
        // sheet unit with cells of 0.05 and four octaves).
        std::println!("continuity: {:.3e} {:.3e}", worst[0], worst[1]);
        assert!(worst[0] < 1e-3);
        assert!(worst[1] < 0.6 * worst[0]);
    }

    /// Lag (sheet units) at which the autocorrelation of $T$ along `dir` first drops below
    /// 1/2, sampled at steps of `step`.
    fn correlation_length(t: &FiberTexture, dir: [f64; 2], step: f64) -> f64 {
        // R2 low-discrepancy points: starts at every phase of the lattice.
        let starts: Vec<(f64, f64)> = (0..12_000)
            .map(|k| {
                let k = f64::from(k);
                (
                    30.0 * (k * 0.754_877_666_246_692_8).fract(),
                    30.0 * (k * 0.569_840_290_998_053_2).fract(),
                )
            })
            .collect();
        let all: Vec<f64> = starts.iter().map(|&(u, v)| t.value(u, v)).collect();
        let mean = all.iter().sum::<f64>() / all.len() as f64;
        let var = all.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / all.len() as f64;
        for lag in 1..2000 {
            let l = lag as f64 * step;
            let cov = starts
                .iter()
                .map(|&(u, v)| {
                    (t.value(u, v) - mean) * (t.value(u + l * dir[0], v + l * dir[1]) - mean)
                })
                .sum::<f64>()
                / starts.len() as f64;
            if cov < 0.5 * var {
                return l;
            }
        }
        f64::INFINITY
    }

    #[test]
    fn anisotropy_follows_the_fiber_direction() {
        let direction = 0.6f64;
        let t = FiberTexture::new(FiberSettings {
            direction,
            aspect: 4.0,
            ..FiberSettings::default()
        })
        .unwrap();
        let along = [direction.cos(), direction.sin()];
        let across = [-direction.sin(), direction.cos()];
        let l_along = correlation_length(&t, along, 0.0005);
        let l_across = correlation_length(&t, across, 0.0005);
        let ratio = l_along / l_across;
        // Measured (12 000 starts): along 0.063, across 0.016, ratio 3.94 (the aspect, 4);
        // the same at directions 0, 1.2 and 2.5 (3.94 to 4.06). Isotropic: 0.97 to 1.00.
        std::println!("correlation length along {l_along} across {l_across} ratio {ratio}");
        assert!(ratio > 3.4 && ratio < 4.6, "ratio {ratio}");
        let iso = FiberTexture::new(FiberSettings {
            aspect: 1.0,
            ..FiberSettings::default()
        })
        .unwrap();
        let r_iso =
            correlation_length(&iso, along, 0.0005) / correlation_length(&iso, across, 0.0005);
        std::println!("isotropic ratio {r_iso}");
        assert!(r_iso > 0.85 && r_iso < 1.18, "isotropic ratio {r_iso}");
    }

    #[test]
    fn non_finite_and_huge_input() {
        let t = texture(1);
        assert_eq!(t.value(f64::NAN, 0.0), NON_FINITE_VALUE);
        assert_eq!(t.value(0.0, f64::INFINITY), NON_FINITE_VALUE);
        for x in [1e300, -1e300, f64::MAX, 1e15, -7e12] {
            let y = t.value(x, 0.3);
            assert!((0.0..=1.0).contains(&y), "{x} -> {y}");
        }
    }

    #[test]
    fn validate_names_the_field() {
        let bad = |s: FiberSettings| FiberTexture::new(s).unwrap_err().path.to_string();
        let d = FiberSettings::default();
        assert_eq!(bad(FiberSettings { scale: 0.0, ..d }), "scale");
        assert_eq!(bad(FiberSettings { octaves: 0, ..d }), "octaves");
        let nan = FiberSettings {
            aspect: f64::NAN,
            ..d
        };
        assert_eq!(bad(nan), "aspect");
        assert_eq!(bad(FiberSettings { gain: 2.0, ..d }), "gain");
        assert!(d.validate().is_ok());
    }

    #[test]
    fn gradient_noise_is_zero_on_the_lattice_and_bounded() {
        let mut worst = 0.0f64;
        for (x, y) in grid(300, 20.0) {
            worst = worst.max(gradient_noise(9, x - 10.0, y - 10.0).abs());
        }
        assert!(worst <= core::f64::consts::FRAC_1_SQRT_2 + 1e-12);
        assert_eq!(gradient_noise(9, 3.0, -2.0), 0.0);
    }
}
