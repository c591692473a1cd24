//! Synchronization along the dog-ear line (seed `003_…` Sec. 2.2.1, Fig. 4, and Sec. 3.1
//! step 6): lines of the page parallel to the dog-ear line stay parallel lines when the page
//! is lifted, so particles that rest at the same distance from that line move together.
//!
//! **Direction.** While the page is held and the finger has moved by
//! $d = (G_x - P_x,\ G_z - P_z)$ in the page plane from the grabbed rest point $P$, the
//! dog-ear line (the fold of the grab) is perpendicular to $\hat d = d/\lVert d\rVert$ and
//! only its direction matters. When $\lVert d\rVert$ is at most $10^{-3}$ of the smaller
//! particle spacing (the direction would be the finger's jitter), or nothing is held, the
//! line is the spine: $\hat d = (1, 0)$, and the groups are the particle columns.
//!
//! **Edge grip.** [`super::SpringPage`] asks for the spine direction (no displacement) while
//! an edge is held ([`super::Grip::Edge`]), wherever the finger goes. The held column moves
//! as one translated copy of its rest line, so the only fold line consistent with it is
//! parallel to that column; and a line tilted against the fixed spine would make each strip
//! of the page translate rigidly while one end of it lies on the fixed column. On the shared
//! page turn, whose finger also moves along the spine by up to $0.12H$ (tilting
//! $\hat d$ by up to 60° early in the drag), grouping perpendicular to the displacement
//! stretched the particle grid by 18 % per frame on average (the earlier default springs),
//! columns by 9.3 % (measured, [`super`] module docs). The seed's own experiment moves its
//! edge across the spine only, where both give the columns.
//!
//! **Groups.** Particle $k$ with rest position $\bar x_k$ has the signed distance
//! $s_k = \bar x_k^X \hat d_X + \bar x_k^Z \hat d_Z$ and the group
//! $g_k = \mathrm{round}((s_k - \min_l s_l)/b)$ with bin width $b$ half the smaller particle
//! spacing: a group spans less than $b$ of rest distance, and particles whose rest distances
//! differ by $b$ or more never share one. Along a grid axis the groups are exactly the
//! particle columns (or rows), along a square grid's diagonal exactly its diagonals (lines
//! $0.71$ spacings apart); in other directions the distinct parallel lines through the
//! particles are closer than $b$ and a group collects the particles of a strip $b$ wide.
//!
//! **Correction.** With the displacements $\delta_k = x_k - \bar x_k$ and the velocities
//! $v_k$ after the integration step and $F_g$ the free particles of group $g$,
//! $$\bar\delta_g = \frac{1}{|F_g|}\sum_{k \in F_g}\delta_k,\qquad
//!   \bar v_g = \frac{1}{|F_g|}\sum_{k \in F_g} v_k,\qquad
//!   x_k \leftarrow \bar x_k + \bar\delta_g,\quad v_k \leftarrow \bar v_g \quad (k \in F_g),$$
//! so each group moves by one common vector and a group's image is its rest segment
//! translated: parallel to the dog-ear line, as the seed's segment $BE \to QT$.
//!
//! **Velocity.** When the state before the step was synchronized for the same groups
//! ($x^n_k = \bar x_k + \bar\delta^n_g$), $x_k = x^n_k + h v_k$ gives
//! $\bar v_g = v_k + (\bar x_k + \bar\delta_g - x_k)/h$: the group's mean velocity is the
//! velocity plus the position correction over the step, $v \mathrel{+}= \Delta x/h$, and the
//! state stays consistent, $x^{n+1} = x^n + h v^{n+1}$. With equal masses the correction is
//! the orthogonal projection onto the group translations, so a synchronized run is
//! semi-implicit Euler of the reduced system and keeps its energy behaviour (measured in
//! `tests/tests/page_spring.rs`). Averaging the velocity rather than adding $\Delta x/h$
//! differs only when the state before the step was not synchronized (a new state, a change
//! of the groups when the finger turns): there $\Delta x/h$ would turn the jump onto the
//! group lines into speed (a random state of the seed page, $E = 52$, jumped to
//! $E = 4.8\cdot 10^4$ in one frame), while the mean never adds kinetic energy
//! ($\sum_{k\in F_g}\lVert v_k\rVert^2 \ge |F_g|\thinspace\lVert\bar v_g\rVert^2$).
//!
//! Fixed and gripped particles are neither moved nor counted.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::{Real, Vec3Ops, math};

use super::network::Role;

/// Group buffers and the last grouping (module docs).
#[derive(Clone, Debug)]
pub struct Synchronizer<T: Real> {
    bin: T,
    threshold: T,
    group: Vec<u32>,
    sum: Vec<T::Vec3>,
    velocity: Vec<T::Vec3>,
    count: Vec<u32>,
    direction: [T; 2],
}

impl<T: Real> Synchronizer<T> {
    /// Buffers for `particles` particles on a page of `size` with the given particle
    /// `spacing` (both $> 0$).
    #[must_use]
    pub fn new(particles: usize, size: [T; 2], spacing: [T; 2]) -> Self {
        let small = if spacing[0] < spacing[1] {
            spacing[0]
        } else {
            spacing[1]
        };
        let bin = small * T::HALF;
        // s spans at most W + H; one more bin for the rounding at each end.
        let span = ((size[0] + size[1]) / bin).to_f64();
        let bins = if span.is_finite() && span < 1e7 {
            span as usize + 3
        } else {
            particles
        };
        Self {
            bin,
            threshold: small * T::from_f64(1e-3),
            group: vec![0; particles],
            sum: vec![T::Vec3::ZERO; bins],
            velocity: vec![T::Vec3::ZERO; bins],
            count: vec![0; bins],
            direction: [T::ONE, T::ZERO],
        }
    }

    /// The unit direction $\hat d$ (X, Z) for a finger displacement `d` (X, Z), or the spine
    /// normal $(1, 0)$ when `d` is `None` or shorter than the threshold (module docs).
    #[must_use]
    pub fn direction_of(&self, d: Option<[T; 2]>) -> [T; 2] {
        match d {
            Some([dx, dz]) => {
                let len = math::sqrt(dx * dx + dz * dz);
                if len.is_finite() && len > self.threshold {
                    [dx / len, dz / len]
                } else {
                    [T::ONE, T::ZERO]
                }
            }
            None => [T::ONE, T::ZERO],
        }
    }

    /// Groups the particles by the rest distance along `direction` (unit, X and Z) into
    /// [`Synchronizer::groups`].
    pub fn group(&mut self, rest: &[T::Vec3], direction: [T; 2]) {
        self.direction = direction;
        let s = |p: &T::Vec3| p.x() * direction[0] + p.z() * direction[1];
        let mut lo = T::MAX;
        for p in rest {
            let v = s(p);
            if v < lo {
                lo = v;
            }
        }
        let last = self.sum.len().saturating_sub(1);
        for (g, p) in self.group.iter_mut().zip(rest) {
            let r = ((s(p) - lo) / self.bin).to_f64() + 0.5;
            let b = if r.is_finite() && r > 0.0 {
                r as usize
            } else {
                0
            };
            *g = b.min(last) as u32;
        }
    }

    /// Moves every free particle to its group's mean displacement and gives it the group's
    /// mean velocity (module docs), for the grouping of the last [`Synchronizer::group`].
    pub fn apply(
        &mut self,
        x: &mut [T::Vec3],
        v: &mut [T::Vec3],
        rest: &[T::Vec3],
        roles: &[Role],
    ) {
        self.sum.iter_mut().for_each(|s| *s = T::Vec3::ZERO);
        self.velocity.iter_mut().for_each(|s| *s = T::Vec3::ZERO);
        self.count.iter_mut().for_each(|c| *c = 0);
        for ((&g, (&xk, &vk)), (&rk, role)) in self
            .group
            .iter()
            .zip(x.iter().zip(v.iter()))
            .zip(rest.iter().zip(roles))
        {
            let g = g as usize;
            if *role != Role::Free {
                continue;
            }
            if let (Some(s), Some(u), Some(c)) = (
                self.sum.get_mut(g),
                self.velocity.get_mut(g),
                self.count.get_mut(g),
            ) {
                *s += xk - rk;
                *u += vk;
                *c += 1;
            }
        }
        for (((&g, xk), vk), (&rk, role)) in self
            .group
            .iter()
            .zip(x.iter_mut())
            .zip(v.iter_mut())
            .zip(rest.iter().zip(roles))
        {
            let g = g as usize;
            if *role != Role::Free {
                continue;
            }
            let (Some(&s), Some(&u), Some(&c)) =
                (self.sum.get(g), self.velocity.get(g), self.count.get(g))
            else {
                continue;
            };
            if c == 0 {
                continue;
            }
            let inv = T::ONE / T::from_f64(f64::from(c));
            *xk = rk + s * inv;
            *vk = u * inv;
        }
    }

    /// The group of every particle at the last grouping (module docs).
    #[must_use]
    pub fn groups(&self) -> &[u32] {
        &self.group
    }

    /// $\hat d$ (X, Z) of the last grouping.
    #[must_use]
    pub fn direction(&self) -> [T; 2] {
        self.direction
    }

    /// The bin width $b$ (page units).
    #[must_use]
    pub fn bin_width(&self) -> T {
        self.bin
    }
}
