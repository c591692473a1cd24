//! The render surface through the particles: tensor-product Lagrange interpolation (seed
//! `003_…` Sec. 2.2.2), on a local stencil of a chosen degree.
//!
//! **The seed's surface.** With the particles $P_{ij}$ at material coordinates
//! $(u_i, v_j)$, $u_i = W i/(n_x - 1)$, $v_j = H j/(n_z - 1)$, the seed interpolates all of
//! them at once,
//! $$S(u, v) = \sum_{i=0}^{n_x-1}\sum_{j=0}^{n_z-1} \ell_i(u)\thinspace m_j(v)\thinspace P_{ij},\qquad
//!   \ell_i(u) = \prod_{k \ne i}\frac{u - u_k}{u_i - u_k},\quad
//!   m_j(v) = \prod_{k \ne j}\frac{v - v_k}{v_j - v_k},$$
//! a polynomial of degree $n_x - 1$ in $u$ and $n_z - 1$ in $v$ with $S(u_i, v_j) = P_{ij}$
//! ($\ell_i(u_k) = \delta_{ik}$, the seed's argument).
//!
//! **Local stencils (a departure from the seed).** The seed keeps 6 particles per side and
//! says Runge's phenomenon need not be considered. It must be beyond that: equispaced
//! interpolation amplifies wiggles between the nodes, its Lebesgue constant grows like
//! $2^n/(e\thinspace n\ln n)$ (measured 3.1 for the seed's 6 nodes, 10.9 for 9, 51 for 12 and
//! $5.9\cdot 10^3$ for 20: the worst amplification of a particle's deviation from a
//! polynomial into the surface). On the shared page turn of the book page ($9 \times 12$
//! particles, [`super::SpringSettings::default`], render grid $24 \times 34$ quads) the
//! global surface of degree $8 \times 11$ overshoots wherever the page bends sharply: with
//! the earlier page dynamics its render edges stretched by up to 6700 % (67×, 820 % on
//! average per frame) and render points dipped to $y = -25$ under the table while every
//! particle stayed on or above it; with the current dynamics (smoother particles) still
//! 27 % (mean 4.6 %) and $y = -0.37$. So each direction uses the Lagrange polynomial of a
//! chosen degree $p$ (the setting `interpolation_degree`) through the $p + 1$ consecutive
//! particles $a, \dots, a + p$ nearest the point,
//! $$a(t) = \min\negthinspace\Big(\max\negthinspace\Big(\big\lfloor t/\Delta\big\rfloor -
//!   \big\lfloor\tfrac{p-1}{2}\big\rfloor,\ 0\Big),\ n - 1 - p\Big),\qquad
//!   S(u, v) = \sum_{i=a(u)}^{a(u)+p}\sum_{j=a(v)}^{a(v)+p}\ell^a_i(u)\thinspace m^a_j(v)\thinspace P_{ij}$$
//! ($\Delta$ the particle spacing; $\ell^a_i$, $m^a_j$ the Lagrange basis of the stencil
//! only): centred on the particle cell holding $t$ for odd $p$, one-sided near the page
//! border (the start clamped to the grid). Properties:
//! - it still passes through every particle, $S(u_i, v_j) = P_{ij}$;
//! - it reproduces every polynomial of degree $\le p$ in $u$ and in $v$ exactly;
//! - it is continuous: the stencil changes only on particle lines ($\lfloor t/\Delta\rfloor$
//!   jumps at a node), where both neighbouring stencils pass through the same particles;
//!   it is a piecewise polynomial, not smooth across particle lines for $p < n - 1$;
//! - its Lebesgue constant is that of $p + 1$ nodes (1.63 at $p = 3$ on the outer cell of a
//!   one-sided stencil, 1.25 on a centred cell), whatever the number of particles;
//! - for $p \ge n - 1$ the stencil is the whole grid: the seed's global polynomial
//!   ([`super::SpringSettings::seed_experiment`] keeps it, degree 5 on 6 particles).
//!
//! Measured on the shared page turn (max render-edge stretch per frame, mean and worst; the
//! particle grid's own is 0.8 % and 2.8 %): degree 1 (bilinear) 0.8 % and 2.8 %, faceted
//! along every particle line; degree 3, the default, 1.5 % and 6.0 %; degree 5 2.0 % and
//! 8.3 %; the global $8 \times 11$ 4.6 % and 27 %. Between particles a curved page's render
//! edges are longer than the chords the particles keep, so a smooth surface measures more
//! stretch than the particles do (about twice at degree 3).
//!
//! **Table.** A polynomial through particles that lie on the table next to lifted ones
//! dips under it between them (the cubic through heights $0, 0, c, 4c$ is
//! $c\thinspace t(t-1)(t+1)/6 < 0$ on the first cell): $y = -0.05$ at worst on the shared page turn
//! at degree 3. With the table on ([`LagrangeSurface::with_floor`], the page's setting
//! `floor`) a surface point under the plane $y = 0$ is lifted onto it, the contact every
//! free particle obeys: particles on or above the table are still interpolated exactly. (A
//! particle held under the table by the finger is not lifted, its render point is.)
//!
//! **Stretch guard.** Where the particles fold sharply (a flick, a page pushed together on
//! the table until it buckles) a polynomial of degree $p > 1$ through them overshoots between
//! them: with every stretch and shear spring within Provot's 10 %
//! ([`super::limit`]) the cubic's render edges measured up to 100 % (a finger flicking the
//! fore edge to the spine's height; `tests/tests/bounded_pages.rs`). With a guard
//! ([`LagrangeSurface::with_stretch_guard`], the page's `strain_limit`) a render grid
//! sampled with an edge outside $[1 - \tau, 1 + \tau]$ of its rest length is sampled again
//! with the bilinear surface ($p = 1$ both ways) for that frame: its edges along a particle
//! line are pieces of the links, and across a cell they are convex combinations of the two
//! links beside them, so they stretch no more than the links do and never dip under the
//! table. The surface is then faceted for that frame; [`LagrangeSurface::eval`] (the finger
//! gap) keeps degree $p$.
//!
//! **Evaluation.** Barycentric form on the stencil,
//! $\ell^a_i(t) = \frac{w_{i-a}/(t - t_i)}{\sum_{k=a}^{a+p} w_{k-a}/(t - t_k)}$, with the
//! equispaced weights $w_k = (-1)^k\binom{p}{k}$ (Berrut and Trefethen 2004), forward stable
//! for $t$ on the page; at a node ($\lvert t - t_i\rvert \le \varepsilon$ times the extent)
//! the basis is the unit vector, so a render node on a particle reproduces it to rounding.
//!
//! Cost: [`LagrangeSurface::eval`] $O(p^2)$ per point, [`LagrangeSurface::sample`]
//! $O(n_x\thinspace p)$ per render row plus $O(p)$ per render node; no allocation (the basis values
//! live on the stack).

use alloc::vec::Vec;
use folio_geometry::QuadGrid;
use folio_kernels::{Real, Vec3Ops};

use super::settings::MAX_PARTICLES_PER_SIDE;
use crate::{PageError, material_point};

/// The interpolation nodes of one direction and the barycentric weights of its stencil.
#[derive(Clone, Debug)]
struct Axis<T> {
    nodes: Vec<T>,
    /// The stencil's degree $p \le n - 1$; $p + 1$ weights.
    degree: usize,
    weights: Vec<T>,
    /// $(n - 1)/\text{extent}$: a coordinate times this is in node spacings.
    per_length: T,
    /// $\varepsilon \cdot$ extent: closer than this to a node counts as on it.
    snap: T,
}

impl<T: Real> Axis<T> {
    /// `n` nodes over `extent`, stencils of `degree` (cut to $[1, n - 1]$).
    fn new(n: usize, extent: T, degree: usize) -> Self {
        let n = n.clamp(1, MAX_PARTICLES_PER_SIDE);
        let grid = QuadGrid { nx: n, nz: 1 };
        let nodes = (0..n)
            .map(|i| material_point(grid, [extent, T::ZERO], i)[0])
            .collect();
        let degree = degree.clamp(1, n.saturating_sub(1).max(1));
        // w_k = (-1)^k C(p, k), by C(p, k) = C(p, k-1) (p-k+1)/k (exact in f64 here).
        let mut weights = Vec::with_capacity(degree + 1);
        let mut c = 1.0f64;
        for k in 0..=degree {
            if k > 0 {
                c = c * (degree + 1 - k) as f64 / k as f64;
            }
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            weights.push(T::from_f64(sign * c));
        }
        Self {
            nodes,
            degree,
            weights,
            per_length: T::from_f64(n.saturating_sub(1) as f64) / extent,
            snap: T::EPSILON * extent,
        }
    }

    /// The first node $a(t)$ of the stencil of `t` (module docs).
    fn start(&self, t: T) -> usize {
        let last = self.nodes.len().saturating_sub(1 + self.degree);
        let cell = (t * self.per_length).to_f64();
        let cell = if cell.is_finite() && cell > 0.0 {
            cell as usize
        } else {
            0
        };
        cell.saturating_sub((self.degree - 1) / 2).min(last)
    }

    /// The stencil start $a$ of `t` and the basis values $\ell^a_{a+k}(t)$ into
    /// `out[k]`, $k = 0..=p$.
    fn basis(&self, t: T, out: &mut [T; MAX_PARTICLES_PER_SIDE]) -> usize {
        let a = self.start(t);
        let count = self.degree + 1;
        let nodes = self.nodes.get(a..a + count).unwrap_or(&[]);
        for (k, &tk) in nodes.iter().enumerate() {
            let d = t - tk;
            if d <= self.snap && -d <= self.snap {
                out[..count].iter_mut().for_each(|o| *o = T::ZERO);
                out[k] = T::ONE;
                return a;
            }
        }
        let mut total = T::ZERO;
        for ((o, &tk), &wk) in out.iter_mut().zip(nodes).zip(&self.weights) {
            *o = wk / (t - tk);
            total += *o;
        }
        let scale = T::ONE / total;
        for o in &mut out[..count] {
            *o *= scale;
        }
        a
    }
}

/// The tensor-product Lagrange surface through a particle grid (module docs).
#[derive(Clone, Debug)]
pub struct LagrangeSurface<T: Real> {
    particles: QuadGrid,
    size: [T; 2],
    across: Axis<T>,
    along: Axis<T>,
    /// The degree-1 axes of the stretch guard's fallback.
    linear: [Axis<T>; 2],
    floor: bool,
    guard: Option<T>,
}

impl<T: Real> LagrangeSurface<T> {
    /// The surface through the particles of `particles` (at most
    /// [`MAX_PARTICLES_PER_SIDE`] per side; larger grids are cut to it) on a page of `size`,
    /// interpolated per direction by the Lagrange polynomial of `degree` on the nearest
    /// `degree + 1` particles (module docs). A degree of 0 counts as 1; one at or above
    /// $n - 1$ gives the seed's global polynomial in that direction.
    #[must_use]
    pub fn new(particles: QuadGrid, size: [T; 2], degree: usize) -> Self {
        Self {
            particles,
            size,
            across: Axis::new(particles.nx, size[0], degree),
            along: Axis::new(particles.nz, size[1], degree),
            linear: [
                Axis::new(particles.nx, size[0], 1),
                Axis::new(particles.nz, size[1], 1),
            ],
            floor: false,
            guard: None,
        }
    }

    /// The same surface with (`Some(limit)`) or without the stretch guard ("Stretch
    /// guard" in the module docs): a sampled render grid with an edge stretched or
    /// compressed by more than `limit` is sampled again at degree 1.
    #[must_use]
    pub fn with_stretch_guard(mut self, limit: Option<T>) -> Self {
        self.guard = limit;
        self
    }

    /// The same surface, with (`true`) or without the table's contact on its points: a
    /// point of $S$ under the plane $y = 0$ is lifted onto it, $y \leftarrow \max(y, 0)$
    /// (module docs, "Table").
    #[must_use]
    pub fn with_floor(mut self, floor: bool) -> Self {
        self.floor = floor;
        self
    }

    /// `true` when the table's contact applies to the surface's points.
    #[must_use]
    pub fn floor(&self) -> bool {
        self.floor
    }

    /// The point `p` of the surface, lifted onto the table when it is on and `p` is under it.
    #[inline]
    fn contact(&self, p: T::Vec3) -> T::Vec3 {
        if self.floor && p.y() < T::ZERO {
            T::Vec3::new(p.x(), T::ZERO, p.z())
        } else {
            p
        }
    }

    /// The particle grid interpolated.
    #[must_use]
    pub fn particles(&self) -> QuadGrid {
        self.particles
    }

    /// The page size $(W, H)$.
    #[must_use]
    pub fn size(&self) -> [T; 2] {
        self.size
    }

    /// The degrees used across and along (the asked degree cut to $[1, n - 1]$ per
    /// direction).
    #[must_use]
    pub fn degrees(&self) -> [usize; 2] {
        [self.across.degree, self.along.degree]
    }

    /// $S(u, v)$ at `at` $= (u, v)$ for particle positions `x` (index $i + n_x j$). Returns
    /// the zero vector for a position slice shorter than the grid.
    #[must_use]
    pub fn eval(&self, x: &[T::Vec3], at: [T; 2]) -> T::Vec3 {
        let (nx, nz) = (self.across.nodes.len(), self.along.nodes.len());
        if x.len() < self.particles.len() || nx != self.particles.nx || nz != self.particles.nz {
            return T::Vec3::ZERO;
        }
        let mut l = [T::ZERO; MAX_PARTICLES_PER_SIDE];
        let mut m = [T::ZERO; MAX_PARTICLES_PER_SIDE];
        let a = self.across.basis(at[0], &mut l);
        let b = self.along.basis(at[1], &mut m);
        let (pu, pv) = (self.across.degree + 1, self.along.degree + 1);
        let mut p = T::Vec3::ZERO;
        for (row, &mj) in x.chunks_exact(nx).skip(b).zip(&m[..pv]) {
            if mj == T::ZERO {
                continue;
            }
            let mut r = T::Vec3::ZERO;
            for (&xij, &li) in row.iter().skip(a).zip(&l[..pu]) {
                if li != T::ZERO {
                    r += xij * li;
                }
            }
            p += r * mj;
        }
        self.contact(p)
    }

    /// Writes $S$ at the material point of every node of the render `grid`
    /// ([`material_point`]) into `out`, for particle positions `x`. Separable: per render
    /// row the particle rows of its stencil are first contracted along $v$,
    /// $R_i = \sum_j m^a_j(v) P_{ij}$ for every $i$, then each node is
    /// $\sum_i \ell^a_i(u) R_i$ over its stencil: $O(n_x\thinspace p)$ per render row plus $O(p)$ per
    /// node. A particle grid that does not match `x` gives zero vectors.
    ///
    /// # Errors
    /// [`PageError::SampleCount`] unless `out.len() == grid.len()`.
    pub fn sample(
        &self,
        x: &[T::Vec3],
        grid: QuadGrid,
        out: &mut [T::Vec3],
    ) -> Result<(), PageError> {
        crate::check_count(grid.len(), out.len())?;
        let (nx, nz) = (self.across.nodes.len(), self.along.nodes.len());
        if x.len() < self.particles.len()
            || nx != self.particles.nx
            || nz != self.particles.nz
            || grid.nx == 0
        {
            out.iter_mut().for_each(|o| *o = T::Vec3::ZERO);
            return Ok(());
        }
        self.sample_on(&self.across, &self.along, x, grid, out);
        if let Some(limit) = self.guard {
            let linear = self.across.degree == 1 && self.along.degree == 1;
            if !linear && crate::metrics::max_stretch(grid, self.size, out) > limit {
                let [across, along] = &self.linear;
                self.sample_on(across, along, x, grid, out);
            }
        }
        Ok(())
    }

    /// [`LagrangeSurface::sample`] on the stencils of `across` and `along` (checked input).
    fn sample_on(
        &self,
        across: &Axis<T>,
        along: &Axis<T>,
        x: &[T::Vec3],
        grid: QuadGrid,
        out: &mut [T::Vec3],
    ) {
        let nx = across.nodes.len();
        let (pu, pv) = (across.degree + 1, along.degree + 1);
        let mut l = [T::ZERO; MAX_PARTICLES_PER_SIDE];
        let mut m = [T::ZERO; MAX_PARTICLES_PER_SIDE];
        let mut rows = [T::Vec3::ZERO; MAX_PARTICLES_PER_SIDE];
        for (jr, line) in out.chunks_exact_mut(grid.nx).enumerate() {
            let v = material_point(grid, self.size, grid.index(0, jr))[1];
            let b = along.basis(v, &mut m);
            rows[..nx].iter_mut().for_each(|r| *r = T::Vec3::ZERO);
            for (row, &mj) in x.chunks_exact(nx).skip(b).zip(&m[..pv]) {
                if mj == T::ZERO {
                    continue;
                }
                for (r, &xij) in rows.iter_mut().zip(row) {
                    *r += xij * mj;
                }
            }
            for (ir, o) in line.iter_mut().enumerate() {
                let u = material_point(grid, self.size, grid.index(ir, jr))[0];
                let a = across.basis(u, &mut l);
                let mut p = T::Vec3::ZERO;
                for (&r, &li) in rows[..nx].iter().skip(a).zip(&l[..pu]) {
                    if li != T::ZERO {
                        p += r * li;
                    }
                }
                *o = self.contact(p);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stencil's basis at `t` as (start, values).
    fn basis(axis: &Axis<f64>, t: f64) -> (usize, Vec<f64>) {
        let mut out = [0.0; MAX_PARTICLES_PER_SIDE];
        let a = axis.basis(t, &mut out);
        (a, out[..=axis.degree].to_vec())
    }

    #[test]
    fn the_weights_are_signed_binomials() {
        let axis = Axis::<f64>::new(9, 4.0, 4);
        assert_eq!(axis.weights, [1.0, -4.0, 6.0, -4.0, 1.0]);
        // The degree is cut to the nodes there are.
        assert_eq!(Axis::<f64>::new(3, 1.0, 7).degree, 2);
        assert_eq!(Axis::<f64>::new(1, 1.0, 3).degree, 1);
    }

    #[test]
    fn the_basis_is_a_partition_of_unity_that_reproduces_its_degree() {
        let axis = Axis::<f64>::new(9, 4.0, 3);
        for k in 0..=40 {
            let t = 4.0 * f64::from(k) / 40.0 + 1e-3;
            let (a, l) = basis(&axis, t);
            assert!(
                a + axis.degree < 9,
                "stencil {a} runs off the nodes at t = {t}"
            );
            let sum: f64 = l.iter().sum();
            assert!((sum - 1.0).abs() < 1e-12, "sum {sum} at t = {t}");
            // A cubic is reproduced exactly by the cubic stencil.
            let cubic = |x: f64| x * x * x - 2.0 * x + 0.5;
            let p: f64 = l
                .iter()
                .enumerate()
                .map(|(i, w)| w * cubic(axis.nodes[a + i]))
                .sum();
            assert!(
                (p - cubic(t)).abs() < 1e-10,
                "{p} vs {} at t = {t}",
                cubic(t)
            );
        }
    }

    #[test]
    fn at_a_node_the_basis_is_the_unit_vector() {
        let axis = Axis::<f64>::new(5, 2.0, 2);
        for (i, &t) in axis.nodes.iter().enumerate() {
            let (a, l) = basis(&axis, t);
            for (k, &v) in l.iter().enumerate() {
                assert_eq!(v, if a + k == i { 1.0 } else { 0.0 }, "node {i}");
            }
        }
    }

    #[test]
    fn stencils_start_centred_and_stay_on_the_page() {
        let axis = Axis::<f64>::new(9, 8.0, 3);
        assert_eq!(axis.start(-5.0), 0);
        assert_eq!(axis.start(f64::NAN), 0);
        assert_eq!(axis.start(4.5), 3);
        assert_eq!(axis.start(100.0), 5);
    }
}
