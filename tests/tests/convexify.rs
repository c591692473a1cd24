//! `Settings::convexify`: which Hessian of each potential the Newton step assembles.
//!
//! The model is a column of soft-isometry links (seed `000_…` eq. 13, `Iso3d`, weight
//! `WEIGHT`) standing on a fixed node along +Y, each node free along Y only and weighed
//! down by gravity. At its equilibrium every link is compressed by the weight of the nodes
//! above it, so the convex stand-in (which drops the compressive part $4sI$, $s < 0$)
//! differs from the exact Hessian there; started with every link squeezed below
//! $L/\sqrt 3$, the exact Hessian along the column, $12 d^2 - 4L^2$, is negative and the
//! step's matrix indefinite. A step of 10^4 s is the static problem (its inertia is 1e-9),
//! whose equilibrium is known without the solver: link $k$ carries the weight $F_k$ of the
//! nodes above it, $4 w (L^2 - d_k^2) d_k = F_k$.
//!
//! What each choice must do:
//! - `Never` (the exact Hessian) needs the inertia correction's shift from the squeezed
//!   start (measured: 19 iterations, 94 factorizations, and it settles 0.6 away from the
//!   column's equilibrium, folded; printed, not asserted);
//! - `Always` (the convex stand-in) needs no shift but converges only linearly;
//! - `WhenIndefinite` needs no shift, converges quadratically near the equilibrium, and
//!   reaches the column's equilibrium.

use folio_kernels::gravity::Gravity;
use folio_kernels::iso3d::Iso3d;
use folio_solvers::{
    Convexify, Model, PotentialSet, Settings, Solver, State, StepReport, StepStatus, TermVisitor,
};
use folio_tests::models::G;

const LINKS: usize = 12;
const LENGTH: f64 = 0.3;
const MASS: f64 = 0.1;
/// The links' weight.
const WEIGHT: f64 = 100.0;
/// The mass gravity pulls on at each node.
const LOAD: f64 = 0.025;
/// Newton's tolerance on the eq. 3 residual, $h^2 M^{-1}$ times the force (length units):
/// its rounding floor on this column is about 2e-9.
const TOLERANCE: f64 = 1e-7;
/// The start's link length as a fraction of `LENGTH`: below $1/\sqrt 3$.
const SQUEEZE: f64 = 0.5;

/// The column (module docs).
struct Column {
    links: PotentialSet<f64, Iso3d<f64>, 2>,
    gravity: PotentialSet<f64, Gravity<f64>, 1>,
}

impl Column {
    fn new() -> Self {
        let mut links = PotentialSet::new(WEIGHT);
        let mut gravity = PotentialSet::new(1.0);
        for k in 0..LINKS {
            links.push(Iso3d::new(LENGTH).unwrap(), [k as u32, k as u32 + 1]);
        }
        for k in 0..=LINKS {
            gravity.push(Gravity::new(G, LOAD).unwrap(), [k as u32]);
        }
        Self { links, gravity }
    }

    /// Every link squeezed to `SQUEEZE` of its length.
    fn squeezed() -> State<f64> {
        State::at_rest(
            (0..=LINKS)
                .map(|k| glam::DVec3::new(0.0, k as f64 * SQUEEZE * LENGTH, 0.0))
                .collect(),
        )
    }

    /// The equilibrium's link lengths, without the solver: $d_k$ in $(L/\sqrt 3, L]$ with
    /// $4 w (L^2 - d_k^2) d_k = F_k$ (that side of the cubic's maximum is the stable one),
    /// by bisection.
    fn equilibrium() -> Vec<f64> {
        (0..LINKS)
            .map(|k| {
                let load = (LINKS - k) as f64 * LOAD * G;
                let force = |d: f64| 4.0 * WEIGHT * (LENGTH * LENGTH - d * d) * d;
                let (mut lo, mut hi) = (LENGTH / 3f64.sqrt(), LENGTH);
                assert!(force(lo) > load, "the column buckles");
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if force(mid) > load {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                0.5 * (lo + hi)
            })
            .collect()
    }
}

impl Model<f64> for Column {
    fn topology_version(&self) -> u64 {
        1
    }
    fn node_count(&self) -> usize {
        LINKS + 1
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        node == 0 || axis != 1
    }
    fn mass(&self, _node: usize) -> f64 {
        MASS
    }
    fn visit_terms<V: TermVisitor<f64>>(&self, v: &mut V) {
        v.potentials(&self.links);
        v.potentials(&self.gravity);
    }
}

/// One step from the squeezed column with `convexify`, `iterations` Newton iterations and
/// tolerance `tolerance`: the state and the report.
fn step(convexify: Convexify, iterations: u32, tolerance: f64) -> (State<f64>, StepReport<f64>) {
    let settings = Settings {
        time_step: 100.0,
        newton_iterations: iterations,
        tolerance,
        convexify,
        ..Settings::default()
    };
    let mut solver = Solver::new(settings).unwrap();
    let mut state = Column::squeezed();
    let report = solver.step(&Column::new(), &mut state).unwrap();
    (state, report)
}

/// The residual after each of the first `n` iterations (tolerance 0: every one runs).
fn residuals(convexify: Convexify, n: u32) -> Vec<f64> {
    (1..=n)
        .map(|k| step(convexify, k, 0.0).1.residual.unwrap_or(f64::NAN))
        .collect()
}

#[test]
fn the_exact_hessian_of_a_squeezed_column_needs_a_shift() {
    let (_, report) = step(Convexify::Never, 1, 0.0);
    assert!(report.hessian_shift > 0.0, "{report:?}");
    let (_, report) = step(Convexify::Always, 1, 0.0);
    assert_eq!(report.hessian_shift, 0.0, "{report:?}");
}

#[test]
fn when_indefinite_needs_no_shift_and_ends_at_the_columns_equilibrium() {
    let (exact_end, exact) = step(Convexify::Never, 20, TOLERANCE);
    let (adaptive, report) = step(Convexify::WhenIndefinite, 20, TOLERANCE);
    println!("exact: {exact:?}\nwhen indefinite: {report:?}");
    // The squeezed start is a hard case: the exact Hessian's steps are shifted, and take
    // longer.
    assert!(exact.hessian_shift > 0.0, "{exact:?}");
    assert!(exact.iterations > report.iterations, "{exact:?}");
    assert_eq!(report.status, StepStatus::Converged, "{report:?}");
    assert_eq!(report.hessian_shift, 0.0);
    // The column's equilibrium (independent of the solver), every link compressed. The
    // step's inertia M/h^2 = 1e-5 on nodes that moved by up to 1.1 adds at most 1e-4 to a
    // link's load, against a link stiffness 4w(L^2 - 3d^2) of about -36: 3e-6.
    let reference = Column::equilibrium();
    let worst = |x: &[glam::DVec3]| {
        reference.iter().enumerate().fold(0.0, |w: f64, (k, d)| {
            folio_tests::worst(w, (x[k + 1].y - x[k].y - d).abs())
        })
    };
    let (adaptive_error, exact_error) = (worst(&adaptive.x), worst(&exact_end.x));
    println!(
        "from the column's equilibrium: when indefinite {adaptive_error:.1e}, exact {exact_error:.1e}"
    );
    assert!(reference.iter().all(|d| *d < LENGTH));
    assert!(adaptive_error <= 1e-5, "{adaptive_error:e}");
}

/// The observed order of convergence of the last three residuals of `r`:
/// $\log(r_{k+2}/r_{k+1}) / \log(r_{k+1}/r_k)$ (2 for Newton's, 1 for a linear rate).
fn observed_order(r: &[f64]) -> f64 {
    let [a, b, c] = r[r.len() - 3..] else {
        unreachable!("three residuals")
    };
    (c / b).ln() / (b / a).ln()
}

#[test]
fn when_indefinite_converges_quadratically_and_the_convex_hessian_linearly() {
    let adaptive = residuals(Convexify::WhenIndefinite, 20);
    let convex = residuals(Convexify::Always, 20);
    println!("when indefinite: {adaptive:?}\nalways convex: {convex:?}");
    // Up to the first residual within the tolerance (near it, rounding decides).
    let first_below = |r: &[f64]| r.iter().position(|&v| v <= TOLERANCE);
    let reached = first_below(&adaptive).expect("when indefinite reaches the tolerance");
    let adaptive_order = observed_order(&adaptive[..=reached]);
    let convex_order =
        observed_order(&convex[..first_below(&convex).unwrap_or(convex.len() - 1) + 1]);
    println!(
        "observed order: when indefinite {adaptive_order:.2}, always convex {convex_order:.2}"
    );
    assert!(adaptive_order >= 1.8, "{adaptive:?}");
    assert!(convex_order <= 1.2, "{convex:?}");
    // Linear: more iterations to the same residual, if it gets there at all.
    if let Some(k) = first_below(&convex) {
        assert!(k > reached, "convex {k}, when indefinite {reached}");
    }
}
