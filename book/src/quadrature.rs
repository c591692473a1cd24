//! The active page's bending and masses as a quadrature over the page (issue 21): the
//! discrete energy converges to the plate's at every grid, so a grid of any resolution is
//! the same physical page.
//!
//! **Continuum.** A page is developable and unstretched ($K = 0$), so its plate bending
//! energy has one principal curvature $\kappa$:
//! $$E = \frac D2 \int (\kappa_1^2 + \kappa_2^2)\,dA = \frac D2 \int (2H)^2\,dA
//!   = \frac D2 \int \kappa^2\,dA,$$
//! $D$ the bending stiffness (energy: page masses $\cdot$ page units$^2$/s$^2$, i.e. the
//! bending moment per unit width per unit curvature). A DOG is parametrized by its grid
//! $(u, v)$ with both grid curves geodesics meeting at right angles (seed `000_…` Sec. 3.2),
//! so $x_{uu} = \kappa_u n$ and $x_{vv} = \kappa_v n$ are normal, $\Delta x = 2H\,n$ and
//! $\lVert\Delta x\rVert^2 = \kappa^2$.
//!
//! **Discrete.** With $\Delta_h$ the five-point Laplacian on the rest spacings $h_x, h_y$ and
//! $A_v$ the dual-cell area of vertex $v$ (the rest-grid cell around it: $h_x h_y$ inside,
//! half of it on an edge, a quarter at a corner), the page bending of seed eq. 10 is
//! $$V_h = w_{\mathrm{bend3D}} \sum_v A_v \lVert \Delta_h x_v\rVert^2
//!   \;\to\; w_{\mathrm{bend3D}} \int \kappa^2\,dA,
//!   \qquad\text{so}\qquad D = 2\,w_{\mathrm{bend3D}}$$
//! at every grid spacing ([`bending_stiffness`]); a stack of $k$ pages has $k D$
//! ([`crate::BookTerms::set_stack`]). Inner vertices use the inner stencil
//! ([`folio_kernels::dog_laplacian::inner_area`]): on square cells it is the seed's
//! $\lVert\tilde L\rVert^2$ term exactly, so the seed's weight 120 keeps its meaning there.
//! An edge vertex (a 3-neighbour star) sees only the second difference along its boundary
//! curve ([`folio_kernels::dog_laplacian::boundary_area`]), with half a cell of area. That
//! is exact where the curvature across the edge vanishes: a free edge that carries no
//! moment, the hinge at the binding, and a page bent about an axis across the edge (the
//! cantilever's top and bottom rows). Elsewhere the missing curvature costs $O(h)$ in a
//! strip of width $h/2$, as a trapezoid rule that drops an edge term would. Corners have no
//! second difference and carry no term (a quarter cell each, $O(h^2)$).
//!
//! Before issue 21 the terms carried no area: the seed's $\lVert\tilde L\rVert^2 =
//! h^2\lVert\Delta_h x\rVert^2$ inside, which is right on square cells, and
//! $\lVert 2 h\,\partial^2_h x\rVert^2 = 4h^2\lVert\partial^2_h x\rVert^2$ on the edges,
//! 8 times the edge's half cell. For a page bent into a cylinder across its rows (rulings
//! along the binding, $n_x \times n_y$ vertices), the sum was
//! $\kappa^2 h^2 (n_x - 2)(n_y + 6)$ instead of $A\kappa^2 = \kappa^2 h^2 (n_x-1)(n_y-1)$:
//! 1.43 times at the 8x11 grid, 1.24 at 16x22, tending to 1 only as $1/n$.
//!
//! **Masses.** Gravity $\int \rho g y\,dA$ with the same quadrature: node $v$ carries
//! $\rho A_v$ of the page's mass ([`mass_fraction`]). Equal node masses put
//! $1/(n_x n_y)$ of the page on each edge node, twice its area's share; a cantilever
//! then carries an extra end load, 3.7 % more tip sag at 8 quads across.
//!
//! The clamped page sags like the cantilever elastica with this $D$
//! (`tests/tests/elastica_page.rs`, which gives the figures).
//!
//! **In the book.** [`crate::BookTerms`] builds these terms and masses. At first the page
//! turn's largest DOG residual rose from 1.0e-4 to 1.8e-3 at the grab (bound 1e-3) and its
//! largest stretch from 1.1 % to 4.4 %: the page's edges carry an eighth of their former
//! bending, the projection moved more, and the collision after each projection pass found
//! a node again, so the step ended on a push. Holding pushed nodes along their contact
//! normal only, one-sided ([`folio_solvers::Pins`], `Book::project`), and the default
//! bending weight 172 (the former page's stiffness at 8x11, [`crate::Weights::bend_page`])
//! brought the built-in scenes to DOG residuals of 9.3e-5 to 1.0e-4 and largest stretches
//! of 0.55 % (page turn, 1.07 % before) to 3.1 % (`three-and-back`, 2.7 % before), every
//! page count as before (`folio run SCENE` for each).

use alloc::vec::Vec;
use folio_geometry::{QuadGrid, Star};
use folio_kernels::dog_laplacian::{self, DogLaplacianBoundary, DogLaplacianInner};
use folio_kernels::{KernelError, Real};

/// The page's bending stiffness $D = 2\,w_{\mathrm{bend3D}}$ (module docs; page masses
/// $\cdot$ page units$^2$/s$^2$) for the weight `bend_page`, at every grid.
#[inline]
#[must_use]
pub fn bending_stiffness<T: Real>(bend_page: T) -> T {
    T::TWO * bend_page
}

/// The share of the page's area in vertex `k`'s dual cell: $\frac{c_i c_j}{(n_x-1)(n_y-1)}$
/// with $c = 1/2$ on the border and 1 inside (module docs). The shares sum to 1.
#[must_use]
pub fn mass_fraction(grid: QuadGrid, k: usize) -> f64 {
    let (i, j) = grid.coords(k);
    let share = |at: usize, n: usize| if at == 0 || at + 1 == n { 0.5 } else { 1.0 };
    share(i, grid.nx) * share(j, grid.nz) / ((grid.nx - 1) * (grid.nz - 1)) as f64
}

/// Vertex `k`'s dual-cell area on the rest spacing `[across, along]` (page units²).
#[must_use]
pub fn dual_area(grid: QuadGrid, spacing: [f64; 2], k: usize) -> f64 {
    let page = spacing[0] * spacing[1] * ((grid.nx - 1) * (grid.nz - 1)) as f64;
    mass_fraction(grid, k) * page
}

/// The node masses of a page of mass `mass`, in grid order ([`mass_fraction`]).
#[must_use]
pub fn node_masses<T: Real>(grid: QuadGrid, mass: T) -> Vec<T> {
    (0..grid.len())
        .map(|k| mass * T::from_f64(mass_fraction(grid, k)))
        .collect()
}

/// One vertex's bending term and the grid nodes its stencil reads, in the stencil's order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PageBending<T: Real> {
    /// An inner star, nodes `[p0, xf, yf, xb, yb]`.
    Inner(DogLaplacianInner<T>, [usize; 5]),
    /// A 3-neighbour star, nodes `[p0, forward, back]` along its boundary curve.
    Boundary(DogLaplacianBoundary<T>, [usize; 3]),
}

/// The bending term of `star` (module docs) on the rest spacing `[across, along]`; `None`
/// for a corner.
///
/// # Errors
/// A spacing that is not a usable length.
pub fn bending<T: Real>(
    grid: QuadGrid,
    spacing: [f64; 2],
    star: Star,
) -> Result<Option<PageBending<T>>, KernelError> {
    let rest_of = |a: usize, b: usize| {
        let along_row = grid.coords(a).1 == grid.coords(b).1;
        T::from_f64(if along_row { spacing[0] } else { spacing[1] })
    };
    let area = |k: usize| T::from_f64(dual_area(grid, spacing, k));
    Ok(match star {
        Star::Inner(s) => {
            let rest = [1, 2, 3, 4].map(|k| rest_of(s[0], s[k]));
            let lap = dog_laplacian::inner_area(rest, area(s[0]))?;
            Some(PageBending::Inner(lap, s))
        }
        Star::Boundary(s) => {
            let rest = [rest_of(s[0], s[1]), rest_of(s[0], s[3])];
            let lap = dog_laplacian::boundary_area(rest, area(s[0]))?;
            Some(PageBending::Boundary(lap, [s[0], s[1], s[3]]))
        }
        Star::Corner(_) => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use folio_kernels::{Potential, math};

    fn grid() -> QuadGrid {
        QuadGrid::new(8, 11).unwrap()
    }

    #[test]
    fn the_shares_cover_the_page_once() {
        let g = grid();
        let sum: f64 = (0..g.len()).map(|k| mass_fraction(g, k)).sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
        let masses = node_masses(g, 3.0_f64);
        assert!((masses.iter().sum::<f64>() - 3.0).abs() < 1e-12);
        // A corner holds a quarter of an inner vertex's share, an edge vertex half.
        let inner = mass_fraction(g, g.index(1, 1));
        assert!((mass_fraction(g, g.index(0, 0)) - inner / 4.0).abs() < 1e-15);
        assert!((mass_fraction(g, g.index(0, 3)) - inner / 2.0).abs() < 1e-15);
    }

    /// On square cells the inner term is the seed's $\lVert\tilde L\rVert^2$ (module
    /// docs) and the edge term a quarter of the unweighted one, times the half cell over
    /// $h^2$.
    #[test]
    fn square_cells_keep_the_seed_inner_term() {
        let h = 1.5_f64;
        let seed = dog_laplacian::inner([h; 4]).unwrap().weights;
        let area = dog_laplacian::inner_area([h; 4], h * h).unwrap().weights;
        for (a, b) in seed.iter().zip(area) {
            assert!((a - b).abs() < 1e-15, "{seed:?} {area:?}");
        }
        let seed = dog_laplacian::boundary([h; 2]).unwrap().weights;
        let area = dog_laplacian::boundary_area([h; 2], h * h / 2.0)
            .unwrap()
            .weights;
        for (a, b) in seed.iter().zip(area) {
            // Weights scale with the square root of the energy's factor 1/8.
            assert!(
                (a / b - math::sqrt(8.0_f64)).abs() < 1e-12,
                "{seed:?} {area:?}"
            );
        }
    }

    /// A page rolled onto a cylinder of curvature $\kappa$ across its rows (rulings along
    /// the binding), on oblong cells: every vertex off the two edge columns adds its dual
    /// area times the squared second difference of the rolled rows,
    /// $\kappa_h = \kappa\,2(1 - \cos h\kappa)/(h\kappa)^2$; the edge columns' stencils
    /// run along the straight rulings and add nothing (the $O(h)$ strip of the module
    /// docs), and the corners have no term.
    #[test]
    fn a_rolled_page_sums_its_areas_times_the_curvature_squared() {
        type V = <f64 as Real>::Vec3;
        let g = grid();
        let spacing = [1.5, 1.6];
        let kappa = 0.05_f64;
        let r = 1.0 / kappa;
        let x: Vec<V> = (0..g.len())
            .map(|k| {
                let (i, j) = g.coords(k);
                let t = i as f64 * spacing[0] * kappa;
                V::new(
                    r * math::sin(t),
                    r * (1.0 - math::cos(t)),
                    j as f64 * spacing[1],
                )
            })
            .collect();
        let mut sum = 0.0;
        for star in g.stars() {
            match bending::<f64>(g, spacing, star).unwrap() {
                Some(PageBending::Inner(lap, n)) => sum += lap.value(&n.map(|k| x[k])),
                Some(PageBending::Boundary(lap, n)) => sum += lap.value(&n.map(|k| x[k])),
                None => {}
            }
        }
        let hk = spacing[0] * kappa;
        let kappa_h = kappa * 2.0 * (1.0 - math::cos(hk)) / (hk * hk);
        let area: f64 = (0..g.len())
            .filter(|&k| !matches!(g.coords(k).0, 0 | 8))
            .map(|k| dual_area(g, spacing, k))
            .sum();
        let expected = area * kappa_h * kappa_h;
        assert!((sum / expected - 1.0).abs() < 1e-9, "{sum} {expected}");
        // 7 of the 8 columns of cells: the edge columns' half cells are the O(h) strip.
        assert!((area / (8.0 * 1.5 * 11.0 * 1.6) - 7.0 / 8.0).abs() < 1e-12);
    }
}
