//! The implicit-Euler SQP step: Newton's quadratic convergence, the hanging chain's static
//! equilibrium, bad input, redundant constraints and settings validation.

use folio_kernels::{Real, Vec3Ops};
use folio_solvers::{Pins, Settings, Solver, SolverError, State, StepStatus};
use folio_tests::models::{Chain, DogSheet, hanging_chain};

const LINKS: usize = 10;
const LENGTH: f64 = 0.3;
const MASS: f64 = 0.1;

/// The chain hung as a "V" between `(0, 0)` and `(span, 0)`: exact link lengths.
fn v_shape<T: Real>(span: f64) -> State<T> {
    let cos = span / (LINKS as f64 * LENGTH);
    let sin = (1.0 - cos * cos).sqrt();
    let x = (0..=LINKS)
        .map(|k| {
            let down = k.min(LINKS - k) as f64;
            T::Vec3::new(
                T::from_f64(k as f64 * LENGTH * cos),
                T::from_f64(-down * LENGTH * sin),
                T::ZERO,
            )
        })
        .collect();
    State::at_rest(x)
}

/// Residual after `iterations` Newton iterations of one step from `start`.
fn residual_after(iterations: u32, start: &State<f64>, chain: &Chain<f64>) -> f64 {
    let settings = Settings {
        time_step: 0.1,
        newton_iterations: iterations,
        constraint_hessian: true,
        line_search: false,
        tolerance: 0.0,
        ..Settings::default()
    };
    let mut solver = Solver::new(settings).unwrap();
    let mut state = start.clone();
    let report = solver.step(chain, &mut state).unwrap();
    assert_eq!(report.iterations, iterations);
    report.residual.unwrap()
}

#[test]
fn newton_converges_quadratically_with_the_constraint_hessian() {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut start = v_shape::<f64>(2.0);
    // A kick so that the first iterate is far from the solution.
    for (k, v) in start.v.iter_mut().enumerate() {
        *v = glam::DVec3::new(0.0, if k % 2 == 0 { 3.0 } else { -2.0 }, 0.5);
    }
    let r: Vec<f64> = (1..=9).map(|k| residual_after(k, &start, &chain)).collect();
    println!("residual per iteration: {r:?}");
    let mut quadratic_steps = 0;
    for w in r.windows(2) {
        if w[0] < 1e-2 && w[0] > 1e-9 {
            // Quadratic down to the rounding floor: r_{k+1} <= C r_k^2 + floor.
            let floor = 1e-14;
            assert!(
                w[1] <= 10.0 * w[0] * w[0] + floor,
                "not quadratic: {:e} -> {:e}",
                w[0],
                w[1]
            );
            quadratic_steps += 1;
        }
    }
    assert!(
        quadratic_steps >= 2,
        "too few iterations in the quadratic range: {r:?}"
    );
    assert!(r[8] <= 1e-12, "final residual {:e}", r[8]);
}

#[test]
fn hanging_chain_settles_to_the_static_equilibrium() {
    let span = 2.0;
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut state = v_shape::<f64>(span);
    let settings = Settings {
        time_step: 0.2,
        newton_iterations: 3,
        tolerance: 1e-12,
        ..Settings::default()
    };
    let mut solver = Solver::new(settings).unwrap();
    for _ in 0..400 {
        let report = solver.step(&chain, &mut state).unwrap();
        assert!(report.status.advanced(), "{report:?}");
    }
    let expected = hanging_chain(LINKS, LENGTH, MASS, span);
    let mut worst: f64 = 0.0;
    for (x, e) in state.x.iter().zip(&expected) {
        let errors = [(x.x - e[0]).abs(), (x.y - e[1]).abs(), x.z.abs()];
        worst = errors.into_iter().fold(worst, folio_tests::worst);
    }
    println!("max distance to the independent equilibrium: {worst:.2e}");
    assert!(worst <= 1e-8, "distance {worst:e}");
}

#[test]
fn non_finite_state_or_input_leaves_the_state_untouched() {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut solver = Solver::new(Settings::default()).unwrap();
    let mut state = v_shape::<f64>(2.0);
    state.v[3].y = f64::NAN;
    let before = format!("{state:?}");
    let report = solver.step(&chain, &mut state).unwrap();
    assert_eq!(report.status, StepStatus::NonFiniteInput);
    assert_eq!(format!("{state:?}"), before);

    let mut sheet = DogSheet::<f32>::new(11, 8, 12.0 / 11.0);
    let mut state = sheet.rolled(6.0);
    let mut solver = Solver::new(Settings::default()).unwrap();
    assert!(solver.step(&sheet, &mut state).unwrap().status.advanced());
    sheet.set_target(glam::Vec3A::new(f32::NAN, 0.0, 0.0));
    let before = format!("{state:?}");
    let report = solver.step(&sheet, &mut state).unwrap();
    assert_eq!(report.status, StepStatus::NonFiniteInput);
    assert_eq!(format!("{state:?}"), before);
}

#[test]
fn redundant_constraints_are_regularized_and_reported() {
    let mut chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    chain.duplicate_links();
    let mut solver = Solver::new(Settings::default()).unwrap();
    let mut state = v_shape::<f64>(2.0);
    let report = solver.step(&chain, &mut state).unwrap();
    println!("{report:?}");
    assert!(report.status.advanced(), "{report:?}");
    assert!(report.regularized_pivots >= LINKS, "{report:?}");
    assert!(state.x.iter().all(|p| p.is_finite()));
    // The healthy chain reports none.
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut state = v_shape::<f64>(2.0);
    let report = Solver::new(Settings::default())
        .unwrap()
        .step(&chain, &mut state)
        .unwrap();
    assert_eq!(report.regularized_pivots, 0, "{report:?}");
}

#[test]
fn topology_change_reruns_the_analysis_and_nothing_else_does() {
    let mut chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut solver = Solver::new(Settings::default()).unwrap();
    let mut state = v_shape::<f64>(2.0);
    assert!(solver.step(&chain, &mut state).unwrap().analysed);
    assert!(!solver.step(&chain, &mut state).unwrap().analysed);
    chain.duplicate_links();
    assert!(solver.step(&chain, &mut state).unwrap().analysed);
    assert!(!solver.step(&chain, &mut state).unwrap().analysed);
}

#[test]
fn bad_settings_get_typed_errors() {
    let cases: [(Settings<f64>, &str); 7] = [
        (
            Settings {
                time_step: 0.0,
                ..Settings::default()
            },
            "time_step",
        ),
        (
            Settings {
                time_step: -0.01,
                ..Settings::default()
            },
            "time_step",
        ),
        (
            Settings {
                time_step: f64::NAN,
                ..Settings::default()
            },
            "time_step",
        ),
        (
            Settings {
                newton_iterations: 0,
                ..Settings::default()
            },
            "newton_iterations",
        ),
        (
            Settings {
                tolerance: f64::INFINITY,
                ..Settings::default()
            },
            "tolerance",
        ),
        (
            Settings {
                krylov_restart: 0,
                ..Settings::default()
            },
            "krylov_restart",
        ),
        (
            Settings {
                krylov_restart: 51,
                ..Settings::default()
            },
            "krylov_restart",
        ),
    ];
    for (settings, name) in cases {
        match Solver::new(settings) {
            Err(SolverError::InvalidSetting(e)) => assert_eq!(e.path.to_string(), name),
            other => panic!("{name}: {other:?}"),
        }
    }
    let mut solver = Solver::<f64>::new(Settings::default()).unwrap();
    let bad = Settings {
        regularization: 0.0,
        ..Settings::default()
    };
    assert!(solver.set_settings(bad).is_err());
    assert_eq!(*solver.settings(), Settings::default());
}

#[test]
fn wrong_state_length_is_an_error() {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut state = v_shape::<f64>(2.0);
    state.x.pop();
    let err = Solver::new(Settings::default())
        .unwrap()
        .step(&chain, &mut state);
    assert!(matches!(
        err,
        Err(SolverError::StateLength {
            expected: 11,
            positions: 10,
            ..
        })
    ));
}

/// The chain at rest on its catenary.
fn catenary_state() -> State<f64> {
    let catenary = hanging_chain(LINKS, LENGTH, MASS, 2.0);
    State::at_rest(
        catenary
            .iter()
            .map(|p| glam::DVec3::new(p[0], p[1], 0.0))
            .collect(),
    )
}

/// Largest link-length error of the chain.
fn link_error(x: &[glam::DVec3]) -> f64 {
    x.windows(2)
        .map(|w| ((w[1] - w[0]).length() - LENGTH).abs())
        .fold(0.0, folio_tests::worst)
}

#[test]
fn projection_restores_the_constraints_and_keeps_pinned_nodes() {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut solver = Solver::new(Settings::default()).unwrap();
    // The catenary (curved, so a small push of one node stays feasible).
    let mut state = catenary_state();
    let pinned: Vec<bool> = (0..=LINKS).map(|k| k == 4).collect();
    // Nothing to project with before the first step.
    let none = solver
        .project_constraints(&chain, &mut state, Pins::isotropic(&pinned, 1e4), 1e-12, 5)
        .unwrap();
    assert_eq!(none.steps, 0);
    solver.step(&chain, &mut state).unwrap();
    // A collision-like push of node 4 stretches its two links by a few percent.
    let push = glam::DVec3::new(0.01, -0.015, 0.0);
    state.x[4] += push;
    let pushed_to = state.x[4];
    let before = link_error(&state.x);
    let v_before = state.v.clone();
    let mut free = state.clone();
    solver
        .clone()
        .project_constraints(&chain, &mut free, Pins::isotropic(&pinned, 1.0), 1e-11, 8)
        .unwrap();
    let c = solver
        .project_constraints(&chain, &mut state, Pins::isotropic(&pinned, 1e4), 1e-11, 8)
        .unwrap();
    let after = link_error(&state.x);
    println!("projection: {c:?}, link error {before:.2e} -> {after:.2e}");
    assert!(before > 1e-3, "the push must stretch the chain ({before})");
    // Gauss-Newton with a fresh Jacobian: 1e-2 to 1e-11 in a handful of iterations.
    assert!(after <= 1e-11, "link error after projection {after:.3e}");
    assert!(c.steps <= 6, "{c:?}");
    // Pinned (weight 1e4), the node moves two orders of magnitude less than unpinned.
    let pinned_moved = (state.x[4] - pushed_to).length();
    let free_moved = (free.x[4] - pushed_to).length();
    println!("node 4 moved {pinned_moved:.2e} pinned, {free_moved:.2e} free");
    assert!(
        pinned_moved < 1e-2 * free_moved,
        "pinned node moved {pinned_moved:.2e}, free {free_moved:.2e}"
    );
    // The velocities see the move over the step.
    let h = Settings::<f64>::default().time_step;
    assert!((state.v[3] - v_before[3]).length() > 0.0);
    assert!(((state.v[4] - v_before[4]) * h - (state.x[4] - pushed_to)).length() < 1e-12);
    // A flag per node is required.
    assert!(matches!(
        solver.project_constraints(
            &chain,
            &mut state,
            Pins::isotropic(&pinned[1..], 1e4),
            1e-12,
            5
        ),
        Err(SolverError::StateLength { .. })
    ));
}

/// The projection of a chain whose node 4 a collision pushed by `push` after one step,
/// with node 4 held by `pins` (built from the flags and normals given).
fn pushed_chain_projection(
    push: glam::DVec3,
    normal: Option<glam::DVec3>,
    weight: f64,
) -> (glam::DVec3, glam::DVec3, f64) {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut solver = Solver::new(Settings::default()).unwrap();
    let mut state = catenary_state();
    solver.step(&chain, &mut state).unwrap();
    state.x[4] += push;
    let pushed_to = state.x[4];
    let pinned: Vec<bool> = (0..=LINKS).map(|k| k == 4).collect();
    let normals: Vec<glam::DVec3> = (0..=LINKS)
        .map(|k| {
            if k == 4 {
                normal.unwrap_or(glam::DVec3::ZERO)
            } else {
                glam::DVec3::ZERO
            }
        })
        .collect();
    let pins = Pins {
        nodes: &pinned,
        normals: if normal.is_some() { &normals } else { &[] },
        weight,
    };
    solver
        .project_constraints(&chain, &mut state, pins, 1e-11, 8)
        .unwrap();
    (pushed_to, state.x[4], link_error(&state.x))
}

/// A contact held along its normal (a pushed node on a floor): the node does not sink
/// (free, the links pull it 5.5e-3 down; held, it sinks by less than 1e-2 of that, and
/// may rise off the floor: the contact is one-sided) but slides along the floor,
/// where a node held in every direction barely moves; and the contact is one-sided: a
/// node the constraints pull off its surface (the same push with the surface above it) is
/// let go and lands where it would free.
#[test]
fn a_node_held_along_its_normal_slides_and_is_let_go_when_pulled_off() {
    let push = glam::DVec3::new(0.0, 0.015, 0.0);
    let up = glam::DVec3::Y;
    let (at, free, free_error) = pushed_chain_projection(push, None, 1.0);
    let (_, iso, _) = pushed_chain_projection(push, None, 1e3);
    let (_, held, held_error) = pushed_chain_projection(push, Some(up), 1e3);
    let (_, off, _) = pushed_chain_projection(push, Some(-up), 1e3);
    println!(
        "free {:?} iso {:?} held {:?} off {:?}",
        free - at,
        iso - at,
        held - at,
        off - at
    );
    assert!(
        free_error <= 1e-11 && held_error <= 1e-11,
        "{free_error:.2e} {held_error:.2e}"
    );
    // The links pull node 4 back down: a floor holds it.
    assert!(
        (free - at).y < -1e-3,
        "the push must be undone when free: {:?}",
        free - at
    );
    assert!(
        (held - at).y >= -1e-2 * (free - at).y.abs(),
        "{:?}",
        held - at
    );
    // It slides along the floor, far more than a node held in every direction moves.
    let slide = |p: glam::DVec3| (p - at).x.abs();
    assert!(
        slide(held) > 10.0 * slide(iso),
        "held {:.2e} iso {:.2e}",
        slide(held),
        slide(iso)
    );
    // A surface above it does not hold it down: let go, it moves as if free.
    assert!((off - free).length() <= 1e-6, "{:?} {:?}", off, free);
}

/// A step of the chain kicked out of its "V" (Newton to 1e-12, the constraint Hessian):
/// the state it ends in, and its report.
fn converged_step(predictor: bool) -> (State<f64>, folio_solvers::StepReport<f64>) {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut state = v_shape::<f64>(2.0);
    for (k, v) in state.v.iter_mut().enumerate() {
        *v = glam::DVec3::new(0.5, if k % 2 == 0 { 1.0 } else { -0.7 }, 0.3);
    }
    let settings = Settings {
        time_step: 0.05,
        newton_iterations: 20,
        constraint_hessian: true,
        tolerance: 1e-12,
        predictor,
        ..Settings::default()
    };
    let mut solver = Solver::new(settings).unwrap();
    let report = solver.step(&chain, &mut state).unwrap();
    assert_eq!(report.status, StepStatus::Converged, "{report:?}");
    (state, report)
}

#[test]
fn the_predictor_changes_where_newton_starts_not_where_it_ends() {
    let (cold, cold_report) = converged_step(false);
    let (predicted, predicted_report) = converged_step(true);
    let mut worst: f64 = 0.0;
    for (a, b) in cold.x.iter().zip(&predicted.x) {
        worst = folio_tests::worst(worst, (*a - *b).abs().max_element());
    }
    println!(
        "iterations: from x {} , from x + h v {}; states {worst:.1e} apart",
        cold_report.iterations, predicted_report.iterations
    );
    assert!(worst <= 1e-9, "the two starts ended {worst:e} apart");
}

#[test]
fn warm_multipliers_start_a_chain_at_rest_converged() {
    let chain = Chain::<f64>::new(LINKS, LENGTH, MASS);
    let mut state = v_shape::<f64>(2.0);
    let settings = Settings {
        time_step: 0.2,
        newton_iterations: 5,
        constraint_hessian: true,
        tolerance: 1e-9,
        warm_multipliers: true,
        ..Settings::default()
    };
    let mut warm = Solver::new(settings).unwrap();
    for _ in 0..400 {
        let report = warm.step(&chain, &mut state).unwrap();
        assert!(report.status.advanced(), "{report:?}");
    }
    let mut cold = warm.clone();
    cold.set_settings(Settings {
        warm_multipliers: false,
        ..settings
    })
    .unwrap();
    let (mut a, mut b) = (state.clone(), state.clone());
    let warm_report = warm.step(&chain, &mut a).unwrap();
    let cold_report = cold.step(&chain, &mut b).unwrap();
    println!(
        "at rest: warm {} iterations (residual {:?}), cold {} (residual {:?})",
        warm_report.iterations, warm_report.residual, cold_report.iterations, cold_report.residual
    );
    // The link tensions that hold the chain up are the last step's multipliers: started
    // with them, the chain at rest already meets eq. 3; started at 0, gravity is unbalanced.
    assert_eq!(warm_report.status, StepStatus::Converged);
    assert_eq!(warm_report.iterations, 0, "{warm_report:?}");
    assert!(cold_report.iterations >= 1, "{cold_report:?}");
    // A step refused for a non-finite input touches neither the state nor the
    // multipliers: the next step from rest starts warm still.
    let mut bad = a.clone();
    bad.v[2].y = f64::NAN;
    assert_eq!(
        warm.step(&chain, &mut bad).unwrap().status,
        StepStatus::NonFiniteInput
    );
    let after_refusal = warm.step(&chain, &mut a).unwrap();
    assert_eq!(after_refusal.iterations, 0, "{after_refusal:?}");
    // A new topology starts cold: the multipliers belong to the old rows.
    let mut doubled = chain.clone();
    doubled.duplicate_links();
    let first = warm.step(&doubled, &mut a).unwrap();
    assert!(first.iterations >= 1, "{first:?}");
}
