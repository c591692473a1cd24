//! Branch-free elementary functions for batched kernels.
//!
//! A loop that calls libm cannot be vectorized; these functions use only `+ - * /`,
//! comparisons and selects, so a loop over slices that inlines them becomes SIMD code
//! (SSE2/AVX on x86-64, NEON on aarch64). They serve [`crate::cone`]'s batched map.
//!
//! Accuracy, measured by this module's tests against the math shim (absolute error, which
//! is what positions need): `sin_cos` over $|x| \le 10^4\pi$ 3.1e-16 (`f64`) and 1.3e-7
//! (`f32`), both under 4 machine epsilons; `atan2` likewise under 4 epsilons.

use crate::real::Real;

/// `if c { a } else { b }` written so that it lowers to a select.
#[inline(always)]
fn select<T: Real>(c: bool, a: T, b: T) -> T {
    if c { a } else { b }
}

/// $|x|$ without a library call.
#[inline(always)]
fn abs<T: Real>(x: T) -> T {
    select(x < T::ZERO, -x, x)
}

/// Nearest integer (ties to even) of `x`, valid for $|x| < 2^{22}$ (`f32`) or
/// $2^{51}$ (`f64`): adding and subtracting $1.5 \cdot 2^{p}$ drops the fraction bits.
#[inline(always)]
fn round<T: Real>(x: T) -> T {
    (x + T::ROUND_MAGIC) - T::ROUND_MAGIC
}

/// Horner evaluation of $\sum_k c_k u^k$.
#[inline(always)]
fn horner<T: Real>(coeffs: &[T], u: T) -> T {
    let mut acc = T::ZERO;
    for &c in coeffs.iter().rev() {
        acc = acc * u + c;
    }
    acc
}

/// $(\sin x, \cos x)$, branch-free.
///
/// Reduction $x = k\pi + r$, $|r| \le \pi/2$ (Cody-Waite with a three-part $\pi$), then
/// $\sin r = r + r^3 P(r^2)$, $\cos r = 1 + r^2 Q(r^2)$ and both signs flipped for odd $k$.
/// Valid for $|x| \le 10^4 \pi$ (the range the cone map uses); beyond it the reduction
/// loses accuracy but stays finite for finite `x`.
#[inline(always)]
#[must_use]
pub fn sin_cos<T: Real>(x: T) -> (T, T) {
    let inv_pi = T::ONE / T::PI;
    let k = round(x * inv_pi);
    let [pa, pb, pc] = T::PI_SPLIT;
    let r = ((x - k * pa) - k * pb) - k * pc;
    let u = r * r;
    let s = r + r * u * horner(T::SIN_POLY, u);
    let c = T::ONE + u * horner(T::COS_POLY, u);
    // floor(k / 2) for integral k, then parity k - 2 floor(k / 2) in {0, 1}.
    let half = round(k * T::HALF - T::from_f64(0.25));
    let odd = (k - T::TWO * half) > T::HALF;
    (select(odd, -s, s), select(odd, -c, c))
}

/// Four-quadrant $\operatorname{atan2}(y, x) \in [-\pi, \pi]$, branch-free; `atan2(0, 0) = 0`.
///
/// With $t = \min(|x|,|y|)/\max(|x|,|y|) \in [0, 1]$, reduced once more by
/// $\arctan t = \pi/4 + \arctan\frac{t-1}{t+1}$ when $t > \tan(\pi/8)$, then
/// $\arctan t = t + t^3 A(t^2)$ and the octant/quadrant undone by selects.
#[inline(always)]
#[must_use]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    let ax = abs(x);
    let ay = abs(y);
    let swap = ay > ax;
    let hi = select(swap, ay, ax);
    let lo = select(swap, ax, ay);
    // t = lo/hi, and (t - 1)/(t + 1) = (lo - hi)/(lo + hi): one division either way.
    let big = lo > T::from_f64(0.414_213_562_373_095_03) * hi;
    let num = select(big, lo - hi, lo);
    // `hi == 0` only when both are zero (then num = 0 and t = 0); NaN propagates.
    let den = select(hi == T::ZERO, T::ONE, select(big, lo + hi, hi));
    let t = num / den;
    let u = t * t;
    let mut a = t + t * u * horner(T::ATAN_POLY, u);
    a = select(big, a + T::FRAC_PI_4, a);
    a = select(swap, T::FRAC_PI_2 - a, a);
    a = select(x < T::ZERO, T::PI - a, a);
    select(y < T::ZERO, -a, a)
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::math;

    /// Worst absolute error of `sin_cos` against the math shim over |x| <= 10^4 pi.
    fn sin_cos_error<T: Real>() -> f64 {
        let mut worst: f64 = 0.0;
        let n = 20000;
        for i in 0..=n {
            // Dense near zero, sparse far out.
            let s = (i as f64 / n as f64) * 2.0 - 1.0;
            let x = T::from_f64(s * s * s * 1.0e4 * core::f64::consts::PI);
            let (sl, cl) = sin_cos(x);
            let (sr, cr) = (math::sin(x).to_f64(), math::cos(x).to_f64());
            worst = worst
                .max((sl.to_f64() - sr).abs())
                .max((cl.to_f64() - cr).abs());
        }
        worst
    }

    #[test]
    fn sin_cos_matches_libm() {
        let (e64, e32) = (sin_cos_error::<f64>(), sin_cos_error::<f32>());
        std::println!("sin_cos worst abs error: f64 {e64:e}, f32 {e32:e}");
        assert!(e64 <= 4.0 * f64::EPSILON, "f64 sin_cos error {e64:e}");
        assert!(
            e32 <= 4.0 * f64::from(f32::EPSILON),
            "f32 sin_cos error {e32:e}"
        );
    }

    fn check_atan2<T: Real>() {
        let mut worst: f64 = 0.0;
        for i in 0..200 {
            for j in 0..200 {
                let y = T::from_f64((i as f64 - 100.0) * 0.173);
                let x = T::from_f64((j as f64 - 100.0) * 0.219);
                let err = (atan2(y, x).to_f64() - math::atan2(y, x).to_f64()).abs();
                worst = worst.max(err);
            }
        }
        std::println!(
            "atan2 worst abs error ({}): {worst:e}",
            core::any::type_name::<T>()
        );
        assert!(worst <= 4.0 * T::EPSILON.to_f64(), "atan2 worst {worst:e}");
        assert_eq!(atan2(T::ZERO, T::ZERO), T::ZERO);
    }

    #[test]
    fn atan2_matches_libm() {
        check_atan2::<f64>();
        check_atan2::<f32>();
    }

    #[test]
    fn nan_propagates() {
        assert!(sin_cos(f64::NAN).0.is_nan());
        assert!(atan2(f64::NAN, 1.0).is_nan());
        assert!(atan2(1.0_f32, f32::NAN).is_nan());
    }
}
