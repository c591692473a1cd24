//! Tearing: tears along a border, through a junction, at a corner, on a sheet of two
//! triangles, and membranes whose rest shape is far below any meaningful size.

use folio_kernels::Potential;
use folio_kernels::error::KernelError;
use folio_kernels::membrane::{Membrane, MembraneLaw};
use folio_kernels::{Mat3Ops, Real};
use folio_tearing::sheet::{SheetEffects, SheetSettings, TearingSheet};
use glam::DVec3;

/// A sheet with tearing on, `nx` x `ny` quads on the default 12 x 9 pattern.
fn sheet(nx: usize, ny: usize) -> TearingSheet<f64> {
    TearingSheet::new(SheetSettings {
        nx,
        ny,
        effects: SheetEffects {
            tearing: true,
            ..SheetEffects::default()
        },
        ..SheetSettings::default()
    })
    .unwrap()
}

/// Grabs `pulls` (pattern point, finger displacement at the end) and moves the fingers
/// linearly over `frames` frames; after every frame asserts finite positions and a valid
/// manifold. Returns the triangle count at the end.
fn pull(sheet: &mut TearingSheet<f64>, pulls: &[([f64; 2], DVec3)], frames: u32) -> usize {
    let mut fingers = Vec::new();
    for &(at, by) in pulls {
        let i = sheet.grab(at).expect("grab on the sheet");
        let start = sheet.fingers()[i].target;
        fingers.push((i, start, by));
    }
    for frame in 1..=frames {
        let t = f64::from(frame) / f64::from(frames);
        for &(i, start, by) in &fingers {
            sheet.move_finger(i, start + by * t).unwrap();
        }
        sheet.step();
        assert!(
            sheet.mesh().positions().iter().all(|p| p.is_finite()),
            "frame {frame}: not finite"
        );
        let mut mesh = sheet.mesh().clone();
        assert_eq!(mesh.check(), Ok(()), "frame {frame}: invalid sheet");
    }
    sheet.mesh().triangle_count()
}

/// A tear along a border: two fingers on the bottom edge pulled apart along it, so the
/// tip would run along the boundary where a split leaves slivers. Asserts finite positions
/// and a valid manifold on every frame.
#[test]
fn tear_along_a_border() {
    let mut s = sheet(8, 6);
    pull(
        &mut s,
        &[
            ([4.5, 0.0], DVec3::new(-4.0, 0.0, 0.0)),
            ([7.5, 0.0], DVec3::new(4.0, 0.0, 0.0)),
        ],
        20,
    );
}

/// A tear through a junction: fingers on both sides of an interior vertex where six
/// triangles meet, pulled apart across it. Asserts finite positions and a valid manifold.
#[test]
fn tear_through_a_junction() {
    let mut s = sheet(8, 6);
    pull(
        &mut s,
        &[
            ([4.5, 4.5], DVec3::new(-3.0, 2.0, 0.0)),
            ([7.5, 4.5], DVec3::new(3.0, 2.0, 0.0)),
        ],
        20,
    );
}

/// A tear at a corner: the corner vertex (one triangle) pulled away from a finger holding
/// the sheet next to it. Asserts finite positions and a valid manifold.
#[test]
fn tear_at_a_corner() {
    let mut s = sheet(8, 6);
    pull(
        &mut s,
        &[
            ([0.0, 0.0], DVec3::new(-4.0, -1.0, 3.0)),
            ([3.0, 3.0], DVec3::ZERO),
        ],
        20,
    );
}

/// A sheet of two triangles (one quad) torn at both ends: too few vertices for a tear to
/// split anything. Asserts finite positions, a valid manifold and at least one triangle
/// left.
#[test]
fn tear_a_sheet_of_a_few_triangles() {
    let mut s = sheet(1, 1);
    let left = pull(
        &mut s,
        &[
            ([0.0, 0.0], DVec3::new(-6.0, 0.0, 0.0)),
            ([12.0, 9.0], DVec3::new(6.0, 3.0, 0.0)),
        ],
        15,
    );
    assert!(left >= 1);
}

/// A wrinkling sheet (the tension-field membrane, `SheetSettings::wrinkling`) crushed in the
/// plane by its four corners to a third of its size and pulled back out: most triangles are
/// slack, with no stress and no stiffness, and the Newton matrix keeps only the mass and
/// the hinges. Asserts finite positions and a valid manifold on every frame, and that
/// every step advanced.
#[test]
fn crush_a_wrinkling_sheet() {
    let mut s = TearingSheet::new(SheetSettings {
        wrinkling: true,
        ..SheetSettings::default()
    })
    .unwrap();
    let corners = [[0.0, 0.0], [12.0, 0.0], [12.0, 9.0], [0.0, 9.0]];
    let inward = |c: [f64; 2]| DVec3::new(6.0 - c[0], 4.5 - c[1], 0.0) * (2.0 / 3.0);
    let crush: Vec<_> = corners.iter().map(|&c| (c, inward(c))).collect();
    pull(&mut s, &crush, 30);
    let crushed = s.propagations().len();
    let mesh = s.mesh();
    let slack = mesh
        .triangles()
        .iter()
        .filter(|tri| {
            let m = Membrane::new(tri.map(|i| mesh.pattern()[i as usize]), 3e-3, 0.3)
                .unwrap()
                .with_law(MembraneLaw::TensionField);
            m.stress(&tri.map(|i| mesh.positions()[i as usize])) == [0.0; 3]
        })
        .count();
    let triangles = mesh.triangle_count();
    for (i, &corner) in corners.iter().enumerate() {
        let target = s.fingers()[i].target;
        s.move_finger(i, target - inward(corner) * 1.2).unwrap();
    }
    let mut refused = 0;
    for frame in 0..30 {
        let report = s.step();
        refused += usize::from(!report.status.advanced());
        assert!(
            s.mesh().positions().iter().all(|p| p.is_finite()),
            "frame {frame} of the pull: not finite"
        );
        let mut mesh = s.mesh().clone();
        assert_eq!(
            mesh.check(),
            Ok(()),
            "frame {frame} of the pull: invalid sheet"
        );
    }
    println!(
        "crushed wrinkling sheet: {slack} of {triangles} triangles slack, {crushed} propagations while \
         crushed, {refused} steps refused while pulled out, {} propagations in all",
        s.propagations().len()
    );
    assert!(
        2 * slack > triangles,
        "{slack} of {triangles} triangles slack"
    );
    assert_eq!(refused, 0);
}

/// `Membrane::new` with rest edges of 1e-15 in f32: accepted before, with an infinite energy
/// and Hessian at coordinates of order 1 (issue 20). Asserts the typed refusal
/// `NonPositiveRestArea`.
#[test]
fn membrane_far_below_a_meaningful_size_is_refused() {
    for scale in [1e-15f32, 1e-9, 1e-5] {
        let pattern = [[0.0, 0.0], [scale, 0.0], [0.0, scale]];
        assert_eq!(
            Membrane::new(pattern, 1.0, 0.3),
            Err(KernelError::NonPositiveRestArea { index: 0 }),
            "edge {scale}"
        );
    }
    let tiny = [[0.0, 0.0], [1e-12f64, 0.0], [0.0, 1e-12]];
    assert!(Membrane::new(tiny, 1.0, 0.3).is_err());
}

/// The smallest membrane accepted in f32 (edges of about 1e-3 page units, just above the
/// floor) under a displacement of 100 page units: the quartic energy is largest there.
/// Asserts finite energy, gradient and Hessian.
#[test]
fn membrane_at_the_smallest_accepted_size_stays_finite() {
    let e = 1e-3f32;
    let m = Membrane::new([[0.0, 0.0], [e, 0.0], [0.0, e]], 1.0, 0.3).unwrap();
    let v = <f32 as Real>::Vec3::new;
    let x = [v(0.0, 0.0, 0.0), v(100.0, 0.0, 0.0), v(0.0, 0.0, -100.0)];
    assert!(m.value(&x).is_finite());
    assert!(m.gradient(&x).iter().all(|g| g.is_finite()));
    let h = m.hessian(&x);
    for b in h.iter().flatten() {
        for r in 0..3 {
            for c in 0..3 {
                assert!(b.entry(r, c).is_finite(), "Hessian entry ({r}, {c})");
            }
        }
    }
}
