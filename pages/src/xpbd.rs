//! The position-based page: what a game engineer would reach for. Particles on the page's
//! grid, inextensible distance constraints on the grid's edges and cell diagonals, and
//! isometric bending in its squared-Hessian form, solved by XPBD in small steps
//! ([`constraints`] has the formulas and their sources).
//!
//! **One frame** ([`PageModel::step`]) is $n$ substeps of $h = \Delta t/n$
//! ([`XpbdSettings::substeps`]; Macklin, Storey, Lu, Terdiman, Chentanez, Jeschke and
//! Müller 2019, *Small Steps in Physics Simulation*: one constraint sweep per substep and
//! many substeps beat many sweeps per step), each:
//! 1. the gripped particles are placed on the way to the finger (below);
//! 2. every free particle is predicted, $v \leftarrow v/(1 + c h) + h g$ (the drag $c$
//!    implicit in the velocity it slows, so any rate is stable, and gravity after it, so
//!    that the drag, zero at rest, does not move an equilibrium), $x \leftarrow x + h v$;
//! 3. the multipliers are reset and the constraints are swept [`XpbdSettings::iterations`]
//!    times in Gauss-Seidel order: the bending constraints, then the distance constraints,
//!    so that the page leaves a sweep as inextensible as one sweep makes it;
//! 4. the table (if on): a free particle under the plane $y = 0$ is put on it;
//! 5. $v = (x - x^{start})/h$; a free particle on the table keeps no downward velocity
//!    (the mass-spring page's contact).
//!
//! A frame that leaves a coordinate non-finite or beyond [`Real::COORD_MAX`] restores the
//! state of the frame's start and reports [`PageStatus::Stalled`].
//!
//! **Masses and load.** Particle $v$ carries $\rho A_v$, its dual cell's share of the page
//! ([`constraints::dual_area`]), so gravity is the quadrature of $\int\rho g y\,dA$ with
//! the same weights as the bending; the spine particles are fixed (inverse mass 0).
//!
//! **Touch.** A grab at the material point $(u, v)$ grips the particles of the grid cell
//! holding it that carry its bilinear weight (more than $10^{-3}$ of it: 1, 2 or 4
//! particles; a spine particle is never gripped): a zero-compliance attachment, the
//! particle made immovable (inverse mass 0) and moved by the finger. While the finger is
//! at $G$ a gripped particle's target is $\bar x_k + s(G - P)$, $\bar x_k$ its rest position
//! and $P = (u, 0, v)$ the grabbed rest point (both mirrored, $x \to -x$, for a page taken
//! on the left), so the gripped cell moves rigidly and the held material point of the
//! bilinear surface is on the finger. In substep $s$ of $n$ a gripped particle is at
//! $x_k^0 + \tfrac sn(x_k^{target} - x_k^0)$, $x_k^0$ its place at the frame's start. The
//! factor $s \in [0, 1]$ cuts the finger's translation to the page's reach, as the
//! mass-spring page does: the largest $s$ that keeps every gripped particle within
//! $(1 + \tau_r)$ of its rest distance to every spine particle ([`REACH_SLACK`] $= \tau_r$),
//! the farthest an inextensible page reaches with that much slack; such a frame reports
//! [`PageStatus::Unreachable`]. Without the cut, a finger far out drags the gripped
//! particles along and the page stretches without bound. A release gives the gripped
//! particles back their masses and the velocity of their last substep.
//!
//! **Output.** The page's surface at a render node is the bilinear interpolation of the
//! particle grid at its material point; with the table on, every particle is on or above
//! it, and so is the surface. The frame's finger gap is the distance from that surface's
//! held point to the finger.
//!
//! **Calibration** (`tests/tests/elastica_xpbd.rs`): the page clamped at the spine
//! ([`Spine::Clamp`]) settles to the cantilever elastica under its own weight with the
//! default $D$, at loads $\rho g W^3/D$ = 0.1, 1, 10: tip +2.58 %, +2.58 %, +2.29 % at the
//! default $8 \times 11$ quads and 29 substeps (+1.6 % of it is the grid's, the five-point
//! beam's own error at 8 cells; the rest is the small steps' bias). At $16 \times 22$ quads
//! the same 29 substeps give +21.3 %, +20.7 %, +6.8 %: one sweep per substep leaves a bias
//! of order $(h\,\omega_{max})^2$, $\omega_{max} \propto \sqrt D$ the stiffest bending
//! frequency, which grows as the inverse square of the spacing, so the finer page is a
//! softer page unless its substeps grow fourfold (116: +1.57 %, +1.55 %, +0.88 %). The
//! default substeps hold $h\,\omega_{max}$ where 24 substeps held it for $D = 240$ (the
//! page before issue 21's recalibration): $24\sqrt{344/240} = 28.7$. At $D = 344$, 24
//! substeps gave +3.06 % at load 0.1 (outside 3 %), 29 the figures above, 32 +2.40 %. Two
//! findings shaped the constraints:
//! - **Bending: the Hessian form, not the Laplacian.** With Bergou's cotangent Laplacian
//!   alone, $\frac D2\sum A_v\lVert\Delta_h x_v\rVert^2$ (mean curvature squared), a
//!   saddle costs no bending, and the distance constraints resist it only to second order
//!   in the deflection: the clamped page took a saddle (its border rows 20 % above its
//!   middle rows) and sagged +52 %, +17 %, +3.2 % past the elastica; 64 sweeps per substep
//!   only brought that to +18 % at load 0.1. The separate second differences and the twist
//!   ([`constraints`]) price both curvatures and fixed it.
//! - **Shear links not quite rigid**: rigid diagonals kept a heavily loaded page from
//!   settling at small substeps ([`XpbdSettings::shear_compliance`]).
//!
//! **The shared page turn** (`tests/tests/page_models.rs`, render grid $24 \times 34$
//! quads): 96 % of the page ends left of the spine, the render grid's max stretch per frame
//! averages 1.21 % (worst 5.9 %, f32 alike), the finger gap is 0. The worst stretch is in
//! the cells next to the two gripped particles, folded sharply while the finger lifts the
//! page. A flick is not bounded: one sweep per substep cannot follow gripped particles that
//! jump within a frame (a link at 33 % on a small coarse page flicked in one frame,
//! `tests/tests/bounded_pages.rs`, open); unlike the mass-spring page there is no strain
//! limit iterated to convergence.
//!
//! Setup allocates (the particles, the constraints, their multipliers); [`PageModel::step`]
//! and [`PageModel::sample`] do not.

pub mod constraints;
pub mod settings;

use alloc::vec;
use alloc::vec::Vec;
use folio_geometry::{BlockSide, QuadGrid};
use folio_kernels::{Real, Vec3Ops, math};

pub use constraints::{Bending, Distance, dual_area};
pub use settings::{MAX_ITERATIONS, MAX_QUADS_PER_SIDE, MAX_SUBSTEPS, Spine, XpbdSettings};

use super::{PageError, PageModel, PageStatus, PageStep, check_grab, material_point};
use crate::hold::{self, Hold, all_in_range};

/// Slack $\tau_r$ of the finger's reach (module docs, "Touch"): a gripped particle stays
/// within $1 + \tau_r$ of its rest distance to every spine particle.
pub const REACH_SLACK: f64 = 0.01;

/// A gripped particle carries more than this share of the grab point's bilinear weight.
const GRIP_WEIGHT: f64 = 1e-3;

/// The position-based page (module docs).
#[derive(Clone, Debug)]
pub struct XpbdPage<T: Real> {
    settings: XpbdSettings<T>,
    /// The particle grid ($n_x + 1$ by $n_z + 1$ particles).
    grid: QuadGrid,
    rest: Vec<T::Vec3>,
    mass: Vec<T>,
    inverse_mass: Vec<T>,
    x: Vec<T::Vec3>,
    v: Vec<T::Vec3>,
    /// Positions at the start of the substep.
    start: Vec<T::Vec3>,
    /// Positions and velocities at the start of the frame (kept on a stall).
    frame_x: Vec<T::Vec3>,
    frame_v: Vec<T::Vec3>,
    distances: Vec<Distance<T>>,
    distance_lambda: Vec<T>,
    bendings: Vec<Bending<T>>,
    bending_lambda: Vec<T::Vec3>,
    /// Rest positions of the spine particles (the reach).
    spine: Vec<T::Vec3>,
    gripped: Vec<u32>,
    hold: Option<Hold<T>>,
    out_of_reach: bool,
    frame: u64,
}

impl<T: Real> XpbdPage<T> {
    /// The page of `settings` flat at rest on the plane $y = 0$.
    ///
    /// # Errors
    /// [`PageError::InvalidSetting`] naming the first bad setting
    /// ([`XpbdSettings::validate`]).
    pub fn new(settings: XpbdSettings<T>) -> Result<Self, PageError> {
        settings.validate()?;
        let grid = QuadGrid {
            nx: settings.quads_across + 1,
            nz: settings.quads_along + 1,
        };
        let size = [settings.width, settings.height];
        let spacing = settings.spacing();
        let rest: Vec<T::Vec3> = (0..grid.len())
            .map(|k| {
                let p = material_point(grid, size, k);
                T::Vec3::new(p[0], T::ZERO, p[1])
            })
            .collect();
        let mass: Vec<T> = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                settings.areal_density * dual_area(grid, spacing, i, j)
            })
            .collect();
        let inverse_mass = (0..grid.len())
            .map(|k| {
                if grid.coords(k).0 == 0 {
                    T::ZERO
                } else {
                    T::ONE / mass[k]
                }
            })
            .collect();
        let distances = constraints::distances(grid, &rest, &settings);
        let bendings = constraints::bendings(grid, &settings);
        let spine = (0..grid.nz).map(|j| rest[grid.index(0, j)]).collect();
        let n = grid.len();
        Ok(Self {
            distance_lambda: vec![T::ZERO; distances.len()],
            bending_lambda: vec![T::Vec3::ZERO; bendings.len()],
            x: rest.clone(),
            v: vec![T::Vec3::ZERO; n],
            start: rest.clone(),
            frame_x: rest.clone(),
            frame_v: vec![T::Vec3::ZERO; n],
            gripped: Vec::with_capacity(4),
            settings,
            grid,
            rest,
            mass,
            inverse_mass,
            distances,
            bendings,
            spine,
            hold: None,
            out_of_reach: false,
            frame: 0,
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &XpbdSettings<T> {
        &self.settings
    }

    /// The particle grid (particles, not quads).
    #[must_use]
    pub fn grid(&self) -> QuadGrid {
        self.grid
    }

    /// Particle positions (page frame), index $i + (n_x + 1) j$.
    #[must_use]
    pub fn positions(&self) -> &[T::Vec3] {
        &self.x
    }

    /// Particle velocities (page units per second).
    #[must_use]
    pub fn velocities(&self) -> &[T::Vec3] {
        &self.v
    }

    /// Rest positions of the particles.
    #[must_use]
    pub fn rest(&self) -> &[T::Vec3] {
        &self.rest
    }

    /// Particle masses $\rho A_v$ (page masses).
    #[must_use]
    pub fn masses(&self) -> &[T] {
        &self.mass
    }

    /// The distance constraints (stretch and shear).
    #[must_use]
    pub fn distances(&self) -> &[Distance<T>] {
        &self.distances
    }

    /// The bending constraints.
    #[must_use]
    pub fn bendings(&self) -> &[Bending<T>] {
        &self.bendings
    }

    /// The gripped particles.
    #[must_use]
    pub fn gripped(&self) -> &[u32] {
        &self.gripped
    }

    /// Frames stepped since construction.
    #[must_use]
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// The bending energy $\frac D2\sum_v A_v\lVert\Delta_h x_v\rVert^2$ at the current
    /// positions ([`constraints`]).
    #[must_use]
    pub fn bending_energy(&self) -> T {
        let mut e = T::ZERO;
        for b in &self.bendings {
            let mut c = T::Vec3::ZERO;
            for (&k, &w) in b.nodes[..b.len].iter().zip(&b.weights) {
                let p = self.x[k as usize];
                c += T::Vec3::new(w.x() * p.x(), w.y() * p.y(), w.z() * p.z());
            }
            e += c.dot(c) / (T::TWO * b.compliance);
        }
        e
    }

    /// The surface point at material point `at`: the bilinear interpolation of the particle
    /// grid (module docs, "Output").
    #[must_use]
    pub fn eval(&self, at: [T; 2]) -> T::Vec3 {
        let ([i, j], [a, b]) = self.cell(at);
        let g = self.grid;
        let p = |i: usize, j: usize| self.x[g.index(i, j)];
        let bottom = p(i, j) * (T::ONE - a) + p(i + 1, j) * a;
        let top = p(i, j + 1) * (T::ONE - a) + p(i + 1, j + 1) * a;
        bottom * (T::ONE - b) + top * b
    }

    /// The cell $(i, j)$ holding material point `at` and the point's local coordinates in
    /// it, each in $[0, 1]$.
    fn cell(&self, at: [T; 2]) -> ([usize; 2], [T; 2]) {
        let spacing = self.settings.spacing();
        let local = |t: T, h: T, quads: usize| {
            let f = (t / h).to_f64();
            let c = if f.is_finite() && f > 0.0 {
                (f as usize).min(quads - 1)
            } else {
                0
            };
            let a = t / h - T::from_f64(c as f64);
            let a = if a < T::ZERO {
                T::ZERO
            } else if a > T::ONE {
                T::ONE
            } else {
                a
            };
            (c, a)
        };
        let (i, a) = local(at[0], spacing[0], self.settings.quads_across);
        let (j, b) = local(at[1], spacing[1], self.settings.quads_along);
        ([i, j], [a, b])
    }

    /// Frees the gripped particles (their velocities stay).
    fn let_go(&mut self) {
        for &k in &self.gripped {
            let k = k as usize;
            if let (Some(w), Some(&m)) = (self.inverse_mass.get_mut(k), self.mass.get(k)) {
                *w = T::ONE / m;
            }
        }
        self.gripped.clear();
        self.hold = None;
    }

    /// The rest position of particle `k`, mirrored across the spine for a page held on the
    /// left.
    fn rest_of(&self, k: usize, mirrored: bool) -> T::Vec3 {
        let r = self.rest[k];
        if mirrored {
            T::Vec3::new(-r.x(), r.y(), r.z())
        } else {
            r
        }
    }

    /// The largest $s \in [0, 1]$ that keeps every gripped particle, translated by $s\,d$,
    /// within $\rho = 1 + \tau_r$ of its rest distance to every spine particle (module
    /// docs). With $e = \bar x_k - \bar x_f$ the bound
    /// $\lVert e + s\,d\rVert^2 \le \rho^2\lVert e\rVert^2$ holds up to the positive root
    /// $s = \big(\sqrt{(e\cdot d)^2 + (\rho^2 - 1)\lVert e\rVert^2\lVert d\rVert^2} -
    /// e\cdot d\big)/\lVert d\rVert^2$ (it holds at $s = 0$); $d$ is first divided by its
    /// largest component, so that a finger far away does not overflow.
    fn reach(&self, d: T::Vec3, mirrored: bool) -> T {
        let largest = [d.x(), d.y(), d.z()]
            .into_iter()
            .map(math::abs)
            .fold(T::ZERO, |m, c| if c > m { c } else { m });
        if !(largest > T::ZERO && largest.is_finite()) {
            return T::ONE;
        }
        let unit = d / largest;
        let dd = unit.dot(unit);
        let rho = T::ONE + T::from_f64(REACH_SLACK);
        let slack = rho * rho - T::ONE;
        let mut s = T::MAX;
        for &k in &self.gripped {
            let xk = self.rest_of(k as usize, mirrored);
            for &f in &self.spine {
                let e = xk - f;
                let ed = e.dot(unit);
                let root = (math::sqrt(ed * ed + slack * e.dot(e) * dd) - ed) / dd;
                if root < s {
                    s = root;
                }
            }
        }
        let s = s / largest;
        if s < T::ONE { s } else { T::ONE }
    }

    /// The finger's translation of the gripped particles this frame, cut to the reach
    /// (module docs), or `None` while the finger has not moved.
    fn shift(&mut self) -> Option<(T::Vec3, bool)> {
        let hold = self.hold?;
        let d = hold.displacement()?;
        let s = self.reach(d, hold.mirrored);
        if s < T::ONE {
            self.out_of_reach = true;
        }
        Some((d * s, hold.mirrored))
    }

    /// Substep `s` of `n` (module docs) with the finger's translation `shift`.
    fn substep(&mut self, s: u32, n: u32, shift: Option<(T::Vec3, bool)>) {
        let h = self.settings.substep();
        self.start.copy_from_slice(&self.x);
        if let Some((d, mirrored)) = shift {
            let fraction = T::from_f64(f64::from(s) / f64::from(n.max(1)));
            for index in 0..self.gripped.len() {
                let k = self.gripped[index] as usize;
                let target = self.rest_of(k, mirrored) + d;
                let from = self.frame_x[k];
                self.x[k] = if s >= n {
                    target
                } else {
                    from + (target - from) * fraction
                };
            }
        }
        let gravity = T::Vec3::new(T::ZERO, -self.settings.gravity, T::ZERO) * h;
        let drag = T::ONE / (T::ONE + self.settings.damping * h);
        for ((x, v), &w) in self.x.iter_mut().zip(&mut self.v).zip(&self.inverse_mass) {
            if w > T::ZERO {
                *v = *v * drag + gravity;
                *x += *v * h;
            }
        }
        self.solve(h);
        let floor = self.settings.floor;
        for (((x, v), &start), &w) in self
            .x
            .iter_mut()
            .zip(&mut self.v)
            .zip(&self.start)
            .zip(&self.inverse_mass)
        {
            let free = w > T::ZERO;
            if floor && free && x.y() < T::ZERO {
                *x = T::Vec3::new(x.x(), T::ZERO, x.z());
            }
            // A fixed particle never moves (v = 0); a gripped one moves with the finger.
            *v = (*x - start) / h;
            if floor && free && x.y() <= T::ZERO && v.y() < T::ZERO {
                *v = T::Vec3::new(v.x(), T::ZERO, v.z());
            }
        }
    }

    /// Step 3 of a substep (module docs): the constraint sweeps.
    fn solve(&mut self, h: T) {
        let inverse_h2 = T::ONE / (h * h);
        self.distance_lambda.iter_mut().for_each(|l| *l = T::ZERO);
        self.bending_lambda
            .iter_mut()
            .for_each(|l| *l = T::Vec3::ZERO);
        for _ in 0..self.settings.iterations {
            for (c, l) in self.distances.iter().zip(&mut self.distance_lambda) {
                constraints::project_distance(
                    &mut self.x,
                    l,
                    c,
                    &self.inverse_mass,
                    c.compliance * inverse_h2,
                );
            }
            for (c, l) in self.bendings.iter().zip(&mut self.bending_lambda) {
                constraints::project_bending(
                    &mut self.x,
                    l,
                    c,
                    &self.inverse_mass,
                    c.compliance * inverse_h2,
                );
            }
        }
    }
}

impl<T: Real> PageModel<T> for XpbdPage<T> {
    fn name(&self) -> &'static str {
        "xpbd"
    }

    fn size(&self) -> [T; 2] {
        [self.settings.width, self.settings.height]
    }

    /// Grips the particles of the cell holding `at` that carry its bilinear weight (module
    /// docs), letting go of any earlier grab first.
    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError> {
        check_grab(at, self.size())?;
        self.let_go();
        let ([i, j], [a, b]) = self.cell(at);
        let corners = [
            (i, j, (T::ONE - a) * (T::ONE - b)),
            (i + 1, j, a * (T::ONE - b)),
            (i, j + 1, (T::ONE - a) * b),
            (i + 1, j + 1, a * b),
        ];
        for (ci, cj, weight) in corners {
            let k = self.grid.index(ci, cj);
            if weight > T::from_f64(GRIP_WEIGHT) && ci > 0 {
                self.inverse_mass[k] = T::ZERO;
                self.gripped.push(k as u32);
            }
        }
        self.hold = Some(Hold::new(at));
        Ok(())
    }

    /// Left of the spine when its particles' mean X is negative.
    fn lying_side(&self) -> BlockSide {
        crate::lying_side::<T>(&self.x)
    }

    fn taken_from(&mut self, side: BlockSide) {
        hold::taken_from(&mut self.hold, side);
    }

    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError> {
        hold::drag(&mut self.hold, finger)
    }

    fn release(&mut self) {
        self.let_go();
    }

    fn step(&mut self) -> Result<PageStep<T>, PageError> {
        self.frame_x.copy_from_slice(&self.x);
        self.frame_v.copy_from_slice(&self.v);
        self.out_of_reach = false;
        let shift = self.shift();
        let n = self.settings.substeps.max(1);
        for s in 1..=n {
            self.substep(s, n, shift);
        }
        let status = if !all_in_range::<T>(&self.x) || !all_in_range::<T>(&self.v) {
            self.x.copy_from_slice(&self.frame_x);
            self.v.copy_from_slice(&self.frame_v);
            PageStatus::Stalled
        } else if self.out_of_reach {
            PageStatus::Unreachable
        } else {
            PageStatus::Moved
        };
        self.frame += 1;
        let finger_gap = self.hold.and_then(|hold| {
            hold.finger
                .map(|f| math::length::<T>(self.eval(hold.at) - f))
        });
        Ok(PageStep { status, finger_gap })
    }

    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError> {
        super::check_count(grid.len(), out.len())?;
        let size = self.size();
        for (k, p) in out.iter_mut().enumerate() {
            *p = self.eval(material_point(grid, size, k));
        }
        Ok(())
    }
}
