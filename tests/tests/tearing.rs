//! The tearing validations of seed `002_…` Sec. 7 on [`TearingSheet`]: the straight tear of
//! symmetric pulls (Fig. 14), the hyperbola of asymmetric pulls (Fig. 2, 15, O'Keefe), the
//! zigzag of alternating hands (Fig. 16), the start points (Fig. 12-15: flattening a bent
//! sheet tears near a finger, twisting at a junction point), the branch of changed finger
//! positions (Fig. 17), determinism, a valid manifold and finite values after every frame,
//! and bad input. Run with `--nocapture` for the measured figures.

use folio_geometry::SheetMesh;
use folio_tearing::Kind;
use folio_tearing::sheet::{FrameReport, SheetSettings, TearingSheet, TearingSheetError};
use folio_tests::paths::{distance_to_path, length as path_length, off_hyperbola};
use glam::DVec3;

/// Rows and columns of the default 12 x 9 sheet (8 x 6 quads): vertex `i + 9 j` is at
/// $(1.5 i, 1.5 j)$.
const COLUMNS: u32 = 9;

fn vertex(i: u32, j: u32) -> u32 {
    i + COLUMNS * j
}

/// The default sheet with a slit from the middle of the bottom edge up to $(6, 1.5)$: the
/// notch of seed Fig. 14 (an inward angle of $2\pi$ at its tip).
fn notched(settings: SheetSettings<f64>) -> TearingSheet<f64> {
    let mut mesh = SheetMesh::rectangle(12.0, 9.0, 8, 6).expect("mesh");
    mesh.cut_edge(vertex(4, 0), vertex(4, 1)).expect("slit");
    TearingSheet::with_mesh(mesh, settings).expect("sheet")
}

/// A finger moving at constant velocity from where it grabbed.
struct Pull {
    finger: usize,
    start: DVec3,
    velocity: DVec3,
}

fn grab(sheet: &mut TearingSheet<f64>, at: [f64; 2], velocity: DVec3) -> Pull {
    let finger = sheet.grab(at).expect("grab");
    Pull {
        finger,
        start: sheet.fingers()[finger].target,
        velocity,
    }
}

/// Every frame: the mesh is a valid manifold with boundary and every value finite.
fn assert_sound(sheet: &TearingSheet<f64>, frame: usize) {
    let mut mesh = sheet.mesh().clone();
    mesh.check()
        .unwrap_or_else(|e| panic!("frame {frame}: invalid mesh: {e}"));
    assert!(
        sheet
            .mesh()
            .positions()
            .iter()
            .chain(sheet.mesh().velocities())
            .all(|x| x.is_finite()),
        "frame {frame}: non-finite state"
    );
}

/// Plays `frames` frames (or until the first tear is `length` long), moving the fingers.
fn play(
    sheet: &mut TearingSheet<f64>,
    pulls: &[Pull],
    frames: usize,
    length: f64,
) -> Vec<FrameReport<f64>> {
    let mut reports = Vec::new();
    for frame in 0..frames {
        place(sheet, pulls, frame);
        reports.push(sheet.step());
        assert_sound(sheet, frame);
        if tear_length(sheet) >= length {
            break;
        }
    }
    reports
}

fn tear_length(sheet: &TearingSheet<f64>) -> f64 {
    sheet
        .tears()
        .tears()
        .first()
        .map_or(0.0, |t| path_length(&t.path))
}

/// Moves every finger of `pulls` to where it is at the end of frame `frame`, $t = (f+1)h$.
fn place(sheet: &mut TearingSheet<f64>, pulls: &[Pull], frame: usize) {
    let t = (frame + 1) as f64 * sheet.settings().time_step;
    for p in pulls {
        sheet
            .move_finger(p.finger, p.start + p.velocity * t)
            .expect("move");
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
}

/// Seed Fig. 14: two fingers at equal distance from the notch tip pull the lips apart; the
/// tear runs straight along the perpendicular bisector. Deviation: the angle between the
/// chord of the path and the bisector, at most 2°.
#[test]
fn symmetric_pulls_tear_straight() {
    let mut sheet = notched(SheetSettings::default());
    let pulls = [
        grab(&mut sheet, [4.5, 0.0], DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, 0.0)),
    ];
    play(&mut sheet, &pulls, 400, 5.0);
    let tears = sheet.tears().tears();
    assert!(!tears.is_empty(), "no tear");
    let first = sheet.propagations()[0];
    assert_eq!(
        first.kind,
        Kind::InwardAngle,
        "the tear starts at the notch"
    );
    let path = &tears[0].path;
    let (a, b) = (path[0], *path.last().unwrap());
    let deviation = (b[0] - a[0]).atan2(b[1] - a[1]).abs().to_degrees();
    let lateral = path
        .iter()
        .map(|p| (p[0] - 6.0).abs())
        .fold(0.0, folio_tests::worst);
    println!(
        "symmetric: tear length {:.3}, {} points, chord deviation {deviation:.4} deg, max |u - 6| {lateral:.2e}",
        tear_length(&sheet),
        path.len()
    );
    assert!(
        tear_length(&sheet) >= 3.0,
        "the tear stopped at {}",
        tear_length(&sheet)
    );
    assert!(deviation <= 2.0, "deviation {deviation} deg");
}

/// A tear that reaches the sheet's edge separates the piece cleanly: the mesh becomes two
/// valid components, and the sheet goes on being simulated.
#[test]
fn a_tear_reaching_the_edge_separates_the_piece() {
    let mut sheet = notched(SheetSettings::default());
    let pulls = [
        grab(&mut sheet, [4.5, 0.0], DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, 0.0)),
    ];
    let mut separated_at = None;
    for frame in 0..400 {
        place(&mut sheet, &pulls, frame);
        let report = sheet.step();
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        assert_sound(&sheet, frame);
        if separated_at.is_none()
            && sheet
                .propagations()
                .iter()
                .any(|p| p.edit == folio_tearing::Edit::Separated)
        {
            separated_at = Some(frame);
        }
        if separated_at.is_some_and(|f| frame >= f + 30) {
            break;
        }
    }
    let frame = separated_at.expect("the tear never reached the edge");
    assert_eq!(
        components(sheet.mesh()),
        2,
        "two pieces after the separation"
    );
    assert!(sheet.tears().tears()[0].tip.is_none(), "the tear ended");
    println!(
        "separated at frame {frame}; {} propagations",
        sheet.propagations().len()
    );
}

/// Connected components of the mesh through shared edges.
fn components(mesh: &SheetMesh<f64>) -> usize {
    let n = mesh.triangle_count();
    let mut label = vec![usize::MAX; n];
    let mut count = 0;
    for start in 0..n {
        if label[start] != usize::MAX {
            continue;
        }
        let mut stack = vec![start];
        label[start] = count;
        while let Some(t) = stack.pop() {
            for k in 0..3 {
                let g = mesh.twin((3 * t + k) as u32);
                if g != folio_geometry::sheet::NONE && label[g as usize / 3] == usize::MAX {
                    label[g as usize / 3] = count;
                    stack.push(g as usize / 3);
                }
            }
        }
        count += 1;
    }
    count
}

/// Seed Fig. 2 and 15 (O'Keefe): with the fingers at different distances from the notch the
/// tear follows the hyperbola with the fingers' pattern points as foci: $|pA| - |pB|$ stays
/// within 2 % of the tear length of its start value.
///
/// Not met: measured 20.3 %. The tip's nodal pulls follow the shape of its fan: where
/// the tear runs close to a grid line, slides leave lip triangles 0.03 thick whose stress is
/// three times their neighbours' and turns the pulls by 15-40°. Tried, not kept: loads
/// through a disk of fixed radius around the tip (5.3 %, 3.6 % with ten relaxation steps per
/// propagation, but the edge separation and the zigzag stopped), a shape bound on slides
/// (worse), smoothing the pattern near the tip (worse), Delaunay flips around the tip
/// (11.8 %, but the zigzag and the branch stopped). The probe `examples/hyperbola_probe.rs`
/// cuts the sheet along the exact hyperbola and evaluates the split at the tip: its
/// direction scatters about the hyperbola's tangent by 15-18° rms for 8, 16 and 32 columns
/// alike and after 5 or 120 frames of pulling, so the scatter is the method's on this load
/// case, not the mesh's or the dynamics'; 2 % needs about 1°. Issue 8 is blocked on this
/// bound.
#[test]
#[ignore = "hyperbola residual measured at 20.3 % of the tear length, bound 2 %: the seed's split scatters 15-18 deg rms along the exact path (examples/hyperbola_probe.rs); issue 8 blocked"]
fn asymmetric_pulls_follow_the_hyperbola() {
    let mut sheet = notched(SheetSettings::default());
    let (a, b) = ([3.0, 0.0], [7.5, 0.0]);
    let pulls = [
        grab(&mut sheet, a, DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, b, DVec3::new(0.3, 0.0, 0.0)),
    ];
    play(&mut sheet, &pulls, 400, 5.0);
    let tears = sheet.tears().tears();
    assert!(!tears.is_empty(), "no tear");
    let path = &tears[0].path;
    let worst = off_hyperbola(path, a, b);
    let length = tear_length(&sheet);
    println!(
        "asymmetric: tear length {length:.3}, {} points, max ||pA|-|pB| - d0| = {worst:.4} ({:.2} % of the length)",
        path.len(),
        100.0 * worst / length
    );
    for p in path {
        println!(
            "  ({:.3}, {:.3})  |pA|-|pB| = {:.4}",
            p[0],
            p[1],
            dist(*p, a) - dist(*p, b)
        );
    }
    assert!(length >= 3.0, "the tear stopped at {length}");
    assert!(
        worst <= 0.02 * length,
        "hyperbola residual {worst} over length {length}"
    );
}

/// Seed Fig. 16: alternating which hand pulls turns the tear one way, then the other. The
/// left finger pulls (down and out) for 40 frames while the right one holds still, then the
/// right one for 40 frames, and so on; the tear's sideways direction changes sign at least
/// three times.
#[test]
fn alternating_hands_tear_a_zigzag() {
    let mut sheet = notched(SheetSettings::default());
    let a = sheet.grab([4.5, 0.0]).expect("grab");
    let b = sheet.grab([7.5, 0.0]).expect("grab");
    let (mut xa, mut xb) = (sheet.fingers()[a].target, sheet.fingers()[b].target);
    let h = sheet.settings().time_step;
    for frame in 0..300 {
        if (frame / 40) % 2 == 0 {
            xa += DVec3::new(-0.4, -0.4, 0.0) * h;
        } else {
            xb += DVec3::new(0.4, -0.4, 0.0) * h;
        }
        sheet.move_finger(a, xa).expect("move");
        sheet.move_finger(b, xb).expect("move");
        let report = sheet.step();
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        assert_sound(&sheet, frame);
    }
    let path = &sheet.tears().tears()[0].path;
    // Sideways direction of each segment longer than 0.05, then its sign changes.
    let signs: Vec<f64> = path
        .windows(2)
        .filter(|w| (w[1][0] - w[0][0]).abs() > 0.05)
        .map(|w| (w[1][0] - w[0][0]).signum())
        .collect();
    let turns = signs.windows(2).filter(|s| s[0] != s[1]).count();
    println!(
        "zigzag: tear length {:.2}, {} points, {turns} changes of sideways direction",
        tear_length(&sheet),
        path.len()
    );
    assert!(turns >= 3, "{turns} turns: {path:?}");
    assert!(tear_length(&sheet) >= 4.0);
}

/// Seed Fig. 13: twisting the bottom border (each hand holds a corner with two fingers and
/// turns about the vertical, the two hands in opposite directions, drawing apart slowly)
/// bends the sheet into cones; the tear starts at a junction point.
#[test]
fn a_twist_starts_its_tear_at_a_junction_point() {
    let mut sheet = TearingSheet::<f64>::new(SheetSettings::default()).expect("sheet");
    let mut fingers = Vec::new();
    for (points, centre, side) in [
        ([[0.0, 0.0], [1.5, 0.0]], 0.75, -1.0),
        ([[12.0, 0.0], [10.5, 0.0]], 11.25, 1.0),
    ] {
        for p in points {
            fingers.push((sheet.grab(p).expect("grab"), p, centre, side));
        }
    }
    let h = sheet.settings().time_step;
    for frame in 0..120 {
        let t = (frame + 1) as f64 * h;
        let angle = t; // one radian per second
        for &(f, p, centre, side) in &fingers {
            let d = p[0] - centre;
            let target = DVec3::new(
                centre + side * 0.05 * t + d * angle.cos(),
                p[1],
                side * d * angle.sin(),
            );
            sheet.move_finger(f, target).expect("move");
        }
        let report = sheet.step();
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        assert_sound(&sheet, frame);
        if !sheet.propagations().is_empty() {
            break;
        }
    }
    let first = sheet.propagations().first().expect("no tear within 2 s");
    println!(
        "twist: the tear starts at {:?} ({:?})",
        first.from, first.kind
    );
    assert_eq!(first.kind, Kind::Junction);
}

/// Same bits twice.
#[test]
fn tearing_is_deterministic() {
    let run = || {
        let mut sheet = notched(SheetSettings::default());
        let pulls = [
            grab(&mut sheet, [3.0, 0.0], DVec3::new(-0.3, 0.0, 0.1)),
            grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, -0.1)),
        ];
        play(&mut sheet, &pulls, 120, f64::INFINITY);
        let m = sheet.mesh();
        let mut bits: Vec<u64> = m
            .positions()
            .iter()
            .flat_map(|x| x.to_array())
            .map(f64::to_bits)
            .collect();
        bits.extend(m.pattern().iter().flatten().map(|x| x.to_bits()));
        bits.extend(m.triangles().iter().flatten().map(|&i| u64::from(i)));
        bits
    };
    let (a, b) = (run(), run());
    assert!(a.len() > 100);
    assert_eq!(a, b);
}

/// Bad input gives a status, never a panic: a finger off the sheet, two fingers on one
/// point, a non-finite target; a sheet nobody pulls never tears.
#[test]
fn bad_input_is_refused() {
    let mut sheet = notched(SheetSettings::default());
    assert_eq!(
        sheet.grab([20.0, 1.0]),
        Err(TearingSheetError::FingerOffSheet)
    );
    assert_eq!(
        sheet.grab([f64::NAN, 1.0]),
        Err(TearingSheetError::FingerOffSheet)
    );
    let f = sheet.grab([3.0, 3.0]).expect("grab");
    assert!(matches!(
        sheet.grab([3.0, 3.0]),
        Err(TearingSheetError::CoincidentFingers { .. })
    ));
    assert_eq!(
        sheet.move_finger(f, DVec3::new(f64::INFINITY, 0.0, 0.0)),
        Err(TearingSheetError::NonFiniteTarget)
    );
    assert_eq!(
        sheet.move_finger(7, DVec3::ZERO),
        Err(TearingSheetError::NoSuchFinger { index: 7 })
    );
    for frame in 0..60 {
        let r = sheet.step();
        assert!(r.status.advanced(), "{r:?}");
        assert_sound(&sheet, frame);
    }
    assert!(sheet.propagations().is_empty(), "an unloaded sheet tore");
}

/// A finger's pad holds every vertex within its radius on its own side of a tear, and
/// moves them with the finger: a 12 x 9 sheet of 16 x 12 quads (cells 0.75) slit up
/// $u = 6$ to $v = 2.25$, a pad of radius 1 at $(6.75, 0.75)$ right of the slit. Held: the
/// grid vertices within 1 of the point (counted here from the grid), of which the slit's
/// lip at $(6, 0.75)$ only on the right; moved by the finger's displacement after a frame;
/// released, nothing is held. A pad of radius 0 holds its one vertex.
#[test]
fn a_finger_pad_holds_its_side_of_a_tear() {
    let slit = |radius: f64| {
        let mut mesh = SheetMesh::rectangle(12.0, 9.0, 16, 12).expect("mesh");
        for j in 0..3 {
            mesh.cut_edge(8 + 17 * j, 8 + 17 * (j + 1)).expect("slit");
        }
        let settings = SheetSettings {
            nx: 16,
            ny: 12,
            finger_radius: radius,
            ..SheetSettings::default()
        };
        TearingSheet::with_mesh(mesh, settings).expect("sheet")
    };
    let held = |sheet: &TearingSheet<f64>| -> Vec<u32> {
        (0..sheet.mesh().vertex_count() as u32)
            .filter(|&v| sheet.model().is_held(v as usize))
            .collect()
    };
    let at = [6.75, 0.75];
    let within: usize = (0..=16)
        .flat_map(|i| (0..=12).map(move |j| [0.75 * f64::from(i), 0.75 * f64::from(j)]))
        .filter(|&p| dist(p, at) <= 1.0)
        .count();

    let mut sheet = slit(1.0);
    let finger = sheet.grab(at).expect("grab");
    let pad = held(&sheet);
    assert_eq!(pad.len(), within, "{pad:?}");
    let mesh = sheet.mesh();
    let on_lip: Vec<u32> = pad
        .iter()
        .copied()
        .filter(|&v| mesh.pattern()[v as usize] == [6.0, 0.75])
        .collect();
    assert_eq!(on_lip.len(), 1, "one of the two lips at (6, 0.75)");
    let right_of_slit = mesh.fan_iter(on_lip[0]).all(|h| {
        let t = mesh.triangles()[h as usize / 3];
        t.iter()
            .map(|&i| mesh.pattern()[i as usize][0])
            .sum::<f64>()
            / 3.0
            > 6.0
    });
    assert!(right_of_slit, "the pad holds the far lip");

    let start: Vec<DVec3> = pad
        .iter()
        .map(|&v| sheet.mesh().positions()[v as usize])
        .collect();
    let push = DVec3::new(0.05, -0.02, 0.01);
    let target = sheet.fingers()[finger].target + push;
    sheet.move_finger(finger, target).expect("move");
    assert!(sheet.step().status.advanced());
    for (&v, x0) in pad.iter().zip(&start) {
        let x = sheet.mesh().positions()[v as usize];
        assert!(
            (x - (*x0 + push)).length() < 1e-12,
            "vertex {v}: {x} from {x0}"
        );
    }
    sheet.release(finger).expect("release");
    assert!(held(&sheet).is_empty());

    let mut point = slit(0.0);
    point.grab(at).expect("grab");
    assert_eq!(held(&point).len(), 1);
}

/// A point the mesh refuses to advance does not hold back the others: with the disk
/// estimator on 16 x 12 quads (fingers at $u$ = 3 and 7.5 drawn apart, cones off), a kink
/// next to the tip leaves an inward angle whose split the mesh refuses, and which has the
/// largest $E_r / E_f$. When only that point was tried, the tear took 183 frames to grow
/// 2 units, 130 of them refused; now the next point by ratio is tried, and it takes 71
/// frames (9 refusals). Asserted: at most 120 frames.
#[test]
fn a_refused_point_does_not_stall_the_tear() {
    let mut mesh = SheetMesh::rectangle(12.0, 9.0, 16, 12).expect("mesh");
    for j in 0..2 {
        mesh.cut_edge(8 + 17 * j, 8 + 17 * (j + 1)).expect("slit");
    }
    let mut settings = SheetSettings {
        nx: 16,
        ny: 12,
        hinge_bending: folio_tearing::sheet::HingeBending::Folds,
        ..SheetSettings::default()
    };
    settings.tearing.estimator = folio_tearing::Estimator::Disk;
    settings.effects.cones = false;
    let mut sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
    let pulls = [
        grab(&mut sheet, [3.0, 0.0], DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, 0.0)),
    ];
    let reports = play(&mut sheet, &pulls, 400, 2.0);
    let refused: u32 = reports.iter().map(|r| r.refused).sum();
    println!(
        "disk estimator, 16 x 12: tear length {:.3} after {} frames, {refused} refusals",
        tear_length(&sheet),
        reports.len()
    );
    assert!(
        tear_length(&sheet) >= 2.0,
        "stalled at {}",
        tear_length(&sheet)
    );
    assert!(
        reports.len() <= 120,
        "{} frames to grow 2 units",
        reports.len()
    );
}

/// A non-finite load is counted, never read as "nothing to tear" nor as a value: the
/// pulled notched sheet's loads with a NaN in one triangle at the notch (its gradients,
/// Eshelby tensor and deformation gradient) make the tearing step count the notch's
/// candidate as non-finite and propagate nothing, with either estimator; the same loads
/// without the NaN give the notch a finite, positive release rate.
#[test]
fn a_non_finite_load_is_counted() {
    use folio_tearing::{Estimator, LoadBuffers, TearSettings, Tears};
    // The lips pulled apart for half a second with tearing off.
    let mut settings = SheetSettings::default();
    settings.effects.tearing = false;
    let mut sheet = notched(settings);
    let pulls = [
        grab(&mut sheet, [4.5, 0.0], DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, 0.0)),
    ];
    play(&mut sheet, &pulls, 30, f64::INFINITY);
    for estimator in [Estimator::Split, Estimator::Disk] {
        let mut buffers = LoadBuffers::default();
        sheet
            .model()
            .triangle_loads(sheet.mesh().positions(), &mut buffers);
        let tear_settings = TearSettings {
            estimator,
            ..TearSettings::default()
        };
        let fingers: Vec<u32> = sheet.fingers().iter().map(|f| f.vertex).collect();
        let mut tears = Tears::<f64>::new(tear_settings, [12.0, 9.0]).expect("tears");
        let mut mesh = sheet.mesh().clone();
        let clean = tears.step(&mut mesh, &buffers.loads(0.003, 0.3), &fingers, &[]);
        assert_eq!(clean.non_finite, 0, "{estimator:?}");
        let tip = vertex(4, 1);
        let read = |tears: &Tears<f64>| {
            tears
                .evaluations()
                .iter()
                .find(|e| e.candidate.vertex == tip)
                .map(|e| e.release_rate)
        };
        assert!(
            read(&tears).is_some_and(|r| r > 0.0 && r.is_finite()),
            "{estimator:?}: the pulled notch has a load"
        );

        // The same, with a NaN stress in a triangle at the notch's tip.
        let t = sheet
            .mesh()
            .triangles()
            .iter()
            .position(|t| t.contains(&tip))
            .expect("a triangle at the tip");
        for corner in &mut buffers.gradients[t] {
            corner.x = f64::NAN;
        }
        buffers.eshelby[t][0] = f64::NAN;
        buffers.deformations[t][0].x = f64::NAN;
        let mut tears = Tears::<f64>::new(tear_settings, [12.0, 9.0]).expect("tears");
        let mut mesh = sheet.mesh().clone();
        let bad = tears.step(&mut mesh, &buffers.loads(0.003, 0.3), &fingers, &[]);
        println!(
            "{estimator:?}: {} candidate(s) with a non-finite load",
            bad.non_finite
        );
        assert!(bad.non_finite >= 1, "{estimator:?}: {bad:?}");
        assert!(bad.propagation.is_none(), "{estimator:?}: {bad:?}");
        assert_eq!(read(&tears), None, "{estimator:?}: the notch was read");
    }
}

/// Two fingers grabbing close points and pulled apart violently: the solver may
/// refuse steps, but the sheet stays valid and finite.
#[test]
fn violent_pulls_stay_finite() {
    let mut sheet = notched(SheetSettings::default());
    let pulls = [
        grab(&mut sheet, [6.0, 4.0], DVec3::new(-40.0, 10.0, 30.0)),
        grab(&mut sheet, [6.0, 5.0], DVec3::new(40.0, -10.0, -30.0)),
    ];
    let reports = play(&mut sheet, &pulls, 120, f64::INFINITY);
    let failed = reports.iter().filter(|r| !r.status.advanced()).count();
    println!(
        "violent: {failed} of {} frames refused by the solver, {} propagations, {} triangles",
        reports.len(),
        sheet.propagations().len(),
        sheet.mesh().triangle_count()
    );
}

/// Pattern point `(u, v)` of the sheet bent about the $v$ axis by two hands (seed Fig. 12,
/// "bent into a locally cylindrical shape"): the strips $u < 1.5$ and $u > 10.5$ are flat
/// (held by the hands) and inclined by $\mp\varphi$, the part between is a circular arc of
/// turning $2\varphi$ (length 9, radius $9 / (2\varphi)$), rising toward $+z$ on both sides.
/// The map is an isometry of the pattern (a cylinder), so the bent sheet is at rest.
fn bent(u: f64, v: f64, phi: f64) -> DVec3 {
    let (a, b) = (1.5, 10.5);
    let c = 0.5 * (a + b);
    let r = (b - a) / (2.0 * phi);
    let s = u.clamp(a, b);
    let psi = (s - c) / r;
    let on_arc = DVec3::new(c + r * psi.sin(), v, r - r * psi.cos());
    let tangent = DVec3::new(psi.cos(), 0.0, psi.sin());
    on_arc + tangent * (u - s)
}

/// The hands of the flattening experiment (seed Fig. 12): each hand is two fingers on the
/// line where its flat strip meets the curved part ($u = 1.5$ and $u = 10.5$), a thumb 0.75
/// from the bottom border and a forefinger at $v = 4.5$.
const FLATTENING_FINGERS: [[f64; 2]; 4] = [[1.5, 0.75], [1.5, 4.5], [10.5, 0.75], [10.5, 4.5]];

/// Plays the flattening experiment for at most `frames` frames, until the first
/// propagation: the sheet starts bent (`bent` at $\varphi = 0.5$ rad) and held by
/// [`FLATTENING_FINGERS`]; after 0.5 s of holding still, each hand turns in its own plane at
/// `omega` rad/s about the midpoint of its two fingers, the two hands in opposite senses so
/// that the thumbs move apart along the bottom border and the forefingers come together.
/// Returns the frames played.
fn flatten(sheet: &mut TearingSheet<f64>, omega: f64, frames: usize) -> usize {
    let phi: f64 = 0.5;
    let fingers: Vec<usize> = FLATTENING_FINGERS
        .iter()
        .map(|&p| sheet.grab(p).expect("grab"))
        .collect();
    let h = sheet.settings().time_step;
    for frame in 0..frames {
        let t = (frame + 1) as f64 * h;
        let angle = omega * (t - 0.5).max(0.0);
        for (&f, &[u, v]) in fingers.iter().zip(&FLATTENING_FINGERS) {
            // The hand's plane is spanned by the along-u tangent of its flat strip and +v;
            // turning moves the thumb (below the midpoint) outward, away from the other hand.
            let (along, outward) = if u < 6.0 {
                (DVec3::new(phi.cos(), 0.0, -phi.sin()), -1.0)
            } else {
                (DVec3::new(phi.cos(), 0.0, phi.sin()), 1.0)
            };
            let mid = 0.5 * (FLATTENING_FINGERS[0][1] + FLATTENING_FINGERS[1][1]);
            let d = v - mid;
            let target = bent(u, mid, phi)
                + DVec3::Y * (d * angle.cos())
                + along * (-outward * d * angle.sin());
            sheet.move_finger(f, target).expect("move");
        }
        let report = sheet.step();
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        assert_sound(sheet, frame);
        if !sheet.propagations().is_empty() {
            return frame + 1;
        }
    }
    frames
}

/// Seed Fig. 12 and Sec. 7.1 (a), "the tear begins at a finger position": a sheet bent into a
/// cylinder by two hands, whose hands then turn to flatten its bottom border, tears near a
/// finger, at the bottom border where a hand's flat part meets the curved part. The sheet
/// has no notch, so neither a notch nor a tear tip can start it.
///
/// Asserted: the first propagation is of kind [`Kind::Finger`] (the boundary vertex nearest to
/// a finger), it starts on the flattened bottom border at most 1.0 (two thirds of a mesh cell)
/// from a finger, and it runs into the sheet (its first step makes at least 30° with the
/// border), not along it. Control: the same sheet held bent without turning the hands for as
/// long does not tear, so it is the flattening that tears it.
#[test]
fn flattening_tears_near_a_finger() {
    let frames = 240;
    let sheet_of = || {
        let mut mesh = SheetMesh::rectangle(12.0, 9.0, 8, 6).expect("mesh");
        let pattern = mesh.pattern().to_vec();
        for (x, p) in mesh.positions_mut().iter_mut().zip(&pattern) {
            *x = bent(p[0], p[1], 0.5);
        }
        TearingSheet::with_mesh(mesh, SheetSettings::default()).expect("sheet")
    };

    let mut held = sheet_of();
    flatten(&mut held, 0.0, frames);
    assert!(
        held.propagations().is_empty(),
        "the sheet tore without being flattened: {:?}",
        held.propagations()[0]
    );

    let mut sheet = sheet_of();
    let played = flatten(&mut sheet, 0.4, frames);
    let first = *sheet
        .propagations()
        .first()
        .unwrap_or_else(|| panic!("no tear in {frames} frames of flattening"));
    let (finger, distance) = FLATTENING_FINGERS
        .iter()
        .map(|&f| (f, dist(f, first.from)))
        .fold((FLATTENING_FINGERS[0], f64::INFINITY), |a, b| {
            if b.1 < a.1 { b } else { a }
        });
    let step = [first.to[0] - first.from[0], first.to[1] - first.from[1]];
    let across = step[1].atan2(step[0].abs()).to_degrees();
    println!(
        "flattening: the first propagation at frame {played} (hands turned by {:.3} rad) is {:?} \
         from ({:.3}, {:.3}) to ({:.3}, {:.3}): {distance:.3} from the finger at {finger:?}, \
         {across:.1} deg from the border; E_r {:.3e}, E_f {:.3e}",
        0.4 * (played as f64 * sheet.settings().time_step - 0.5),
        first.kind,
        first.from[0],
        first.from[1],
        first.to[0],
        first.to[1],
        first.release_rate,
        first.fracture_energy
    );
    assert_eq!(first.kind, Kind::Finger, "{first:?}");
    assert!(
        first.from[1].abs() <= 1e-9,
        "not on the bottom border: {first:?}"
    );
    assert!(distance <= 1.0, "{distance} from the nearest finger");
    assert!(
        across >= 30.0,
        "the tear runs along the border: {across} deg"
    );
}

/// Seed Fig. 17 and Sec. 5.3 ("the tear could thus even branch"): fingers that change
/// position during the deformation branch the tear. First the notch is torn straight up by
/// fingers pulling its lips apart (as in Fig. 14) to a length of 3; then both fingers let go
/// and grab the left half of the sheet again, one below and one above the middle of the tear
/// ($(4.5, 1.5)$ and $(4.5, 4.5)$), and pull apart along the tear ($\mp v$ at 0.4 / s): the
/// left lip is now stretched along its length, and a new tear starts on it and runs sideways.
///
/// Asserted: no branch before the re-grab; after it a tear with a parent that starts on the
/// parent's path at least 0.5 from the parent's tip (a side branch, not a fork of the tip),
/// both paths of nonzero length, the branch at least 45° from the parent's direction, and
/// their own alpha masks: they differ, and on the branch, beyond the reach of the parent's
/// cut, the branch's masks are cut (one of them transparent) where the parent's are both
/// opaque.
/// The mesh is valid and every value finite after every frame.
#[test]
fn changed_finger_positions_branch_the_tear() {
    use folio_tearing::Side;
    use folio_tearing::texture::{OPAQUE, TRANSPARENT};

    let mut sheet = notched(SheetSettings::default());
    let pulls = [
        grab(&mut sheet, [4.5, 0.0], DVec3::new(-0.3, 0.0, 0.0)),
        grab(&mut sheet, [7.5, 0.0], DVec3::new(0.3, 0.0, 0.0)),
    ];
    let first = play(&mut sheet, &pulls, 400, 3.0);
    assert!(
        tear_length(&sheet) >= 3.0,
        "phase 1: {}",
        tear_length(&sheet)
    );
    assert!(
        sheet.tears().tears().iter().all(|t| t.parent.is_none()),
        "a branch before the fingers moved"
    );
    let before = sheet.propagations().len();

    sheet.release(1).expect("release");
    sheet.release(0).expect("release");
    let pulls = [
        grab(&mut sheet, [4.5, 1.5], DVec3::new(0.0, -0.4, 0.0)),
        grab(&mut sheet, [4.5, 4.5], DVec3::new(0.0, 0.4, 0.0)),
    ];
    let side_branch = |sheet: &TearingSheet<f64>| {
        let tears = sheet.tears().tears();
        tears.iter().position(|t| {
            t.parent.is_some_and(|p| {
                let parent = &tears[p].path;
                distance_to_path(t.path[0], parent) <= 1e-9
                    && dist(t.path[0], *parent.last().unwrap()) >= 0.5
                    && path_length(&t.path) >= 1.0
            })
        })
    };
    let mut frames = 0;
    let mut branched = None;
    while frames < 480 && side_branch(&sheet).is_none() {
        place(&mut sheet, &pulls, frames);
        let report = sheet.step();
        assert!(report.status.advanced(), "frame {frames}: {report:?}");
        assert_sound(&sheet, first.len() + frames);
        frames += 1;
        if branched.is_none() && sheet.tears().tears().iter().any(|t| t.parent.is_some()) {
            branched = Some(frames);
        }
    }
    let tears = sheet.tears().tears();
    for (i, t) in tears.iter().enumerate() {
        println!(
            "tear {i}: parent {:?}, length {:.3}, from ({:.3}, {:.3}) to ({:.3}, {:.3})",
            t.parent,
            path_length(&t.path),
            t.path[0][0],
            t.path[0][1],
            t.path.last().unwrap()[0],
            t.path.last().unwrap()[1]
        );
    }
    for p in &sheet.propagations()[before..] {
        println!(
            "  after the re-grab: tear {} {:?} {:?} ({:.3}, {:.3}) -> ({:.3}, {:.3})",
            p.tear, p.kind, p.edit, p.from[0], p.from[1], p.to[0], p.to[1]
        );
    }
    let b = side_branch(&sheet)
        .unwrap_or_else(|| panic!("no side branch in {frames} frames after the re-grab"));
    let (branch, parent) = (&tears[b], &tears[tears[b].parent.unwrap()]);
    let chord = |path: &[[f64; 2]]| {
        let (a, z) = (path[0], *path.last().unwrap());
        let l = dist(a, z);
        [(z[0] - a[0]) / l, (z[1] - a[1]) / l]
    };
    let (cb, cp) = (chord(&branch.path), chord(&parent.path));
    let turn = (cb[0] * cp[0] + cb[1] * cp[1])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    println!(
        "branch {b} starts at ({:.3}, {:.3}), {:.3} from the parent's tip, {:.3} long, \
         {turn:.1} deg from the parent; the first branch {branched:?} frames and this one \
         {frames} frames after the re-grab",
        branch.path[0][0],
        branch.path[0][1],
        dist(branch.path[0], *parent.path.last().unwrap()),
        path_length(&branch.path)
    );
    assert!(path_length(&parent.path) > 0.0 && path_length(&branch.path) > 0.0);
    assert!(turn >= 45.0, "the branch turns by {turn} deg only");
    assert_ne!(branch.alpha, parent.alpha, "one alpha pair for both");
    // The middle of the branch segment farthest from the parent: the parent's cut reaches
    // $4\sigma$ plus two pixels to each side of its path (the band of `AlphaPair::cut`).
    let (mid, off) = branch
        .path
        .windows(2)
        .map(|w| {
            let m = [0.5 * (w[0][0] + w[1][0]), 0.5 * (w[0][1] + w[1][1])];
            (m, distance_to_path(m, &parent.path))
        })
        .fold(
            ([0.0; 2], f64::NEG_INFINITY),
            |a, b| if b.1 > a.1 { b } else { a },
        );
    let pixel_size = branch.alpha.raster().pixel_size();
    let band = 4.0 * sheet.tears().settings().detail.sigma + 2.0 * pixel_size[0].max(pixel_size[1]);
    assert!(
        off > band,
        "the branch stays within the parent's cut: {off} <= {band}"
    );
    let pixel = branch.alpha.raster().pixel_of(mid);
    let alpha = |pair: &folio_tearing::AlphaPair, side| pair.alpha(side, pixel).unwrap();
    assert_eq!(
        alpha(&branch.alpha, Side::Left).min(alpha(&branch.alpha, Side::Right)),
        TRANSPARENT,
        "the branch's masks are not cut at {mid:?}"
    );
    assert_eq!(
        (
            alpha(&parent.alpha, Side::Left),
            alpha(&parent.alpha, Side::Right)
        ),
        (OPAQUE, OPAQUE),
        "the parent's masks are cut at {mid:?}, on the branch"
    );
}

/// `tearing::advance` keeps its promise "the mesh is unchanged on error" for any request:
/// random tips (boundary vertices), directions, lengths, slides or splits, the seed's
/// remesh or the shaped one, on sheets torn at random. Every refused advance leaves pattern, positions and triangles as they were, and
/// every accepted one leaves a valid manifold. (A split once inserted its new vertex and then
/// failed to cut, leaving the sheet a vertex larger than the solver's state.)
#[test]
fn refused_advances_leave_the_sheet_unchanged() {
    use folio_tearing::advance::advance;
    let mut rng = folio_tests::Rng::new(0x7ea2);
    let (mut refused, mut accepted) = (0, 0);
    for _sheet in 0..400 {
        let mut mesh = SheetMesh::<f64>::rectangle(12.0, 9.0, 8, 6).expect("mesh");
        for _ in 0..60 {
            let boundary: Vec<u32> = (0..mesh.vertex_count() as u32)
                .filter(|&v| mesh.is_boundary(v))
                .collect();
            let p = boundary[(rng.next_u64() % boundary.len() as u64) as usize];
            let angle = rng.uniform(0.0, core::f64::consts::TAU);
            let t = [angle.cos(), angle.sin()];
            let length = rng.uniform(0.01, 2.0).powi(2);
            let straight = rng.next_u64() % 2 == 0;
            let shaped = rng.next_u64() % 2 == 0;
            let before = (
                mesh.pattern().to_vec(),
                mesh.positions().to_vec(),
                mesh.triangles().to_vec(),
            );
            match advance(&mut mesh, p, t, length, straight, 0.12, shaped) {
                Ok(_) => {
                    accepted += 1;
                    mesh.check().expect("a valid sheet after an advance");
                }
                Err(_) => {
                    refused += 1;
                    assert_eq!(mesh.pattern(), &before.0[..], "pattern changed");
                    assert_eq!(mesh.positions(), &before.1[..], "positions changed");
                    assert_eq!(mesh.triangles(), &before.2[..], "triangles changed");
                }
            }
        }
    }
    println!("advances: {accepted} accepted, {refused} refused");
    assert!(accepted > 100 && refused > 100, "{accepted} / {refused}");
}
