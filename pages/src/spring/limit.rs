//! Provot's correction of over-deformed springs (Provot 1995, *Deformation constraints in a
//! mass-spring model to describe rigid cloth behavior*, Sec. 5: a spring whose deformation
//! rate $\lvert\ell/L^0 - 1\rvert$ exceeds a critical $\tau_c$ (his 10 %) has its ends moved
//! back to $\tau_c$ after the integration step, "inverse dynamics"), as the last part of
//! every substep of [`super::SpringPage`], for both integrators.
//!
//! **Links.** Every stretch and shear spring $(a, b)$ with rest length $L^0$ is a link that
//! must keep $\ell = \lVert x_a - x_b\rVert \in [(1 - \tau) L^0,\ (1 + \tau) L^0]$,
//! $\tau$ = [`super::SpringSettings::strain_limit`]. A link outside moves its free ends
//! along $\hat d$ onto the nearest bound: both by half the excess when both are free, the
//! free one by all of it when the other is fixed or gripped, neither when neither is free.
//! Provot limits elongation only; the page also limits compression, because the page's
//! measure of stretch is two-sided ([`crate::metrics`]) and because a spring crushed below
//! its rest length has a transverse stiffness $k(1 - L^0/\ell)$ that tends to $-\infty$ as
//! $\ell \to 0$: the explicit integrator blew up on it (a finger pushing the fore edge over
//! the spine along the table, measured in `tests/tests/bounded_pages.rs`).
//!
//! **Buckling.** A row (or column) pushed together within the table's plane cannot lengthen
//! its links along itself: the ends are held and the chain is straight. For every bend
//! triple $a, b, c$ (three particles in a row, the bend spring $a$–$c$, $b$ free) whose chord
//! $e = x_c - x_a$ is shorter than the two shortest admissible links,
//! $\lVert e\rVert < (1 - \tau)(L^0_{ab} + L^0_{bc})$, one of whose links is too short, and
//! whose middle lies nearly on the chord (its foot $f = x_a + t e$,
//! $t = (x_b - x_a)\cdot e/\lVert e\rVert^2 \in (0, 1)$, at most a quarter of the shorter
//! admissible link from it: a bent triple is left to the links), $b$ moves perpendicular to
//! the chord to the height
//! $$h = \sqrt{\max\left((1-\tau)^2 (L^0_{ab})^2 - t^2\lVert e\rVert^2,\
//!   (1-\tau)^2 (L^0_{bc})^2 - (1 - t)^2\lVert e\rVert^2\right)}$$
//! on the side where it already is, or up ($+Y$, away from the table; the axis least along
//! the chord if the chord is vertical) when it lies on the chord: the strip buckles, as
//! paper pushed along a table does. (Moving every short triple, bent or not, made the sweeps
//! cycle on folded pages: measured, a link left at 31 % after 1024 sweeps.)
//!
//! **Sweeps.** Links and triples are corrected in order (Gauss-Seidel), then the table (if
//! on) puts every free particle below $y = 0$ back on it; sweeps repeat until no link was
//! off by more than $10^{-2}\tau$ in a sweep or [`MAX_SWEEPS`] have run (a page at rest
//! costs one sweep: a check of every link). The sweeps may stop short of the bound where the
//! constraints fight (random flicks of small, coarse pages; open, `tests/tests/bounded_pages.rs`).
//! The velocities take the correction over the substep, $v \mathrel{+}= \Delta x / h$, so
//! that the next step does not undo it (the state stays consistent,
//! $x^{n+1} = x^n + h v^{n+1}$, as for the synchronization, [`super::sync`]); this removes
//! the kinetic energy of the motion the constraint forbids, as an inelastic collision does.
//! The correction runs after the synchronization and may move a particle off its group's
//! translate by as much as a link needs. Sweeps that run out without reaching the bound
//! (a page tangled around its spine by a finger far faster than its time step: measured,
//! links left at 12 % after 1024 sweeps at $h = 10^{-4}$ s) fail the frame:
//! [`super::SpringPage`] keeps its previous state and reports
//! [`crate::PageStatus::Stalled`], so that a page never shows the violation and the run
//! counts the frame as failed.
//!
//! **The grip.** A finger can go anywhere a touch script puts it (up to $10^6$ away); the
//! springs cannot follow it beyond the page's reach. The translation $d = G - P$ of the
//! gripped particles is therefore scaled back along itself, $d \leftarrow s\thinspace d$ with the
//! largest $s \in [0, 1]$ that keeps every gripped particle $k$ within
//! $(1 + \tau/2)\lVert\bar x_k - \bar x_f\rVert$ of every fixed particle $f$
//! ([`reach`]): a straight line in the page between them is at most that long when no link
//! stretches by more than $\tau/2$, so the links can follow with half of $\tau$ to spare.
//! A frame whose finger was out of reach reports [`crate::PageStatus::Unreachable`].
//!
//! **Cost**, measured on the shared page turn (`TouchScript::page_turn`, 240 frames, the
//! book page's defaults, release build, step time summed over 5 runs with and without the
//! correction in one process): semi-implicit Euler 0.23 s → 1.07 s (4.7x: in about 15 % of
//! the substeps, with the held column pulling the page along the spine, the sweeps run
//! about 100 times before every link is within $10^{-2}\tau$), implicit Euler 8.38 s →
//! 8.75 s (1.05x). A page at rest costs one check of every link per substep.
//!
//! Allocates at construction only.

use alloc::vec::Vec;
use folio_kernels::spring::SpringKind;
use folio_kernels::{Real, Vec3Ops, math};

use super::network::{Role, SpringNetwork};

/// Most Gauss-Seidel sweeps per substep (module docs).
pub const MAX_SWEEPS: u32 = 1024;

/// A stretch or shear spring as a link: particles and rest length.
#[derive(Clone, Copy, Debug)]
struct Link<T> {
    a: u32,
    b: u32,
    rest: T,
}

/// A bend triple $a, b, c$ with the rest lengths of $a$–$b$ and $b$–$c$.
#[derive(Clone, Copy, Debug)]
struct Triple<T> {
    nodes: [u32; 3],
    rest: [T; 2],
}

/// The correction's links, triples and workspace (module docs).
#[derive(Clone, Debug)]
pub struct StrainLimit<T: Real> {
    limit: T,
    links: Vec<Link<T>>,
    triples: Vec<Triple<T>>,
    start: Vec<T::Vec3>,
    sweeps: u32,
    converged: bool,
}

impl<T: Real> StrainLimit<T> {
    /// The links and triples of `network` with the limit $\tau$ = `limit` (in $(0, 1)$).
    #[must_use]
    pub fn new(network: &SpringNetwork<T>, limit: T) -> Self {
        let rest = network.rest();
        let links = network
            .springs()
            .terms()
            .iter()
            .zip(network.kinds())
            .filter(|(_, kind)| **kind != SpringKind::Bend)
            .map(|(t, _)| Link {
                a: t.nodes[0],
                b: t.nodes[1],
                rest: t.kernel.rest_length,
            })
            .collect();
        let grid = network.grid();
        let length = |a: usize, b: usize| math::length::<T>(rest[a] - rest[b]);
        let mut triples = Vec::new();
        for j in 0..grid.nz {
            for i in 0..grid.nx {
                let k = grid.index(i, j);
                let mut add = |b: usize, c: usize| {
                    triples.push(Triple {
                        nodes: [k as u32, b as u32, c as u32],
                        rest: [length(k, b), length(b, c)],
                    });
                };
                if i + 2 < grid.nx {
                    add(grid.index(i + 1, j), grid.index(i + 2, j));
                }
                if j + 2 < grid.nz {
                    add(grid.index(i, j + 1), grid.index(i, j + 2));
                }
            }
        }
        Self {
            limit,
            links,
            triples,
            start: alloc::vec![T::Vec3::ZERO; rest.len()],
            sweeps: 0,
            converged: true,
        }
    }

    /// The limit $\tau$.
    #[must_use]
    pub fn limit(&self) -> T {
        self.limit
    }

    /// Whether the last [`StrainLimit::apply`] brought every link within $10^{-2}\tau$ of the
    /// bound before [`MAX_SWEEPS`] ran out.
    #[must_use]
    pub fn converged(&self) -> bool {
        self.converged
    }

    /// Sweeps the last [`StrainLimit::apply`] ran (1 when every link was within bounds).
    #[must_use]
    pub fn sweeps(&self) -> u32 {
        self.sweeps
    }

    /// Corrects the free particles of `x` (module docs), the table at $y = 0$ if `floor`,
    /// and adds the correction over the substep `h` to `v`. Returns the largest violation
    /// $\max(\lvert\ell/L^0 - 1\rvert - \tau, 0)$ over the links in the last sweep, before
    /// its corrections; [`StrainLimit::converged`] tells whether that was within tolerance.
    pub fn apply(
        &mut self,
        x: &mut [T::Vec3],
        v: &mut [T::Vec3],
        roles: &[Role],
        floor: bool,
        h: T,
    ) -> T {
        let free = |k: u32| roles.get(k as usize) == Some(&Role::Free);
        let tolerance = self.limit * T::from_f64(1e-2);
        let (low, high) = (T::ONE - self.limit, T::ONE + self.limit);
        self.start.copy_from_slice(x);
        self.sweeps = 0;
        let mut worst = T::ZERO;
        while self.sweeps < MAX_SWEEPS {
            worst = T::ZERO;
            for link in &self.links {
                let (ia, ib) = (link.a as usize, link.b as usize);
                let (Some(&xa), Some(&xb)) = (x.get(ia), x.get(ib)) else {
                    continue;
                };
                let d = xb - xa;
                let len = math::length::<T>(d);
                let ratio = len / link.rest;
                let target = if ratio > high {
                    high
                } else if ratio < low {
                    low
                } else {
                    continue;
                };
                let off = abs(ratio - target);
                if off > worst {
                    worst = off;
                }
                if len < T::LENGTH_FLOOR {
                    // No direction to push along: the triples (or the next sweep) move it.
                    continue;
                }
                let (wa, wb) = (weight(free(link.a)), weight(free(link.b)));
                if wa + wb == T::ZERO {
                    continue;
                }
                let fix = d * ((len - target * link.rest) / (len * (wa + wb)));
                if let Some(p) = x.get_mut(ia) {
                    *p += fix * wa;
                }
                if let Some(p) = x.get_mut(ib) {
                    *p -= fix * wb;
                }
            }
            for triple in &self.triples {
                if free(triple.nodes[1]) {
                    buckle(x, triple, low);
                }
            }
            if floor {
                for (p, role) in x.iter_mut().zip(roles) {
                    if *role == Role::Free && p.y() < T::ZERO {
                        *p = T::Vec3::new(p.x(), T::ZERO, p.z());
                    }
                }
            }
            self.sweeps += 1;
            if worst <= tolerance {
                break;
            }
        }
        self.converged = worst <= tolerance;
        if self.sweeps > 1 || worst > T::ZERO {
            let rate = T::ONE / h;
            for ((vk, &xk), &x0) in v.iter_mut().zip(x.iter()).zip(&self.start) {
                *vk += (xk - x0) * rate;
            }
        }
        worst
    }
}

/// Inverse-mass weight of a particle in a link: 1 when free, 0 otherwise.
#[inline]
#[must_use]
fn weight<T: Real>(free: bool) -> T {
    if free { T::ONE } else { T::ZERO }
}

#[inline]
#[must_use]
fn abs<T: Real>(x: T) -> T {
    if x < T::ZERO { -x } else { x }
}

/// The buckling move of the middle particle of `triple` (module docs), `low` $= 1 - \tau$.
fn buckle<T: Real>(x: &mut [T::Vec3], triple: &Triple<T>, low: T) {
    let [a, b, c] = triple.nodes.map(|k| k as usize);
    let (Some(&xa), Some(&xb), Some(&xc)) = (x.get(a), x.get(b), x.get(c)) else {
        return;
    };
    let (ma, mc) = (low * triple.rest[0], low * triple.rest[1]);
    let e = xc - xa;
    let chord2 = e.dot(e);
    let chord = math::sqrt(chord2);
    if chord >= ma + mc || chord < T::LENGTH_FLOOR {
        return;
    }
    let (la, lc) = (math::length::<T>(xb - xa), math::length::<T>(xc - xb));
    if la >= ma && lc >= mc {
        return;
    }
    let t = (xb - xa).dot(e) / chord2;
    if !(t > T::ZERO && t < T::ONE) {
        return;
    }
    let foot = xa + e * t;
    let need_a = ma * ma - t * t * chord2;
    let need_c = mc * mc - (T::ONE - t) * (T::ONE - t) * chord2;
    let need = if need_a > need_c { need_a } else { need_c };
    if need <= T::ZERO {
        return;
    }
    let height = math::sqrt(need);
    let side = xb - foot;
    let off = math::length::<T>(side);
    let short = if ma < mc { ma } else { mc };
    if off > short * T::from_f64(0.25) {
        // Bent enough already: the links push it out of line themselves.
        return;
    }
    let normal = if off > ma * T::from_f64(1e-3) {
        side / off
    } else {
        up_from::<T>(e / chord)
    };
    if let Some(p) = x.get_mut(b) {
        *p = foot + normal * height;
    }
}

/// A unit vector perpendicular to the unit chord `u`: $+Y$ without its component along
/// `u`, or, for a chord within 30° of $Y$, the axis of `u`'s smallest component likewise.
fn up_from<T: Real>(u: T::Vec3) -> T::Vec3 {
    let up = T::Vec3::new(T::ZERO, T::ONE, T::ZERO);
    let along = u.dot(up);
    let axis = if abs(along) < T::from_f64(0.866) {
        up
    } else if abs(u.x()) < abs(u.z()) {
        T::Vec3::new(T::ONE, T::ZERO, T::ZERO)
    } else {
        T::Vec3::new(T::ZERO, T::ZERO, T::ONE)
    };
    let p = axis - u * u.dot(axis);
    p / math::length::<T>(p)
}

/// The largest $s \in [0, 1]$ with $\lVert \bar x_k + s\thinspace d - \bar x_f\rVert \le
/// \rho\thinspace\lVert \bar x_k - \bar x_f\rVert$ for every gripped $k$ and fixed $f$ (module docs),
/// $\rho$ = `reach` $\ge 1$. With $d = L\hat n$ and $c = \bar x_f - \bar x_k$ the bound is the
/// positive root of $\lvert \sigma\hat n - c\rvert^2 = \rho^2\lvert c\rvert^2$,
/// $\sigma = \hat n\cdot c + \sqrt{(\hat n\cdot c)^2 + (\rho^2 - 1)\lvert c\rvert^2}$,
/// $s = \sigma / L$, the least over all pairs ($d$ is scaled by its largest component first,
/// so that a finger far away does not overflow). 1 without fixed particles or for $d = 0$.
/// With `mirrored` (a page taken on the left) the gripped particles' rest positions are
/// mirrored across the spine, $\bar x_k = (-x, y, z)$, as the grip places them.
#[must_use]
pub fn reach<T: Real>(
    d: T::Vec3,
    gripped: &[u32],
    rest: &[T::Vec3],
    roles: &[Role],
    reach: T,
    mirrored: bool,
) -> T {
    let big = [abs(d.x()), abs(d.y()), abs(d.z())]
        .into_iter()
        .fold(T::ZERO, |m, c| if c > m { c } else { m });
    if big == T::ZERO || !big.is_finite() {
        return T::ONE;
    }
    let scaled = d / big;
    let norm = math::length::<T>(scaled);
    let n = scaled / norm;
    let excess = reach * reach - T::ONE;
    let mut sigma = T::MAX;
    for &k in gripped {
        let Some(&xk) = rest.get(k as usize) else {
            continue;
        };
        let xk = if mirrored {
            T::Vec3::new(-xk.x(), xk.y(), xk.z())
        } else {
            xk
        };
        for (&xf, role) in rest.iter().zip(roles) {
            if *role != Role::Fixed {
                continue;
            }
            let c = xf - xk;
            let nc = n.dot(c);
            let root = nc + math::sqrt(nc * nc + excess * c.dot(c));
            if root < sigma {
                sigma = root;
            }
        }
    }
    // sigma / |d|, computed as (sigma / big) / norm; at most 1.
    let s = sigma / big / norm;
    if s < T::ONE { s } else { T::ONE }
}
