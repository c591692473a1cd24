//! The one math shim. Every kernel calls `math::sqrt`, `math::sin`, ... and never a
//! method such as `x.sqrt()`, so the backend is chosen here and only here:
//! the platform libm through `std` with the `std` feature, the pure-Rust `libm` crate
//! without it (Cortex-M, wasm).

use crate::real::{Real, sealed::Sealed};

/// Square root, $\sqrt{x}$.
#[inline(always)]
#[must_use]
pub fn sqrt<T: Real>(x: T) -> T {
    x.sqrt_impl()
}

/// Sine (radians).
#[inline(always)]
#[must_use]
pub fn sin<T: Real>(x: T) -> T {
    x.sin_impl()
}

/// Cosine (radians).
#[inline(always)]
#[must_use]
pub fn cos<T: Real>(x: T) -> T {
    x.cos_impl()
}

/// Four-quadrant arctangent of `y / x` in $(-\pi, \pi]$; `atan2(0, 0) = 0`.
#[inline(always)]
#[must_use]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    y.atan2_impl(x)
}

/// Arcsine in $[-\pi/2, \pi/2]$ (NaN outside $[-1, 1]$).
#[inline(always)]
#[must_use]
pub fn asin<T: Real>(x: T) -> T {
    x.asin_impl()
}

/// Absolute value.
#[inline(always)]
#[must_use]
pub fn abs<T: Real>(x: T) -> T {
    x.abs_impl()
}

/// Largest integer not above `x`, $\lfloor x \rfloor$ (NaN and infinities pass through).
#[inline(always)]
#[must_use]
pub fn floor<T: Real>(x: T) -> T {
    by_precision(x, floor_f32, floor_f64)
}

/// Exponential $e^x$ (0 for $x \to -\infty$, $+\infty$ on overflow).
#[inline(always)]
#[must_use]
pub fn exp<T: Real>(x: T) -> T {
    by_precision(x, exp_f32, exp_f64)
}

/// Applies the `f32` or the `f64` backend function to `x`, whichever `T` is. [`Real`] is
/// sealed to exactly these two types, told apart by their machine epsilon (a constant, so
/// the branch folds away); the conversions between `T` and the chosen type are exact.
/// (Used by shims added after the sealed backend trait, which lives in `real.rs`.)
#[inline(always)]
fn by_precision<T: Real>(x: T, single: fn(f32) -> f32, double: fn(f64) -> f64) -> T {
    if T::EPSILON.to_f64() == f64::from(f32::EPSILON) {
        T::from_f64(f64::from(single(x.to_f64() as f32)))
    } else {
        T::from_f64(double(x.to_f64()))
    }
}

macro_rules! backend_fn {
    ($name:ident, $t:ident, $method:ident, $libm:ident) => {
        #[inline(always)]
        fn $name(x: $t) -> $t {
            #[cfg(feature = "std")]
            {
                $t::$method(x)
            }
            #[cfg(not(feature = "std"))]
            {
                libm::$libm(x)
            }
        }
    };
}

backend_fn!(floor_f32, f32, floor, floorf);
backend_fn!(floor_f64, f64, floor, floor);
backend_fn!(exp_f32, f32, exp, expf);
backend_fn!(exp_f64, f64, exp, exp);

/// Euclidean length $\lVert v \rVert = \sqrt{v \cdot v}$.
#[inline(always)]
#[must_use]
pub fn length<T: Real>(v: T::Vec3) -> T {
    use crate::real::Vec3Ops;
    sqrt(v.dot(v))
}

macro_rules! backend {
    ($t:ident, $sqrt:ident, $sin:ident, $cos:ident, $atan2:ident, $asin:ident, $fabs:ident) => {
        impl Sealed for $t {
            #[inline(always)]
            fn sqrt_impl(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::sqrt(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$sqrt(self)
                }
            }
            #[inline(always)]
            fn sin_impl(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::sin(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$sin(self)
                }
            }
            #[inline(always)]
            fn cos_impl(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::cos(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$cos(self)
                }
            }
            #[inline(always)]
            fn atan2_impl(self, x: Self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::atan2(self, x)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$atan2(self, x)
                }
            }
            #[inline(always)]
            fn asin_impl(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::asin(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$asin(self)
                }
            }
            #[inline(always)]
            fn abs_impl(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $t::abs(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$fabs(self)
                }
            }
            const SIN_POLY: &'static [Self] = poly::$t::SIN;
            const COS_POLY: &'static [Self] = poly::$t::COS;
            const ATAN_POLY: &'static [Self] = poly::$t::ATAN;
            const PI_SPLIT: [Self; 3] = poly::$t::PI_SPLIT;
            const ROUND_MAGIC: Self = poly::$t::ROUND_MAGIC;
        }
    };
}

backend!(f32, sqrtf, sinf, cosf, atan2f, asinf, fabsf);
backend!(f64, sqrt, sin, cos, atan2, asin, fabs);

/// Polynomial coefficients for [`crate::lanes`], lowest order first. Each set is a
/// Chebyshev fit (in $u = r^2$) computed for Folio with 50-digit arithmetic; the fitting
/// error is below the precision's rounding (see `lanes` tests for measured accuracy).
mod poly {
    #[allow(clippy::excessive_precision)]
    pub mod f64 {
        pub const SIN: &[f64] = &[
            -0.16666666666666666,
            0.008333333333333316,
            -0.00019841269841254974,
            2.7557319219163234e-06,
            -2.5052107616996182e-08,
            1.6058977312464087e-10,
            -7.643970296798572e-13,
            2.7314447669863995e-15,
        ];
        pub const COS: &[f64] = &[
            -0.5,
            0.04166666666666634,
            -0.0013888888888860709,
            2.4801587292446213e-05,
            -2.755731776732053e-07,
            2.0876630867422994e-09,
            -1.1464689885720029e-11,
            4.6276759850181716e-14,
        ];
        pub const ATAN: &[f64] = &[
            -0.3333333333333333,
            0.1999999999999552,
            -0.14285714284666542,
            0.11111111015256361,
            -0.09090904578123903,
            0.07692183190826087,
            -0.06664511447381948,
            0.0585814891280221,
            -0.0508544973794026,
            0.03923165829558719,
            -0.01917688711906226,
        ];
        /// 32 + 32 + 53 bits of pi.
        pub const PI_SPLIT: [f64; 3] = [
            3.1415926534682512,
            1.2154201012607932e-10,
            4.044532497591901e-21,
        ];
        pub const ROUND_MAGIC: f64 = 6755399441055744.0;
    }
    #[allow(clippy::excessive_precision)]
    pub mod f32 {
        pub const SIN: &[f32] = &[
            -0.1666666716337204,
            0.00833333283662796,
            -0.00019841086759697646,
            2.75364641311171e-06,
            -2.408019028621311e-08,
        ];
        pub const COS: &[f32] = &[
            -0.5,
            0.0416666604578495,
            -0.0013888651737943292,
            2.4774579287623055e-05,
            -2.62975163423107e-07,
        ];
        pub const ATAN: &[f32] = &[
            -0.3333333134651184,
            0.19999539852142334,
            -0.14263956248760223,
            0.10743731260299683,
            -0.06451927870512009,
        ];
        /// 10 + 10 + 24 bits of pi.
        pub const PI_SPLIT: [f32; 3] = [3.140625, 0.0009679794311523438, -3.2584136988589307e-07];
        pub const ROUND_MAGIC: f32 = 12582912.0;
    }
}

#[cfg(test)]
mod tests {
    use super::{exp, floor};

    #[test]
    fn floor_and_exp_in_both_precisions() {
        let cases: [(f64, f64); 5] = [
            (2.5, 2.0),
            (-2.5, -3.0),
            (-0.0, -0.0),
            (7.0, 7.0),
            (-1e-30, -1.0),
        ];
        for (x, f) in cases {
            assert_eq!(floor(x).to_bits(), f.to_bits());
            assert_eq!(floor(x as f32).to_bits(), (f as f32).to_bits());
        }
        assert!(floor(f64::NAN).is_nan() && floor(f32::INFINITY) == f32::INFINITY);
        assert_eq!(exp(0.0f64), 1.0);
        assert!((exp(1.0f64) - core::f64::consts::E).abs() < 4e-16);
        assert!((exp(1.0f32) - core::f32::consts::E).abs() < 3e-7);
        assert_eq!(exp(-1e3f64), 0.0);
        assert_eq!(exp(-1e3f32), 0.0);
        assert_eq!(exp(1e3f64), f64::INFINITY);
    }
}
