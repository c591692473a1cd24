//! Frames of the sheet allocate nothing (DESIGN.md: "setup allocates; stepping does not"),
//! held by a counting global allocator:
//! - a tearing-free frame: [`TearingSheet::step`] with the effect `tearing` off and `cones`
//!   on (physics step, cone-layer update, remesh) on a bent sheet whose fingers keep moving,
//!   after a few warm-up frames;
//! - a frame that tears, with every effect on: the tip slides, splits (a new topology: the
//!   model is rebuilt and the solver analyses it again), the mesh refuses a split, or no
//!   tearing point passes. The tear edits the mesh in its reserved room, the model is
//!   rebuilt in place, the solver's analysis refills its reserved buffers, and the detail
//!   path, the texture cut and a new tear use reserved ones
//!   (`folio_tearing::sheet::SheetSettings::reserved_vertices`, `TearSettings::reserved_tears`).

use core::f64::consts::PI;
use folio_geometry::SheetMesh;
use folio_geometry::sheet::Region;
use folio_kernels::{Real, Vec3Ops};
use folio_tearing::sheet::{HingeBending, SheetEffects, SheetSettings, TearingSheet};
use folio_tearing::{Estimator, TearSettings, TipRemesh};

use folio_counting::{Counting, allocations};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Pattern point `(u, v)` of the 12 x 9 sheet bent about the v axis: flat for $u < 3$ and
/// $u > 9$, a circular arc of turning $2\varphi$ between (a cylinder, developable).
fn bent(u: f64, v: f64, phi: f64) -> [f64; 3] {
    let (a, b) = (3.0, 9.0);
    let c = 0.5 * (a + b);
    let r = (b - a) / (2.0 * phi);
    let arc = |s: f64| {
        let psi = (s - c) / r;
        [c + r * psi.sin(), v, r - r * psi.cos()]
    };
    let s = u.clamp(a, b);
    let [x, y, z] = arc(s);
    let (dx, dz) = if u < a {
        (phi.cos(), -phi.sin())
    } else {
        (phi.cos(), phi.sin())
    };
    [x + dx * (u - s), y, z + dz * (u - s)]
}

fn vec3<T: Real>(x: [f64; 3]) -> T::Vec3 {
    T::Vec3::new(T::from_f64(x[0]), T::from_f64(x[1]), T::from_f64(x[2]))
}

/// What the counted frames did.
struct Counted {
    allocations: usize,
    frames: usize,
    flips: u32,
    analyses: u32,
    /// Fewest curved triangles of the cone layer over the counted frames.
    curved: usize,
}

/// A sheet bent into a cylinder, held by four fingers (two per hand, on the flat parts); the
/// hands rock the bend between $\varphi = 0.55$ and $0.65$ rad and drift sideways. Tearing is
/// off, cones on. `warm_up` frames, then the allocations of the next `frames` frames.
fn allocations_of_tearing_free_frames<T: Real>(warm_up: usize, frames: usize) -> Counted {
    let settings = SheetSettings::<T> {
        effects: SheetEffects {
            tearing: false,
            cones: true,
            ..SheetEffects::default()
        },
        ..SheetSettings::default()
    };
    let mut mesh = SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)
        .expect("mesh");
    let pattern = mesh.pattern().to_vec();
    for (x, p) in mesh.positions_mut().iter_mut().zip(&pattern) {
        *x = vec3::<T>(bent(p[0].to_f64(), p[1].to_f64(), 0.6));
    }
    let mut sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
    let at = [[1.5, 1.5], [1.5, 7.5], [10.5, 1.5], [10.5, 7.5]];
    let fingers: Vec<usize> = at
        .iter()
        .map(|p| sheet.grab(p.map(T::from_f64)).expect("grab"))
        .collect();
    let h = settings.time_step.to_f64();
    let mut counted = Counted {
        allocations: 0,
        frames,
        flips: 0,
        analyses: 0,
        curved: usize::MAX,
    };
    for frame in 0..warm_up + frames {
        let t = (frame + 1) as f64 * h;
        let phi = 0.6 + 0.05 * (2.0 * PI * t).sin();
        let drift = 0.2 * t;
        for (&f, p) in fingers.iter().zip(&at) {
            let [x, y, z] = bent(p[0], p[1], phi);
            sheet
                .move_finger(f, vec3::<T>([x + drift, y, z]))
                .expect("move");
        }
        let before = allocations();
        let report = sheet.step();
        let made = allocations() - before;
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        if frame >= warm_up {
            counted.allocations += made;
            counted.flips += report.flips;
            counted.analyses += report.analyses;
            let curved = sheet
                .layer()
                .regions
                .iter()
                .filter(|&&r| r != Region::Flat)
                .count();
            counted.curved = counted.curved.min(curved);
        }
    }
    assert!(sheet.propagations().is_empty(), "tearing is off");
    counted
}

#[test]
fn tearing_free_frames_do_not_allocate() {
    for (name, c) in [
        ("f64", allocations_of_tearing_free_frames::<f64>(10, 60)),
        ("f32", allocations_of_tearing_free_frames::<f32>(10, 60)),
    ] {
        println!(
            "{name}: {} allocations in {} frames; {} flips, {} analyses; at least {} curved triangles",
            c.allocations, c.frames, c.flips, c.analyses, c.curved
        );
        // The frames must exercise the remesh (curved triangles) without changing the
        // topology (a flip is a topology change, after which the model is rebuilt: setup).
        assert!(c.curved > 0, "{name}: the sheet is not bent");
        assert_eq!(c.flips, 0, "{name}: flips in the counted frames");
        assert_eq!(c.analyses, 0, "{name}: analyses in the counted frames");
        assert_eq!(c.allocations, 0, "{name}: a tearing-free frame allocated");
    }
}

/// What the counted tearing frames did.
#[derive(Debug, Default)]
struct TearingFrames {
    /// Frames that propagated without a new analysis (the tip slid) and their allocations.
    slid: usize,
    slid_allocations: usize,
    /// Frames that propagated nothing, and their allocations.
    quiet: usize,
    quiet_allocations: usize,
    /// Frames with a new analysis (a split or a cut) and their allocations.
    analysed: usize,
    analysed_allocations: usize,
    /// Propagations the mesh refused (their frames are quiet or slid: a refused split leaves
    /// the topology as it was).
    refused: u32,
}

/// The default sheet (every effect on) with a slit from the bottom edge's middle up to
/// $(6, 1.5)$, pulled apart by two fingers on the bottom edge, at $(3, 0)$ (unequal arms,
/// so the tear turns and splits as well as slides) and $(7.5, 0)$, moving outward and down
/// in the sheet's plane. Counts the allocations of each frame after the first `warm_up`.
fn allocations_of_tearing_frames(
    settings: SheetSettings<f64>,
    warm_up: usize,
    frames: usize,
) -> TearingFrames {
    let mut mesh = SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)
        .expect("mesh");
    // Vertex i + 9 j is at (1.5 i, 1.5 j): the slit is (6, 0) - (6, 1.5).
    mesh.cut_edge(4, 13).expect("slit");
    let mut sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
    let pulls = [([3.0, 0.0], [-0.3, -0.1]), ([7.5, 0.0], [0.3, -0.1])];
    let fingers: Vec<(usize, glam::DVec3, glam::DVec3)> = pulls
        .iter()
        .map(|&(at, [du, dv])| {
            let f = sheet.grab(at).expect("grab");
            (f, sheet.fingers()[f].target, glam::DVec3::new(du, dv, 0.0))
        })
        .collect();
    let h = settings.time_step;
    let mut counted = TearingFrames::default();
    for frame in 0..warm_up + frames {
        let t = (frame + 1) as f64 * h;
        for &(f, start, velocity) in &fingers {
            sheet.move_finger(f, start + velocity * t).expect("move");
        }
        let before = allocations();
        let report = sheet.step();
        let made = allocations() - before;
        assert!(report.status.advanced(), "frame {frame}: {report:?}");
        if frame < warm_up {
            continue;
        }
        counted.refused += report.refused;
        if report.analyses > 0 {
            counted.analysed += 1;
            counted.analysed_allocations += made;
        } else if report.propagations > 0 {
            counted.slid += 1;
            counted.slid_allocations += made;
        } else {
            counted.quiet += 1;
            counted.quiet_allocations += made;
        }
    }
    assert!(
        sheet.tears().tears().len() <= settings.tearing.reserved_tears,
        "the scene started more tears than are reserved"
    );
    counted
}

#[test]
fn tearing_frames_do_not_allocate() {
    let seed = SheetSettings::default();
    let mesh_independent = SheetSettings {
        hinge_bending: HingeBending::Folds,
        tearing: TearSettings {
            estimator: Estimator::Disk,
            remesh: TipRemesh::Shaped,
            ..TearSettings::default()
        },
        ..SheetSettings::default()
    };
    let mut refused = 0;
    for (name, settings) in [
        ("split, seed remesh", seed),
        ("disk, folds, shaped remesh", mesh_independent),
    ] {
        let c = allocations_of_tearing_frames(settings, 3, 300);
        println!(
            "{name}: slid {} frames, {} allocations; new topology {} frames, {} allocations; \
             quiet {} frames, {} allocations; {} refused",
            c.slid,
            c.slid_allocations,
            c.analysed,
            c.analysed_allocations,
            c.quiet,
            c.quiet_allocations,
            c.refused
        );
        // The scene must exercise sliding tips and splits, and leave quiet frames after them.
        assert!(c.slid >= 3, "{name}: only {} frames slid a tip", c.slid);
        assert!(c.analysed >= 3, "{name}: only {} splits", c.analysed);
        assert!(c.quiet >= 5, "{name}: only {} quiet frames", c.quiet);
        assert_eq!(c.slid_allocations, 0, "{name}: a sliding frame allocated");
        assert_eq!(
            c.analysed_allocations, 0,
            "{name}: a splitting frame allocated"
        );
        assert_eq!(c.quiet_allocations, 0, "{name}: a quiet frame allocated");
        refused += c.refused;
    }
    assert!(refused >= 1, "no refused split among the counted frames");
}
