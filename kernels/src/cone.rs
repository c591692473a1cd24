//! The conical page curl of seed `001_…` (Hong, Card and Chen 2004; the seed's section "The
//! math behind page curling" and its code, which number no equations): a flat page wrapped
//! around a cone with half-angle $\theta$ and apex $(0, A, 0)$ on the spine, then turned
//! by $\rho$ about the spine (the Y axis).
//!
//! Page coordinates $(x, y)$: $x \ge 0$ across the page from the spine, $y$ along it.
//! With the polar coordinates of the page point around the apex,
//! $R = \sqrt{x^2 + (y-A)^2}$, $\alpha = \operatorname{atan2}(x,\thinspace y - A)$, and
//! $s = \sin\theta$, $c = \cos\theta$, $\beta = \alpha / s$:
//! $$v = \bigl(R s \sin\beta,\ A + R - R s^2 (1-\cos\beta),\ R s c\thinspace(1-\cos\beta)\bigr),$$
//! $$T(x,y) = (v_x\cos\rho - v_z\sin\rho,\ v_y,\ v_x\sin\rho + v_z\cos\rho).$$
//! The seed writes $\alpha = \arcsin(x/R)$; the two agree wherever $y \ge A$ (the page
//! above the apex, the seed's use), and the polar angle keeps the map an isometry, finite and
//! continuous on the whole half-plane $x \ge 0$, with bounded derivatives in $A$ even at
//! $y = A$ where $\arcsin$'s derivative is infinite.
//!
//! **Domain.** Any finite $(x, y)$ with $x \ge 0$, any finite $A$ and $\rho$, and
//! $\theta \in [\theta_{min}, \pi/2]$, $\theta_{min} = 10^{-4}$: [`ConeCurl::new`] clamps
//! $\theta$ into it. $\theta = \pi/2$ is the flat page; as $\theta \to 0$ the page winds
//! onto the cone's tangent ruling $x = z = 0$ (every point lies within the cross-section
//! circle's diameter $2R\sin\theta$ of it), which the clamp stops at $2 \cdot 10^{-4} R$.
//! The distance to the apex is preserved exactly, $\lvert T(x,y) - (0, A, 0)\rvert = R$,
//! and the apex ($R = 0$) maps to itself. Near an apex inside the page the surface is
//! self-similar, so neighbour distances there change by a fixed fraction at any sampling;
//! away from it they change to second order in the spacing.
//! Units: lengths in page units, angles in radians.
//!
//! **Jacobian** ([`ConeCurl::jacobian`]) of $T$ with respect to $(\theta, A, \rho)$, exact on
//! the domain (one-sided at its ends; the $\theta$ column is zero where the clamp is active,
//! the derivative of the clamped map). At the apex the $A$ column is the limit from $y > A$.
//! The $\theta$ column grows like $R\alpha/\theta$ as $\theta \to \theta_{min}$ (the page
//! winds faster): finite, but a fit should keep $\theta$ well above the bound.
//!
//! **Batches** ([`ConeCurl::map_batch`]) take structure-of-arrays slices and use the
//! branch-free [`crate::lanes`] functions so the loop vectorizes.

use crate::lanes;
use crate::math;
use crate::real::{Real, Vec3Ops, clamp_keep_nan};

/// Points per block in [`ConeCurl::map_batch`] (two SSE/NEON registers of `f32`, one AVX).
pub const LANES: usize = 8;

/// Smallest cone half-angle the map uses (radians).
pub const THETA_MIN: f64 = 1e-4;

/// A cone-curl deformation with its per-frame trigonometry precomputed (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeCurl<T> {
    theta: T,
    theta_clamped: bool,
    apex: T,
    rho: T,
    sin_t: T,
    cos_t: T,
    inv_sin_t: T,
    sin_r: T,
    cos_r: T,
}

/// Per-point intermediate quantities shared by the map and its Jacobian.
struct Polar<T> {
    radius: T,
    cos_a: T,
    sin_a: T,
    beta: T,
    sin_b: T,
    cos_b: T,
}

impl<T: Real> ConeCurl<T> {
    /// The curl with cone half-angle `theta` (clamped into $[\theta_{min}, \pi/2]$), apex
    /// position `apex` on the spine and turn angle `rho`. Total: NaN parameters are kept and
    /// make every mapped point NaN.
    #[must_use]
    pub fn new(theta: T, apex: T, rho: T) -> Self {
        let lo = T::from_f64(THETA_MIN);
        let t = clamp_keep_nan(theta, lo, T::FRAC_PI_2);
        let sin_t = math::sin(t);
        Self {
            theta: t,
            theta_clamped: theta < lo || theta > T::FRAC_PI_2,
            apex,
            rho,
            sin_t,
            cos_t: math::cos(t),
            inv_sin_t: T::ONE / sin_t,
            sin_r: math::sin(rho),
            cos_r: math::cos(rho),
        }
    }

    /// The half-angle in use (after clamping), radians.
    #[must_use]
    pub fn theta(&self) -> T {
        self.theta
    }

    /// The apex position on the spine, page units.
    #[must_use]
    pub fn apex(&self) -> T {
        self.apex
    }

    /// The turn angle about the spine, radians.
    #[must_use]
    pub fn rho(&self) -> T {
        self.rho
    }

    fn polar(&self, x: T, y: T) -> Polar<T> {
        let dy = y - self.apex;
        let radius = math::sqrt(x * x + dy * dy);
        // `+ 0` turns x = -0.0 into +0.0, so the spine below the apex maps one way only.
        let alpha = math::atan2(x + T::ZERO, dy);
        let (cos_a, sin_a) = if radius > T::ZERO {
            (dy / radius, x / radius)
        } else {
            (T::ONE, T::ZERO)
        };
        let beta = alpha * self.inv_sin_t;
        Polar {
            radius,
            cos_a,
            sin_a,
            beta,
            sin_b: math::sin(beta),
            cos_b: math::cos(beta),
        }
    }

    /// $v$ before the turn, from the radius and $\sin\beta$, $\cos\beta$.
    #[inline(always)]
    fn cone_point(&self, radius: T, sin_b: T, cos_b: T) -> (T, T, T) {
        let (s, c) = (self.sin_t, self.cos_t);
        let one_minus_cos = T::ONE - cos_b;
        let rs = radius * s;
        (
            rs * sin_b,
            self.apex + radius - rs * s * one_minus_cos,
            rs * c * one_minus_cos,
        )
    }

    /// The turn by $\rho$ about the Y axis.
    #[inline(always)]
    fn turn(&self, v: (T, T, T)) -> (T, T, T) {
        (
            v.0 * self.cos_r - v.2 * self.sin_r,
            v.1,
            v.0 * self.sin_r + v.2 * self.cos_r,
        )
    }

    /// $T(x, y)$ for one page point (module docs), through the math shim.
    #[must_use]
    pub fn map_point(&self, x: T, y: T) -> T::Vec3 {
        let p = self.polar(x, y);
        let (a, b, c) = self.turn(self.cone_point(p.radius, p.sin_b, p.cos_b));
        T::Vec3::new(a, b, c)
    }

    /// The columns $[\partial T/\partial\theta,\ \partial T/\partial A,\ \partial T/\partial\rho]$
    /// at page point $(x, y)$ (module docs). With $\beta = \alpha/s$:
    /// $\partial_\theta v = \bigl(Rc(\sin\beta - \beta\cos\beta),\ -Rsc\thinspace(2(1-\cos\beta) - \beta\sin\beta),~
    ///  R((c^2-s^2)(1-\cos\beta) - c^2\beta\sin\beta)\bigr)$,
    /// $\partial_A v = \bigl(\cos\beta\sin\alpha - s\sin\beta\cos\alpha,~
    ///  1 - \cos\alpha\thinspace(1 - s^2(1-\cos\beta)) - s\sin\beta\sin\alpha,~
    ///  c\thinspace(\sin\beta\sin\alpha - s(1-\cos\beta)\cos\alpha)\bigr)$,
    /// both turned by $\rho$, and $\partial_\rho T = (-T_z, 0, T_x)$.
    #[must_use]
    pub fn jacobian(&self, x: T, y: T) -> [T::Vec3; 3] {
        let p = self.polar(x, y);
        let (s, c) = (self.sin_t, self.cos_t);
        let (r, b) = (p.radius, p.beta);
        let omc = T::ONE - p.cos_b;
        let d_theta = if self.theta_clamped {
            (T::ZERO, T::ZERO, T::ZERO)
        } else {
            self.turn((
                r * c * (p.sin_b - b * p.cos_b),
                -r * s * c * (T::TWO * omc - b * p.sin_b),
                r * ((c * c - s * s) * omc - c * c * b * p.sin_b),
            ))
        };
        let d_apex = self.turn((
            p.cos_b * p.sin_a - s * p.sin_b * p.cos_a,
            T::ONE - p.cos_a * (T::ONE - s * s * omc) - s * p.sin_b * p.sin_a,
            c * (p.sin_b * p.sin_a - s * omc * p.cos_a),
        ));
        let t = self.turn(self.cone_point(r, p.sin_b, p.cos_b));
        let v = |q: (T, T, T)| T::Vec3::new(q.0, q.1, q.2);
        [v(d_theta), v(d_apex), v((-t.2, T::ZERO, t.0))]
    }

    /// Maps a batch of page points given as structure-of-arrays `xs`, `ys` into `out_x`,
    /// `out_y`, `out_z`. Processes `n` = the shortest slice length and returns `n`.
    /// Works in blocks of [`LANES`] points, stage by stage over fixed-size arrays with the
    /// branch-free [`crate::lanes`] functions, so each stage becomes SIMD code (SSE2 or NEON
    /// lanes by default; with `std` on x86-64 the same code compiled for AVX2 is chosen at run
    /// time when the CPU has it). Results agree with [`ConeCurl::map_point`] to a few ulp.
    pub fn map_batch(
        &self,
        out_x: &mut [T],
        out_y: &mut [T],
        out_z: &mut [T],
        xs: &[T],
        ys: &[T],
    ) -> usize {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        if std::is_x86_feature_detected!("avx2") {
            #[allow(unsafe_code)]
            // SAFETY: `map_batch_avx2` only requires AVX2, which the CPU was just found to have.
            return unsafe { self.map_batch_avx2(out_x, out_y, out_z, xs, ys) };
        }
        self.map_batch_portable(out_x, out_y, out_z, xs, ys)
    }

    /// [`ConeCurl::map_batch`]'s body compiled with AVX2 enabled (8 `f32` or 4 `f64` lanes).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    fn map_batch_avx2(
        &self,
        out_x: &mut [T],
        out_y: &mut [T],
        out_z: &mut [T],
        xs: &[T],
        ys: &[T],
    ) -> usize {
        self.map_batch_portable(out_x, out_y, out_z, xs, ys)
    }

    /// The batch body, inlined into each instruction-set variant.
    #[inline(always)]
    fn map_batch_portable(
        &self,
        out_x: &mut [T],
        out_y: &mut [T],
        out_z: &mut [T],
        xs: &[T],
        ys: &[T],
    ) -> usize {
        let n = xs
            .len()
            .min(ys.len())
            .min(out_x.len())
            .min(out_y.len())
            .min(out_z.len());
        let full = n - n % LANES;
        let blocks = out_x[..full]
            .chunks_exact_mut(LANES)
            .zip(out_y[..full].chunks_exact_mut(LANES))
            .zip(out_z[..full].chunks_exact_mut(LANES))
            .zip(
                xs[..full]
                    .chunks_exact(LANES)
                    .zip(ys[..full].chunks_exact(LANES)),
            );
        for (((ox, oy), oz), (x, y)) in blocks {
            let x = <[T; LANES]>::try_from(x).unwrap_or([T::ZERO; LANES]);
            let y = <[T; LANES]>::try_from(y).unwrap_or([T::ZERO; LANES]);
            let (a, b, c) = self.map_lanes(&x, &y);
            ox.copy_from_slice(&a);
            oy.copy_from_slice(&b);
            oz.copy_from_slice(&c);
        }
        // The tail, padded into one more block.
        let tail = n - full;
        if tail > 0 {
            let (mut x, mut y) = ([T::ZERO; LANES], [T::ZERO; LANES]);
            x[..tail].copy_from_slice(&xs[full..n]);
            y[..tail].copy_from_slice(&ys[full..n]);
            let (a, b, c) = self.map_lanes(&x, &y);
            out_x[full..n].copy_from_slice(&a[..tail]);
            out_y[full..n].copy_from_slice(&b[..tail]);
            out_z[full..n].copy_from_slice(&c[..tail]);
        }
        n
    }

    /// One block of [`LANES`] points, each stage a simple loop over the lanes.
    #[inline(always)]
    fn map_lanes(&self, x: &[T; LANES], y: &[T; LANES]) -> ([T; LANES], [T; LANES], [T; LANES]) {
        let mut radius = [T::ZERO; LANES];
        let mut beta = [T::ZERO; LANES];
        for k in 0..LANES {
            let dy = y[k] - self.apex;
            radius[k] = math::sqrt(x[k] * x[k] + dy * dy);
            beta[k] = lanes::atan2(x[k] + T::ZERO, dy) * self.inv_sin_t;
        }
        let (mut ox, mut oy, mut oz) = ([T::ZERO; LANES], [T::ZERO; LANES], [T::ZERO; LANES]);
        for k in 0..LANES {
            let (sin_b, cos_b) = lanes::sin_cos(beta[k]);
            (ox[k], oy[k], oz[k]) = self.turn(self.cone_point(radius[k], sin_b, cos_b));
        }
        (ox, oy, oz)
    }
}
