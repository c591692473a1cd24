//! The energy a tear releases, read over a disk of fixed size (`folio_tearing::release`),
//! checked against an independent reference and against the mesh: a 12 x 9 sheet with an
//! edge notch, its left and right borders clamped and drawn apart, held still; tearing off,
//! hinges counting folds only (`HingeBending::Folds`). The reference is the energy the
//! discrete sheet actually releases when its notch is cut one edge longer, and one edge
//! shorter: $G \approx (V(a - h) - V(a + h)) / 2h$ at the same pulls. Run with
//! `--nocapture` for the figures.

use folio_geometry::SheetMesh;
use folio_kernels::Potential;
use folio_tearing::LoadBuffers;
use folio_tearing::release::{cone_weights, configurational_force};
use folio_tearing::sheet::{HingeBending, SheetSettings, TearingSheet};
use folio_tearing::{Estimator, TipRemesh};
use folio_tests::paths::{distance_to_path, length, off_hyperbola};
use glam::DVec3;

/// Half the distance the clamped borders are drawn apart (sheet units).
const PULL: f64 = 0.02;

/// A 12 x 9 sheet of `n` x `3n/4` quads with a slit up the grid line $u$ = `notch` from
/// the bottom border to `cells` cells deep, at rest, with fingers whose pads have `radius`;
/// tearing and cones off, hinges counting folds only. Returns the sheet and its tip vertex.
fn slit(n: usize, notch: f64, cells: u32, radius: f64) -> (TearingSheet<f64>, u32) {
    let (mesh, tip) = slit_mesh(n, notch, cells);
    let mut settings = SheetSettings {
        nx: n,
        ny: 3 * n / 4,
        hinge_bending: HingeBending::Folds,
        finger_radius: radius,
        ..SheetSettings::default()
    };
    settings.effects.tearing = false;
    settings.effects.cones = false;
    let sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
    (sheet, tip)
}

/// The mesh of [`slit`] and its tip vertex.
fn slit_mesh(n: usize, notch: f64, cells: u32) -> (SheetMesh<f64>, u32) {
    let (nx, ny) = (n, 3 * n / 4);
    let mut mesh = SheetMesh::rectangle(12.0, 9.0, nx, ny).expect("mesh");
    let columns = nx as u32 + 1;
    let column = (notch * n as f64 / 12.0).round() as u32;
    for j in 0..cells {
        mesh.cut_edge(column + columns * j, column + columns * (j + 1))
            .expect("slit");
    }
    (mesh, column + columns * cells)
}

/// Fingers grab the pattern points of `pulls` and move along $x$ by their distances, over
/// 10 frames, then hold still for 10 (the sheet is light: it is at rest by then).
fn pull_apart(sheet: &mut TearingSheet<f64>, pulls: &[([f64; 2], f64)]) {
    let held: Vec<(usize, DVec3, f64)> = pulls
        .iter()
        .map(|&(p, pull)| {
            let f = sheet.grab(p).expect("grab");
            (f, sheet.fingers()[f].target, pull)
        })
        .collect();
    let ramp = 10;
    for frame in 0..2 * ramp {
        let s = ((frame + 1) as f64 / ramp as f64).min(1.0);
        for &(f, start, pull) in &held {
            sheet
                .move_finger(f, start + DVec3::X * pull * s)
                .expect("move");
        }
        assert!(sheet.step().status.advanced(), "frame {frame}");
    }
}

/// [`slit`] up the middle, $u = 6$, with the left and right borders clamped (each vertex
/// held on its own) and drawn apart by `2 PULL` ([`pull_apart`]).
fn clamped_notch(n: usize, cells: u32) -> (TearingSheet<f64>, u32) {
    let (mut sheet, tip) = slit(n, 6.0, cells, 0.0);
    let border: Vec<([f64; 2], f64)> = sheet
        .mesh()
        .pattern()
        .iter()
        .filter(|p| p[0] == 0.0 || p[0] == 12.0)
        .map(|p| (*p, if p[0] == 0.0 { -PULL } else { PULL }))
        .collect();
    pull_apart(&mut sheet, &border);
    (sheet, tip)
}

/// The sheet's stretching energy.
fn membrane_energy(sheet: &TearingSheet<f64>) -> f64 {
    let x = sheet.mesh().positions();
    sheet
        .model()
        .membranes()
        .terms()
        .iter()
        .map(|t| t.kernel.value(&t.nodes.map(|i| x[i as usize])))
        .sum()
}

/// $J$ at `tip` over a disk of `radius`.
fn j_at(sheet: &TearingSheet<f64>, tip: u32, radius: f64) -> [f64; 2] {
    let mut buffers = LoadBuffers::default();
    sheet
        .model()
        .triangle_loads(sheet.mesh().positions(), &mut buffers);
    let settings = sheet.settings();
    let loads = buffers.loads(settings.stretch_modulus, settings.poisson);
    let mut q = Vec::new();
    cone_weights(sheet.mesh(), tip, radius, &buffers.prescribed, &mut q);
    configurational_force(sheet.mesh(), &loads, &q)
}

/// Notch depth 1.5 in cells of `12 / n`.
fn cells(n: usize) -> u32 {
    (1.5 * n as f64 / 12.0).round() as u32
}

/// $J$ is the energy the discrete sheet releases: within 3 % of the central difference of
/// the stretching energy over a notch one cell longer and one shorter, on three meshes
/// (measured: 1.3 %, 0.2 %, 0.3 % at 16, 32 and 48 quads across). It points straight up the
/// notch (the set-up is symmetric).
#[test]
fn the_release_rate_is_the_energy_a_longer_notch_releases() {
    for n in [16, 32, 48] {
        let k = cells(n);
        let h = 12.0 / n as f64;
        let (sheet, tip) = clamped_notch(n, k);
        let j = j_at(&sheet, tip, 1.0);
        let shorter = membrane_energy(&clamped_notch(n, k - 1).0);
        let longer = membrane_energy(&clamped_notch(n, k + 1).0);
        let released = (shorter - longer) / (2.0 * h);
        let gap = (j[1] - released).abs() / released;
        println!(
            "{n} quads across: J = ({:.4e}, {:.4e}); released {released:.4e}; gap {:.2} %",
            j[0],
            j[1],
            100.0 * gap
        );
        assert!(
            released > 0.0 && gap < 0.03,
            "{n}: {j:?} against {released}"
        );
        assert!(j[0].abs() < 1e-9 * j[1], "{n}: sideways {j:?}");
    }
}

/// The same pulls on three meshes give the same release rate within 10 % (measured
/// 1.424e-7, 1.464e-7 and 1.483e-7 at 32, 48 and 64 quads across, each finer one closer),
/// and the disk's size does not matter (path independence: within 1 % for $R$ from 0.75 to
/// 1.25 on the finest).
#[test]
fn the_release_rate_converges_with_the_mesh() {
    let mut rates = Vec::new();
    for n in [32, 48, 64] {
        let (sheet, tip) = clamped_notch(n, cells(n));
        let by_radius: Vec<f64> = [0.75, 1.0, 1.25]
            .iter()
            .map(|&r| j_at(&sheet, tip, r)[1])
            .collect();
        println!(
            "{n} quads across: J for R = 0.75, 1, 1.25: {:.4e}, {:.4e}, {:.4e}",
            by_radius[0], by_radius[1], by_radius[2]
        );
        let (lo, hi) = by_radius
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        assert!(hi / lo - 1.0 < 0.01, "{n}: {by_radius:?}");
        rates.push(by_radius[1]);
    }
    let (lo, hi) = (rates[0].min(rates[2]), rates[0].max(rates[2]));
    assert!(rates.iter().all(|&r| r >= lo && r <= hi), "{rates:?}");
    assert!(hi / lo - 1.0 < 0.10, "{rates:?}");
    assert!(
        (rates[2] - rates[1]).abs() < (rates[1] - rates[0]).abs(),
        "{rates:?}"
    );
}

/// [`slit`] 1.5 deep up $u$ = `notch`, pulled by two fingers on the bottom border 1.5
/// either side of it, with pads of `radius`, drawn apart by `2 PULL` ([`pull_apart`]).
fn pulled_notch(n: usize, notch: f64, radius: f64) -> (TearingSheet<f64>, u32) {
    let (mut sheet, tip) = slit(n, notch, cells(n), radius);
    pull_apart(
        &mut sheet,
        &[([notch - 1.5, 0.0], -PULL), ([notch + 1.5, 0.0], PULL)],
    );
    (sheet, tip)
}

/// Two fingers pulling the lips of a notch apart release the same energy on every mesh
/// when they hold pads of a fixed size (the default radius, 0.7): within 12 % at 32, 48
/// and 64 quads across (measured 3.24e-7, 3.32e-7, 3.61e-7). What is left is the grid's
/// sampling of the pad's rim (a radius of 0.8 gives 4.11e-7, 4.39e-7, 4.25e-7) and the
/// first-order convergence of linear triangles at a tip (a square pad on grid lines gives
/// 5.81e-7, 5.36e-7, 5.18e-7). A finger pinching one vertex is a point load whose grip
/// softens on every finer mesh (1.56e-7, 1.35e-7, 1.23e-7): printed for comparison.
#[test]
fn finger_pads_release_the_same_energy_on_every_mesh() {
    let radius = SheetSettings::<f64>::default().finger_radius;
    let mut rates = Vec::new();
    for n in [32, 48, 64] {
        let (sheet, tip) = pulled_notch(n, 6.0, radius);
        let j = j_at(&sheet, tip, 1.0);
        let (point, point_tip) = pulled_notch(n, 6.0, 0.0);
        let single = j_at(&point, point_tip, 1.0);
        println!(
            "{n} quads across: J = {:.4e} with pads, {:.4e} with single vertices",
            j[1], single[1]
        );
        rates.push(j[1]);
    }
    let (lo, hi) = rates.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &v| {
        (lo.min(v), hi.max(v))
    });
    assert!(lo > 0.0 && hi / lo - 1.0 < 0.12, "{rates:?}");
}

/// Symmetric pulls point the release straight up the notch, wherever the notch is: the
/// direction of $J$ within 2° of the notch at $u$ = 6, 5.25 and 4.5, on 32 and 48 quads
/// across (measured 0° and 0°, +0.8° and +0.1°, −0.5° and −1.3°). Closer to the border the
/// narrower strip on that side is softer and the release turns toward it: about −2.5°, −3.1°,
/// −3.1° at $u$ = 3.75 and −5.0°, −5.3°, −5.0° at 3 on 32, 48 and 64 quads across, a
/// property of the sheet, not of the mesh.
#[test]
fn symmetric_pulls_release_straight_ahead_at_every_notch() {
    let radius = SheetSettings::<f64>::default().finger_radius;
    for notch in [6.0, 5.25, 4.5] {
        for n in [32, 48] {
            let (sheet, tip) = pulled_notch(n, notch, radius);
            let j = j_at(&sheet, tip, 1.0);
            let angle = j[0].atan2(j[1]).to_degrees();
            println!(
                "notch at u = {notch}, {n} quads across: J = ({:.4e}, {:.4e}), {angle:+.2} deg",
                j[0], j[1]
            );
            assert!(angle.abs() <= 2.0, "notch {notch}, {n}: {angle} deg");
        }
    }
}

/// Williams' displacement $u = \sqrt{r/2\pi}/(2\mu)\thinspace(K_I g_I + K_{II} g_{II})$ at
/// polar point $(r, \theta)$ of the crack's frame, plane stress (Anderson, *Fracture
/// Mechanics*, Table 2.2).
fn williams(r: f64, theta: f64, k: [f64; 2], mu: f64, nu: f64) -> [f64; 2] {
    let kappa = (3.0 - nu) / (1.0 + nu);
    let (s, c) = ((0.5 * theta).sin(), (0.5 * theta).cos());
    let scale = (r / (2.0 * core::f64::consts::PI)).sqrt() / (2.0 * mu);
    [
        scale * (k[0] * c * (kappa - 1.0 + 2.0 * s * s) + k[1] * s * (kappa + 1.0 + 2.0 * c * c)),
        scale * (k[0] * s * (kappa + 1.0 - 2.0 * c * c) - k[1] * c * (kappa - 1.0 - 2.0 * s * s)),
    ]
}

/// The interaction integral reads the mixity of an exact crack-tip field back: a 12 x 9
/// sheet slit along $v = 4.5$ from the left border to $(6, 4.5)$, its vertices moved by
/// Williams' field of $K_I$ and $K_{II} = \rho K_I$ (strains of about $10^{-3}$), then
/// turned in space (30° about $x$, then 20° about $z$). `mode_mixity` over a disk of
/// radius 1 gives $\rho$ within 0.02 + 3 % on 32 and 48 quads across, and the kink of the
/// maximum hoop stress follows.
#[test]
fn the_mode_mixity_of_a_williams_field_is_read_back() {
    use folio_tearing::mixity::{kink_angle, mode_mixity};
    use folio_tearing::release::cone_weights;
    let (y, nu) = (0.003, 0.3);
    let mu = y / (2.0 * (1.0 + nu));
    let turn = glam::DQuat::from_rotation_z(20f64.to_radians())
        * glam::DQuat::from_rotation_x(30f64.to_radians());
    for n in [32, 48] {
        let (nx, ny) = (n, 3 * n / 4);
        let h = 12.0 / n as f64;
        let row = (4.5 / h).round() as u32;
        let columns = nx as u32 + 1;
        let base = SheetMesh::<f64>::rectangle(12.0, 9.0, nx, ny).expect("mesh");
        let mut slit = base.clone();
        for i in 0..nx as u32 / 2 {
            slit.cut_edge(i + columns * row, i + 1 + columns * row)
                .expect("slit");
        }
        let tip_vertex = nx as u32 / 2 + columns * row;
        let tip = [6.0, 4.5];
        for rho in [0.0, 0.25, -0.5, 1.0] {
            let k = [2.0 * mu * 1e-3, 2.0 * mu * 1e-3 * rho];
            let mut mesh = slit.clone();
            let pattern = mesh.pattern().to_vec();
            // A vertex on the slit's line behind the tip is on the upper lip when its
            // triangles lie above the line.
            let above: Vec<bool> = (0..mesh.vertex_count() as u32)
                .map(|v| {
                    mesh.fan_iter(v).any(|e| {
                        let t = mesh.triangles()[e as usize / 3];
                        t.iter().map(|&i| pattern[i as usize][1]).sum::<f64>() / 3.0 > 4.5
                    })
                })
                .collect();
            for (v, x) in mesh.positions_mut().iter_mut().enumerate() {
                let p = pattern[v];
                let d = [p[0] - tip[0], p[1] - tip[1]];
                let r = (d[0] * d[0] + d[1] * d[1]).sqrt();
                let mut theta = d[1].atan2(d[0]);
                if d[1] == 0.0 && d[0] < 0.0 {
                    theta = if above[v] {
                        core::f64::consts::PI
                    } else {
                        -core::f64::consts::PI
                    };
                }
                let u = williams(r, theta, k, mu, nu);
                *x = turn * DVec3::new(p[0] + u[0], p[1] + u[1], 0.0);
            }
            let mut buffers = LoadBuffers::default();
            let settings = SheetSettings {
                nx,
                ny,
                stretch_modulus: y,
                poisson: nu,
                ..SheetSettings::default()
            };
            let sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
            sheet
                .model()
                .triangle_loads(sheet.mesh().positions(), &mut buffers);
            let mut q = Vec::new();
            cone_weights(sheet.mesh(), tip_vertex, 1.0, &[], &mut q);
            let read = mode_mixity(sheet.mesh(), &buffers.loads(y, nu), tip, [1.0, 0.0], &q)
                .expect("an opening");
            println!(
                "{n} quads across: rho {rho:+.3} read {read:+.4}; kink {:+.2} deg",
                kink_angle(read).to_degrees()
            );
            assert!(
                (read - rho).abs() <= 0.02 + 0.03 * rho.abs(),
                "{n}: {rho} read {read}"
            );
        }
    }
    assert!(kink_angle(0.0) == 0.0);
    assert!((kink_angle(1e6).to_degrees() + 70.53).abs() < 0.01);
    assert!(
        (kink_angle(0.01) + 0.02).abs() < 1e-4,
        "-2 rho for a slight mixity"
    );
}

/// What [`tear_by_pulls`] found.
struct Torn {
    /// The first tear's path.
    path: Vec<[f64; 2]>,
    /// Tears made.
    tears: usize,
    /// The smallest pattern angle of any triangle, over every frame (degrees).
    worst_angle: f64,
}

/// A 12 x 9 sheet of `n` x `3n/4` quads with a notch 1.5 deep up $u$ = `notch`, the
/// `estimator` and the tip's `remesh`, hinges counting folds; fingers grab the bottom border at `fingers` and move
/// outward along it at 0.3 per second each, until the first tear separates a piece or 400
/// frames. Every frame the mesh must be a valid manifold.
fn tear_with(
    n: usize,
    notch: f64,
    fingers: [f64; 2],
    estimator: Estimator,
    remesh: TipRemesh,
) -> Torn {
    let (mesh, _) = slit_mesh(n, notch, cells(n));
    let mut settings = SheetSettings {
        nx: n,
        ny: 3 * n / 4,
        hinge_bending: HingeBending::Folds,
        ..SheetSettings::default()
    };
    settings.tearing.estimator = estimator;
    settings.tearing.remesh = remesh;
    let mut sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
    let held: Vec<(usize, DVec3, f64)> = fingers
        .iter()
        .map(|&u| {
            let f = sheet.grab([u, 0.0]).expect("grab");
            (
                f,
                sheet.fingers()[f].target,
                if u < notch { -0.3 } else { 0.3 },
            )
        })
        .collect();
    let h = sheet.settings().time_step;
    let mut worst_angle = 180.0f64;
    for frame in 0..400 {
        let t = (frame + 1) as f64 * h;
        for &(f, start, speed) in &held {
            sheet
                .move_finger(f, start + DVec3::X * speed * t)
                .expect("move");
        }
        let report = sheet.step();
        assert!(report.status.advanced(), "{n}: frame {frame}: {report:?}");
        let mut mesh = sheet.mesh().clone();
        mesh.check()
            .unwrap_or_else(|e| panic!("{n}: frame {frame}: {e}"));
        worst_angle = folio_tests::least(worst_angle, mesh.worst_angle().to_degrees());
        if sheet
            .tears()
            .tears()
            .first()
            .is_some_and(|t| t.tip.is_none())
        {
            break;
        }
    }
    let tears = sheet.tears().tears();
    Torn {
        path: tears.first().map(|t| t.path.clone()).unwrap_or_default(),
        tears: tears.len(),
        worst_angle,
    }
}

/// [`tear_with`] the disk estimator and the shaped remesh: the first tear's path and the
/// number of tears.
fn tear_by_pulls(n: usize, notch: f64, fingers: [f64; 2]) -> (Vec<[f64; 2]>, usize) {
    let torn = tear_with(n, notch, fingers, Estimator::Disk, TipRemesh::Shaped);
    (torn.path, torn.tears)
}

/// The angle of the chord of `path` from straight up, degrees (positive to the right).
fn chord_angle(path: &[[f64; 2]]) -> f64 {
    let (a, b) = (path[0], path[path.len() - 1]);
    (b[0] - a[0]).atan2(b[1] - a[1]).to_degrees()
}

/// Symmetric pulls tear straight, with the disk estimator, on 16 and 32 quads across:
/// fingers 1.5 either side of a notch at $u$ = 6, 5.25 and 6.75 drawn apart along the
/// border; the first tear runs at least 5 units and its chord is within 2° of the notch's
/// line. (Measured, not asserted: a notch at $u$ = 4.5 tears −0.5° and −2.9° off: the
/// narrower strip on its left is softer, and the 32-quad figure is over the bound.)
#[test]
fn symmetric_pulls_tear_straight_on_two_meshes() {
    for notch in [6.0, 5.25, 6.75] {
        for n in [16, 32] {
            let (path, tears) = tear_by_pulls(n, notch, [notch - 1.5, notch + 1.5]);
            let angle = chord_angle(&path);
            println!(
                "notch at u = {notch}, {n} quads across: length {:.3}, {tears} tears, chord {angle:+.2} deg",
                length(&path)
            );
            assert!(length(&path) >= 5.0, "{notch}, {n}: {path:?}");
            assert!(angle.abs() <= 2.0, "{notch}, {n}: {angle} deg");
        }
    }
}

/// Refining the mesh moves the tear of asymmetric pulls (fingers at $u$ = 3 and 7.5, the
/// notch at 6) by less than 3 % of its length: the largest distance from either path to
/// the other, 16 against 32 quads across (measured 1.6 %); both tears run at least 5
/// units. Printed: how far the path is from O'Keefe's hyperbola with the fingers' starting
/// points as foci (about 12 % of the length: this flat membrane carries compression, and
/// the tear runs nearly straight).
#[test]
fn refining_the_mesh_keeps_the_path() {
    let (a, b) = ([3.0, 0.0], [7.5, 0.0]);
    let coarse = tear_by_pulls(16, 6.0, [a[0], b[0]]).0;
    let fine = tear_by_pulls(32, 6.0, [a[0], b[0]]).0;
    let gap = fine
        .iter()
        .map(|&p| distance_to_path(p, &coarse))
        .chain(coarse.iter().map(|&p| distance_to_path(p, &fine)))
        .fold(0.0, folio_tests::worst);
    for (n, path) in [(16, &coarse), (32, &fine)] {
        let off = off_hyperbola(path, a, b);
        println!(
            "{n} quads across: length {:.3}, chord {:+.2} deg, off the hyperbola {:.1} % of the length",
            length(path),
            chord_angle(path),
            100.0 * off / length(path)
        );
    }
    println!(
        "largest distance between the paths {gap:.3} ({:.2} % of the length)",
        100.0 * gap / length(&fine)
    );
    assert!(length(&coarse) >= 5.0 && length(&fine) >= 5.0);
    assert!(gap <= 0.03 * length(&fine), "{gap}");
}

/// Tearing with [`TipRemesh::Shaped`] keeps the sheet a valid manifold and its triangles
/// well shaped, at every frame, for symmetric and asymmetric pulls, with both estimators,
/// on 16 and 32 quads across: no triangle's smallest pattern angle falls below 2°. What is
/// left is a split's short step: a turn of a step of 0.05-0.1 splits the tip, and the new
/// tip's triangles have an angle of about the step over the edge at the old one. The
/// seed's remesh is run on the same cases, to show what it leaves (printed; its worst is
/// asserted below 1°, so that this test would notice if the cases stopped being hard).
#[test]
fn the_shaped_remesh_keeps_the_triangles_well_shaped() {
    let mut worst = [180.0f64; 2];
    for (n, estimator) in [
        (16, Estimator::Split),
        (16, Estimator::Disk),
        (32, Estimator::Disk),
    ] {
        for fingers in [[4.5, 7.5], [3.0, 7.5], [3.0, 6.75]] {
            for (k, remesh) in [TipRemesh::Seed, TipRemesh::Shaped].into_iter().enumerate() {
                let torn = tear_with(n, 6.0, fingers, estimator, remesh);
                println!(
                    "{n} quads across, {estimator:?}, {remesh:?}, fingers at {fingers:?}: \
                     tear {:.2} long, smallest angle {:.2} deg",
                    length(&torn.path),
                    torn.worst_angle
                );
                worst[k] = folio_tests::least(worst[k], torn.worst_angle);
            }
        }
    }
    println!(
        "smallest angle: seed {:.2} deg, shaped {:.2} deg",
        worst[0], worst[1]
    );
    assert!(worst[0] < 1.0, "{worst:?}");
    assert!(worst[1] >= 2.0, "{worst:?}");
}
