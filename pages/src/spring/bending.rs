//! The bending of the mass-spring page in physical terms (issue 21): what the bend springs
//! give, and the plate bending term that gives a stiffness $D$.
//!
//! **The bend springs have no bending stiffness $D$.** A plate of bending stiffness $D$
//! (energy: mass·length²/s², N·m in SI; the bending moment per unit width per unit
//! curvature) rolled into a cylinder of curvature $\kappa$ stores $\frac D2\kappa^2$ per unit
//! area. Roll the particle grid across its rows (the rulings along the spine, spacings
//! $h_x$ across and $h_z$ along) with every stretch spring at its rest length: each row is a
//! polygon of sides $h_x$ inscribed in a circle of radius $1/\kappa$, turning by
//! $\varphi = 2\arcsin(\kappa h_x/2) = \kappa h_x + O(\kappa^3)$ at each particle. A bend
//! spring (Provot's skip-one spring, rest length $2h_x$) spans two sides, so its chord is
//! $2h_x\cos(\varphi/2)$: it is shorter by
//! $$\delta = 2h_x\bigl(1 - \cos(\varphi/2)\bigr) = \tfrac14\kappa^2 h_x^3 + O(\kappa^4),$$
//! second order in $\kappa$, and its energy $\frac12 k\delta^2 = \frac{1}{32}k\kappa^4h_x^6$ is
//! quartic. The shear springs keep their rest lengths (each cell stays a flat rectangle to
//! first order) and the bend springs along the spine are straight. With one such spring per
//! particle, the area $h_x h_z$, the rolled page stores
//! $$\frac{k\kappa^4 h_x^5}{32\,h_z}\ \text{per unit area}
//!   = \frac{D_{\mathrm{eq}}(\kappa)}{2}\kappa^2,\qquad
//!   D_{\mathrm{eq}}(\kappa) = \frac{k\kappa^2h_x^5}{16\,h_z}$$
//! ([`bend_spring_equivalent`]): an equivalent stiffness that vanishes at small curvature.
//! A flat page has no linear bending stiffness at all, and a sagging one stiffens as it
//! bends; a single $D$ cannot describe it. (If the stretch springs give, the chord recovers
//! part of $\delta$ by stretching the sides, and $D_{\mathrm{eq}}$ is smaller still: with a
//! stretch spring $k_s$ per side and shear ignored, $k$ becomes $k k_s/(k_s + 4k)$, half of
//! $k$ at the default's $k_s = 4k$.) The same holds for any particle's zig-zag: moving one
//! particle by $\epsilon$ out of the flat page changes no spring's length at first order
//! (every spring lies in the page), so every spring's energy is quartic in $\epsilon$.
//! Measured on the default page rolled to $\kappa = 10^{-3}, 10^{-2}, 5\cdot10^{-2}$ in
//! `tests/tests/elastica_spring.rs`: the bend springs' energy grows as $\kappa^4$ and
//! matches $D_{\mathrm{eq}}$.
//!
//! **The plate term.** The page gets its $D$ from a term of its own
//! ([`super::SpringSettings::bending_stiffness`], default 0, no term), a finite-difference
//! Kirchhoff plate (the plate's bending energy, e.g. Timoshenko and Woinowsky-Krieger,
//! *Theory of Plates and Shells*, 1959) with Poisson's ratio 0 on the rest grid $(u, v)$:
//! $$V_{\mathrm{bend}} = \frac D2\int \lVert x_{uu}\rVert^2 + 2\lVert x_{uv}\rVert^2 +
//!   \lVert x_{vv}\rVert^2\,dA \approx \frac D2\Bigl(\sum_v A_v\lVert\delta_u^2 x_v\rVert^2 +
//!   \sum_v A_v\lVert\delta_v^2 x_v\rVert^2 + 2\sum_c h_xh_z\lVert\delta_{uv}x_c\rVert^2\Bigr),$$
//! with the second differences $\delta_u^2 x_v = (x_{i+1,j} - 2x_{ij} + x_{i-1,j})/h_x^2$ at
//! particles inside along $u$ (likewise $\delta_v^2$ along $v$ with $h_z$), the twist
//! $\delta_{uv}x_c = (x_{i+1,j+1} - x_{i+1,j} - x_{i,j+1} + x_{ij})/(h_xh_z)$ on every cell
//! $c$, and $A_v$ the rest grid's dual-cell area of particle $v$ ($h_xh_z$ inside, half on an
//! edge, a quarter at a corner). For an unstretched page parametrized by its rest grid,
//! $x_{uu}$, $x_{uv}$, $x_{vv}$ are normal (differentiate $\lVert x_u\rVert = \lVert x_v\rVert
//! = 1$, $x_u\cdot x_v = 0$), so the integrand is the second fundamental form's squared norm
//! $\kappa_1^2 + \kappa_2^2$; for a developable page ($K = 0$, one principal curvature
//! $\kappa$) that is the plate's $\frac D2\int\kappa^2\,dA$. A saddle costs
//! $\kappa_1^2 + \kappa_2^2 > 0$ too: the Laplacian form $\lVert\Delta x\rVert^2 =
//! (\kappa_1 + \kappa_2)^2$ (Poisson's ratio 1), tried first, gave a saddle nothing to pay,
//! and the clamped page, which only the springs' quartic stretching kept developable, sagged
//! too far by 54 % at $\alpha = 0.1$ on the default grid and by 76 % at twice its
//! resolution (measured with `tests/tests/elastica_spring.rs`). With Poisson's ratio 0 the
//! cylinder is the clamped page's equilibrium (no anticlastic curl at the free edges): a
//! beam of stiffness $D$ per unit width, the elastica's assumption.
//!
//! On the rest spacings the second difference of a polygon of sides $h$ inscribed in a
//! circle of curvature $\kappa$ is $\lVert x_{i+1} - 2x_i + x_{i-1}\rVert = 2h\sin(\varphi/2)
//! = \kappa h^2$ exactly, so a page rolled across its rows stores
//! $\frac D2\kappa^2\sum A_v$ over the particles inside along $u$, at any spacing. A particle
//! on the edges $u = 0, W$ has no second difference along $u$: exact where the curvature
//! across that edge vanishes (a free edge, which carries no moment, and a page bent about an
//! axis across it); elsewhere the missing term costs $O(h)$ in a strip $h/2$ wide. The term
//! is quadratic in the positions: its Hessian is constant, which the implicit integrator
//! assembles like any other, and the explicit one needs only its gradient.
//! [`plate_stencils`] lists the stencils; [`super::SpringNetwork`] puts them into two
//! [`folio_kernels::stencil::SquaredStencil`] families of weight $D/2$, with the stencil
//! weights the difference's coefficients times the square root of the stencil's area
//! weight ($A_v$, or $2h_xh_z$ for a twist). That is the one place where $D$ becomes the
//! solver's weights.
//!
//! **Clamp** ([`super::SpringSettings::clamped_spine`]). A particle on the fixed spine
//! column has no second difference across the page; a clamped spine gives it one with a
//! ghost particle beyond the spine, the mirror image of its neighbour across the plane
//! $X = 0$ (the finite-difference clamp $w_{-1} = w_1$): with $x_0$ on the spine at rest
//! and $x_1$ its neighbour, $x_{-1} = (-x_{1,X}, x_{1,Y}, x_{1,Z})$ and
//! $\delta_u^2 x_0 = 2P(x_1 - x_0)/h_x^2$, $P = \mathrm{diag}(0, 1, 1)$, so the spine row adds
//! $\frac D2 A_0\cdot 4\lVert P(x_1 - x_0)\rVert^2/h_x^4$ ([`SpineClamp`], $A_0$ the spine
//! particle's dual area). This is exactly half of a page twice as wide whose middle column
//! is held: the page's tangent at the spine is held along $\pm X$ (a page turned over to lie
//! flat on the left is at rest at the spine too; on the way it passes the vertical against
//! the clamp's largest moment). The twists of the ghost cells are constant and the spine's
//! own second differences along it are fixed: neither adds a term.
//!
//! **Masses.** A page of areal density $\rho$ puts $\rho A_v$ on particle $v$ when
//! [`super::SpringSettings::area_masses`] is on ([`mass_share`]), the same quadrature as the
//! bending, so that gravity $\int\rho g\,y\,dA$ and the bending are the same physical page at
//! every grid; equal particle masses (the seed's) would put twice their area's share on the
//! edge particles, an extra end load on a cantilever. [`super::SpringSettings::physical`]
//! describes a page by its size, $\rho$, $D$ and $g$.
//!
//! The clamped page sags like the cantilever elastica with this $D$
//! (`tests/tests/elastica_spring.rs`, which gives the figures).

use folio_geometry::QuadGrid;
use folio_kernels::term::{Blocks, NodeVecs};
use folio_kernels::{Mat3Ops, Potential, Real, Vec3Ops};

/// The rolled page's equivalent bending stiffness of bend springs of stiffness `k` at
/// curvature `kappa` on the spacings `[h_x, h_z]` with rigid sides (module docs):
/// $D_{\mathrm{eq}} = k\kappa^2h_x^5/(16h_z)$, zero at $\kappa = 0$.
#[must_use]
pub fn bend_spring_equivalent<T: Real>(k: T, spacing: [T; 2], kappa: T) -> T {
    let [hx, hz] = spacing;
    let h2 = hx * hx;
    k * kappa * kappa * h2 * h2 * hx / (T::from_f64(16.0) * hz)
}

/// Particle `k`'s share of an inner particle's area, $c_i c_j$ with $c = \frac12$ on the
/// border and 1 inside (module docs): 1, $\frac12$ on an edge, $\frac14$ at a corner; 1 for
/// every particle when `area` is off (equal masses).
#[must_use]
pub fn mass_share(grid: QuadGrid, k: usize, area: bool) -> f64 {
    if !area {
        return 1.0;
    }
    let (i, j) = grid.coords(k);
    let c = |at: usize, n: usize| if at == 0 || at + 1 == n { 0.5 } else { 1.0 };
    c(i, grid.nx) * c(j, grid.nz)
}

/// One stencil of the plate term (module docs): $a\lVert\sum_k c_k x_k\rVert^2$ over its
/// particles, $a$ its area weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlateStencil {
    /// A second difference along a grid line, particles `[p, forward, back]`.
    Second {
        /// Particle indices.
        nodes: [usize; 3],
        /// Coefficients $c_k$ (1/length²).
        coefficients: [f64; 3],
        /// $a = A_v$ (length²).
        area: f64,
    },
    /// A cell's twist, particles `[(i, j), (i+1, j), (i, j+1), (i+1, j+1)]`.
    Twist {
        /// Particle indices.
        nodes: [usize; 4],
        /// Coefficients $c_k$ (1/length²).
        coefficients: [f64; 4],
        /// $a = 2h_xh_z$ (length²).
        area: f64,
    },
}

impl PlateStencil {
    /// Nodes, coefficients and area weight, whatever the kind.
    #[must_use]
    pub fn parts(&self) -> (&[usize], &[f64], f64) {
        match self {
            Self::Second {
                nodes,
                coefficients,
                area,
            } => (nodes, coefficients, *area),
            Self::Twist {
                nodes,
                coefficients,
                area,
            } => (nodes, coefficients, *area),
        }
    }
}

/// Calls `each` with every stencil of the plate term on the rest spacings `[h_x, h_z]`
/// (module docs): per particle its second differences along $u$ and along $v$ where it has
/// neighbours on both sides, then per cell its twist.
pub fn plate_stencils(grid: QuadGrid, spacing: [f64; 2], mut each: impl FnMut(PlateStencil)) {
    let [hx, hz] = spacing;
    let (cx, cz) = (1.0 / (hx * hx), 1.0 / (hz * hz));
    let c = |at: usize, n: usize| if at == 0 || at + 1 == n { 0.5 } else { 1.0 };
    for k in 0..grid.len() {
        let (i, j) = grid.coords(k);
        let area = c(i, grid.nx) * c(j, grid.nz) * hx * hz;
        if i > 0 && i + 1 < grid.nx {
            each(PlateStencil::Second {
                nodes: [k, grid.index(i + 1, j), grid.index(i - 1, j)],
                coefficients: [-2.0 * cx, cx, cx],
                area,
            });
        }
        if j > 0 && j + 1 < grid.nz {
            each(PlateStencil::Second {
                nodes: [k, grid.index(i, j + 1), grid.index(i, j - 1)],
                coefficients: [-2.0 * cz, cz, cz],
                area,
            });
        }
    }
    let t = 1.0 / (hx * hz);
    for j in 0..grid.nz.saturating_sub(1) {
        for i in 0..grid.nx.saturating_sub(1) {
            each(PlateStencil::Twist {
                nodes: [
                    grid.index(i, j),
                    grid.index(i + 1, j),
                    grid.index(i, j + 1),
                    grid.index(i + 1, j + 1),
                ],
                coefficients: [t, -t, -t, t],
                area: 2.0 * hx * hz,
            });
        }
    }
}

/// The clamp's term on the spine's neighbour $x_1$ (module docs):
/// $V = w\lVert P(x_1 - p)\rVert^2$ with $P = \mathrm{diag}(0, 1, 1)$, $p$ the spine
/// particle's position and $w = 4A_0/h_x^4$ (the family weight $D/2$ multiplies it);
/// gradient $2wP(x_1 - p)$, Hessian $2wP$ (constant).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpineClamp<T: Real> {
    /// $p$: the spine particle's (fixed) position.
    pub spine: T::Vec3,
    /// $w = 4A_0/h_x^4$ (1/length²).
    pub weight: T,
}

impl<T: Real> SpineClamp<T> {
    /// $P(x - p)$.
    #[inline]
    fn across(&self, x: T::Vec3) -> T::Vec3 {
        let d = x - self.spine;
        T::Vec3::new(T::ZERO, d.y(), d.z())
    }
}

impl<T: Real> Potential<T, 1> for SpineClamp<T> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        let d = self.across(x[0]);
        self.weight * d.dot(d)
    }

    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        [self.across(x[0]) * (T::TWO * self.weight)]
    }

    fn hessian(&self, _x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        let w = T::TWO * self.weight;
        [[T::Mat3::diagonal(T::Vec3::new(T::ZERO, w, w))]]
    }
}

/// What the flat page's plate term and its stability bound read of the page's settings
/// (`SpringSettings::flat_page`): the particle grid and its rest spacing (page units), the
/// spine's clamp, the three spring families' stiffness summed, the plate's $D$ and the
/// particle masses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatPage {
    /// The particle grid (across, along).
    pub grid: QuadGrid,
    /// Rest spacing `[across, along]` (page units).
    pub spacing: [f64; 2],
    /// The spine is fixed and clamped (`fixed_spine` and `clamped_spine`).
    pub clamped_spine: bool,
    /// $\sum k$ over stretch, shear and bend springs.
    pub spring_stiffness: f64,
    /// The plate's bending stiffness $D$ (0: no plate term).
    pub plate_stiffness: f64,
    /// The mass of an inner particle.
    pub particle_mass: f64,
    /// Edge and corner particles carry their area's share ([`mass_share`]).
    pub area_masses: bool,
}

/// The clamp's terms of `page` (module docs): `(spine particle, neighbour, w)` per row,
/// none unless the spine is fixed and clamped and the page has two columns or more.
pub fn spine_clamps(page: &FlatPage, mut each: impl FnMut(usize, usize, f64)) {
    let QuadGrid { nx, nz } = page.grid;
    if !page.clamped_spine || nx < 2 {
        return;
    }
    let [hx, hz] = page.spacing;
    let grid = page.grid;
    for j in 0..nz {
        let c = if j == 0 || j + 1 == nz { 0.5 } else { 1.0 };
        let area = 0.5 * c * hx * hz;
        each(
            grid.index(0, j),
            grid.index(1, j),
            4.0 * area / (hx * hx * hx * hx),
        );
    }
}

/// A Gershgorin bound on the largest $\omega^2$ of the flat page's springs and plate term
/// over the particle masses of `page` (`SpringSettings::omega_squared_bound` for validated
/// settings): for each particle, the springs' estimate $4\sum k$ of
/// [`super::Integrator::SemiImplicitEuler`] plus the plate term's absolute Hessian row sums
/// at it, $D\sum a\lvert c_k\rvert\sum_l\lvert c_l\rvert$ over the stencils that read it,
/// divided by its mass, the largest of them. With equal masses and no plate term it is the
/// earlier $4\sum k/m$. Allocates one number per particle (setup only).
#[must_use]
pub fn omega_squared_bound(page: &FlatPage) -> f64 {
    let grid = page.grid;
    let mut rows = alloc::vec![0.0f64; grid.len()];
    let d = page.plate_stiffness;
    if d > 0.0 {
        plate_stencils(grid, page.spacing, |stencil| {
            let (nodes, c, area) = stencil.parts();
            let total: f64 = c.iter().map(|v| v.abs()).sum();
            for (&n, &ca) in nodes.iter().zip(c) {
                if let Some(r) = rows.get_mut(n) {
                    *r += d * area * ca.abs() * total;
                }
            }
        });
        // The clamp's Hessian 2 (D/2) w P on the neighbour: row sum D w.
        spine_clamps(page, |_, k, w| {
            if let Some(r) = rows.get_mut(k) {
                *r += d * w;
            }
        });
    }
    let springs = 4.0 * page.spring_stiffness;
    (0..grid.len())
        .map(|k| {
            let share = mass_share(grid, k, page.area_masses);
            (springs + rows.get(k).copied().unwrap_or(0.0)) / (page.particle_mass * share)
        })
        .fold(0.0, f64::max)
}
