//! The DOG page clamped at the binding sags like the cantilever elastica (issue 21).
//!
//! **Clamp.** A clamp is a mirror: a page clamped horizontally at its bound column sags as
//! either half of a page twice as wide whose middle column is held (all coordinates
//! eliminated). By symmetry the middle column's tangent stays horizontal, and its bending
//! terms are the inner stars' (a ghost-node clamp), so the clamp needs no term of its own:
//! the page is the book's DOG constraints ([`folio_book::terms`]), the area-weighted page
//! bending and node masses of [`folio_book::quadrature`] (the book's own terms),
//! the soft isometry with the book's weight, and gravity.
//!
//! **Reference.** [`folio_tests::elastica::cantilever`] at $\alpha = \rho g L^3 / D$, with
//! $L$ the page width, $\rho$ the page mass over its area and
//! $D = 2 w_{\mathrm{bend3D}}$ ([`folio_book::quadrature::bending_stiffness`]); the loads
//! are set through the gravity with the bending weight [`BENDING_WEIGHT`] (the default book page is
//! $\alpha = 0.24$ at its weight 172). The tip is the mean of the two middle rows' free ends.
//!
//! **Equilibrium.** Implicit-Euler steps of the book's solver (1/60 s, three Newton
//! iterations with the constraint Hessian, air drag [`DRAG`]) until no node moves by more
//! than 1e-8 page widths in a step (the nearly rigid page keeps creeping by 4e-9 page units
//! a step, decaying slowly, which moves its tip by about 3e-4 of itself), from a slight
//! curl (the rows rolled at equal arc length onto a radius of 100 page widths, an exact
//! DOG): from the flat page, whose stars are all flat, the DOG rows' linearization is
//! degenerate and the page crept for thousands of steps.
//! The settled page is a DOG to rounding (checked), a cylinder: each row carries mass and
//! bending stiffness in the same proportion.

use folio_book::terms::{DogBoundary, DogInner, Isometry};
use folio_book::{BookSettings, IsometryHessian, quadrature};
use folio_geometry::{QuadGrid, Star};
use folio_kernels::dog_laplacian::{DogLaplacianBoundary, DogLaplacianInner};
use folio_kernels::gravity::Gravity;
use folio_kernels::iso3d::Iso3d;
use folio_kernels::{Constraint, Real, Vec3Ops};
use folio_solvers::{ConstraintSet, Model, PotentialSet, Settings, Solver, State, TermVisitor};
use folio_tests::elastica::cantilever;

type V3 = <f64 as Real>::Vec3;

/// Air drag of the settling steps (1/s): about critical for the page's first mode at
/// $\alpha = 1$.
const DRAG: f64 = 10.0;

/// The mirrored page: `2 quads_across x quads_along` quads, middle column held.
struct ClampedPage {
    grid: QuadGrid,
    middle: usize,
    /// Page width (one half), page units.
    width: f64,
    rest: Vec<V3>,
    masses: Vec<f64>,
    dog_inner: ConstraintSet<DogInner<f64>, 5>,
    dog_boundary: ConstraintSet<DogBoundary<f64>, 4>,
    bend_inner: PotentialSet<f64, DogLaplacianInner<f64>, 5>,
    bend_boundary: PotentialSet<f64, DogLaplacianBoundary<f64>, 3>,
    iso: PotentialSet<f64, Isometry<f64>, 2>,
    gravity: PotentialSet<f64, Gravity<f64>, 1>,
}

impl ClampedPage {
    /// The page of `settings` (its grid is one half) with gravity `g`.
    fn new(settings: &BookSettings<f64>, g: f64) -> Self {
        let qa = settings.quads_across;
        let grid = QuadGrid::new(2 * qa, settings.quads_along).expect("grid");
        let spacing = settings.grid_spacing();
        let w = &settings.weights;
        let rest: Vec<V3> = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                V3::new(
                    (i as f64 - qa as f64) * spacing[0],
                    0.0,
                    j as f64 * spacing[1],
                )
            })
            .collect();
        // One half weighs one page.
        let page_mass = 2.0 * settings.page_mass;
        let masses = quadrature::node_masses(grid, page_mass);
        let mut page = Self {
            grid,
            middle: qa,
            width: settings.params.page_width,
            rest,
            masses,
            dog_inner: ConstraintSet::new(),
            dog_boundary: ConstraintSet::new(),
            bend_inner: PotentialSet::new(w.bend_page),
            bend_boundary: PotentialSet::new(w.bend_page),
            iso: PotentialSet::new(w.iso_page * settings.iso_scale()),
            gravity: PotentialSet::new(1.0),
        };
        let rest_of = |a: usize, b: usize| {
            if grid.coords(a).1 == grid.coords(b).1 {
                spacing[0]
            } else {
                spacing[1]
            }
        };
        let u32s = |n: &[usize]| -> Vec<u32> { n.iter().map(|&k| k as u32).collect() };
        for star in grid.stars() {
            match star {
                Star::Inner(s) => {
                    let n: [u32; 5] = u32s(&s).try_into().unwrap();
                    page.dog_inner.push(DogInner::default(), n);
                }
                Star::Boundary(s) => {
                    let n: [u32; 4] = u32s(&s).try_into().unwrap();
                    page.dog_boundary.push(DogBoundary::default(), n);
                }
                Star::Corner(_) => {}
            }
            match quadrature::bending(grid, spacing, star).expect("bending") {
                Some(quadrature::PageBending::Inner(lap, n)) => {
                    page.bend_inner.push(lap, u32s(&n).try_into().unwrap());
                }
                Some(quadrature::PageBending::Boundary(lap, n)) => {
                    page.bend_boundary.push(lap, u32s(&n).try_into().unwrap());
                }
                None => {}
            }
        }
        let projected = settings.isometry_hessian == IsometryHessian::Projected;
        for [a, b] in grid.edges() {
            let edge = Isometry {
                edge: Iso3d::new(rest_of(a, b)).unwrap(),
                projected,
            };
            page.iso.push(edge, [a as u32, b as u32]);
        }
        for (k, &m) in page.masses.iter().enumerate() {
            page.gravity.push(Gravity::new(g, m).unwrap(), [k as u32]);
        }
        page
    }

    /// The settled page (module docs), or `None` if it did not settle in 5000 steps.
    fn settle(&self) -> Option<Vec<V3>> {
        let h = 1.0 / 60.0;
        let settings = Settings {
            time_step: h,
            newton_iterations: 3,
            constraint_hessian: true,
            ..BookSettings::<f64>::default().solver
        };
        let mut solver = Solver::new(settings).expect("settings");
        let r = 100.0 * self.width;
        let curled = self
            .rest
            .iter()
            .map(|p| {
                let t = p.x().abs() / r;
                V3::new(p.x().signum() * r * t.sin(), -r * (1.0 - t.cos()), p.z())
            })
            .collect();
        let mut state = State::at_rest(curled);
        for _ in 0..5000 {
            let before = state.x.clone();
            state.v.iter_mut().for_each(|v| *v /= 1.0 + DRAG * h);
            let report = solver.step(self, &mut state).expect("step");
            assert!(report.status.advanced(), "{report:?}");
            let moved = before
                .iter()
                .zip(&state.x)
                .map(|(a, b)| (*a - *b).length())
                .fold(0.0, f64::max);
            if moved < 1e-8 * self.width {
                return Some(state.x);
            }
        }
        None
    }

    /// The largest DOG residual $\lvert\varphi\rvert$ at `x` (seed Sec. 3.2).
    fn dog_residual(&self, x: &[V3]) -> f64 {
        let local = |n: &[u32]| n.iter().map(|&k| x[k as usize]).collect::<Vec<_>>();
        let inner = self.dog_inner.terms().iter().flat_map(|t| {
            let p: [V3; 5] = local(&t.nodes).try_into().unwrap();
            t.kernel.value(&p)
        });
        let boundary = self.dog_boundary.terms().iter().flat_map(|t| {
            let p: [V3; 4] = local(&t.nodes).try_into().unwrap();
            t.kernel.value(&p)
        });
        inner.chain(boundary).fold(0.0, |m, v: f64| m.max(v.abs()))
    }

    /// Tip deflections (units of the page width) of the two halves' middle rows, and the
    /// largest relative edge stretch.
    fn tips(&self, x: &[V3], width: f64) -> ([f64; 2], f64) {
        let nz = self.grid.nz;
        let rows = [(nz - 1) / 2, nz / 2];
        let tip = |i: usize| {
            rows.iter()
                .map(|&j| -x[self.grid.index(i, j)].y() / width)
                .sum::<f64>()
                / rows.len() as f64
        };
        let stretch = self
            .grid
            .edges()
            .iter()
            .map(|&[a, b]| {
                let l0 = (self.rest[a] - self.rest[b]).length();
                ((x[a] - x[b]).length() / l0 - 1.0).abs()
            })
            .fold(0.0, f64::max);
        ([tip(0), tip(self.grid.nx - 1)], stretch)
    }
}

impl Model<f64> for ClampedPage {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.grid.len()
    }
    fn is_fixed(&self, node: usize, _axis: usize) -> bool {
        self.grid.coords(node).0 == self.middle
    }
    fn mass(&self, node: usize) -> f64 {
        self.masses[node]
    }
    fn visit_terms<V: TermVisitor<f64>>(&self, v: &mut V) {
        v.potentials(&self.bend_inner);
        v.potentials(&self.bend_boundary);
        v.potentials(&self.iso);
        v.potentials(&self.gravity);
        v.constraints(&self.dog_inner);
        v.constraints(&self.dog_boundary);
    }
}

/// The bending weight of the pages here: the default book's before issue 21.
const BENDING_WEIGHT: f64 = 120.0;

/// One settled page at `alpha` on the default grid times `scale`.
#[derive(Debug)]
struct Sag {
    /// Tip deflection, page widths (mean of the two halves).
    tip: f64,
    /// The elastica's.
    reference: f64,
    /// Largest relative edge stretch.
    stretch: f64,
    /// Largest DOG residual.
    dog: f64,
}

impl Sag {
    fn error(&self) -> f64 {
        self.tip / self.reference - 1.0
    }
}

fn sag(alpha: f64, scale: usize) -> Sag {
    let mut settings = BookSettings::<f64>::default();
    // The loads scale with the bending weight at a given alpha, the soft isometry's weight
    // does not: with the default book's 172 the alpha = 10 page at 16x22 (gravity 1.43x
    // this one's) settled with its halves 1.5 % apart, a twist the mirror should not have.
    settings.weights.bend_page = BENDING_WEIGHT;
    settings.quads_across *= scale;
    settings.quads_along *= scale;
    let p = settings.params;
    let (width, height) = (p.page_width, p.page_height());
    let rho = settings.page_mass / (width * height);
    let d = quadrature::bending_stiffness(settings.weights.bend_page);
    let g = alpha * d / (rho * width.powi(3));
    settled(&settings, g, alpha, scale)
}

/// The page of `settings` under gravity `g` settled and compared with the elastica at
/// `alpha` (`scale`: the grid's multiple of the default, for the printout).
fn settled(settings: &BookSettings<f64>, g: f64, alpha: f64, scale: usize) -> Sag {
    let width = settings.params.page_width;
    let page = ClampedPage::new(settings, g);
    let x = page.settle().expect("the page settles");
    let ([left, right], stretch) = page.tips(&x, width);
    // The halves agree to 3e-6 up to alpha = 10; the hanging page's to 0.3 % (16x22).
    assert!((left - right).abs() < 1e-2 * right, "{left} {right}");
    let sag = Sag {
        tip: 0.5 * (left + right),
        reference: cantilever(alpha, 2000).tip_deflection,
        stretch,
        dog: page.dog_residual(&x),
    };
    eprintln!(
        "{}x{} alpha {alpha:>5}: tip {:.5} elastica {:.5} error {:+.2} % stretch {:.1e} \
         DOG residual {:.1e}",
        8 * scale,
        11 * scale,
        sag.tip,
        sag.reference,
        100.0 * sag.error(),
        sag.stretch,
        sag.dog
    );
    sag
}

/// Within 3 % of the elastica at the default grid and 1 % at twice its resolution, from a
/// nearly rigid page (tip 1.2 % of the width below the clamp) to one that hangs 70 %.
#[test]
fn the_clamped_page_sags_like_the_elastica() {
    for scale in [1, 2] {
        for alpha in [0.1, 1.0, 10.0] {
            let s = sag(alpha, scale);
            let limit = if scale == 1 { 0.03 } else { 0.01 };
            assert!(
                s.error().abs() < limit,
                "alpha {alpha}, grid x{scale}: {s:?}"
            );
            assert!(s.dog < 1e-8, "alpha {alpha}, grid x{scale}: {s:?}");
        }
    }
}

/// A real page: the default paper (80 g/m² on an A5 page, `folio_book::Paper`, sag number
/// 6.9) given to the book by `Paper::apply` (its bending weight, at the book's page mass and
/// gravity, and the projected isometry Hessian it asks for) sags as the elastica at the
/// paper's sag number, computed from the paper's figures in metres and kilograms, within
/// 3 % at the default grid.
#[test]
fn the_default_paper_sags_like_its_elastica() {
    let paper = folio_book::Paper::default();
    let mut settings = BookSettings::<f64>::default();
    paper.apply(&mut settings).unwrap();
    assert_eq!(settings.isometry_hessian, IsometryHessian::Projected);
    let alpha = paper.areal_density * 9.81 * paper.width.powi(3) / paper.bending_stiffness;
    // The same sag number with bending and load both scaled up to the bending weight of the
    // clamped pages above: the shape at rest is the same, and the settling loop (it stops
    // once a step moves no node by 1e-8 page widths) reaches it within its 5,000 steps,
    // which the softer page's slowest mode, 20 times weaker, does not (measured: moving
    // 6e-7 widths a step after 5,000).
    let scale = BENDING_WEIGHT / settings.weights.bend_page;
    settings.weights.bend_page = BENDING_WEIGHT;
    let s = settled(&settings, scale * settings.gravity, alpha, 1);
    assert!(s.error().abs() < 0.03, "{paper}: {s:?}");
}

/// A hanging page ($\alpha = 100$, tip 94 % of the width below the clamp) misses the
/// issue's 3 % and 1 %: its bending lies in a layer at the clamp of width about
/// $L/\sqrt\alpha$, 0.1 page widths, under one cell of the default grid (0.125) and under
/// two at twice its resolution, and the coarse page hangs too straight (measured: +6.7 % at
/// 8x11, +1.3 % at 16x22). The error is the resolution's: it falls by over 3x per halving.
#[test]
fn a_hanging_page_converges_to_the_elastica() {
    let [coarse, fine] = [1, 2].map(|scale| sag(100.0, scale));
    assert!(
        fine.error().abs() < coarse.error().abs() / 3.0,
        "{coarse:?} {fine:?}"
    );
    assert!(fine.error().abs() < 0.02, "{fine:?}");
}
