//! Degenerate and non-finite input (every term, both precisions): zero-length edges,
//! coincident points, collinear stars, edges at the length floor, coordinates at
//! `Real::COORD_MAX` never panic and give finite output; a NaN or infinite coordinate gives a
//! non-finite value (documented in `folio-kernels`: NaN propagates, never a finite-looking
//! result).

use folio_kernels::hinge::Hinge;
use folio_kernels::membrane::Membrane;
use folio_kernels::real::Vec3Ops;
use folio_kernels::term::NodeVecs;
use folio_kernels::{Potential, Real};
use folio_tests::terms::{Terms, evaluate_all};

const PARAMS: [f64; 12] = [1.0, 0.8, 1.2, 0.9, 1.1, 0.7, 1.3, 1.0, 0.6, 0.9, 1.0, 0.5];

fn v<T: Real>(x: f64, y: f64, z: f64) -> T::Vec3 {
    T::Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

fn scenarios<T: Real>() -> Vec<(&'static str, NodeVecs<T, 5>)> {
    let o = v::<T>(0.3, -0.2, 0.1);
    let star = [
        o,
        o + v::<T>(1.0, 0.0, 0.0),
        o + v::<T>(0.0, 1.0, 0.0),
        o + v::<T>(-1.0, 0.0, 0.0),
        o + v::<T>(0.0, -1.0, 0.0),
    ];
    let floor = T::LENGTH_FLOOR;
    let big = T::COORD_MAX;
    let mut zero_edge = star;
    zero_edge[1] = o;
    let mut at_floor = star;
    at_floor[1] = o + T::Vec3::AXES[0] * floor;
    let mut below_floor = star;
    below_floor[1] = o + T::Vec3::AXES[0] * (floor * T::HALF);
    let collinear = [0.0, 1.0, 2.0, -1.0, -2.0].map(|s| o + v::<T>(s, 2.0 * s, -s));
    let huge = [
        star[0] * big,
        star[1] * big,
        star[2] * big,
        star[3] * big,
        star[4] * big,
    ];
    let mut folded = star;
    folded[2] = star[1];
    vec![
        ("regular star", star),
        ("all points coincident", [o; 5]),
        ("zero-length edge", zero_edge),
        ("edge at the length floor", at_floor),
        ("edge below the length floor", below_floor),
        ("collinear star", collinear),
        ("two neighbours coincide", folded),
        ("coordinates at COORD_MAX", huge),
    ]
}

fn finite_everywhere<T: Real>() {
    let terms = Terms::<T>::new(&PARAMS);
    let lambda = [T::ONE, -T::TWO, T::HALF];
    for (case, x) in scenarios::<T>() {
        for (name, outputs) in evaluate_all(&terms, &x, &lambda) {
            for out in &outputs {
                assert!(
                    out.iter().all(|e| e.is_finite()),
                    "{name} on '{case}' gave {out:?}"
                );
            }
        }
    }
}

#[test]
fn degenerate_input_gives_finite_output() {
    finite_everywhere::<f64>();
    finite_everywhere::<f32>();
}

fn non_finite_propagates<T: Real>(bad: T) {
    let terms = Terms::<T>::new(&PARAMS);
    let lambda = [T::ONE, -T::TWO, T::HALF];
    let mut x = scenarios::<T>()[0].1;
    for axis in 0..3 {
        let mut c = [x[0].x(), x[0].y(), x[0].z()];
        c[axis] = bad;
        x[0] = T::Vec3::new(c[0], c[1], c[2]);
        for (name, [values, first, _]) in evaluate_all(&terms, &x, &lambda) {
            let values = if values.is_empty() { first } else { values };
            // Gravity reads only Y and the binding rows only X and Y; every other term reads
            // all coordinates of node 0.
            let reads = !((name == "gravity" && axis != 1) || (name == "binding" && axis == 2));
            if reads {
                assert!(
                    values.iter().any(|e| !e.is_finite()),
                    "{name}: {bad} in axis {axis} gave finite {values:?}"
                );
            }
        }
        x = scenarios::<T>()[0].1;
    }
}

#[test]
fn non_finite_input_gives_non_finite_values() {
    non_finite_propagates::<f64>(f64::NAN);
    non_finite_propagates::<f64>(f64::INFINITY);
    non_finite_propagates::<f32>(f32::NAN);
    non_finite_propagates::<f32>(f32::NEG_INFINITY);
}

/// Value, gradient and Hessian (and for the membrane the projected Hessian and the
/// deformation gradient) of the sheet terms, flattened.
fn sheet_outputs<T: Real>(x: &NodeVecs<T, 5>) -> Vec<(&'static str, Vec<f64>)> {
    let p = |a: f64, b: f64| [T::from_f64(a), T::from_f64(b)];
    let m = Membrane::new(
        [p(0.0, 0.0), p(1.0, 0.1), p(0.3, 0.9)],
        T::ONE,
        T::from_f64(0.3),
    )
    .unwrap();
    let h = Hinge::new([p(0.0, 0.0), p(1.0, 0.1), p(0.3, 0.9), p(0.6, -0.8)]).unwrap();
    let x3: NodeVecs<T, 3> = core::array::from_fn(|k| x[k]);
    let x4: NodeVecs<T, 4> = core::array::from_fn(|k| x[k]);
    let (f0, f1) = m.deformation_gradient(&x3);
    let membrane = [
        vec![m.value(&x3).to_f64()],
        folio_tests::flat_vecs::<T, 3>(&m.gradient(&x3)),
        folio_tests::flat_blocks::<T, 3>(&m.hessian(&x3)),
        folio_tests::flat_blocks::<T, 3>(&m.hessian_projected(&x3)),
        folio_tests::flat_vecs::<T, 2>(&[f0, f1]),
    ]
    .concat();
    let hinge = [
        vec![h.value(&x4).to_f64()],
        folio_tests::flat_vecs::<T, 4>(&h.gradient(&x4)),
        folio_tests::flat_blocks::<T, 4>(&h.hessian(&x4)),
    ]
    .concat();
    vec![("membrane", membrane), ("hinge", hinge)]
}

fn sheet_finite_everywhere<T: Real>() {
    let mut cases = scenarios::<T>();
    // An inverted (reflected) triangle and a crushed one.
    let mut inverted = cases[0].1;
    inverted[2] = v::<T>(0.3, -1.2, 0.1);
    let mut crushed = cases[0].1;
    crushed[1] = crushed[0] + v::<T>(1e-3, 0.0, 0.0);
    cases.push(("inverted triangle", inverted));
    cases.push(("crushed triangle", crushed));
    for (case, x) in cases {
        for (name, out) in sheet_outputs::<T>(&x) {
            assert!(
                out.iter().all(|e| e.is_finite()),
                "{name} on '{case}' gave {out:?}"
            );
        }
    }
}

#[test]
fn membrane_and_hinge_give_finite_output_on_degenerate_input() {
    sheet_finite_everywhere::<f64>();
    sheet_finite_everywhere::<f32>();
}

fn sheet_non_finite_propagates<T: Real>(bad: T) {
    for node in 0..4 {
        for axis in 0..3 {
            let mut x = scenarios::<T>()[0].1;
            let mut c = [x[node].x(), x[node].y(), x[node].z()];
            c[axis] = bad;
            x[node] = T::Vec3::new(c[0], c[1], c[2]);
            for (name, out) in sheet_outputs::<T>(&x) {
                // Node 3 is not part of the membrane.
                if name == "membrane" && node == 3 {
                    assert!(out[0].is_finite(), "membrane read node 3");
                } else {
                    assert!(
                        !out[0].is_finite(),
                        "{name}: {bad} at node {node} axis {axis} gave value {}",
                        out[0]
                    );
                }
            }
        }
    }
}

#[test]
fn membrane_and_hinge_propagate_non_finite_input() {
    sheet_non_finite_propagates::<f64>(f64::NAN);
    sheet_non_finite_propagates::<f64>(f64::INFINITY);
    sheet_non_finite_propagates::<f32>(f32::NAN);
    sheet_non_finite_propagates::<f32>(f32::NEG_INFINITY);
}
