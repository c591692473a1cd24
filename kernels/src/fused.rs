//! Multiply-add for the solvers' hot loops: fused on aarch64, plain elsewhere.
//!
//! Rust never contracts `acc + a * b` into a fused multiply-add by itself, so without help
//! an aarch64 build computes every update with a separate `fmul` and `fadd`. On aarch64
//! (NEON, part of its baseline) [`mul_add`] and [`mul_sub`] round once,
//! $\operatorname{fl}(acc \pm a b)$, through the NEON intrinsics `vfma_f64` / `vfms_f64`
//! (`vfma_f32` / `vfms_f32`): a sparse scatter or gather becomes a scalar `fmadd` /
//! `fmsub`, and a loop over contiguous slices becomes vector `fmla` / `fmls` (2 `f64` or 4
//! `f32` lanes). Everywhere else they are exactly `acc + a * b` and `acc - a * b`: x86-64's
//! baseline has no FMA (`f64::mul_add` would be a libm call there), and the Cortex-M
//! firmware keeps its figures, so results there stay bit for bit what the plain code gave.
//! On aarch64 they differ from the plain code by the one rounding saved per update.

use crate::real::Real;

/// $acc + a\,b$, fused (one rounding) on aarch64, plain `acc + a * b` elsewhere.
#[inline(always)]
#[must_use]
pub fn mul_add<T: Real>(acc: T, a: T, b: T) -> T {
    #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
    {
        by_precision(acc, a, b, neon::mul_add_f32, neon::mul_add_f64)
    }
    #[cfg(not(all(target_arch = "aarch64", target_feature = "neon")))]
    {
        acc + a * b
    }
}

/// $acc - a\,b$, fused (one rounding) on aarch64, plain `acc - a * b` elsewhere.
#[inline(always)]
#[must_use]
pub fn mul_sub<T: Real>(acc: T, a: T, b: T) -> T {
    #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
    {
        by_precision(acc, a, b, neon::mul_sub_f32, neon::mul_sub_f64)
    }
    #[cfg(not(all(target_arch = "aarch64", target_feature = "neon")))]
    {
        acc - a * b
    }
}

/// Applies the `f32` or the `f64` function to `(acc, a, b)`, whichever `T` is (told apart
/// by the machine epsilon, a constant, so the branch folds away; the conversions are exact
/// and fold away too).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[inline(always)]
fn by_precision<T: Real>(
    acc: T,
    a: T,
    b: T,
    single: fn(f32, f32, f32) -> f32,
    double: fn(f64, f64, f64) -> f64,
) -> T {
    if T::EPSILON.to_f64() == f64::from(f32::EPSILON) {
        let narrow = |x: T| x.to_f64() as f32;
        T::from_f64(f64::from(single(narrow(acc), narrow(a), narrow(b))))
    } else {
        T::from_f64(double(acc.to_f64(), a.to_f64(), b.to_f64()))
    }
}

/// The fused operations on one lane of a NEON register (the loop vectorizer widens them to
/// full-width `fmla` / `fmls` where the loop allows).
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
#[allow(unsafe_code)]
mod neon {
    use core::arch::aarch64::{
        vdup_n_f32, vdup_n_f64, vfma_f32, vfma_f64, vfms_f32, vfms_f64, vget_lane_f32,
        vget_lane_f64,
    };

    /// `$name(acc, a, b)` = `acc ± a * b` with one rounding, on lane 0 of a 64-bit register.
    macro_rules! lane_fn {
        ($name:ident, $t:ty, $dup:ident, $op:ident, $get:ident) => {
            #[inline(always)]
            pub(super) fn $name(acc: $t, a: $t, b: $t) -> $t {
                // SAFETY: the intrinsics only require NEON, which this module is compiled with.
                unsafe { $get::<0>($op($dup(acc), $dup(a), $dup(b))) }
            }
        };
    }

    lane_fn!(mul_add_f64, f64, vdup_n_f64, vfma_f64, vget_lane_f64);
    lane_fn!(mul_sub_f64, f64, vdup_n_f64, vfms_f64, vget_lane_f64);
    lane_fn!(mul_add_f32, f32, vdup_n_f32, vfma_f32, vget_lane_f32);
    lane_fn!(mul_sub_f32, f32, vdup_n_f32, vfms_f32, vget_lane_f32);
}

#[cfg(test)]
mod tests {
    use super::{mul_add, mul_sub};

    /// With $a = 1 + 2^{-p}$ ($p$ mantissa bits), $a^2 = 1 + 2^{1-p} + 2^{-2p}$: the plain
    /// product rounds the last term away, the fused operation keeps it. So
    /// $a \cdot a - (1 + 2^{1-p})$ is $2^{-2p}$ fused and 0 plain, and the fused form is
    /// taken exactly on aarch64.
    #[test]
    fn fused_exactly_on_aarch64() {
        let fused = cfg!(all(target_arch = "aarch64", target_feature = "neon"));
        let a = 1.0 + f64::EPSILON;
        let tail = f64::EPSILON * f64::EPSILON;
        let want = if fused { tail } else { 0.0 };
        assert_eq!(mul_add(-(1.0 + 2.0 * f64::EPSILON), a, a), want);
        assert_eq!(mul_sub(1.0 + 2.0 * f64::EPSILON, a, a), -want);
        let a = 1.0 + f32::EPSILON;
        let tail = f32::EPSILON * f32::EPSILON;
        let want = if fused { tail } else { 0.0 };
        assert_eq!(mul_add(-(1.0 + 2.0 * f32::EPSILON), a, a), want);
        assert_eq!(mul_sub(1.0 + 2.0 * f32::EPSILON, a, a), -want);
    }

    /// Where nothing rounds, fused and plain agree: $3 + 2 \cdot 5$ and $3 - 2 \cdot 5$.
    #[test]
    fn exact_cases() {
        assert_eq!(mul_add(3.0_f64, 2.0, 5.0), 13.0);
        assert_eq!(mul_sub(3.0_f64, 2.0, 5.0), -7.0);
        assert_eq!(mul_add(3.0_f32, 2.0, 5.0), 13.0);
        assert_eq!(mul_sub(3.0_f32, 2.0, 5.0), -7.0);
    }
}
