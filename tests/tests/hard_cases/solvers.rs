//! Hard cases of the $LDL^\top$ factor, the refined solve and the time step: zero and tiny
//! pivots, redundant and contradictory constraints, a condition number of $10^{12}$, a
//! structurally singular block, stiffness ratios of $10^9$, time steps from $10^{-6}$ s to
//! 1 s. Matrices are written densely and handed to [`Kkt`] through
//! [`folio_tests::dense_kkt`].

use folio_kernels::Real;
use folio_solvers::ldlt::FactorOutcome;
use folio_solvers::{
    Kkt, Model, Ordering, Settings, Solver, SolverError, State, StepStatus, TermVisitor,
};
use folio_tests::dense_kkt::{dense_kkt, dense_residual};
use folio_tests::models::Chain;

/// Every ordering of the analysis.
const ORDERINGS: [Ordering; 4] = [
    Ordering::Natural,
    Ordering::Amd,
    Ordering::AmdDelayedDuals,
    Ordering::AmdQuasiDefinite,
];

/// Factorizes the dense `k` (first `dofs` unknowns primal) with the default thresholds and
/// solves $K z = b$ with refinement: the outcome, $z$, the solver's relative residual and
/// the true one (f64, dense).
fn solve<T: Real>(
    dofs: usize,
    k: &[f64],
    b: &[f64],
    ordering: Ordering,
) -> (FactorOutcome, Vec<f64>, f64, f64) {
    let mut kkt: Kkt<T> = dense_kkt(dofs, k, ordering).expect("a KKT structure");
    let s = Settings::<T>::default();
    let outcome = kkt.factorize(s.pivot_epsilon, s.regularization);
    let rhs: Vec<T> = b.iter().map(|&v| T::from_f64(v)).collect();
    let mut z = vec![T::ZERO; b.len()];
    let r = kkt.solve_refined(&mut z, &rhs, s.refinement_steps, s.refinement_tolerance);
    let residual = dense_residual(k, &z, b);
    let z = z.iter().map(|v| v.to_f64()).collect();
    (outcome, z, r.relative_residual.to_f64(), residual)
}

/// The regularized pivots of an outcome (panics on a non-finite one).
fn regularized(outcome: FactorOutcome) -> usize {
    match outcome {
        FactorOutcome::Factored { regularized, .. } => regularized,
        other => panic!("a finite matrix factorized to {other:?}"),
    }
}

/// Issue 20's probe: a constraint row with no Jacobian entry but a stored diagonal of -1
/// (a compliant constraint, structurally zero in the analysis). The factor used to replace
/// that pivot by $-\delta$ without counting it, so $K = \mathrm{diag}(1.0625, -1)$ came out
/// "clean" with a refined relative residual of $10^8$. Asserts: no regularized pivot, the
/// exact solution $z = (b_0 / 1.0625, -b_1)$ and a residual at rounding level, in every
/// ordering and both precisions.
#[test]
fn compliant_constraint_row_keeps_its_stored_diagonal() {
    let k = [1.0625, 0.0, 0.0, -1.0];
    let b = [2.125, 3.0];
    for ordering in ORDERINGS {
        let (outcome, z, _, residual) = solve::<f64>(1, &k, &b, ordering);
        assert_eq!(regularized(outcome), 0, "{ordering:?}");
        assert!(residual <= 1e-15, "{ordering:?}: residual {residual:e}");
        assert!(
            (z[0] - 2.0).abs() <= 1e-15 && (z[1] + 3.0).abs() <= 1e-15,
            "{z:?}"
        );
        let (outcome, _, _, residual) = solve::<f32>(1, &k, &b, ordering);
        assert_eq!(regularized(outcome), 0, "{ordering:?}");
        assert!(residual <= 1e-6, "f32 {ordering:?}: residual {residual:e}");
    }
}

/// A constraint row with no entry at all (no Jacobian, a zero diagonal): $K$ is singular
/// in any order. The factor used to take it as an ordering artefact (a static $-\delta$,
/// not counted) and report a clean factor. Asserts: it is counted, in every ordering, and
/// the solution stays finite.
#[test]
fn empty_constraint_row_is_counted_as_singular() {
    let k = [2.0, 0.0, 0.0, 0.0];
    for ordering in ORDERINGS {
        let (outcome, z, _, _) = solve::<f64>(1, &k, &[1.0, 0.0], ordering);
        assert!(regularized(outcome) >= 1, "{ordering:?}: {outcome:?}");
        assert!(z.iter().all(|v| v.is_finite()), "{z:?}");
        assert_eq!(z[0], 0.5, "the primal part is untouched");
    }
}

/// A zero primal pivot ($H = 0$): replaced by $+\delta$ and counted as a primal
/// regularization (what the inertia correction reacts to). Asserts the count and a finite
/// solution.
#[test]
fn zero_primal_pivot_is_regularized_and_counted() {
    for ordering in ORDERINGS {
        let (outcome, z, _, _) = solve::<f64>(1, &[0.0], &[1.0], ordering);
        assert_eq!(
            outcome,
            FactorOutcome::Factored {
                regularized: 1,
                regularized_primal: 1
            },
            "{ordering:?}"
        );
        assert!(z[0].is_finite(), "{z:?}");
    }
}

/// Tiny pivots on each side of the threshold ($10^3 \varepsilon$ of the largest primal
/// diagonal): $10^{-10}$ is kept and solves exactly (residual $\le 10^{-15}$); $10^{-14}$
/// is replaced and counted.
#[test]
fn tiny_pivots_are_kept_above_the_threshold_and_counted_below() {
    let b = [1.0, 1e-10];
    let (outcome, z, _, residual) = solve::<f64>(2, &[1.0, 0.0, 0.0, 1e-10], &b, Ordering::Amd);
    assert_eq!(regularized(outcome), 0);
    assert!(
        residual <= 1e-15 && (z[1] - 1.0).abs() <= 1e-12,
        "{z:?} {residual:e}"
    );
    let (outcome, _, _, _) = solve::<f64>(2, &[1.0, 0.0, 0.0, 1e-14], &b, Ordering::Amd);
    assert_eq!(regularized(outcome), 1);
}

/// The orderings that eliminate the constraint rows after the unknowns they couple to, so
/// that a singular constraint block shows as pivots (an order that eliminates a row first
/// gives it a static $-\delta$ instead, and leaves the singularity to the refinement).
const DUALS_LAST: [Ordering; 2] = [Ordering::Natural, Ordering::AmdDelayedDuals];

/// $H = \mathrm{diag}(2, 3)$ with two constraint rows, both $x_0 + x_1$, zero compliance.
#[rustfmt::skip]
const TWIN_ROWS: [f64; 16] = [
    2.0, 0.0, 1.0, 1.0,
    0.0, 3.0, 1.0, 1.0,
    1.0, 1.0, 0.0, 0.0,
    1.0, 1.0, 0.0, 0.0,
];

/// Two copies of one constraint row (redundant constraints, zero compliance): $K$ is
/// singular. Asserts: the orderings that eliminate the rows last count a regularized
/// pivot; in every ordering, with a consistent right-hand side, the refined solution is
/// finite and satisfies both rows to $10^{-8}$ (residual $\le 10^{-8}$).
#[test]
fn redundant_constraints_are_counted_and_still_solved() {
    let k = TWIN_ROWS;
    let b = [1.0, 2.0, 0.5, 0.5];
    for ordering in ORDERINGS {
        let (outcome, z, _, residual) = solve::<f64>(2, &k, &b, ordering);
        if DUALS_LAST.contains(&ordering) {
            assert!(regularized(outcome) >= 1, "{ordering:?}: {outcome:?}");
        }
        assert!(z.iter().all(|v| v.is_finite()), "{z:?}");
        assert!((z[0] + z[1] - 0.5).abs() <= 1e-8, "{ordering:?}: {z:?}");
        assert!(residual <= 1e-8, "{ordering:?}: residual {residual:e}");
    }
}

/// Two copies of one constraint row asking for different values (contradictory
/// constraints): no solution. Asserts: the orderings that eliminate the rows last count
/// the singularity; in every ordering the solution is finite and the refinement does not
/// claim its target: it reports the residual it left (above $10^{-3}$), within a factor 10
/// of the true one.
#[test]
fn contradictory_constraints_report_the_residual_they_leave() {
    let k = TWIN_ROWS;
    let b = [1.0, 2.0, 0.5, 1.5];
    for ordering in ORDERINGS {
        let (outcome, z, claimed, residual) = solve::<f64>(2, &k, &b, ordering);
        if DUALS_LAST.contains(&ordering) {
            assert!(regularized(outcome) >= 1, "{ordering:?}: {outcome:?}");
        }
        assert!(z.iter().all(|v| v.is_finite()), "{z:?}");
        assert!(claimed > 1e-3, "{ordering:?}: claimed {claimed:e}");
        assert!(
            claimed <= 10.0 * residual && residual <= 10.0 * claimed,
            "{ordering:?}: {claimed:e} vs {residual:e}"
        );
    }
}

/// $H = \mathrm{diag}(1, 10^{-12})$ with a constraint on both unknowns: a condition number
/// near $10^{12}$, every pivot above the threshold. Asserts: a clean factor and a refined
/// relative residual of at most $10^{-12}$ in every ordering.
#[test]
fn condition_number_1e12_solves_to_the_refinement_target() {
    #[rustfmt::skip]
    let k = [
        1.0, 0.0, 1.0,
        0.0, 1e-12, 1e-6,
        1.0, 1e-6, -1e-12,
    ];
    let b = [1.0, 1e-12, 1.0];
    for ordering in ORDERINGS {
        let (outcome, z, _, residual) = solve::<f64>(2, &k, &b, ordering);
        assert_eq!(regularized(outcome), 0, "{ordering:?}");
        assert!(z.iter().all(|v| v.is_finite()), "{z:?}");
        assert!(residual <= 1e-12, "{ordering:?}: residual {residual:e}");
    }
}

/// A structurally singular constraint block: three constraint rows on one unknown
/// (a $3 \times 1$ Jacobian has rank 1). Asserts: the orderings that eliminate the rows
/// last count at least two regularized pivots; every ordering gives a finite solution.
#[test]
fn structurally_singular_block_counts_its_rank_deficiency() {
    #[rustfmt::skip]
    let k = [
        4.0, 1.0, 2.0, 3.0,
        1.0, 0.0, 0.0, 0.0,
        2.0, 0.0, 0.0, 0.0,
        3.0, 0.0, 0.0, 0.0,
    ];
    for ordering in ORDERINGS {
        let (outcome, z, _, _) = solve::<f64>(1, &k, &[1.0, 1.0, 2.0, 3.0], ordering);
        if DUALS_LAST.contains(&ordering) {
            assert!(regularized(outcome) >= 2, "{ordering:?}: {outcome:?}");
        }
        assert!(z.iter().all(|v| v.is_finite()), "{z:?}");
    }
}

/// Springs of stiffness 1 and $10^9$ in one chain of three unknowns with one constraint
/// (a stiffness ratio of $10^9$). A relative residual cannot go below the rounding of
/// $Kz$, about $\varepsilon \lVert K\rVert \lVert z\rVert$, here $10^{-7}$; so asserts a
/// clean factor and a normwise backward error $\lVert Kz - b\rVert / (\lVert K\rVert
/// \lVert z\rVert + \lVert b\rVert)$ of at most $10^3 \varepsilon$ in f64, in every ordering; in f32
/// (beyond its precision) a finite solution, and a clean factor only with a backward error
/// of at most $10^{-6}$.
#[test]
fn stiffness_ratio_1e9_factorizes_clean() {
    let (soft, stiff) = (1.0, 1e9);
    #[rustfmt::skip]
    let k = [
        soft + 1.0, -soft, 0.0, 1.0,
        -soft, soft + stiff, -stiff, 0.0,
        0.0, -stiff, stiff + 1.0, 1.0,
        1.0, 0.0, 1.0, 0.0,
    ];
    let b = [1.0, 0.0, -1.0, 0.0];
    let k_norm = 2.0 * stiff + 2.0;
    let backward = |z: &[f64], residual: f64| {
        residual
            / (k_norm
                * z.iter()
                    .fold(0.0, |m: f64, v| folio_tests::worst(m, v.abs()))
                + 1.0)
    };
    for ordering in ORDERINGS {
        let (outcome, z, _, residual) = solve::<f64>(3, &k, &b, ordering);
        assert_eq!(regularized(outcome), 0, "{ordering:?}");
        let eta = backward(&z, residual);
        assert!(
            eta <= 1e3 * f64::EPSILON,
            "{ordering:?}: backward error {eta:e}"
        );
        // f32 resolves a ratio of 1e7 at most: eliminating the stiff pair can cancel a
        // pivot to nothing, which must then be counted, never passed off as clean.
        let (outcome, z, _, residual) = solve::<f32>(3, &k, &b, ordering);
        assert!(z.iter().all(|v| v.is_finite()), "f32 {ordering:?}: {z:?}");
        let eta = backward(&z, residual);
        assert!(
            regularized(outcome) > 0 || eta <= 1e-6,
            "f32 {ordering:?}: clean, backward error {eta:e}"
        );
    }
}

/// A NaN in the matrix: the factor names the non-finite pivot (a typed outcome, no panic,
/// no NaN written as a pivot).
#[test]
fn nan_entry_is_a_non_finite_outcome() {
    let k = [1.0, f64::NAN, f64::NAN, 1.0];
    for ordering in [Ordering::Natural, Ordering::Amd] {
        let mut kkt: Kkt<f64> = dense_kkt(2, &k, ordering).expect("a structure");
        let s = Settings::<f64>::default();
        let outcome = kkt.factorize(s.pivot_epsilon, s.regularization);
        assert!(
            matches!(outcome, FactorOutcome::NonFinite { .. }),
            "{ordering:?}: {outcome:?}"
        );
    }
}

/// A factor handed the analysis of another matrix of the same order: refused with
/// [`SolverError::SymbolicMismatch`], the right-hand side untouched.
#[test]
fn foreign_analysis_is_refused() {
    let a: Kkt<f64> = dense_kkt(2, &[1.0, 0.0, 0.0, 1.0], Ordering::Natural).expect("a");
    let b: Kkt<f64> = dense_kkt(1, &[1.0, 1.0, 1.0, 0.0], Ordering::Natural).expect("b");
    let mut x = [1.0, 2.0];
    let refused = a.factor().solve_permuted(b.symbolic(), &mut x);
    assert!(
        matches!(refused, Err(SolverError::SymbolicMismatch { .. })),
        "{refused:?}"
    );
    assert_eq!(x, [1.0, 2.0]);
}

/// The hanging chain (10 links, pinned ends) stepped from a kicked "V" with time steps
/// from $10^{-6}$ to 1 s, Newton up to 20 iterations. Asserts for each: three steps
/// advance, the state is finite, and the report tells the truth: every link's
/// $\lvert \ell^2 - \ell_0^2\rvert$ is within the last report's constraint residual (plus
/// rounding); up to $10^{-2}$ s the step converges and the links hold to $10^{-4}$.
#[test]
fn time_steps_from_1e_minus_6_to_1_keep_the_chain() {
    let (links, length, mass) = (10, 0.3, 0.1);
    let chain = Chain::<f64>::new(links, length, mass);
    for time_step in [1e-6, 1e-4, 1e-2, 1e-1, 1.0] {
        let settings = Settings {
            time_step,
            newton_iterations: 20,
            ..Settings::default()
        };
        let mut solver = Solver::new(settings).expect("valid settings");
        let mut state = v_shape(links, length);
        for (k, v) in state.v.iter_mut().enumerate() {
            *v = glam::DVec3::new(0.0, if k % 2 == 0 { 1.0 } else { -1.0 }, 0.2);
        }
        let mut last = None;
        for _ in 0..3 {
            let report = solver.step(&chain, &mut state).expect("a valid model");
            assert!(report.status.advanced(), "dt {time_step}: {report:?}");
            last = Some(report);
        }
        let report = last.expect("three steps");
        assert!(
            state.x.iter().chain(&state.v).all(|p| p.is_finite()),
            "dt {time_step}"
        );
        let reported = report.constraint_residual.expect("a constrained model");
        for w in state.x.windows(2) {
            let l2 = (w[1] - w[0]).length_squared();
            let error = (l2 - length * length).abs();
            assert!(
                error <= reported + 1e-12,
                "dt {time_step}: |l^2 - l0^2| {error:e} > {reported:e}"
            );
            if time_step <= 1e-2 {
                assert_eq!(report.status, StepStatus::Converged, "dt {time_step}");
                let l = l2.sqrt();
                assert!((l / length - 1.0).abs() <= 1e-4, "dt {time_step}: link {l}");
            }
        }
    }
}

/// The chain with link masses of $10^{-4}$ and $10^5$ alternating (a mass ratio, hence a
/// primal-block stiffness ratio $M/h^2$, of $10^9$). Asserts: three steps advance, the
/// state is finite, and the links keep their lengths to $10^{-6}$.
#[test]
fn mass_ratio_1e9_steps_keep_the_chain() {
    let (links, length) = (6, 0.3);
    let chain = HeavyLight(Chain::<f64>::new(links, length, 1.0));
    let settings = Settings {
        newton_iterations: 20,
        ..Settings::default()
    };
    let mut solver = Solver::new(settings).expect("valid settings");
    let mut state = v_shape(links, length);
    for _ in 0..3 {
        let report = solver.step(&chain, &mut state).expect("a valid model");
        assert!(report.status.advanced(), "{report:?}");
    }
    assert!(state.x.iter().chain(&state.v).all(|p| p.is_finite()));
    for w in state.x.windows(2) {
        let l = (w[1] - w[0]).length();
        assert!((l / length - 1.0).abs() <= 1e-6, "link {l}");
    }
}

/// A chain whose node masses alternate between $10^{-4}$ and $10^5$.
struct HeavyLight(Chain<f64>);

impl Model<f64> for HeavyLight {
    fn topology_version(&self) -> u64 {
        self.0.topology_version()
    }
    fn node_count(&self) -> usize {
        self.0.node_count()
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        self.0.is_fixed(node, axis)
    }
    fn mass(&self, node: usize) -> f64 {
        if node % 2 == 0 { 1e-4 } else { 1e5 }
    }
    fn visit_terms<V: TermVisitor<f64>>(&self, visitor: &mut V) {
        self.0.visit_terms(visitor);
    }
}

/// The chain of `links` links of `length` hung as a "V" from $(0, 0)$ to
/// $(\text{links} \cdot \text{length}/2, 0)$, at rest, every link exactly `length`.
fn v_shape(links: usize, length: f64) -> State<f64> {
    let cos: f64 = 0.5;
    let sin = (1.0 - cos * cos).sqrt();
    let x = (0..=links)
        .map(|k| {
            let down = k.min(links - k) as f64;
            glam::DVec3::new(k as f64 * length * cos, -down * length * sin, 0.0)
        })
        .collect();
    State::at_rest(x)
}
