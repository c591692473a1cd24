//! Key frames of a simulated page turn (seed `003_…` Sec. 2.2.3 and Sec. 3.1 step 7): every
//! key-frame interval the positions of all particles are recorded, and a repeat of the turn
//! interpolates between the recorded frames instead of simulating (the seed reports an 18 %
//! saving in time).
//!
//! **Timing.** Key frame $k$ holds the particles at frame $k s$ of the run, $s$ the interval
//! in whole frames ([`super::SpringSettings::key_frame_stride`]), i.e. at time
//! $t_k = k\thinspace s\thinspace h$.
//!
//! **Interpolation.** Linear between the bracketing key frames, the seed's "simple
//! interpolation": with $\Delta = s h$, $k = \lfloor t/\Delta\rfloor$ and
//! $\alpha = t/\Delta - k$,
//! $$x(t) \approx (1 - \alpha)\thinspace X_k + \alpha\thinspace X_{k+1},$$
//! exact at the key frames and in error by at most $\frac{\Delta^2}{8}\max\lVert\ddot x\rVert$
//! between them (the linear interpolation remainder). Catmull-Rom would have an
//! $O(\Delta^4)$ error on smooth motion but overshoots at the grab and the release, where the
//! particles' acceleration jumps; linear never leaves the segment between recorded states.
//! Before the first key frame the first is held, after the last the last.
//!
//! **Memory.** Allocated once at setup: `capacity` $\times$ particles $\times$
//! `size_of::<T::Vec3>()` bytes (16 for `f32`, 24 for `f64`): 100 key frames (10 s at 0.1 s)
//! of the book page's 108 particles take 173 kB in `f32`, of the seed's 36 particles 58 kB.

use folio_kernels::{Real, Vec3Ops};
use folio_solvers::Ring;

use crate::PageError;

/// A recording of particle positions at regular key frames (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct KeyFrames<T: Real> {
    stride: u32,
    time_step: T,
    dropped: usize,
    /// The key frames, one row of `particles` positions each (module docs, **Memory**).
    frames: Ring<T::Vec3>,
}

impl<T: Real> KeyFrames<T> {
    /// An empty recording of up to `capacity` key frames of `particles` particles, one key
    /// frame every `stride` frames (at least 1) of `time_step` seconds. Allocates
    /// `capacity * particles` vectors (module docs).
    #[must_use]
    pub fn with_capacity(particles: usize, stride: u32, time_step: T, capacity: usize) -> Self {
        Self {
            stride: stride.max(1),
            time_step,
            dropped: 0,
            frames: Ring::with_capacity(particles, capacity, T::Vec3::ZERO),
        }
    }

    /// Particles per key frame.
    #[must_use]
    pub fn particles(&self) -> usize {
        self.frames.width()
    }

    /// Frames between key frames, $s$.
    #[must_use]
    pub fn stride(&self) -> u32 {
        self.stride
    }

    /// Seconds between key frames, $\Delta = s h$.
    #[must_use]
    pub fn interval(&self) -> T {
        self.time_step * T::from_f64(f64::from(self.stride))
    }

    /// Key frames recorded.
    #[must_use]
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// `true` before the first key frame.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Key frames the recording can hold.
    #[must_use]
    pub fn capacity(&self) -> usize {
        self.frames.capacity()
    }

    /// Key frames refused because the recording was full.
    #[must_use]
    pub fn dropped(&self) -> usize {
        self.dropped
    }

    /// The time of the last key frame, $(n - 1)\Delta$ (0 when empty).
    #[must_use]
    pub fn duration(&self) -> T {
        self.interval() * T::from_f64(self.len().saturating_sub(1) as f64)
    }

    /// The frames run up to the last key frame, $(n - 1) s$.
    #[must_use]
    pub fn frames(&self) -> u64 {
        self.len().saturating_sub(1) as u64 * u64::from(self.stride)
    }

    /// Key frame `k`, if recorded.
    #[must_use]
    pub fn frame(&self, k: usize) -> Option<&[T::Vec3]> {
        self.frames.get(k)
    }

    /// Forgets every key frame (keeps the memory).
    pub fn clear(&mut self) {
        self.frames.clear();
        self.dropped = 0;
    }

    /// Appends a key frame; `false` (and nothing recorded) when full or when `x` does not
    /// hold one position per particle. Does not allocate.
    pub fn push(&mut self, x: &[T::Vec3]) -> bool {
        if x.len() != self.frames.width() {
            return false;
        }
        if self.frames.is_full() {
            self.dropped += 1;
            return false;
        }
        self.frames.push(x)
    }

    /// The positions at frame `frame` of the recorded run into `out` (module docs): key frame
    /// `frame / s` copied exactly when `frame` is a multiple of $s$, else the linear blend
    /// with $\alpha = (\text{frame} \bmod s)/s$; held at the ends.
    ///
    /// # Errors
    /// [`PageError::SampleCount`] unless `out` holds one position per particle;
    /// [`PageError::InvalidInput`] for an empty recording.
    pub fn replay_frame(&self, frame: u64, out: &mut [T::Vec3]) -> Result<(), PageError> {
        self.check(out)?;
        let stride = u64::from(self.stride);
        let k = frame / stride;
        let r = frame % stride;
        let alpha = T::from_f64(r as f64 / stride as f64);
        self.blend(k, alpha, out);
        Ok(())
    }

    /// The positions at time `t` (seconds from the first key frame) into `out`, linearly
    /// interpolated between the bracketing key frames (module docs); held at the ends.
    ///
    /// # Errors
    /// As [`KeyFrames::replay_frame`], and [`PageError::InvalidInput`] for a non-finite `t`.
    pub fn replay_at(&self, t: T, out: &mut [T::Vec3]) -> Result<(), PageError> {
        self.check(out)?;
        if !t.is_finite() {
            return Err(PageError::InvalidInput {
                what: "replay time (not finite)",
            });
        }
        let s = (t / self.interval()).to_f64();
        let last = self.len().saturating_sub(1);
        let (k, alpha) = if s.is_nan() || s <= 0.0 {
            (0, 0.0)
        } else if s >= last as f64 {
            (last as u64, 0.0)
        } else {
            let k = s as u64;
            (k, s - k as f64)
        };
        self.blend(k, T::from_f64(alpha), out);
        Ok(())
    }

    fn check(&self, out: &[T::Vec3]) -> Result<(), PageError> {
        crate::check_count(self.particles(), out.len())?;
        if self.is_empty() {
            return Err(PageError::InvalidInput {
                what: "replay of an empty recording",
            });
        }
        Ok(())
    }

    /// `out = (1 - alpha) X_k + alpha X_{k+1}`, with `k` clamped to the recording and an
    /// exact copy for `alpha == 0` or at the last key frame.
    fn blend(&self, k: u64, alpha: T, out: &mut [T::Vec3]) {
        let last = self.len().saturating_sub(1);
        let k = usize::try_from(k).unwrap_or(usize::MAX).min(last);
        let (Some(a), next) = (self.frame(k), self.frame(k + 1)) else {
            return;
        };
        match next {
            Some(b) if alpha != T::ZERO => {
                let beta = T::ONE - alpha;
                for ((o, &xa), &xb) in out.iter_mut().zip(a).zip(b) {
                    *o = xa * beta + xb * alpha;
                }
            }
            _ => out.copy_from_slice(a),
        }
    }
}
