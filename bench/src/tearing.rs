//! The tearing sheet's scenario for benches and reports (seed `002_…` Fig. 2 and 15, as in
//! `tests/tests/tearing.rs`): the default 12 x 9 sheet of 8 x 6 quads (96 triangles) with a
//! slit cut from $(6, 0)$ to $(6, 1.5)$, two fingers grabbed at $(3, 0)$ and $(7.5, 0)$ and
//! moved apart at 0.3 units/s along $\mp X$, one [`TearingSheet::step`] per frame at 60 fps.
//!
//! Besides the whole frame, the parts of a frame can be replayed on copies of a sheet:
//! [`TearInputs`] (the tearing step, [`Tears::step`]) and [`ConeInputs`] (the cone layer's
//! update and remesh), each built from the sheet's public state the way
//! `folio_tearing::sheet::TearingSheet::step` builds it.

use folio_geometry::SheetMesh;
use folio_geometry::sheet::{ConeLayer, ConeLayerSettings};
use folio_kernels::Real;
use folio_tearing::Estimator;
use folio_tearing::sheet::{FrameReport, HingeBending, SheetEffects, SheetSettings, TearingSheet};
use folio_tearing::{LoadBuffers, TearStep, Tears};

/// The 3D vector type of `f64`.
pub type V3 = <f64 as Real>::Vec3;

/// Frames per second of the scenario.
pub const FPS: f64 = 60.0;

/// Finger speed (sheet units per second) along $\mp X$.
pub const SPEED: f64 = 0.3;

/// The asymmetric grabs: the left finger three units from the notch, the right one 1.5.
pub const ASYMMETRIC: [[f64; 2]; 2] = [[3.0, 0.0], [7.5, 0.0]];

/// The scenario: the sheet, its fingers' start points and velocities, the frame count.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The sheet.
    pub sheet: TearingSheet<f64>,
    /// Finger index, start point and velocity of each pull.
    pub pulls: Vec<(usize, V3, V3)>,
    /// Frames played.
    pub frames: usize,
}

impl Scene {
    /// The notched default sheet with `effects`, grabbed at `grabs` (the first pulled
    /// toward −X, the second toward +X).
    ///
    /// # Panics
    /// On a sheet or grab the fixed scenario never produces (a bench harness).
    #[must_use]
    pub fn notched(effects: SheetEffects, grabs: [[f64; 2]; 2]) -> Self {
        Self::notched_with(
            SheetSettings {
                effects,
                ..SheetSettings::default()
            },
            grabs,
        )
    }

    /// The sheet of `settings` (any mesh size) with the notch of [`Scene::notched`], a slit
    /// up the middle column from the bottom border, $W/8$ deep (1.5 on the default sheet),
    /// grabbed at `grabs`.
    ///
    /// # Panics
    /// As [`Scene::notched`]; for settings the sheet refuses.
    #[must_use]
    pub fn notched_with(settings: SheetSettings<f64>, grabs: [[f64; 2]; 2]) -> Self {
        let columns = settings.nx as u32 + 1;
        let vertex = |i: u32, j: u32| i + columns * j;
        let mut mesh =
            SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)
                .expect("mesh");
        let middle = settings.nx as u32 / 2;
        for j in 0..(settings.nx as u32 / 8).max(1) {
            mesh.cut_edge(vertex(middle, j), vertex(middle, j + 1))
                .expect("slit");
        }
        let mut sheet = TearingSheet::with_mesh(mesh, settings).expect("sheet");
        let mut pulls = Vec::new();
        for (at, sign) in grabs.into_iter().zip([-1.0, 1.0]) {
            let finger = sheet.grab(at).expect("grab");
            let start = sheet.fingers()[finger].target;
            pulls.push((finger, start, V3::new(sign * SPEED, 0.0, 0.0)));
        }
        Self {
            sheet,
            pulls,
            frames: 0,
        }
    }

    /// Moves the fingers to where they are at the next frame (untimed by callers).
    ///
    /// # Panics
    /// Never for the scenario's finite targets.
    pub fn move_fingers(&mut self) {
        let t = (self.frames + 1) as f64 / FPS;
        for &(finger, start, velocity) in &self.pulls {
            self.sheet
                .move_finger(finger, start + velocity * t)
                .expect("move");
        }
    }

    /// One frame: the fingers moved, then [`TearingSheet::step`].
    pub fn frame(&mut self) -> FrameReport<f64> {
        self.move_fingers();
        self.frames += 1;
        self.sheet.step()
    }

    /// The length of the first tear's path in the pattern (0 without a tear).
    #[must_use]
    pub fn tear_length(&self) -> f64 {
        self.sheet.tears().tears().first().map_or(0.0, |t| {
            t.path
                .windows(2)
                .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                .sum()
        })
    }
}

/// The default sheet on `n` x `3n/4` quads, every effect, with the disk estimator and
/// hinges counting folds when `disk`, the seed's split otherwise.
#[must_use]
pub fn sized_settings(n: usize, disk: bool) -> SheetSettings<f64> {
    let mut settings = SheetSettings {
        nx: n,
        ny: 3 * n / 4,
        ..SheetSettings::default()
    };
    if disk {
        settings.tearing.estimator = Estimator::Disk;
        settings.hinge_bending = HingeBending::Folds;
    }
    settings
}

/// Copies of everything one tearing step of a sheet reads and writes.
#[derive(Clone, Debug)]
pub struct TearInputs {
    /// The mesh (edited by a propagation).
    pub mesh: SheetMesh<f64>,
    /// The tears (their buffers, paths and alpha textures).
    pub tears: Tears<f64>,
    /// The membranes' gradients, Eshelby tensors and deformation gradients at the mesh's
    /// positions.
    pub loads: LoadBuffers<f64>,
    /// The membranes' 2D Young's modulus and Poisson's ratio.
    pub material: [f64; 2],
    /// The held vertices.
    pub fingers: Vec<u32>,
    /// The cone layer's junction points (none when cones are off).
    pub junctions: Vec<u32>,
}

impl TearInputs {
    /// The inputs of the next tearing step of `sheet`, copied.
    #[must_use]
    pub fn of(sheet: &TearingSheet<f64>) -> Self {
        let mut loads = LoadBuffers::default();
        sheet
            .model()
            .triangle_loads(sheet.mesh().positions(), &mut loads);
        let junctions = if sheet.settings().effects.cones {
            sheet.layer().junctions.clone()
        } else {
            Vec::new()
        };
        Self {
            mesh: sheet.mesh().clone(),
            tears: sheet.tears().clone(),
            loads,
            material: [sheet.settings().stretch_modulus, sheet.settings().poisson],
            fingers: sheet.fingers().iter().map(|f| f.vertex).collect(),
            junctions,
        }
    }

    /// [`Tears::step`] on the copies.
    pub fn step(&mut self) -> TearStep<f64> {
        let loads = self.loads.loads(self.material[0], self.material[1]);
        self.tears
            .step(&mut self.mesh, &loads, &self.fingers, &self.junctions)
    }
}

/// Copies of everything the cone layer's update and remesh of a sheet read and write.
#[derive(Clone, Debug)]
pub struct ConeInputs {
    /// The mesh (edited by the remesh's flips).
    pub mesh: SheetMesh<f64>,
    /// The layer.
    pub layer: ConeLayer<f64>,
    /// The thresholds.
    pub settings: ConeLayerSettings<f64>,
}

impl ConeInputs {
    /// The inputs of `sheet`'s next cone update, copied.
    #[must_use]
    pub fn of(sheet: &TearingSheet<f64>) -> Self {
        Self {
            mesh: sheet.mesh().clone(),
            layer: sheet.layer().clone(),
            settings: sheet.settings().cones,
        }
    }

    /// [`ConeLayer::update`] then [`ConeLayer::remesh`] on the copies; the flips made.
    pub fn run(&mut self) -> usize {
        self.layer.update(&self.mesh, &self.settings);
        self.layer.remesh(&mut self.mesh, &self.settings)
    }
}
