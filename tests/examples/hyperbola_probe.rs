//! Probes the tear direction of the force split (seed `002_…` Sec. 5.1-5.2) along the exact
//! hyperbola of O'Keefe's experiment, separately from the path's own history.
//!
//! For each cut length $L$: the notched sheet of the `asymmetric_pulls_follow_the_hyperbola`
//! test is cut along the hyperbola through the notch tip with the fingers' pattern points
//! $A = (3, 0)$, $B = (7.5, 0)$ as foci (steps of 0.15 along its tangent, so the cut is the
//! hyperbola up to the snapping of the mesh edits); the sheet is built with tearing off, the
//! fingers pull apart at $\pm 0.3$ units/s for the given number of frames, and the split is
//! evaluated at the tip. The printed error is the angle from the hyperbola's tangent at the
//! tip (the bisector of the directions to the foci, pointing away from them) to the split's
//! direction, counter-clockwise positive. A tear that follows the hyperbola within 2 % of
//! its length needs these errors to stay within a degree or so on average.
//!
//! `cargo run --release -p folio-tests --example hyperbola_probe -- [columns] [frames]`
//! (defaults 8 and 30; the rows are three quarters of the columns).

use folio_geometry::SheetMesh;
use folio_kernels::Potential;
use folio_tearing::advance::advance;
use folio_tearing::sheet::{SheetSettings, TearingSheet};
use folio_tearing::{TearSettings, Tears};
use glam::DVec3;

const A: [f64; 2] = [3.0, 0.0];
const B: [f64; 2] = [7.5, 0.0];
const STEP: f64 = 0.15;

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = v[0].hypot(v[1]);
    [v[0] / n, v[1] / n]
}

/// The tangent of the hyperbola through `p` with foci `A`, `B`, pointing away from them.
fn tangent(p: [f64; 2]) -> [f64; 2] {
    let (a, b) = (
        unit([A[0] - p[0], A[1] - p[1]]),
        unit([B[0] - p[0], B[1] - p[1]]),
    );
    unit([-(a[0] + b[0]), -(a[1] + b[1])])
}

/// The notched sheet cut along the hyperbola for `length`; returns it and its tip.
fn cut_sheet(columns: usize, rows: usize, length: f64) -> Option<(SheetMesh<f64>, u32)> {
    let mut mesh = SheetMesh::rectangle(12.0, 9.0, columns, rows).ok()?;
    let mid = (columns / 2) as u32;
    let mut tip = mid + columns as u32 + 1;
    mesh.cut_edge(mid, tip).ok()?;
    let snap = TearSettings::default().snap;
    let mut done = 0.0;
    let mut first = true;
    while done < length - 1e-9 {
        let p = mesh.pattern()[tip as usize];
        let step = STEP.min(length - done);
        let outcome = advance(&mut mesh, tip, tangent(p), step, !first, snap).ok()?;
        tip = outcome.tip?;
        let q = mesh.pattern()[tip as usize];
        done += (q[0] - p[0]).hypot(q[1] - p[1]);
        first = false;
    }
    Some((mesh, tip))
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let columns = args.first().copied().unwrap_or(8).max(2);
    let frames = args.get(1).copied().unwrap_or(30);
    let rows = (columns * 3 / 4).max(2);
    println!("{columns} x {rows} quads, {frames} frames of pulling before each evaluation");
    println!("  L     tip              error (deg)   E_r");
    let mut errors = Vec::new();
    for k in 1..=10 {
        let length = 0.5 * f64::from(k);
        let Some((mesh, tip)) = cut_sheet(columns, rows, length) else {
            println!("{length:4.1}  the cut was refused by the mesh");
            continue;
        };
        let mut settings = SheetSettings::default();
        settings.effects.tearing = false;
        let Ok(mut sheet) = TearingSheet::with_mesh(mesh, settings) else {
            continue;
        };
        let (Ok(fa), Ok(fb)) = (sheet.grab(A), sheet.grab(B)) else {
            continue;
        };
        let (sa, sb) = (sheet.fingers()[fa].target, sheet.fingers()[fb].target);
        let h = sheet.settings().time_step;
        for frame in 0..frames {
            let t = (frame + 1) as f64 * h;
            let moved = sheet
                .move_finger(fa, sa - DVec3::X * 0.3 * t)
                .and_then(|()| sheet.move_finger(fb, sb + DVec3::X * 0.3 * t));
            if moved.is_err() || !sheet.step().status.advanced() {
                break;
            }
        }
        let x = sheet.mesh().positions();
        let gradients: Vec<[DVec3; 3]> = sheet
            .model()
            .membranes()
            .terms()
            .iter()
            .map(|term| term.kernel.gradient(&term.nodes.map(|i| x[i as usize])))
            .collect();
        let held: Vec<u32> = sheet.fingers().iter().map(|f| f.vertex).collect();
        let Ok(mut tears) = Tears::new(TearSettings::default(), [12.0, 9.0]) else {
            continue;
        };
        tears.evaluate(sheet.mesh(), &gradients, &held, &[]);
        let p = sheet.mesh().pattern()[tip as usize];
        let Some(e) = tears
            .evaluations()
            .iter()
            .find(|e| e.candidate.vertex == tip)
        else {
            println!("{length:4.1}  ({:.3}, {:.3})  not a candidate", p[0], p[1]);
            continue;
        };
        let (t, d) = (tangent(p), e.split.direction);
        let error = (t[0] * d[1] - t[1] * d[0])
            .atan2(t[0] * d[0] + t[1] * d[1])
            .to_degrees();
        errors.push(error);
        println!(
            "{length:4.1}  ({:.3}, {:.3})  {error:+7.2}      {:.3e}",
            p[0], p[1], e.split.release_rate
        );
    }
    let n = errors.len().max(1) as f64;
    let mean = errors.iter().sum::<f64>() / n;
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
    println!(
        "mean error {mean:+.2} deg, rms {rms:.2} deg over {} tips",
        errors.len()
    );
}
