//! The sealed scalar trait [`Real`] (implemented for `f32` and `f64`) and the vector and
//! matrix operations Folio needs from glam's types.
//!
//! `f32` uses glam's 16-byte aligned `Vec3A` / `Mat3A` (SSE2 or NEON lanes where the target
//! has them, plain scalars on a Cortex-M); `f64` uses `DVec3` / `DMat3`.

use core::fmt::{Debug, Display};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

pub(crate) mod sealed {
    /// Seals [`super::Real`] and carries the math backend (see [`crate::math`]).
    pub trait Sealed: Sized + 'static {
        fn sqrt_impl(self) -> Self;
        fn sin_impl(self) -> Self;
        fn cos_impl(self) -> Self;
        fn atan2_impl(self, x: Self) -> Self;
        fn asin_impl(self) -> Self;
        fn abs_impl(self) -> Self;
        /// Coefficients of `sin(r)/r - 1 = r^2 P(r^2)` on `|r| <= pi/2`, lowest order first.
        const SIN_POLY: &'static [Self];
        /// Coefficients of `cos(r) - 1 = r^2 Q(r^2)` on `|r| <= pi/2`, lowest order first.
        const COS_POLY: &'static [Self];
        /// Coefficients of `atan(t)/t = A(t^2)` on `|t| <= tan(pi/8)`, lowest order first.
        const ATAN_POLY: &'static [Self];
        /// pi split into three parts for Cody-Waite range reduction; `k * PI_A` and
        /// `k * PI_B` are exact for the reduction counts the lane math allows.
        const PI_SPLIT: [Self; 3];
        /// `1.5 * 2^(mantissa bits)`: adding and subtracting it rounds to the nearest integer.
        const ROUND_MAGIC: Self;
    }
}

/// Operations on a 3-vector of [`Real`]s (glam's `Vec3A` for `f32`, `DVec3` for `f64`).
pub trait Vec3Ops<T>:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<T, Output = Self>
    + Div<T, Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign<T>
{
    /// `(0, 0, 0)`.
    const ZERO: Self;
    /// Unit vectors along X, Y, Z.
    const AXES: [Self; 3];
    /// `(x, y, z)`.
    fn new(x: T, y: T, z: T) -> Self;
    /// X component.
    fn x(self) -> T;
    /// Y component.
    fn y(self) -> T;
    /// Z component.
    fn z(self) -> T;
    /// Component `i` (0, 1, 2); any other index reads Z.
    fn get(self, i: usize) -> T;
    /// `self . other`.
    fn dot(self, other: Self) -> T;
    /// `self x other`.
    fn cross(self, other: Self) -> Self;
}

/// Operations on a 3x3 matrix of [`Real`]s (glam's `Mat3A` for `f32`, `DMat3` for `f64`).
pub trait Mat3Ops<T, V>:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<T, Output = Self>
    + Mul<V, Output = V>
    + Mul<Self, Output = Self>
    + AddAssign
    + SubAssign
{
    /// The zero matrix.
    const ZERO: Self;
    /// The identity.
    const IDENTITY: Self;
    /// The outer product `a b^T`.
    fn outer(a: V, b: V) -> Self;
    /// `diag(d)`.
    fn diagonal(d: V) -> Self;
    /// The transpose.
    fn transposed(self) -> Self;
    /// Entry at `row`, `col` (0-based; out-of-range indices read the last row/column).
    fn entry(self, row: usize, col: usize) -> T;
}

/// A floating-point scalar Folio computes in: `f32` (the microcontroller path) or `f64`
/// (the reference). Sealed: implemented for exactly these two types.
pub trait Real:
    sealed::Sealed
    + Copy
    + Debug
    + Display
    + Default
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// The 3-vector type.
    type Vec3: Vec3Ops<Self>;
    /// The 3x3 matrix type.
    type Mat3: Mat3Ops<Self, Self::Vec3>;
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// pi.
    const PI: Self;
    /// pi/2.
    const FRAC_PI_2: Self;
    /// pi/4.
    const FRAC_PI_4: Self;
    /// Machine epsilon.
    const EPSILON: Self;
    /// Largest finite value.
    const MAX: Self;
    /// Edges shorter than this (page units) are degenerate and take a term's documented
    /// fallback: `1e-150` for `f64`, `1e-15` for `f32`, so that `1/L^2` stays finite.
    const LENGTH_FLOOR: Self;
    /// Largest coordinate magnitude (page units) for which every kernel maps finite input to
    /// finite output: `1e60` for `f64`, `1e6` for `f32` (quartic terms such as iso3D must
    /// not overflow).
    const COORD_MAX: Self;
    /// Converts from `f64` (rounding for `f32`).
    fn from_f64(v: f64) -> Self;
    /// Converts to `f64` (exact).
    fn to_f64(self) -> f64;
    /// `true` unless NaN or infinite.
    fn is_finite(self) -> bool;
}

macro_rules! impl_vec3 {
    ($t:ty, $v:ty) => {
        impl Vec3Ops<$t> for $v {
            const ZERO: Self = <$v>::ZERO;
            const AXES: [Self; 3] = [<$v>::X, <$v>::Y, <$v>::Z];
            #[inline(always)]
            fn new(x: $t, y: $t, z: $t) -> Self {
                <$v>::new(x, y, z)
            }
            #[inline(always)]
            fn x(self) -> $t {
                self.x
            }
            #[inline(always)]
            fn y(self) -> $t {
                self.y
            }
            #[inline(always)]
            fn z(self) -> $t {
                self.z
            }
            #[inline(always)]
            fn get(self, i: usize) -> $t {
                match i {
                    0 => self.x,
                    1 => self.y,
                    _ => self.z,
                }
            }
            #[inline(always)]
            fn dot(self, other: Self) -> $t {
                <$v>::dot(self, other)
            }
            #[inline(always)]
            fn cross(self, other: Self) -> Self {
                <$v>::cross(self, other)
            }
        }
    };
}

macro_rules! impl_mat3 {
    ($t:ty, $v:ty, $m:ty) => {
        impl Mat3Ops<$t, $v> for $m {
            const ZERO: Self = <$m>::ZERO;
            const IDENTITY: Self = <$m>::IDENTITY;
            #[inline(always)]
            fn outer(a: $v, b: $v) -> Self {
                <$m>::from_cols(a * b.x, a * b.y, a * b.z)
            }
            #[inline(always)]
            fn diagonal(d: $v) -> Self {
                <$m>::from_diagonal(d.into())
            }
            #[inline(always)]
            fn transposed(self) -> Self {
                self.transpose()
            }
            #[inline(always)]
            fn entry(self, row: usize, col: usize) -> $t {
                let c = match col {
                    0 => self.x_axis,
                    1 => self.y_axis,
                    _ => self.z_axis,
                };
                match row {
                    0 => c.x,
                    1 => c.y,
                    _ => c.z,
                }
            }
        }
    };
}

impl_vec3!(f32, glam::Vec3A);
impl_vec3!(f64, glam::DVec3);
impl_mat3!(f32, glam::Vec3A, glam::Mat3A);
impl_mat3!(f64, glam::DVec3, glam::DMat3);

impl Real for f32 {
    type Vec3 = glam::Vec3A;
    type Mat3 = glam::Mat3A;
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const PI: Self = core::f32::consts::PI;
    const FRAC_PI_2: Self = core::f32::consts::FRAC_PI_2;
    const FRAC_PI_4: Self = core::f32::consts::FRAC_PI_4;
    const EPSILON: Self = f32::EPSILON;
    const MAX: Self = f32::MAX;
    const LENGTH_FLOOR: Self = 1e-15;
    const COORD_MAX: Self = 1e6;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
}

impl Real for f64 {
    type Vec3 = glam::DVec3;
    type Mat3 = glam::DMat3;
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const PI: Self = core::f64::consts::PI;
    const FRAC_PI_2: Self = core::f64::consts::FRAC_PI_2;
    const FRAC_PI_4: Self = core::f64::consts::FRAC_PI_4;
    const EPSILON: Self = f64::EPSILON;
    const MAX: Self = f64::MAX;
    const LENGTH_FLOOR: Self = 1e-150;
    const COORD_MAX: Self = 1e60;
    #[inline(always)]
    fn from_f64(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
}

/// `x` clamped into `[lo, hi]`; NaN stays NaN (unlike `f64::max`, which would drop it).
#[inline(always)]
#[must_use]
pub fn clamp_keep_nan<T: Real>(x: T, lo: T, hi: T) -> T {
    if x < lo {
        lo
    } else if x > hi {
        hi
    } else {
        x
    }
}

/// `true` if every component of `v` is finite.
#[inline(always)]
#[must_use]
pub fn vec_is_finite<T: Real>(v: T::Vec3) -> bool {
    v.x().is_finite() && v.y().is_finite() && v.z().is_finite()
}
