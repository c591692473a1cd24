//! Issue 42's R1, held and settled: a novel page's fore-edge middle held by the finger's pad
//! (7 mm, `BookSettings::pad_radius`) and turned about the binding to 45°, its pad's centre
//! at 0.9 of the page width from the hinge, then held until every node is slower than
//! 1e-9 page units a second; Newton with the constraint Hessian and the exact isometry
//! Hessian where it has the inertia of a minimum (`solver.convexify = "when-indefinite"`)
//! to a KKT residual of 1e-9 (at most 20 iterations; the DOG constraints keep 3.8e-9 on
//! 32 x 44, `docs/accuracy.md`, R1). The settled page is read at 13 x 17 material points on
//! 8 x 11, 16 x 22 and 32 x 44 and the grids compared.
//!
//! The bound (16 x 22 within 1 % of the page width RMS of the converged reference,
//! an observed order of at least 1) is not met: this study is ignored and states what it
//! measured (`docs/accuracy.md`, "R1": 0.56 % then 2.39 %, the page's root in the gutter's
//! wedge). Run it with
//! `cargo test --release -p folio-tests --test held_and_settled -- --ignored --nocapture`
//! (about 15 minutes).

use folio_book::pad::{interpolate, pad_point};
use folio_book::{Book, BookSettings, Gutter, IsometryHessian, Stock};
use folio_kernels::Real;
use folio_solvers::Convexify;
use folio_tests::pad::{EdgeGrab, grab_fore_edge_middle};

type V = <f64 as Real>::Vec3;

/// A5's width (ISO 216), m.
const A5_WIDTH: f64 = 0.148;

/// Material points across and along the page where the settled pages are compared.
const SAMPLES: [usize; 2] = [13, 17];

/// What one grid's held page came to.
struct Settled {
    /// The page at [`SAMPLES`] material points, row by row.
    points: Vec<V>,
    /// Whether every node came below 1e-9 page units a second within 3000 frames.
    settled: bool,
    /// The last step's KKT residual.
    residual: f64,
}

/// The novel book on `quads` with the top-page gutter, the pad and Newton to 1e-9, exact
/// where the step has the inertia of a minimum.
fn settings(quads: [usize; 2]) -> BookSettings<f64> {
    let mut s = BookSettings::<f64>::default();
    s.params.left_pages = s.params.total_pages / 2;
    let aspect = s.params.aspect_ratio;
    Stock::NOVEL
        .cut(A5_WIDTH, A5_WIDTH * aspect)
        .apply(&mut s)
        .expect("a built-in paper");
    s.gutter = Gutter::TopPage;
    [s.quads_across, s.quads_along] = quads;
    s.pad_radius = 7e-3 / (A5_WIDTH / 12.0);
    s.solver.constraint_hessian = true;
    s.solver.newton_iterations = 20;
    s.solver.tolerance = 1e-9;
    s.isometry_hessian = IsometryHessian::Exact;
    s.solver.convexify = Convexify::WhenIndefinite;
    s
}

/// The held page on `quads`: grabbed by the pad at the fore-edge's middle, its centre taken
/// in a second (60 frames) along a straight path in angle and distance about the hinge to
/// `degrees` and `chord` page widths, then held.
fn held(quads: [usize; 2], degrees: f64, chord: f64) -> Settled {
    let mut book = Book::new(settings(quads)).expect("the book");
    let [w, h] = book.page_size();
    let EdgeGrab { start, hinge, .. } = grab_fore_edge_middle(&mut book);
    let n = book.nodes();
    let d = start - hinge;
    let (a0, r0) = (d.y.atan2(d.x), d.truncate().length());
    let (a1, r1) = (degrees.to_radians(), chord * w);
    let lift = 60;
    let (mut settled, mut residual) = (false, f64::NAN);
    for f in 0..3000 {
        if f <= lift {
            let s = f as f64 / lift as f64;
            let (a, r) = (a0 + s * (a1 - a0), r0 + s * (r1 - r0));
            let target = V::new(hinge.x + r * a.cos(), hinge.y + r * a.sin(), start.z);
            book.drag_to(target).expect("a drag");
        }
        let report = book.step().expect("a step");
        residual = report.solver.residual.unwrap_or(f64::NAN);
        let speed = book.state().v[n.page_offset()..]
            .iter()
            .map(|v| v.length())
            .fold(0.0, |w: f64, s| if s > w || s.is_nan() { s } else { w });
        if f > lift && speed < 1e-9 {
            settled = true;
            break;
        }
    }
    let page = book.page().expect("a page");
    let spacing = book.grid_spacing();
    let mut points = Vec::new();
    for b in 0..SAMPLES[1] {
        for a in 0..SAMPLES[0] {
            let u = w * a as f64 / (SAMPLES[0] - 1) as f64;
            let v = h * b as f64 / (SAMPLES[1] - 1) as f64;
            let p = pad_point([u, v], spacing, quads, 1.0);
            points.push(interpolate::<f64>(&p, page, n.grid.nx));
        }
    }
    Settled {
        points,
        settled,
        residual,
    }
}

/// RMS distance of two pages' samples, as a fraction of the width `w`.
fn rms(a: &[V], b: &[V], w: f64) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| (*p - *q).length_squared())
        .sum();
    (sum / a.len() as f64).sqrt() / w
}

#[test]
#[ignore = "R1 does not converge yet: 0.56 % then 2.39 % (docs/accuracy.md, R1); ~15 minutes"]
fn a_page_held_by_its_pad_converges_with_the_grid() {
    let grids = [[8, 11], [16, 22], [32, 44]];
    let runs: Vec<Settled> = grids.iter().map(|&q| held(q, 45.0, 0.9)).collect();
    for (q, r) in grids.iter().zip(&runs) {
        println!(
            "{q:?}: settled {}, last KKT residual {:.2e}",
            r.settled, r.residual
        );
    }
    let w = 12.0;
    let d = [
        rms(&runs[0].points, &runs[1].points, w),
        rms(&runs[1].points, &runs[2].points, w),
    ];
    let order = (d[0] / d[1]).log2();
    println!(
        "8x11 -> 16x22 {:.3} %, 16x22 -> 32x44 {:.3} %, observed order {order:.2}",
        100.0 * d[0],
        100.0 * d[1]
    );
    assert!(runs.iter().all(|r| r.settled), "a grid did not settle");
    assert!(order >= 1.0, "observed order {order}");
    // Richardson: the 16 x 22 page's distance from the limit, d1 / (2^p - 1) + d1.
    assert!(d[1] * (1.0 + 1.0 / (2f64.powf(order) - 1.0)) <= 0.01);
}
