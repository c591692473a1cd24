//! A heavy strip settled to rest on a ground (the block's top page of [`super`]).
//!
//! **The continuum.** An inextensible strip of length $L$, bending stiffness $B$ and weight
//! $q$ per unit length, in the XY plane with gravity along $-Y$, rooted at $p(0) = r$, stays
//! where the ground's signed distance $\varphi \ge 0$ and minimises
//! $$E = \int_0^L \tfrac{B}{2}\kappa^2\,ds + \int_0^L q\,y\,ds .$$
//! Over $B$ it depends on $q/B = \alpha/L^3$ alone, with $\alpha = qL^3/B = \rho g L^3/D$
//! the page's sag number ([`crate::paper`]). The root is pinned (free angle, no moment) or
//! clamped at a given angle ([`Root`]).
//!
//! **The discretization.** $N$ segments of rest length $h = L/N$ between nodes
//! $p_0 = r, p_1, \dots, p_N$; every energy is divided by $B$:
//! $$\frac{E_h}{B} = \sum_{k=1}^{N-1}\frac{\psi_k^2}{2h} +
//!   \frac{\alpha}{L^3}\sum_{k=1}^{N} m_k\,y_k +
//!   \frac{s}{2h}\sum_{k=1}^{N}\bigl(\lVert p_k - p_{k-1}\rVert - h\bigr)^2 +
//!   \frac{c}{2}\sum_{k=1}^{N}\min(\varphi(p_k), 0)^2,$$
//! with $\psi_k$ the turning angle at node $k$ (the discrete curvature times $h$), the
//! lumped lengths $m_k = h$ and $m_N = h/2$, and two penalties that stand for constraints:
//! inextensibility with $s = 10^4/h^2$ (a strain of about $10^{-4} q L h^2/B$, below
//! $10^{-8}$ for a page at 200 segments) and the ground with $c = 10^4/h^3$. A clamped root
//! adds the turning angle at $p_0$ from a fixed ghost node $p_{-1} = r - h\,t_0$.
//!
//! **The solver.** Newton on the nodes: each energy but gravity is a sum of squares
//! $\tfrac w2 r^2$ (the turning angles, the stretches, the penetrations), its Hessian
//! $w(\nabla r\nabla r^\top + r\nabla^2 r)$ with the second term of a compressed segment
//! left out; banded with half bandwidth 5 in the node order ([`folio_solvers::banded`]).
//! - **The ground in the step.** Each step minimises the energy's quadratic model with the
//!   ground linearised at each node and each segment over a sharp corner, exactly, by
//!   active sets ([`Elastica::settle`]'s `contact_step`).
//! - **The move.** Each segment turns to its new direction with its length kept to first
//!   order, nodes on the ground slide along it (`retract`).
//! - **Globalisation.** Levenberg–Marquardt damping $\mu I$ with the Armijo test
//!   ($10^{-4}$) on $E_h$; a damped step that is accepted is doubled while the energy
//!   falls (a page turning about its pin).
//! - **Coarse first.** A strip of $N \ge 100$ segments ($N$ even) is first settled at
//!   $N/2$ and refined by midpoints, down to 50 segments.
//!
//! It stops when an undamped Newton step moves no node by more than $10^{-9} L$ (the
//! rounding of a heavy page at 372 segments leaves steps of $3 \cdot 10^{-9} L$), and
//! reports [`ElasticaError::NotSettled`] after 400 iterations. The figures (tests in
//! `folio-tests`' `gutter.rs`): a clamped strip within $1.3\cdot10^{-5} L$ of the shooting
//! reference at $\alpha = 11$ and 200 segments, second order; a block's top page at 200
//! segments within $10^{-4} W$ of the one extrapolated from 800 and 1600.

use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use folio_geometry::BlockSide;
use folio_kernels::SettingError;
use folio_kernels::math;
use folio_kernels::setting::{require, require_positive};
use folio_solvers::banded::Banded;

use super::ground::{Ground, Point2};

/// How the strip is held at its root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Root {
    /// Pinned: any angle, no moment (a page in its binding, issue 42's gutter).
    Pinned,
    /// Clamped at `angle` (radians from $+X$ towards $+Y$).
    Clamped {
        /// The root tangent's angle.
        angle: f64,
    },
}

/// A heavy strip to settle (module docs), in page units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastica {
    /// The root $r$.
    pub root: Point2,
    /// How the root holds the strip.
    pub held: Root,
    /// The strip's length $L$ (> 0).
    pub length: f64,
    /// The sag number $\alpha = qL^3/B \ge 0$.
    pub sag: f64,
    /// Segments $N$, at least 2.
    pub segments: usize,
}

/// Why a strip could not be settled.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ElasticaError {
    /// A field of [`Elastica`] (or the start's length) is out of its range.
    InvalidSetting(SettingError),
    /// The iterations ran out, or no damping gave a step that lowers the energy.
    NotSettled {
        /// Gauss–Newton iterations taken.
        iterations: u32,
        /// The largest net force on a node over a segment's weight when it stopped.
        force: f64,
    },
    /// No start was found: no arch from the root clears the ground ([`Elastica::arched`]).
    NoStart,
    /// The rest reached is not finite (a point, its depth in the ground or its strain).
    NonFinite,
}

impl fmt::Display for ElasticaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidSetting(e) => write!(f, "elastica setting {e}"),
            Self::NotSettled { iterations, force } => write!(
                f,
                "the elastica did not settle in {iterations} iterations (net force {force:.3e} of a segment's weight)"
            ),
            Self::NoStart => write!(f, "no arch from the elastica's root clears the ground"),
            Self::NonFinite => write!(f, "the elastica's rest is not finite"),
        }
    }
}

impl core::error::Error for ElasticaError {}

impl From<SettingError> for ElasticaError {
    fn from(e: SettingError) -> Self {
        Self::InvalidSetting(e)
    }
}

/// A settled strip.
#[derive(Clone, Debug, PartialEq)]
pub struct Settled {
    /// The nodes $p_0 = r, \dots, p_N$, at arc lengths $kL/N$.
    pub points: Vec<Point2>,
    /// Gauss–Newton iterations taken.
    pub iterations: u32,
    /// The last Newton step's largest node move over $L$ (at most $10^{-9}$). The net
    /// forces are no measure at fine grids: the stiff penalties' rounding alone is about a
    /// segment's weight at 1600 segments.
    pub step: f64,
    /// The deepest a node sank into the ground (page units, $\ge 0$).
    pub penetration: f64,
    /// The largest relative change of a segment's length.
    pub strain: f64,
}

impl Settled {
    /// The point at arc length `s` (clamped to $[0, L]$), interpolated along the segment
    /// that holds it.
    #[must_use]
    pub fn at(&self, s: f64, length: f64) -> Point2 {
        let n = self.points.len() - 1;
        let u = (s / length).clamp(0.0, 1.0) * n as f64;
        let k = (u as usize).min(n - 1);
        let t = u - k as f64;
        let (a, b) = (self.points[k], self.points[k + 1]);
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }
}

/// One way the strip may sink into the ground: a gap $d$ that must stay $\ge 0$, linear to
/// first order in the moves of up to two nodes, $d + \sum_i g_i^\top \delta p_{k_i}$.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Contact {
    /// The nodes (0, the root, for none).
    nodes: [usize; 2],
    /// $\partial d/\partial p_{k_i}$.
    grads: [Point2; 2],
    /// The gap $d$ (page units; negative inside the ground).
    gap: f64,
}

/// The fewest segments [`Elastica::settle`] coarsens to.
const COARSEST: usize = 50;

/// How a trial move treats a node ([`Elastica::retract`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hold {
    /// Off the ground: built on from the root.
    Free,
    /// On one face of the ground (outward normal): the step's height over it, sliding.
    Slide(Point2),
    /// On two faces (a crease): where the step puts it.
    Fixed,
}

/// Iterations before [`ElasticaError::NotSettled`].
const MAX_ITERATIONS: u32 = 400;

/// Damping increases (each tenfold) tried in one iteration before
/// [`ElasticaError::NotSettled`].
const MAX_DAMPINGS: u32 = 40;

/// The furthest a damped step is extrapolated, in steps.
const MAX_EXTRAPOLATION: f64 = 1024.0;

/// Active sets tried for one step ([`Elastica::contact_step`]).
const MAX_ACTIVE_SETS: u32 = 50;

/// The stopping step: a Newton step that moves no node by more than this times $L$.
const STEP_TOLERANCE: f64 = 1e-9;

/// The penalties' stiffness relative to the bending at the segment scale (module docs).
const PENALTY: f64 = 1e4;

/// Unknowns per node ($x$, $y$) and the band that the turning angles need.
const HALF_BANDWIDTH: usize = 5;

impl Elastica {
    /// Checks the fields.
    ///
    /// # Errors
    /// The first field out of range: the root and `length` finite (length > 0), `sag`
    /// finite and $\ge 0$ ($> 0$ for a pinned strip), `segments` at least 2, a clamp's angle
    /// finite.
    pub fn validate(&self) -> Result<(), SettingError> {
        for v in self.root {
            require(v.is_finite(), "root", "finite", v)?;
        }
        require_positive("length", self.length)?;
        require(
            self.sag.is_finite() && self.sag >= 0.0,
            "sag",
            "finite and >= 0",
            self.sag,
        )?;
        // Weightless on a pin, a strip rests straight at any angle: no rest to find.
        require(
            self.sag > 0.0 || self.held != Root::Pinned,
            "sag",
            "> 0 for a pinned strip (weightless, it rests at any angle)",
            self.sag,
        )?;
        require(
            self.segments >= 2,
            "segments",
            "at least 2",
            self.segments as f64,
        )?;
        if let Root::Clamped { angle } = self.held {
            require(angle.is_finite(), "held.angle", "finite", angle)?;
        }
        Ok(())
    }

    /// The strip settled on `ground` from `start` ($N + 1$ points, the first one the root;
    /// the root is taken from [`Elastica::root`] whatever `start` holds). The start decides
    /// which rest a strip with several reaches (a page that may lie on either side).
    ///
    /// # Errors
    /// [`ElasticaError::InvalidSetting`] for a field out of range or a start of the wrong
    /// length or not finite; [`ElasticaError::NotSettled`] when the iterations run out;
    /// [`ElasticaError::NonFinite`] for a rest that is not finite.
    pub fn settle(&self, ground: &impl Ground, start: &[Point2]) -> Result<Settled, ElasticaError> {
        self.validate()?;
        let n = self.segments;
        require(
            start.len() == n + 1,
            "start",
            "segments + 1 points long",
            start.len() as f64,
        )?;
        for p in start {
            for v in p {
                require(v.is_finite(), "start", "finite", *v)?;
            }
        }
        if n % 2 != 0 || n / 2 < COARSEST {
            return self.newton(ground, start);
        }
        // Settled on every other node first, then refined: the coarse strip makes the long
        // moves (a fall onto the ground, a page turning about its pin) in few cheap
        // iterations, and the fine one starts next to its rest. Straight at 800 segments,
        // a novel page over its block ran out of iterations.
        let coarse = Self {
            segments: n / 2,
            ..*self
        };
        let every_other: Vec<Point2> = start.iter().step_by(2).copied().collect();
        let settled = coarse.settle(ground, &every_other)?;
        let mut refined = Vec::with_capacity(n + 1);
        for w in settled.points.windows(2) {
            refined.push(w[0]);
            // A midpoint of a chord over a rounded edge lies inside it: moved out along the
            // normal (a few times, for an edge tighter than the chord), or the fine strip
            // starts deep in the ground (a heavy page over a block 0.024 thick: 300
            // iterations at 372 segments, peeling out by damped steps, and no rest).
            let mut mid = [0.5 * (w[0][0] + w[1][0]), 0.5 * (w[0][1] + w[1][1])];
            for _ in 0..4 {
                let (d, n) = ground.signed_distance(mid);
                if d.is_nan() || d >= 0.0 {
                    break;
                }
                mid = [mid[0] - d * n[0], mid[1] - d * n[1]];
            }
            refined.push(mid);
        }
        refined.push(settled.points[n / 2]);
        let mut fine = self.newton(ground, &refined)?;
        fine.iterations += settled.iterations;
        Ok(fine)
    }

    /// [`Elastica::settle`] on this strip alone, from a checked start.
    fn newton(&self, ground: &impl Ground, start: &[Point2]) -> Result<Settled, ElasticaError> {
        let n = self.segments;
        let mut x: Vec<f64> = start[1..].iter().flat_map(|p| [p[0], p[1]]).collect();
        let mut hessian = Banded::new(2 * n, HALF_BANDWIDTH);
        let mut factor = hessian.clone();
        let mut gradient = vec![0.0; 2 * n];
        let mut total = vec![0.0; 2 * n];
        let mut trial = x.clone();
        let mut further = x.clone();
        let mut step = vec![0.0; 2 * n];
        let mut contacts = Vec::new();
        // The line search's own contact list: `contacts` holds the iterate's active sets.
        let mut scratch = Vec::new();
        let mut active = Vec::new();
        let mut holds = Vec::new();
        let weight = self.sag / (self.length * self.length * self.length) * self.h();
        let h = self.h();
        let contact = self.contact_stiffness();
        // The least damping: the bending stiffness of a kink, 1/h^3, times 1e-6.
        let floor = 1e-6 / (h * h * h);
        let mut damping = 0.0;
        let mut force = f64::INFINITY;
        for iteration in 0..MAX_ITERATIONS {
            let energy = self.assemble(
                ground,
                &x,
                &mut scratch,
                Some((&mut gradient, &mut hessian)),
            );
            total.copy_from_slice(&gradient);
            self.contacts(ground, &x, &mut contacts);
            active.clear();
            active.extend(contacts.iter().map(|c| c.gap < 0.0));
            for c in contacts.iter().filter(|c| c.gap < 0.0) {
                add_gradient(&mut total, &c.nodes, &c.grads, contact * c.gap);
            }
            force = folio_solvers::vector::max_abs(&total) / weight.max(self.bending_scale());
            // What rounding leaves of an energy comparison: a few ulps of the terms' sizes.
            let slack = 64.0 * f64::EPSILON * (energy.abs() + self.energy_scale());
            let mut accepted = false;
            for _ in 0..MAX_DAMPINGS {
                if !self.contact_step(
                    &hessian,
                    &gradient,
                    &contacts,
                    damping,
                    &mut active,
                    &mut factor,
                    &mut step,
                ) {
                    damping = (10.0 * damping).max(floor);
                    continue;
                }
                // `step` holds the step's negative: the slope along it is -g.step.
                if damping == 0.0
                    && folio_solvers::vector::max_abs(&step) <= STEP_TOLERANCE * self.length
                {
                    let moved = folio_solvers::vector::max_abs(&step) / self.length;
                    return self.settled(ground, &x, iteration, moved);
                }
                let slope = -folio_solvers::vector::dot(&total, &step);
                holds.clear();
                holds.resize(n + 1, Hold::Free);
                for (c, _) in contacts
                    .iter()
                    .zip(&active)
                    .filter(|(c, a)| **a && c.nodes[1] == 0)
                {
                    let k = c.nodes[0];
                    holds[k] = match holds[k] {
                        Hold::Free => Hold::Slide(c.grads[0]),
                        _ => Hold::Fixed,
                    };
                }
                self.retract(&x, &step, 1.0, &holds, &mut trial);
                let mut reached = self.assemble(ground, &trial, &mut scratch, None);
                if slope < 0.0 && reached <= energy + 1e-4 * slope + slack {
                    accepted = true;
                    if damping > 0.0 {
                        // A damped step along a falling mode (a strip turning about its
                        // pin, whose compressed stiffness the Hessian leaves out) goes on
                        // while the energy falls: twice as far each time.
                        let mut t = 2.0;
                        while t <= MAX_EXTRAPOLATION {
                            self.retract(&x, &step, t, &holds, &mut further);
                            let e = self.assemble(ground, &further, &mut scratch, None);
                            if e.is_nan() || e >= reached {
                                break;
                            }
                            reached = e;
                            core::mem::swap(&mut trial, &mut further);
                            t *= 2.0;
                        }
                    }
                    damping = if damping > floor { damping / 4.0 } else { 0.0 };
                    break;
                }
                damping = (10.0 * damping).max(floor);
            }
            if !accepted {
                return Err(ElasticaError::NotSettled {
                    iterations: iteration,
                    force,
                });
            }
            core::mem::swap(&mut x, &mut trial);
        }
        Err(ElasticaError::NotSettled {
            iterations: MAX_ITERATIONS,
            force,
        })
    }

    /// The step of the model
    /// $m(\delta) = E + g^\top\delta + \tfrac12\delta^\top(H + \mu I)\delta +
    /// \tfrac c2\sum_j \min(d_j + \nabla d_j^\top\delta, 0)^2$: the other terms' quadratic
    /// model with each contact's gap $d_j$ linearized ([`Elastica::contacts`]), minimised
    /// exactly by active sets (the contacts the step leaves inside the ground, from those
    /// inside now, until the set repeats; a convex piecewise quadratic). Writes the step's negative to `step`; `false` when a
    /// factorization fails. The model is exact in the ground at $\delta = 0$, so its minimiser
    /// descends on $E_h$. A Newton step that saw only the nodes inside the ground sent the
    /// nodes above it through it: from a start laid on its block, every built-in paper's
    /// top page ran out of iterations.
    #[allow(clippy::too_many_arguments)]
    fn contact_step(
        &self,
        hessian: &Banded,
        gradient: &[f64],
        contacts: &[Contact],
        damping: f64,
        active: &mut [bool],
        factor: &mut Banded,
        step: &mut [f64],
    ) -> bool {
        let stiffness = self.contact_stiffness();
        for _ in 0..MAX_ACTIVE_SETS {
            factor.clone_from(hessian);
            step.copy_from_slice(gradient);
            for i in 0..factor.order() {
                factor.add(i, i, damping);
            }
            for (c, _) in contacts.iter().zip(active.iter()).filter(|(_, a)| **a) {
                add_gradient(step, &c.nodes, &c.grads, stiffness * c.gap);
                scatter_outer(factor, &c.nodes, &c.grads, stiffness);
            }
            if factor.factor().is_err() {
                return false;
            }
            factor.solve(step);
            let mut changed = false;
            for (c, a) in contacts.iter().zip(active.iter_mut()) {
                let mut predicted = c.gap;
                for (k, g) in c.nodes.iter().zip(c.grads).filter(|(k, _)| **k > 0) {
                    predicted -= g[0] * step[2 * k - 2] + g[1] * step[2 * k - 1];
                }
                let inside = predicted < 0.0;
                changed |= inside != *a;
                *a = inside;
            }
            if !changed {
                break;
            }
        }
        true
    }

    /// A start for [`Elastica::settle`] that clears `ground`: from the root straight up, a
    /// quarter turn of radius $R$ towards `side` ($+X$ for the right block), then straight
    /// on level; $R$ the least of $L/16, L/8, \dots, L$ that keeps every node outside the
    /// ground. `None` when no such $R$ clears the ground (or the fields are out of range).
    #[must_use]
    pub fn arched(&self, ground: &impl Ground, side: BlockSide) -> Option<Vec<Point2>> {
        self.validate().ok()?;
        let sign = match side {
            BlockSide::Left => -1.0,
            BlockSide::Right => 1.0,
        };
        let h = self.h();
        (0..5).find_map(|i| {
            let radius = self.length / 16.0 * f64::from(1u32 << i);
            let quarter = core::f64::consts::FRAC_PI_2 * radius;
            let points: Vec<Point2> = (0..=self.segments)
                .map(|k| {
                    let s = k as f64 * h;
                    let (dx, dy) = if s <= quarter {
                        let turned = s / radius;
                        (
                            radius * (1.0 - math::cos(turned)),
                            radius * math::sin(turned),
                        )
                    } else {
                        (radius + s - quarter, radius)
                    };
                    [self.root[0] + sign * dx, self.root[1] + dy]
                })
                .collect();
            points[1..]
                .iter()
                .all(|&p| ground.signed_distance(p).0 > 0.0)
                .then_some(points)
        })
    }

    /// The segment length $h = L/N$.
    fn h(&self) -> f64 {
        self.length / self.segments as f64
    }

    /// A force scale for a weightless strip: the bending force $B/L^2$ on a segment's
    /// share, $h/L^3$ (over $B$).
    fn bending_scale(&self) -> f64 {
        self.h() / (self.length * self.length * self.length)
    }

    /// A bound on the size of $E_h/B$'s terms near rest: the weight times the largest
    /// height, $\alpha(|r_y| + L)/L^2$, and a bend of a radian over the strip, $1/L$.
    fn energy_scale(&self) -> f64 {
        let l = self.length;
        self.sag * (self.root[1].abs() + l) / (l * l) + 1.0 / l
    }

    /// Node `k` ($0..=N$) of the unknowns `x` (the root for 0).
    fn node(&self, x: &[f64], k: usize) -> Point2 {
        if k == 0 {
            self.root
        } else {
            [x[2 * k - 2], x[2 * k - 1]]
        }
    }

    /// Every contact of the strip at `x` with `ground` into `out`: each node's with each
    /// face it is inside, or with the ground's nearest face ([`Ground::for_each_face`]), then
    /// each sharp corner of the ground's ([`Elastica::corner_contact`]).
    fn contacts(&self, ground: &impl Ground, x: &[f64], out: &mut Vec<Contact>) {
        out.clear();
        for k in 1..=self.segments {
            ground.for_each_face(self.node(x, k), &mut |gap, normal| {
                out.push(Contact {
                    nodes: [k, 0],
                    grads: [normal, [0.0; 2]],
                    gap,
                });
            });
        }
        ground.for_each_corner(&mut |q, n| {
            if let Some(c) = self.corner_contact(x, q, n) {
                out.push(c);
            }
        });
    }

    /// The contact of the strip at `x` with the sharp corner `q` (outward `n`): the
    /// corner's signed distance from the strip's nearest feature, positive on `n`'s side.
    /// - On a segment $(a, b)$ that $q$ projects onto ($\lambda \in [0, 1]$), the distance
    ///   from its line, $d = \sigma\,(e \times (a - q))/\lVert e\rVert$ with $e = b - a$
    ///   and $\sigma = \operatorname{sign}(m^\top n)$ for the segment's left normal $m$.
    /// - Otherwise at the nearest node $p$, $d = \pm\lVert p - q\rVert$, negative when
    ///   $p - q$ points into the ground ($(p - q)^\top n < 0$); at the root, which does not
    ///   move, the first segment's line.
    ///
    /// One feature per corner, so the contact slides from segment to segment through their
    /// node continuously: tested against every segment that $q$ projects onto instead, a
    /// page resting over a block's cut corner met a new contact each time the corner
    /// passed a node, and Newton stalled next to its rest (a random block at 138 segments
    /// ran out of iterations with steps of 1e-8).
    fn corner_contact(&self, x: &[f64], q: Point2, n: Point2) -> Option<Contact> {
        // The nearest feature: (squared distance, segment k or node k, lambda).
        let mut best: Option<(f64, usize, f64)> = None;
        for k in 1..=self.segments {
            let (a, b) = (self.node(x, k - 1), self.node(x, k));
            let e = [b[0] - a[0], b[1] - a[1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            if len2.is_nan() || len2 <= 0.0 {
                continue;
            }
            let lambda = (((q[0] - a[0]) * e[0] + (q[1] - a[1]) * e[1]) / len2).clamp(0.0, 1.0);
            let f = [a[0] + lambda * e[0] - q[0], a[1] + lambda * e[1] - q[1]];
            let d2 = f[0] * f[0] + f[1] * f[1];
            if best.is_none_or(|(d, _, _)| d2 < d) {
                best = Some((d2, k, lambda));
            }
        }
        let (_, k, lambda) = best?;
        // Nearest the root, which does not move: the first segment's line instead, which
        // meets the root's distance where the corner comes onto the segment.
        if (lambda > 0.0 && lambda < 1.0) || (k == 1 && lambda <= 0.0) {
            let (a, b) = (self.node(x, k - 1), self.node(x, k));
            let e = [b[0] - a[0], b[1] - a[1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            let len = math::sqrt(len2);
            let r = [a[0] - q[0], a[1] - q[1]];
            let m = [-e[1] / len, e[0] / len];
            let facing = m[0] * n[0] + m[1] * n[1];
            if facing.abs() < core::f64::consts::FRAC_1_SQRT_2 {
                // The segment meets the corner edge-on, more than 45 degrees off the tangent
                // the corner's outward direction stands on: it is beside the corner, not over
                // or under it, and which side the corner is on says nothing (the nodes'
                // own contacts hold them out of the ground there).
                return None;
            }
            let sigma = if facing < 0.0 { -1.0 } else { 1.0 };
            let gap = sigma * (e[0] * r[1] - e[1] * r[0]) / len;
            // dd/de = sigma (r_y, -r_x)/len - d e/len^2, dd/dr = sigma m.
            let de = [
                sigma * r[1] / len - gap * e[0] / len2,
                -sigma * r[0] / len - gap * e[1] / len2,
            ];
            let ga = [sigma * m[0] - de[0], sigma * m[1] - de[1]];
            return Some(Contact {
                nodes: [k - 1, k],
                grads: [ga, de],
                gap,
            });
        }
        let node = if lambda >= 1.0 { k } else { k - 1 };
        let p = self.node(x, node);
        let d = [p[0] - q[0], p[1] - q[1]];
        let dist = math::sqrt(d[0] * d[0] + d[1] * d[1]);
        let sign = if d[0] * n[0] + d[1] * n[1] < 0.0 {
            -1.0
        } else {
            1.0
        };
        let grad = if dist > 0.0 {
            [sign * d[0] / dist, sign * d[1] / dist]
        } else {
            n
        };
        Some(Contact {
            nodes: [node, 0],
            grads: [grad, [0.0; 2]],
            gap: sign * dist,
        })
    }

    /// The ground penalty's stiffness $c = 10^4/h^3$ (module docs).
    fn contact_stiffness(&self) -> f64 {
        let h = self.h();
        PENALTY / (h * h * h)
    }

    /// $E_h/B$ at `x` (module docs); with `Some((gradient, hessian))`, also the gradient and
    /// Hessian over the unknowns of every term but the ground's. `contacts` is a buffer
    /// for the ground's contacts at `x` (no allocation once it has grown).
    fn assemble(
        &self,
        ground: &impl Ground,
        x: &[f64],
        contacts: &mut Vec<Contact>,
        mut derivatives: Option<(&mut Vec<f64>, &mut Banded)>,
    ) -> f64 {
        let n = self.segments;
        let h = self.h();
        let stretch = PENALTY / (h * h);
        let contact = self.contact_stiffness();
        let weight = self.sag / (self.length * self.length * self.length);
        if let Some((g, hess)) = derivatives.as_mut() {
            g.iter_mut().for_each(|v| *v = 0.0);
            hess.clear();
        }
        let mut energy = 0.0;
        // A residual r with its gradient over `nodes`: energy w r^2 / 2, gradient w r grad r,
        // Hessian w grad r grad r^T plus w r times the second derivatives in `curved`: each
        // (from, to, M) the Hessian M of r in the difference p_to - p_from.
        let mut square = |r: f64,
                          w: f64,
                          nodes: &[usize],
                          grads: &[Point2],
                          curved: &[(usize, usize, [[f64; 2]; 2])]| {
            energy += 0.5 * w * r * r;
            let Some((g, hess)) = derivatives.as_mut() else {
                return;
            };
            add_gradient(g, nodes, grads, w * r);
            scatter_outer(hess, nodes, grads, w);
            for &(from, to, m) in curved {
                // r's Hessian M in p_to - p_from: +M on the diagonal blocks, -M across.
                let ends = [(from, -1.0), (to, 1.0)];
                for (ka, sa) in ends.into_iter().filter(|(k, _)| *k > 0) {
                    for (kb, sb) in ends.into_iter().filter(|(k, _)| *k > 0) {
                        scatter_block(hess, ka, kb, |da, db| w * r * sa * sb * m[da][db]);
                    }
                }
            }
        };
        for k in 1..=n {
            let (a, b) = (self.node(x, k - 1), self.node(x, k));
            let d = [b[0] - a[0], b[1] - a[1]];
            let len = math::sqrt(d[0] * d[0] + d[1] * d[1]).max(f64::MIN_POSITIVE);
            let u = [d[0] / len, d[1] / len];
            // The length's Hessian (I - u u^T)/len, kept only in tension: compressed, it
            // would make the matrix indefinite (the strip's buckling), and the penalty
            // holds the length anyway.
            let transverse = [
                [1.0 - u[0] * u[0], -u[0] * u[1]],
                [-u[0] * u[1], 1.0 - u[1] * u[1]],
            ];
            let curved = [(k - 1, k, transverse.map(|row| row.map(|v| v / len)))];
            let tension = if len > h { &curved[..] } else { &[] };
            square(
                len - h,
                stretch / h,
                &[k - 1, k],
                &[[-u[0], -u[1]], u],
                tension,
            );
        }
        // The turning angle psi = phi(b) - phi(a), phi(v) = atan2(v_y, v_x), with
        // grad phi = v_perp/|v|^2 (v_perp = (-v_y, v_x)) and
        // Hess phi = [[2 v_x v_y, v_y^2 - v_x^2], [v_y^2 - v_x^2, -2 v_x v_y]]/|v|^4.
        let turning = |before: Point2, at: Point2, after: Point2| {
            let a = [at[0] - before[0], at[1] - before[1]];
            let b = [after[0] - at[0], after[1] - at[1]];
            let psi = math::atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]);
            let angle = |v: Point2| {
                let vv = (v[0] * v[0] + v[1] * v[1]).max(f64::MIN_POSITIVE);
                let (xy, d) = (2.0 * v[0] * v[1], v[1] * v[1] - v[0] * v[0]);
                (
                    [-v[1] / vv, v[0] / vv],
                    [[xy, d], [d, -xy]].map(|r| r.map(|e| e / (vv * vv))),
                )
            };
            let ((ga, ha), (gb, hb)) = (angle(a), angle(b));
            let grads = [ga, [-ga[0] - gb[0], -ga[1] - gb[1]], gb];
            (psi, grads, ha.map(|r| r.map(|e| -e)), hb)
        };
        if let Root::Clamped { angle } = self.held {
            let ghost = [
                self.root[0] - h * math::cos(angle),
                self.root[1] - h * math::sin(angle),
            ];
            let (psi, grads, _, hb) = turning(ghost, self.root, self.node(x, 1));
            // The clamped tangent is at s = 0, segment 1's at h/2: half a dual cell.
            square(psi, 2.0 / h, &[0, 1], &grads[1..], &[(0, 1, hb)]);
        }
        for k in 1..n {
            let (psi, grads, ha, hb) =
                turning(self.node(x, k - 1), self.node(x, k), self.node(x, k + 1));
            square(
                psi,
                1.0 / h,
                &[k - 1, k, k + 1],
                &grads,
                &[(k - 1, k, ha), (k, k + 1, hb)],
            );
        }
        // The ground's energy; its derivatives are the step's business ([`Elastica::settle`]).
        self.contacts(ground, x, contacts);
        for c in contacts.iter().filter(|c| c.gap < 0.0) {
            energy += 0.5 * contact * c.gap * c.gap;
        }
        for k in 1..=n {
            let m = if k == n { 0.5 * h } else { h };
            energy += weight * m * x[2 * k - 1];
            if let Some((g, _)) = derivatives.as_mut() {
                g[2 * k - 1] += weight * m;
            }
        }
        energy
    }

    /// `out` = the nodes `x` moved by minus `step`, each segment turned to its moved
    /// direction and given its length to first order, $\lVert a\rVert + \hat a^\top \delta a$,
    /// built outwards from the root (a co-rotational update), except that a node the step
    /// leaves on the ground (`active`) keeps the step's own height over the ground (along
    /// its normal in `ground_at`) and slides only along it.
    ///
    /// A plain move lengthens a segment it turns by $\beta$ by $h(\sec\beta - 1)$, which the
    /// stiff inextensibility penalty reads as stretch: the line search cut the steps of a
    /// clamped strip at $\alpha = 0.5$ to 1/32 for 60 iterations. Built from the root
    /// throughout, the length kept by a turned segment near the root moved every node lying
    /// on the ground beyond it into the ground, and a page lying on its block peeled off a
    /// node every few iterations; a second-order correction through the step's factor
    /// (Nocedal and Wright, Sec. 15.6) in its place took 240 iterations on the free
    /// cantilever that this update settles in 5.
    fn retract(&self, x: &[f64], step: &[f64], t: f64, holds: &[Hold], out: &mut [f64]) {
        let mut before = self.root;
        let mut moved_before = self.root;
        let shift = |k: usize, d: usize| {
            if k == 0 {
                0.0
            } else {
                -t * step[2 * k - 2 + d]
            }
        };
        for k in 1..=self.segments {
            let at = self.node(x, k);
            let a = [at[0] - before[0], at[1] - before[1]];
            let da = [shift(k, 0) - shift(k - 1, 0), shift(k, 1) - shift(k - 1, 1)];
            let len = math::sqrt(a[0] * a[0] + a[1] * a[1]).max(f64::MIN_POSITIVE);
            let length = len + (a[0] * da[0] + a[1] * da[1]) / len;
            let b = [a[0] + da[0], a[1] + da[1]];
            let blen = math::sqrt(b[0] * b[0] + b[1] * b[1]).max(f64::MIN_POSITIVE);
            let mut moved = [
                moved_before[0] + length * b[0] / blen,
                moved_before[1] + length * b[1] / blen,
            ];
            let plain = [at[0] + shift(k, 0), at[1] + shift(k, 1)];
            match holds[k] {
                Hold::Free => {}
                Hold::Slide(n) => {
                    let off = (moved[0] - plain[0]) * n[0] + (moved[1] - plain[1]) * n[1];
                    moved = [moved[0] - off * n[0], moved[1] - off * n[1]];
                }
                Hold::Fixed => moved = plain,
            }
            out[2 * k - 2] = moved[0];
            out[2 * k - 1] = moved[1];
            before = at;
            moved_before = moved;
        }
    }

    /// The result at `x`; [`ElasticaError::NonFinite`] when a point, its depth or a
    /// segment's strain is not finite (the folds keep a NaN, they do not skip it).
    fn settled(
        &self,
        ground: &impl Ground,
        x: &[f64],
        iterations: u32,
        step: f64,
    ) -> Result<Settled, ElasticaError> {
        let points: Vec<Point2> = (0..=self.segments).map(|k| self.node(x, k)).collect();
        let h = self.h();
        let penetration = largest(points[1..].iter().map(|&p| -ground.signed_distance(p).0));
        let strain = largest(points.windows(2).map(|w| {
            let d = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            (math::sqrt(d[0] * d[0] + d[1] * d[1]) / h - 1.0).abs()
        }));
        let finite = points.iter().flatten().all(|c| c.is_finite());
        if !(finite && penetration.is_finite() && strain.is_finite()) {
            return Err(ElasticaError::NonFinite);
        }
        Ok(Settled {
            points,
            iterations,
            step,
            penetration,
            strain,
        })
    }
}

/// The largest of `values` and 0; NaN when any is NaN (where `f64::max` would skip it).
fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(
        0.0,
        |worst, v| if v.is_nan() || v > worst { v } else { worst },
    )
}

/// `v` += `scale` times the gradient `grads` of a quantity over `nodes` (the root, node 0,
/// has no unknowns).
fn add_gradient(v: &mut [f64], nodes: &[usize], grads: &[Point2], scale: f64) {
    for (&k, g) in nodes.iter().zip(grads).filter(|(k, _)| **k > 0) {
        v[2 * k - 2] += scale * g[0];
        v[2 * k - 1] += scale * g[1];
    }
}

/// Adds `value(da, db)` to the Hessian's block of nodes `ka`, `kb` (their lower triangle).
fn scatter_block(hess: &mut Banded, ka: usize, kb: usize, value: impl Fn(usize, usize) -> f64) {
    for da in 0..2 {
        for db in 0..2 {
            let (i, j) = (2 * ka - 2 + da, 2 * kb - 2 + db);
            if j <= i {
                hess.add(i, j, value(da, db));
            }
        }
    }
}

/// Adds $w\,\nabla r\nabla r^\top$ for the gradient `grads` of $r$ over `nodes`.
fn scatter_outer(hess: &mut Banded, nodes: &[usize], grads: &[Point2], w: f64) {
    for (&ka, ga) in nodes.iter().zip(grads).filter(|(k, _)| **k > 0) {
        for (&kb, gb) in nodes.iter().zip(grads).filter(|(k, _)| **k > 0) {
            scatter_block(hess, ka, kb, |da, db| w * ga[da] * gb[db]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Elastica, ElasticaError, Root};
    use crate::gutter::Air;
    use alloc::vec::Vec;

    fn strip() -> Elastica {
        Elastica {
            root: [0.0, 0.0],
            held: Root::Clamped { angle: 0.5 },
            length: 2.0,
            sag: 0.0,
            segments: 8,
        }
    }

    #[test]
    fn the_largest_keeps_a_nan_and_is_never_below_zero() {
        use super::largest;
        assert_eq!(largest([-1.0, 0.5, 0.25].into_iter()), 0.5);
        assert_eq!(largest([-1.0, -2.0].into_iter()), 0.0);
        // `f64::max` would give 3 for both.
        assert!(largest([f64::NAN, 3.0].into_iter()).is_nan());
        assert!(largest([3.0, f64::NAN].into_iter()).is_nan());
    }

    #[test]
    fn a_weightless_clamped_strip_stays_straight() {
        let e = strip();
        let start: Vec<[f64; 2]> = (0..=8).map(|k| [0.25 * k as f64, 0.0]).collect();
        let s = e.settle(&Air, &start).expect("it settles");
        for (k, p) in s.points.iter().enumerate() {
            let r = 0.25 * k as f64;
            assert!(
                (p[0] - r * 0.5f64.cos()).abs() < 1e-9 && (p[1] - r * 0.5f64.sin()).abs() < 1e-9,
                "{k}: {p:?}"
            );
        }
    }

    #[test]
    fn bad_fields_and_starts_are_refused_by_name() {
        let field = |e: Elastica, start: &[[f64; 2]]| match e.settle(&Air, start) {
            Err(ElasticaError::InvalidSetting(s)) => s.path.to_string(),
            other => panic!("{other:?}"),
        };
        let start: Vec<[f64; 2]> = (0..=8).map(|k| [0.25 * k as f64, 0.0]).collect();
        let e = strip();
        assert_eq!(
            field(
                Elastica {
                    length: f64::NAN,
                    ..e
                },
                &start
            ),
            "length"
        );
        assert_eq!(field(Elastica { sag: -1.0, ..e }, &start), "sag");
        assert_eq!(
            field(Elastica { segments: 1, ..e }, &start[..2]),
            "segments"
        );
        assert_eq!(
            field(
                Elastica {
                    root: [f64::INFINITY, 0.0],
                    ..e
                },
                &start
            ),
            "root"
        );
        assert_eq!(
            field(
                Elastica {
                    held: Root::Clamped { angle: f64::NAN },
                    ..e
                },
                &start
            ),
            "held.angle"
        );
        assert_eq!(field(e, &start[..5]), "start");
        let mut nan = start.clone();
        nan[3][1] = f64::NAN;
        assert_eq!(field(e, &nan), "start");
        assert!(e.arched(&Air, folio_geometry::BlockSide::Left).is_some());
        assert!(
            Elastica { sag: f64::NAN, ..e }
                .arched(&Air, folio_geometry::BlockSide::Left)
                .is_none()
        );
    }
}
