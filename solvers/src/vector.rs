//! Reductions over dense vectors shared by the solves: $u^\top v$, $\lVert v\rVert_2$ and
//! $\lVert v\rVert_\infty$.
//!
//! The sums use [`mul_add`], fused (one rounding per term) on aarch64 and plain elsewhere, so
//! x86 and the Cortex-M firmware keep their exact results.

use folio_kernels::Real;
use folio_kernels::fused::mul_add;
use folio_kernels::math;

/// $u^\top v = \sum_i u_i v_i$, summed in index order.
#[must_use]
#[inline]
pub fn dot<T: Real>(u: &[T], v: &[T]) -> T {
    u.iter()
        .zip(v)
        .fold(T::ZERO, |acc, (&a, &b)| mul_add(acc, a, b))
}

/// $\lVert v\rVert_2 = \sqrt{v^\top v}$ (no scaling against overflow: the solves' vectors are
/// equilibrated residuals and steps).
#[must_use]
#[inline]
pub fn norm2<T: Real>(v: &[T]) -> T {
    math::sqrt(dot(v, v))
}

/// $\lVert v\rVert_\infty$; NaN if any entry is NaN.
#[must_use]
pub fn max_abs<T: Real>(v: &[T]) -> T {
    let mut m = T::ZERO;
    for &x in v {
        if !x.is_finite() {
            return if x < T::ZERO { -x } else { x };
        }
        let a = if x < T::ZERO { -x } else { x };
        if a > m {
            m = a;
        }
    }
    m
}
