//! The cheapest page: the conical curl of seed `001_…` (Hong, Card and Chen 2004; the
//! kernel is [`ConeCurl`]) with its parameters $(\theta, A, \rho)$ either scheduled over
//! time (an automatic flip) or fitted every frame so that the held point follows the finger.
//!
//! **Frames.** The kernel maps page point $(x, y)$ = $(u, v)$ to $T = (T_x, T_y, T_z)$ with
//! $T_y$ along the spine and $T_z$ out of the page; the page frame of [`super`] is
//! $(X, Y, Z) = (T_x, T_z, T_y)$.
//!
//! **Time-driven flip** ([`flip_parameters`]): over $t \in [0, 1]$,
//! $\rho = \pi\thinspace\mathrm{smoothstep}(t)$, $\theta = \pi/2 - (\pi/2 - \theta_c)\sin\pi t$,
//! $A = -a H \sin\pi t$: the page lifts, curls most at mid-turn around a cone whose apex lies
//! below the page (so the curl is stronger at the bottom corner), and lands flat on the other
//! side. $\theta_c$ and $a$ are settings (0.3 rad and 2 by default). The seed's demo derives
//! its parameters from a time slider without giving formulas; this schedule is Folio's.
//!
//! **Touch-driven fit.** With the material point $P = (u_0, v_0)$ held and the finger at $G$
//! (kernel frame), each frame solves
//! $$\min_{p = (\theta, A, \rho)} \tfrac12\lVert T(P; p) - G\rVert^2,\quad
//!   \theta \in [\max(\theta_{lo}, \theta_{fold}(A)), \pi/2],\ \rho \in [0, \pi],\
//!   A \in [-A_{max}, 0]$$
//! ($A \in [H, H + A_{max}]$ for a page held in its upper half: the apex stays off the page;
//! $\theta_{fold}$, [`fold_theta_min`], keeps the fold wide enough for the render grid)
//! by projected Levenberg-Marquardt on the kernel's Jacobian, warm-started from the previous
//! frame so the page moves continuously. The cone keeps every point's distance $R$ to the
//! apex $(0, A, 0)$, so $G$ is reachable only if $\lVert G - (0,A,0)\rVert = R(A)$ for some
//! admissible $A$, which is $A = (u_0^2 + v_0^2 - \lVert G\rVert^2) / (2(v_0 - G_y))$ (for
//! $G_y = v_0$ the finger must stay at distance $u_0$ from the spine). When no admissible
//! parameters reach $G$ the fit stops at the nearest shape it finds and the frame's status
//! is [`PageStatus::Unreachable`]: the seed names touch tracking as its open problem, and
//! harism's cylinder curl avoided the cone for this reason.
//!
//! **Release.** The parameters ease (smoothstep) to the nearest flat end over
//! `settle_frames`: $\rho \to \pi$ if the page is past the vertical, else $0$;
//! $\theta \to \pi/2$.
//!
//! The page has no thickness: [`super::mesh`] gives it the paper thickness it is asked for,
//! with the back face oriented for rendering.
//!
//! **No physical units.** The curl is pure geometry: an isometric map of the flat page
//! chosen by schedule or by fit, with no stiffness, no mass and no gravity. A bending
//! stiffness $D$ and an areal density (issue 21, as the mass-spring page takes them,
//! `spring::bending`) do not apply to it, and it cannot sag.

use folio_geometry::{BlockSide, QuadGrid};
use folio_kernels::cone::{ConeCurl, LANES};
use folio_kernels::setting::{SettingError, require};
use folio_kernels::{Real, Vec3Ops, math};

use super::{PageError, PageModel, PageStatus, PageStep, check_finger, check_grab, material_point};

/// Settings of the cone page (module docs). Lengths in page units, angles in radians.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeSettings<T: Real> {
    /// Page width $W$.
    pub width: T,
    /// Page height $H$.
    pub height: T,
    /// Frames of the time-driven flip.
    pub flip_frames: u32,
    /// Smallest half-angle of the flip, $\theta_c$.
    pub flip_theta: T,
    /// Apex depth of the flip in page heights, $a$.
    pub flip_apex: T,
    /// Frames a released page takes to land flat.
    pub settle_frames: u32,
    /// Levenberg-Marquardt iterations per frame of the touch fit.
    pub fit_iterations: u32,
    /// The fit stops (and the finger counts as reached) within this distance.
    pub fit_tolerance: T,
    /// Smallest half-angle the fit may use, $\theta_{lo}$, in $[0.01, \pi/2]$ (keeps the curl
    /// away from the kernel's winding limit). The range stops at 0.01 because below it the
    /// fold gets sharper than a render grid can follow: the fore edge dragged over the spine
    /// crushed a 24×34 render grid's edges by 81 % at $\theta_{lo} = 10^{-3}$, against
    /// 0.4 % at 0.01 and 0.8 % at the default 0.05 (hard case
    /// `cone_flat_limit_theta_to_zero`).
    pub fit_theta_min: T,
    /// Bound on the apex position, $A_{max}$.
    pub fit_apex_max: T,
    /// The coarsest render grid the fitted page must stay followable on, in quads across
    /// and along the page (each $\ge 1$): its longest edge $L$ sets the fit's fold bound
    /// $\theta_{fold}$ ([`fold_theta_min`]). The default is the 24 x 34 grid `folio run`
    /// measures with; a finer grid only follows the fold better.
    pub render_quads: [u32; 2],
}

impl<T: Real> Default for ConeSettings<T> {
    /// The seed `000_…` page (12 x 12√2), a one-second flip at 60 fps, a half-second landing.
    fn default() -> Self {
        Self {
            width: T::from_f64(12.0),
            height: T::from_f64(12.0 * core::f64::consts::SQRT_2),
            flip_frames: 60,
            flip_theta: T::from_f64(0.3),
            flip_apex: T::TWO,
            settle_frames: 30,
            fit_iterations: 40,
            fit_tolerance: T::from_f64(1e-3),
            fit_theta_min: T::from_f64(0.05),
            fit_apex_max: T::from_f64(1e3),
            render_quads: [24, 34],
        }
    }
}

impl<T: Real> ConeSettings<T> {
    /// Checks every field against its range (the field docs).
    ///
    /// # Errors
    /// The first bad field, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let positive = |v: T| v.is_finite() && v > T::ZERO;
        let real = |v: T| v.to_f64();
        for (field, v) in [
            ("width", self.width),
            ("height", self.height),
            ("fit_tolerance", self.fit_tolerance),
            ("fit_apex_max", self.fit_apex_max),
        ] {
            require(positive(v), field, "finite and > 0", real(v))?;
        }
        for (field, n) in [
            ("flip_frames", self.flip_frames),
            ("settle_frames", self.settle_frames),
        ] {
            require(n >= 1, field, "at least 1", f64::from(n))?;
        }
        let half_pi = T::from_f64(core::f64::consts::FRAC_PI_2);
        let angle = |v: T, min: f64| v.is_finite() && v >= T::from_f64(min) && v <= half_pi;
        let theta = self.flip_theta;
        require(
            angle(theta, 1e-3),
            "flip_theta",
            "in [1e-3, pi/2]",
            real(theta),
        )?;
        let theta = self.fit_theta_min;
        require(
            angle(theta, 0.01),
            "fit_theta_min",
            "in [0.01, pi/2]",
            real(theta),
        )?;
        let apex = self.flip_apex;
        let ok = apex.is_finite() && apex >= T::ZERO;
        require(ok, "flip_apex", "finite and >= 0", real(apex))?;
        for (i, n) in self.render_quads.into_iter().enumerate() {
            let field = ["render_quads[0]", "render_quads[1]"][i];
            require(n >= 1, field, "at least 1", n as f64)?;
        }
        Ok(())
    }
}

/// The cone parameters $(\theta, A, \rho)$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeParameters<T> {
    /// Half-angle $\theta$ (radians; $\pi/2$ is flat).
    pub theta: T,
    /// Apex position $A$ on the spine (page units).
    pub apex: T,
    /// Turn $\rho$ about the spine (radians; $\pi$ is turned over).
    pub rho: T,
}

impl<T: Real> ConeParameters<T> {
    /// The flat, unturned page.
    #[must_use]
    pub fn flat() -> Self {
        Self {
            theta: T::from_f64(core::f64::consts::FRAC_PI_2),
            apex: T::ZERO,
            rho: T::ZERO,
        }
    }
    fn curl(&self) -> ConeCurl<T> {
        ConeCurl::new(self.theta, self.apex, self.rho)
    }
    fn lerp(&self, to: &Self, s: T) -> Self {
        let mix = |a: T, b: T| a + (b - a) * s;
        Self {
            theta: mix(self.theta, to.theta),
            apex: mix(self.apex, to.apex),
            rho: mix(self.rho, to.rho),
        }
    }
}

/// $3s^2 - 2s^3$ on $s$ clamped to $[0, 1]$.
fn smoothstep<T: Real>(s: T) -> T {
    let s = folio_kernels::real::clamp_keep_nan(s, T::ZERO, T::ONE);
    s * s * (T::from_f64(3.0) - T::TWO * s)
}

/// The time-driven flip's parameters at $t \in [0, 1]$ (module docs).
#[must_use]
pub fn flip_parameters<T: Real>(settings: &ConeSettings<T>, t: T) -> ConeParameters<T> {
    let pi = T::from_f64(core::f64::consts::PI);
    let half_pi = T::from_f64(core::f64::consts::FRAC_PI_2);
    let t = folio_kernels::real::clamp_keep_nan(t, T::ZERO, T::ONE);
    let bump = math::sin::<T>(pi * t);
    ConeParameters {
        theta: half_pi - (half_pi - settings.flip_theta) * bump,
        apex: -settings.flip_apex * settings.height * bump,
        rho: pi * smoothstep(t),
    }
}

/// The fold bound of the touch fit: the smallest half-angle at which a cone with apex
/// $(0, A)$ on the spine keeps every edge of the render grid of `settings.render_quads`
/// within $1 - 2\sqrt2/\pi \approx 9.97\,\%$ of its rest length.
///
/// **Derivation.** A cone of half-angle $\theta$ has principal curvatures $0$ (along the
/// ruling) and $\kappa = \cos\theta / (R\sin\theta) = 1/(R\tan\theta)$ at distance $R$ from
/// the apex: the kernel maps the circle of radius $R$ around the apex onto a cross-section
/// circle of radius $R\sin\theta$ (so $\lvert v - c\rvert = R\sin\theta$ for its centre
/// $c = (0, A + R - R\sin^2\theta, R\sin\theta\cos\theta)$), whose principal normal meets the
/// surface normal at the angle $\theta$, so by Meusnier the fold radius is
/// $R\sin\theta/\cos\theta = R\tan\theta \ge R\sin\theta$. A
/// render edge is a straight segment of length $\ell_0$ on the flat page; the isometry maps
/// it onto a geodesic of the cone, whose curvature is its normal curvature, at most
/// $\kappa_{max} = 1/(R_{min}\tan\theta)$ with $R_{min}$ the page's distance to the apex:
/// $R_{min} = \max(-A,\ A - H,\ 0)$ (the apex lies on the spine, and the fit keeps it off
/// the page). By Schur's comparison theorem its chord is at least that of a circular arc of
/// the same length and curvature $\kappa_{max}$, $\ell \ge (2/\kappa_{max})
/// \sin(\kappa_{max}\ell_0/2)$ while $\kappa_{max}\ell_0 \le \pi$. Asking
/// $\kappa_{max}\ell_0/2 \le \pi/4$ gives $\ell/\ell_0 \ge \sin(\pi/4)/(\pi/4) =
/// 2\sqrt2/\pi$, a compression of at most $9.97\,\%$ (below the run's 10 % bound), for
/// every edge of length $\ell_0 \le L = \max(W/q_x,\ H/q_z)$ when
/// $$R_{min}\tan\theta \ge \frac{2L}{\pi},\qquad
///   \theta_{fold} = \operatorname{atan2}(2L,\ \pi R_{min}) \in (0, \pi/2].$$
/// An apex on the page corner ($R_{min} = 0$) gives $\theta_{fold} = \pi/2$, the flat page:
/// the cone is self-similar there and no sampling follows its fold (module docs).
/// Measured before this bound (the bounded-pages property test's all-zero draw): a
/// 0.1 x 0.14 page with $A_{max} = 10^{-3}$ and a finger far from the grab crushed the
/// 24 x 34 render grid's edges by 34 % at $\theta_{lo} = 0.05$, 86 % at 0.01; after it,
/// 400 drawn cases measured at most 9.92 %.
#[must_use]
pub fn fold_theta_min<T: Real>(settings: &ConeSettings<T>, apex: T) -> T {
    let s = settings;
    let across = s.width / T::from_f64(f64::from(s.render_quads[0].max(1)));
    let along = s.height / T::from_f64(f64::from(s.render_quads[1].max(1)));
    let longest = if across > along { across } else { along };
    let below = -apex;
    let above = apex - s.height;
    let distance = if below > above { below } else { above };
    let distance = if distance > T::ZERO {
        distance
    } else {
        T::ZERO
    };
    math::atan2::<T>(
        T::TWO * longest,
        T::from_f64(core::f64::consts::PI) * distance,
    )
}

/// What drives the parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drive<T: Real> {
    /// Nothing: the page stays.
    Still,
    /// The time-driven flip at frame `frame`.
    Flip { frame: u32 },
    /// Held at material point `at`, finger at `finger` (kernel frame).
    Held { at: [T; 2], finger: T::Vec3 },
    /// Landing from `from` to `to`, at frame `frame` of `settle_frames`.
    Landing {
        from: ConeParameters<T>,
        to: ConeParameters<T>,
        frame: u32,
    },
}

/// The cone page (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConePage<T: Real> {
    settings: ConeSettings<T>,
    params: ConeParameters<T>,
    drive: Drive<T>,
}

/// Page frame $(X, Y, Z)$ from kernel frame $(T_x, T_y, T_z)$ and back (the same swap).
fn swap_yz<T: Real>(p: T::Vec3) -> T::Vec3 {
    T::Vec3::new(p.x(), p.z(), p.y())
}

impl<T: Real> ConePage<T> {
    /// A flat page.
    ///
    /// # Errors
    /// As [`ConeSettings::validate`].
    pub fn new(settings: ConeSettings<T>) -> Result<Self, PageError> {
        settings.validate()?;
        Ok(Self {
            settings,
            params: ConeParameters::flat(),
            drive: Drive::Still,
        })
    }

    /// The parameters in use.
    #[must_use]
    pub fn parameters(&self) -> ConeParameters<T> {
        self.params
    }

    /// Starts the time-driven flip from the flat page (drops any hold).
    pub fn start_flip(&mut self) {
        self.params = ConeParameters::flat();
        self.drive = Drive::Flip { frame: 0 };
    }

    /// The side of the spine the page lies on, or lands on once released: left past the
    /// vertical ($\rho > \pi/2$).
    #[must_use]
    pub fn side(&self) -> BlockSide {
        let rho = match self.drive {
            Drive::Landing { to, .. } => to.rho,
            _ => self.params.rho,
        };
        if rho > T::from_f64(core::f64::consts::FRAC_PI_2) {
            BlockSide::Left
        } else {
            BlockSide::Right
        }
    }

    /// Whether a flip or a landing is still running.
    #[must_use]
    pub fn is_animating(&self) -> bool {
        matches!(self.drive, Drive::Flip { .. } | Drive::Landing { .. })
    }

    /// Clamps parameters into the fit's admissible box for a page held at height `v0`: the
    /// apex stays off the page, below its bottom edge ($A \le 0$) when the page is held in
    /// its lower half, above its top edge ($A \ge H$) otherwise. An apex on the page makes
    /// the surface self-similar around it, and neighbour distances there change by a fixed
    /// fraction at any sampling (measured: 14 % render-grid stretch on the shared drag).
    /// The apex is clamped first, then the half-angle into
    /// $[\max(\theta_{lo}, \theta_{fold}(A)), \pi/2]$ ([`fold_theta_min`]): the fold stays
    /// wide enough for the render grid wherever the apex is.
    fn admissible(&self, p: ConeParameters<T>, v0: T) -> ConeParameters<T> {
        let s = &self.settings;
        let clamp = folio_kernels::real::clamp_keep_nan::<T>;
        let (lo, hi) = if v0 + v0 <= s.height {
            (-s.fit_apex_max, T::ZERO)
        } else {
            (s.height, s.height + s.fit_apex_max)
        };
        let apex = clamp(p.apex, lo, hi);
        let fold = fold_theta_min(s, apex);
        let theta_lo = if fold > s.fit_theta_min {
            fold
        } else {
            s.fit_theta_min
        };
        ConeParameters {
            theta: clamp(p.theta, theta_lo, T::from_f64(core::f64::consts::FRAC_PI_2)),
            apex,
            rho: clamp(p.rho, T::ZERO, T::from_f64(core::f64::consts::PI)),
        }
    }

    /// Fits the parameters to hold `at` on `finger` (kernel frame; module docs) and returns
    /// the remaining distance. Two starts, the better kept: the warm start (last frame's
    /// parameters) with all three free, and the apex set to the one that keeps the held
    /// point's distance to it, $A^* = (u_0^2 + v_0^2 - \lVert G\rVert^2)/(2(v_0 - G_y))$,
    /// with $\theta, \rho$ fitted first and then all three (near the flat page the warm start
    /// sits where the Jacobian is singular and can stall against the apex bound).
    fn fit(&mut self, at: [T; 2], finger: T::Vec3) -> T {
        let warm = self.admissible(self.params, at[1]);
        let mut best = self.levenberg_marquardt(warm, at, finger, [true; 3]);
        let apex =
            (at[0] * at[0] + at[1] * at[1] - finger.dot(finger)) / (T::TWO * (at[1] - finger.y()));
        if apex.is_finite() && best.1 > self.settings.fit_tolerance {
            let start = self.admissible(ConeParameters { apex, ..warm }, at[1]);
            let fixed = self.levenberg_marquardt(start, at, finger, [true, false, true]);
            let polished = self.levenberg_marquardt(fixed.0, at, finger, [true; 3]);
            if polished.1 < best.1 {
                best = polished;
            }
        }
        let p = best.0;
        if p.theta.is_finite() && p.apex.is_finite() && p.rho.is_finite() {
            self.params = p;
        }
        best.1
    }

    /// Projected Levenberg-Marquardt on the parameters flagged `free` from `p`: the normal
    /// equations $(J^\top J + \lambda\thinspace\mathrm{diag}(J^\top J))\thinspace\delta = -J^\top r$, the step
    /// clamped into the admissible box and accepted when $\lVert r\rVert$ falls. Returns the
    /// parameters and $\lVert r\rVert$.
    fn levenberg_marquardt(
        &self,
        mut p: ConeParameters<T>,
        at: [T; 2],
        finger: T::Vec3,
        free: [bool; 3],
    ) -> (ConeParameters<T>, T) {
        let s = self.settings;
        let residual = |p: &ConeParameters<T>| p.curl().map_point(at[0], at[1]) - finger;
        let mut r = residual(&p);
        let mut cost = r.dot(r);
        let mut damping = T::from_f64(1e-3);
        for _ in 0..s.fit_iterations {
            if math::sqrt(cost) <= s.fit_tolerance || !cost.is_finite() {
                break;
            }
            let j = p.curl().jacobian(at[0], at[1]);
            let mut a = [[T::ZERO; 3]; 3];
            let mut g = [T::ZERO; 3];
            for row in 0..3 {
                for col in 0..3 {
                    a[row][col] = if free[row] && free[col] {
                        j[row].dot(j[col])
                    } else {
                        T::ZERO
                    };
                }
                g[row] = if free[row] { -j[row].dot(r) } else { T::ZERO };
            }
            let mut accepted = false;
            for _ in 0..8 {
                let mut m = a;
                for (k, row) in m.iter_mut().enumerate() {
                    row[k] += damping * a[k][k] + T::from_f64(1e-12);
                }
                let Some(d) = solve3(m, g) else {
                    damping *= T::from_f64(10.0);
                    continue;
                };
                let trial = self.admissible(
                    ConeParameters {
                        theta: p.theta + d[0],
                        apex: p.apex + d[1],
                        rho: p.rho + d[2],
                    },
                    at[1],
                );
                let tr = residual(&trial);
                let tc = tr.dot(tr);
                if tc < cost {
                    (p, r, cost) = (trial, tr, tc);
                    damping *= T::from_f64(0.3);
                    accepted = true;
                    break;
                }
                damping *= T::from_f64(10.0);
            }
            if !accepted {
                break;
            }
        }
        (p, math::sqrt(cost))
    }
}

/// Solves the 3x3 system `m x = b` by Cramer's rule; `None` when singular or non-finite.
fn solve3<T: Real>(m: [[T; 3]; 3], b: [T; 3]) -> Option<[T; 3]> {
    let det3 = |c: [[T; 3]; 3]| {
        c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1])
            - c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0])
            + c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])
    };
    let det = det3(m);
    if !(det.is_finite() && det != T::ZERO) {
        return None;
    }
    let mut x = [T::ZERO; 3];
    for (k, xk) in x.iter_mut().enumerate() {
        let mut c = m;
        for (row, &bk) in c.iter_mut().zip(&b) {
            row[k] = bk;
        }
        *xk = det3(c) / det;
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

impl<T: Real> PageModel<T> for ConePage<T> {
    fn name(&self) -> &'static str {
        "cone"
    }

    fn size(&self) -> [T; 2] {
        [self.settings.width, self.settings.height]
    }

    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError> {
        check_grab(at, self.size())?;
        let finger = self.params.curl().map_point(at[0], at[1]);
        self.drive = Drive::Held { at, finger };
        Ok(())
    }

    /// Where the page lies ([`ConePage::side`]).
    fn lying_side(&self) -> BlockSide {
        self.side()
    }

    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError> {
        check_finger::<T>(finger)?;
        if let Drive::Held { at, .. } = self.drive {
            self.drive = Drive::Held {
                at,
                finger: swap_yz::<T>(finger),
            };
        }
        Ok(())
    }

    fn release(&mut self) {
        if matches!(self.drive, Drive::Held { .. }) {
            let turned = self.params.rho > T::from_f64(core::f64::consts::FRAC_PI_2);
            let to = ConeParameters {
                theta: T::from_f64(core::f64::consts::FRAC_PI_2),
                apex: self.params.apex,
                rho: if turned {
                    T::from_f64(core::f64::consts::PI)
                } else {
                    T::ZERO
                },
            };
            self.drive = Drive::Landing {
                from: self.params,
                to,
                frame: 0,
            };
        }
    }

    fn step(&mut self) -> Result<PageStep<T>, PageError> {
        let s = self.settings;
        let mut out = PageStep {
            status: PageStatus::Moved,
            finger_gap: None,
        };
        match self.drive {
            Drive::Still => {}
            Drive::Flip { frame } => {
                let frame = frame + 1;
                let t = T::from_f64(f64::from(frame) / f64::from(s.flip_frames));
                self.params = flip_parameters(&s, t);
                self.drive = if frame >= s.flip_frames {
                    Drive::Still
                } else {
                    Drive::Flip { frame }
                };
            }
            Drive::Held { at, finger } => {
                let gap = self.fit(at, finger);
                out.finger_gap = Some(gap);
                if gap > s.fit_tolerance || !gap.is_finite() {
                    out.status = PageStatus::Unreachable;
                }
            }
            Drive::Landing { from, to, frame } => {
                let frame = frame + 1;
                let t = T::from_f64(f64::from(frame) / f64::from(s.settle_frames));
                self.params = from.lerp(&to, smoothstep(t));
                self.drive = if frame >= s.settle_frames {
                    Drive::Still
                } else {
                    Drive::Landing { from, to, frame }
                };
            }
        }
        Ok(out)
    }

    /// The render nodes mapped in blocks of [`LANES`] through the kernel's SIMD batch map.
    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError> {
        super::check_count(grid.len(), out.len())?;
        let curl = self.params.curl();
        let size = self.size();
        for (block, chunk) in out.chunks_mut(LANES).enumerate() {
            let (mut xs, mut ys) = ([T::ZERO; LANES], [T::ZERO; LANES]);
            for k in 0..chunk.len() {
                let [u, v] = material_point(grid, size, block * LANES + k);
                (xs[k], ys[k]) = (u, v);
            }
            let (mut tx, mut ty, mut tz) = ([T::ZERO; LANES], [T::ZERO; LANES], [T::ZERO; LANES]);
            let n = chunk.len();
            curl.map_batch(&mut tx[..n], &mut ty[..n], &mut tz[..n], &xs[..n], &ys[..n]);
            for (k, p) in chunk.iter_mut().enumerate() {
                *p = T::Vec3::new(tx[k], tz[k], ty[k]);
            }
        }
        Ok(())
    }
}
