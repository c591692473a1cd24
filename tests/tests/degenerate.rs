//! Degenerate and non-finite input (every term, both precisions): zero-length edges,
//! coincident points, collinear stars, edges at the length floor, coordinates at
//! `Real::COORD_MAX` never panic and give finite output; a NaN or infinite coordinate gives a
//! non-finite value (documented in `folio-kernels`: NaN propagates, never a finite-looking
//! result).

use folio_kernels::Real;
use folio_kernels::real::Vec3Ops;
use folio_kernels::term::NodeVecs;
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
