//! The finger's pad (issue 42, the held-and-settled reference R1): a grip with a footprint.
//! The seed's grab holds one node (`000_…` eq. 14), so what a finger holds changes with the
//! grid: a node 1.5 page units from the fore-edge at 8 x 11, 0.375 at 32 x 44. A pad holds
//! every material point of the page within a radius $r$ of its centre (a disc clipped by
//! the page's border), whatever the grid, and the discrete problems converge to one
//! continuum problem as the grid is refined.
//!
//! **Energy.** The pad's material points $\xi_s$ (a lattice of spacing $r/6$ over the disc,
//! [`pad_samples`]) each get an equal share $a_s$ of the pull's weight $w_{\mathrm{pos}}$
//! (seed eq. 14) and a target $p_s$:
//! $$V = w_{\mathrm{pos}} \sum_s a_s \left\lVert x(\xi_s) - p_s \right\rVert^2,
//!   \qquad \sum_s a_s = 1,$$
//! where $x(\xi) = \sum_k N_k(\xi)\, x_k$ is the page's bilinear interpolation on the quad
//! that holds $\xi$. A rigid motion of the pad against its targets therefore pulls with the
//! same force as the seed's pull on one node. Summed per quad, it is one quadratic in the
//! quad's four corners ([`PadQuad`]), with a constant, positive semi-definite Hessian.
//!
//! **Targets.** At the grab each point's target is where it lies; a drag moves the pad's
//! centre to the leashed target $p$ and turns the pad about the binding with the page: the
//! targets are $p_s = p + R_z(\varphi)(q_s - q_c)$, with $q$ the positions at the grab and
//! $\varphi$ the angle, about the binding (the Z axis through the bound node of the pad's
//! row), from the centre at the grab to $p$. A page lifted at its fore-edge to 45° by the pad
//! is held as the flat page turned 45° about the binding would be, near the pad. This is
//! Folio's choice (a finger that pinches the edge and turns with the page), not the seed's.

use alloc::vec::Vec;
use folio_kernels::term::{Blocks, NodeVecs, zero_blocks};
use folio_kernels::{Mat3Ops, Potential, Real, Vec3Ops};

/// The pad's stiffness against the page's bending, $K$ in [`pad_weight`].
pub const PAD_HOLD: f64 = 400.0;

/// The pad's weight $w_{\mathrm{pad}} = \max(w_{\mathrm{pos}},\ K D / r^2)$, with
/// $D = 2 w_{\mathrm{bend3D}}$ the page's bending stiffness ([`crate::quadrature`]), $r$ the
/// pad's radius and $K$ = [`PAD_HOLD`]. A pad is a clamp only if it turns the page's edge
/// with it: its stiffness against a turn, $2 w_{\mathrm{pad}} \sum_s a_s d_s^2 \approx
/// w_{\mathrm{pad}} r^2 / 2$ for points at distances $d_s$ from its centre, must be large
/// against the moment the page's bending brings to it, about $D \kappa$ times the pad's
/// width $2r$, whatever the grid. $K$ was measured (`tests/tests/pad_grip.rs`, the
/// fore-edge's middle turned 20° about the binding and held for a second, the largest
/// distance of a pad point from where the pad puts it, on 8 x 11): with the pull's weight
/// alone ($w_{\mathrm{pos}}$ = 400) the pad was a pin, 0.27 page units off on the seed's
/// card and 0.15 on a novel; with $K$ = 50, 200, 400, 1000 the novel's were 0.12, 0.023,
/// 0.004, 0.008 and the card's at 400 and 1000 0.007 and 0.003. Never below the pull's
/// weight, so that the pad carries the page at least as the seed's pull does.
#[must_use]
pub fn pad_weight<T: Real>(pull: T, bend: T, radius: T) -> T {
    let hold = if radius > T::ZERO {
        T::from_f64(2.0 * PAD_HOLD) * bend / (radius * radius)
    } else {
        T::ZERO
    };
    if hold > pull { hold } else { pull }
}

/// Lattice points per pad radius: the pad's material points lie on a square lattice of
/// spacing $r / 6$ (113 points over a full disc, about 60 over the half disc at an edge).
pub const PAD_LATTICE: usize = 6;

/// The pad's energy on one quad: $V = \sum_{k,l} A_{kl}\, x_k \cdot x_l - 2 \sum_k b_k
/// \cdot x_k + c$ over its corners in the order $(i, j), (i+1, j), (i, j+1), (i+1, j+1)$,
/// which is $\sum_s a_s \lVert \sum_k N_k(\xi_s) x_k - p_s\rVert^2$ with
/// $A_{kl} = \sum_s a_s N_k N_l$, $b_k = \sum_s a_s N_k p_s$, $c = \sum_s a_s \lVert p_s
/// \rVert^2$ (module docs). $\nabla_k V = 2(\sum_l A_{kl} x_l - b_k)$,
/// $\nabla^2_{kl} V = 2 A_{kl} I$. Units: length².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PadQuad<T: Real> {
    /// $A$, symmetric positive semi-definite.
    pub a: [[T; 4]; 4],
    /// $b$, page units.
    pub b: NodeVecs<T, 4>,
    /// $c$, page units².
    pub c: T,
}

impl<T: Real> PadQuad<T> {
    /// No pad point on this quad: zero energy.
    pub const ZERO: Self = Self {
        a: [[T::ZERO; 4]; 4],
        b: [T::Vec3::ZERO; 4],
        c: T::ZERO,
    };

    /// $\sum_l A_{kl} x_l$ for each corner $k$.
    #[inline]
    fn ax(&self, x: &NodeVecs<T, 4>) -> NodeVecs<T, 4> {
        core::array::from_fn(|k| (0..4).fold(T::Vec3::ZERO, |acc, l| acc + x[l] * self.a[k][l]))
    }
}

impl<T: Real> Potential<T, 4> for PadQuad<T> {
    const CONSTANT_HESSIAN: bool = true;
    fn value(&self, x: &NodeVecs<T, 4>) -> T {
        let ax = self.ax(x);
        (0..4).fold(self.c, |acc, k| {
            acc + x[k].dot(ax[k]) - T::TWO * self.b[k].dot(x[k])
        })
    }
    fn gradient(&self, x: &NodeVecs<T, 4>) -> NodeVecs<T, 4> {
        let ax = self.ax(x);
        core::array::from_fn(|k| (ax[k] - self.b[k]) * T::TWO)
    }
    fn hessian(&self, _x: &NodeVecs<T, 4>) -> Blocks<T, 4> {
        let mut h = zero_blocks::<T, 4>();
        for (k, row) in h.iter_mut().enumerate() {
            for (l, block) in row.iter_mut().enumerate() {
                *block = T::Mat3::IDENTITY * (T::TWO * self.a[k][l]);
            }
        }
        h
    }
}

/// One material point of a pad: the quad that holds it (`i + (nx - 1) j`), its bilinear
/// weights on the quad's corners ([`PadQuad`]'s order) and its share $a_s$ of the pad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PadSample {
    /// The quad, `i + (nx - 1) j` for the quad whose lowest corner is node $(i, j)$.
    pub quad: usize,
    /// $N_k(\xi_s)$ on the quad's corners.
    pub shape: [f64; 4],
    /// $a_s$; the shares of a pad sum to 1.
    pub share: f64,
}

/// The quad of a grid of `quads` quads of size `spacing` that holds coordinate `t` (page
/// units), and the local coordinate in $[0, 1]$; `t` is clamped to the page.
fn locate(t: f64, spacing: f64, quads: usize) -> (usize, f64) {
    let s = (t / spacing).clamp(0.0, quads as f64);
    let q = (folio_kernels::math::floor::<f64>(s) as usize).min(quads - 1);
    (q, s - q as f64)
}

/// The pad's material point at `at` = $(u, v)$ on a grid of `quads = [across, along]` quads
/// of `spacing` (page units), with share `share`.
#[must_use]
pub fn pad_point(at: [f64; 2], spacing: [f64; 2], quads: [usize; 2], share: f64) -> PadSample {
    let (i, s) = locate(at[0], spacing[0], quads[0]);
    let (j, t) = locate(at[1], spacing[1], quads[1]);
    PadSample {
        quad: i + quads[0] * j,
        shape: [(1.0 - s) * (1.0 - t), s * (1.0 - t), (1.0 - s) * t, s * t],
        share,
    }
}

/// The pad of radius `radius` centred on `center` = $(u, v)$ (page units, clamped to the
/// page `size`): the points of a square lattice of spacing $r/$[`PAD_LATTICE`] through the
/// centre that lie within the disc and on the page, each with an equal share. A radius of
/// zero (or one smaller than the lattice can resolve) gives the centre alone: the seed's
/// pull at a material point.
#[must_use]
pub fn pad_samples(
    center: [f64; 2],
    radius: f64,
    size: [f64; 2],
    spacing: [f64; 2],
    quads: [usize; 2],
) -> Vec<PadSample> {
    let c = [center[0].clamp(0.0, size[0]), center[1].clamp(0.0, size[1])];
    let step = radius / PAD_LATTICE as f64;
    // A point on the page's border counts as on the page (rounding of `c + k step`).
    let slack = 1e-9 * size[0].max(size[1]);
    let n = PAD_LATTICE as i64;
    let mut points = Vec::new();
    if step > 0.0 && step.is_finite() {
        for dj in -n..=n {
            for di in -n..=n {
                let (du, dv) = (di as f64 * step, dj as f64 * step);
                let p = [c[0] + du, c[1] + dv];
                let on_page = (-slack..=size[0] + slack).contains(&p[0])
                    && (-slack..=size[1] + slack).contains(&p[1]);
                if du * du + dv * dv <= radius * radius * (1.0 + 1e-12) && on_page {
                    points.push(p);
                }
            }
        }
    }
    if points.is_empty() {
        points.push(c);
    }
    let share = 1.0 / points.len() as f64;
    points
        .into_iter()
        .map(|p| pad_point(p, spacing, quads, share))
        .collect()
}

/// The position of the pad point `s` on `x`, the page's nodes in grid order (`nx` across).
#[must_use]
pub fn interpolate<T: Real>(s: &PadSample, x: &[T::Vec3], nx: usize) -> T::Vec3 {
    corners(s.quad, nx)
        .iter()
        .zip(s.shape)
        .fold(T::Vec3::ZERO, |acc, (&k, n)| acc + x[k] * T::from_f64(n))
}

/// The page nodes (grid order) of quad `quad` on a grid `nx` nodes across, in
/// [`PadQuad`]'s order.
#[must_use]
pub fn corners(quad: usize, nx: usize) -> [usize; 4] {
    let (i, j) = (quad % (nx - 1), quad / (nx - 1));
    let k = i + nx * j;
    [k, k + 1, k + nx, k + nx + 1]
}

/// The rotation $R_z(\varphi)$ about the Z axis through `hinge` that turns the direction of
/// `from` into that of `to` in the XY plane, applied to the offset `d`: the identity when
/// either point lies on the hinge's axis.
#[must_use]
pub fn turn_about<T: Real>(hinge: T::Vec3, from: T::Vec3, to: T::Vec3, d: T::Vec3) -> T::Vec3 {
    let (a, b) = (from - hinge, to - hinge);
    let (ax, ay, bx, by) = (a.x(), a.y(), b.x(), b.y());
    let la = folio_kernels::math::sqrt(ax * ax + ay * ay);
    let lb = folio_kernels::math::sqrt(bx * bx + by * by);
    let on_axis = la <= T::LENGTH_FLOOR || lb <= T::LENGTH_FLOOR || !(la * lb).is_finite();
    if on_axis {
        return d;
    }
    let cos = (ax * bx + ay * by) / (la * lb);
    let sin = (ax * by - ay * bx) / (la * lb);
    T::Vec3::new(d.x() * cos - d.y() * sin, d.x() * sin + d.y() * cos, d.z())
}

/// The pad a book holds its active page with, from the grab to the release (empty while
/// no pad holds the page).
#[derive(Clone, Debug)]
pub struct HeldPad<T: Real> {
    /// The pad's points.
    pub samples: Vec<PadSample>,
    /// Each point's offset from the centre at the grab, $q_s - q_c$ (page units).
    pub offsets: Vec<T::Vec3>,
    /// The pad's centre, `None` while no pad holds the page.
    pub center: Option<PadSample>,
    /// The centre at the grab, $q_c$.
    pub grabbed: T::Vec3,
    /// The grid row of the bound node the pad turns about.
    pub row: usize,
    /// The points' targets of the current step (kept to reuse the allocation).
    pub targets: Vec<T::Vec3>,
}

impl<T: Real> HeldPad<T> {
    /// No pad.
    #[must_use]
    pub fn none() -> Self {
        Self {
            samples: Vec::new(),
            offsets: Vec::new(),
            center: None,
            grabbed: T::Vec3::ZERO,
            row: 0,
            targets: Vec::new(),
        }
    }

    /// The targets $p_s = p + R_z(\varphi)(q_s - q_c)$ of the pad's centre at `p`, turned
    /// about `hinge` (module docs), into [`HeldPad::targets`].
    pub fn aim(&mut self, hinge: T::Vec3, p: T::Vec3) {
        let grabbed = self.grabbed;
        self.targets.clear();
        self.targets.extend(
            self.offsets
                .iter()
                .map(|&d| p + turn_about::<T>(hinge, grabbed, p, d)),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type DVec3 = <f64 as Real>::Vec3;

    /// Central differences of the value and the gradient match the gradient and the
    /// Hessian, and the energy is the sum over the pad's points it stands for.
    #[test]
    fn the_quad_energy_is_the_sum_over_its_points_with_exact_derivatives() {
        let pts = [
            ([0.2, 0.3], 0.25, DVec3::new(1.0, 0.5, -0.2)),
            ([0.7, 0.9], 0.5, DVec3::new(-0.3, 0.1, 0.4)),
            ([1.0, 0.0], 0.25, DVec3::new(0.6, -0.8, 0.0)),
        ];
        let mut q = PadQuad::<f64>::ZERO;
        let shape = |st: [f64; 2]| {
            let [s, t] = st;
            [(1.0 - s) * (1.0 - t), s * (1.0 - t), (1.0 - s) * t, s * t]
        };
        for (st, share, p) in pts {
            let n = shape(st);
            for k in 0..4 {
                for l in 0..4 {
                    q.a[k][l] += share * n[k] * n[l];
                }
                q.b[k] += p * (share * n[k]);
            }
            q.c += share * p.dot(p);
        }
        let x = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.1, -0.2, 0.0),
            DVec3::new(0.0, 0.9, 1.2),
            DVec3::new(1.3, 1.0, 0.7),
        ];
        let direct: f64 = pts
            .iter()
            .map(|&(st, share, p)| {
                let n = shape(st);
                let xs = (0..4).fold(DVec3::ZERO, |acc, k| acc + x[k] * n[k]);
                share * (xs - p).length_squared()
            })
            .sum();
        assert!(
            (q.value(&x) - direct).abs() < 1e-12,
            "{} {direct}",
            q.value(&x)
        );
        let h = 1e-6;
        let g = q.gradient(&x);
        let hess = q.hessian(&x);
        for k in 0..4 {
            for axis in 0..3 {
                let mut xp = x;
                let mut xm = x;
                xp[k][axis] += h;
                xm[k][axis] -= h;
                let dv = (q.value(&xp) - q.value(&xm)) / (2.0 * h);
                assert!(
                    (dv - g[k][axis]).abs() < 1e-7,
                    "{k} {axis}: {dv} {}",
                    g[k][axis]
                );
                let (gp, gm) = (q.gradient(&xp), q.gradient(&xm));
                for l in 0..4 {
                    let dg = (gp[l] - gm[l]) / (2.0 * h);
                    assert!(
                        (dg - hess[l][k].col(axis)).length() < 1e-6,
                        "{k} {l} {axis}"
                    );
                }
            }
        }
    }

    /// A pad's points lie within its radius and on the page, their shares sum to 1, and
    /// their count does not depend on the grid.
    #[test]
    fn a_pad_holds_the_same_points_on_every_grid() {
        let size = [12.0, 17.0];
        let (center, r) = ([12.0, 8.5], 0.57);
        let counts: Vec<usize> = [[8usize, 11usize], [16, 22], [32, 44]]
            .into_iter()
            .map(|quads| {
                let spacing = [size[0] / quads[0] as f64, size[1] / quads[1] as f64];
                let pad = pad_samples(center, r, size, spacing, quads);
                let total: f64 = pad.iter().map(|s| s.share).sum();
                assert!((total - 1.0).abs() < 1e-12);
                for s in &pad {
                    assert!(s.quad < quads[0] * quads[1]);
                    let sum: f64 = s.shape.iter().sum();
                    assert!((sum - 1.0).abs() < 1e-12 && s.shape.iter().all(|&n| n >= -1e-12));
                }
                pad.len()
            })
            .collect();
        assert!(counts.windows(2).all(|w| w[0] == w[1]), "{counts:?}");
        // The half disc at the fore-edge: 7 columns of the lattice, 13 + 2 (11 + 9 + 7) + ...
        assert!(counts[0] > 50 && counts[0] < 70, "{counts:?}");
        // No radius: the centre alone.
        assert_eq!(
            pad_samples([3.0, 4.0], 0.0, size, [1.5, 1.5], [8, 11]).len(),
            1
        );
    }

    /// The interpolation of a pad point reproduces an affine field exactly, on any quad.
    #[test]
    fn a_pad_point_lies_where_the_page_puts_it() {
        let quads = [4usize, 3usize];
        let spacing = [1.5, 2.0];
        let nx = quads[0] + 1;
        let nodes: Vec<DVec3> = (0..nx * (quads[1] + 1))
            .map(|k| {
                let (u, v) = ((k % nx) as f64 * spacing[0], (k / nx) as f64 * spacing[1]);
                DVec3::new(2.0 * u + 0.5 * v, -u, v + 3.0)
            })
            .collect();
        for at in [[0.0, 0.0], [6.0, 6.0], [2.2, 3.9], [4.5, 0.1]] {
            let s = pad_point(at, spacing, quads, 1.0);
            let x = interpolate::<f64>(&s, &nodes, nx);
            let want = DVec3::new(2.0 * at[0] + 0.5 * at[1], -at[0], at[1] + 3.0);
            assert!((x - want).length() < 1e-12, "{at:?}: {x} {want}");
        }
    }

    /// The turn about the hinge is a rotation about Z that takes `from`'s direction to
    /// `to`'s, and the identity on the axis.
    #[test]
    fn the_pad_turns_about_the_binding() {
        let hinge = DVec3::new(1.0, 2.0, 0.0);
        let from = DVec3::new(3.0, 2.0, 5.0);
        let to = DVec3::new(1.0, 4.0, 5.0);
        let d = DVec3::new(1.0, 0.0, 0.3);
        let r = turn_about::<f64>(hinge, from, to, d);
        assert!((r - DVec3::new(0.0, 1.0, 0.3)).length() < 1e-12, "{r}");
        assert_eq!(turn_about::<f64>(hinge, hinge, to, d), d);
    }
}
