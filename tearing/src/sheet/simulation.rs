//! [`TearingSheet`]: a sheet of paper held by fingers, one frame at a time (seed `002_…`
//! Fig. 4):
//! 1. the held vertices go to their fingers; one implicit step of [`SheetModel`];
//! 2. (effect `cones`) the generalized-cone layer is estimated and the mesh remeshed toward
//!    the rulings ([`ConeLayer`]); flips re-run the analysis;
//! 3. (effect `tearing`) up to [`SheetSettings::max_propagations`] times: the tearing step
//!    ([`Tears::step`]) with the membranes' in-plane gradients; after a propagation, the
//!    model is rebuilt and one more implicit step "lets the lips of the tear move apart
//!    before treating the next potential tearing point" (step 4).
//!
//! With tearing and cones off, a frame is step 1 alone. A step the solver refuses keeps the
//! previous state and is reported ([`FrameReport::status`]); nothing non-finite is ever
//! written into the sheet.

use alloc::vec::Vec;

use crate::{LoadBuffers, Propagation, Tears};
use folio_geometry::SheetMesh;
use folio_geometry::sheet::ConeLayer;
use folio_kernels::{Real, Vec3Ops};

use super::error::TearingSheetError;
use super::model::SheetModel;
use super::settings::{HingeBending, SheetSettings};
use folio_solvers::report::StepStatus;
use folio_solvers::room::Room;
use folio_solvers::settings::Settings;
use folio_solvers::step::{Solver, State};

/// Propagations the history makes room for at setup (at least; a slide adds no vertex, so
/// the history is not bounded by [`SheetSettings::reserved_vertices`]); beyond it the history
/// grows its buffer, once per doubling.
const PROPAGATION_ROOM: usize = 1024;

/// A finger holding the sheet: the vertex at its point and, through its pad, every vertex
/// within [`SheetSettings::finger_radius`] of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finger<T: Real> {
    /// The vertex at the finger's point (the pad's centre).
    pub vertex: u32,
    /// Where the finger is (3D, sheet units): where its centre vertex goes.
    pub target: T::Vec3,
}

/// A vertex held by a finger's pad: it keeps its offset from the pad's centre, as it was
/// when the finger grabbed (the pad moves rigidly with the finger, without turning).
#[derive(Clone, Copy, Debug, PartialEq)]
struct PadVertex<T: Real> {
    vertex: u32,
    finger: usize,
    offset: T::Vec3,
}

/// What one frame did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameReport<T> {
    /// The status of the frame's first (physics) step; the worst one if a relaxation step
    /// failed.
    pub status: StepStatus,
    /// Symbolic analyses run (topology changes).
    pub analyses: u32,
    /// Edge flips of the cone remesh.
    pub flips: u32,
    /// Propagations made.
    pub propagations: u32,
    /// The last propagation, if any.
    pub last: Option<Propagation<T>>,
    /// Propagations the Griffith criterion allowed but the mesh refused.
    pub refused: u32,
    /// Tearing points whose load was not finite ([`crate::TearStep::non_finite`]): a bad
    /// state, counted, never read as "nothing to tear".
    pub non_finite_loads: u32,
}

/// The tearing sheet (module docs).
#[derive(Clone, Debug)]
pub struct TearingSheet<T: Real> {
    settings: SheetSettings<T>,
    mesh: SheetMesh<T>,
    model: SheetModel<T>,
    solver: Solver<T>,
    state: State<T>,
    layer: ConeLayer<T>,
    tears: Tears<T>,
    fingers: Vec<Finger<T>>,
    /// The fingers' centre vertices, in finger order (the tearing step's finger candidates).
    centres: Vec<u32>,
    /// Every vertex the pads hold, and for each its finger and offset.
    pads: Vec<PadVertex<T>>,
    held: Vec<u32>,
    loads: LoadBuffers<T>,
    propagations: Vec<Propagation<T>>,
    /// The mesh's topology version the model was built for.
    topology_seen: u64,
    frame: u64,
}

impl<T: Real> TearingSheet<T> {
    /// The rectangular sheet of `settings`, flat at $(u, v, 0)$, at rest, no finger.
    ///
    /// # Errors
    /// [`TearingSheetError`] for bad settings.
    pub fn new(settings: SheetSettings<T>) -> Result<Self, TearingSheetError> {
        settings.validate()?;
        let mesh = SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)?;
        Self::with_mesh(mesh, settings)
    }

    /// A sheet on a given mesh (its pattern spans $[0, W] \times [0, H]$ of the settings).
    ///
    /// # Errors
    /// [`TearingSheetError`] for bad settings or a mesh the kernels refuse.
    pub fn with_mesh(
        mut mesh: SheetMesh<T>,
        settings: SheetSettings<T>,
    ) -> Result<Self, TearingSheetError> {
        settings.validate()?;
        mesh.check()?;
        let model = SheetModel::new(&mesh, &[], &settings)?;
        let solver = Solver::new(Settings {
            time_step: settings.time_step,
            ..Settings::default()
        })?;
        let size = [settings.width.to_f64(), settings.height.to_f64()];
        let tears = Tears::new(settings.tearing, size).map_err(|e| e.within("tearing"))?;
        let state = State {
            x: mesh.positions().to_vec(),
            v: mesh.velocities().to_vec(),
        };
        let mut sheet = Self {
            layer: ConeLayer::of(&mesh, &settings.cones),
            settings,
            model,
            solver,
            state,
            tears,
            fingers: Vec::new(),
            centres: Vec::new(),
            pads: Vec::new(),
            held: Vec::new(),
            loads: LoadBuffers::default(),
            propagations: Vec::new(),
            topology_seen: mesh.topology_version(),
            mesh,
            frame: 0,
        };
        sheet.make_room();
        Ok(sheet)
    }

    /// Makes room at setup for [`SheetSettings::reserved_vertices`] more vertices than the
    /// mesh has, in every buffer a frame refills: the mesh's, the model's, the cone layer's,
    /// the tearing step's, the loads', the state's and the solver's ([`Solver::reserve`];
    /// a tear adds at most two triangles per vertex).
    fn make_room(&mut self) {
        let extra = self.settings.reserved_vertices;
        let vertices = self.mesh.vertex_count() + extra;
        let triangles = self.mesh.triangle_count() + 2 * extra;
        self.mesh.reserve(vertices, triangles);
        self.model.reserve(vertices, triangles);
        self.layer.reserve(vertices, triangles);
        self.tears.reserve(vertices);
        self.loads.reserve(triangles, vertices);
        self.state.x.room_for(vertices);
        self.state.v.room_for(vertices);
        self.propagations.room_for(PROPAGATION_ROOM.max(extra));
        // The solver sizes its room from an analysis of the model as it is (one the solver
        // refuses is reported by the next step, as a failed step).
        if self.solver.analyse(&self.model).is_ok() {
            self.solver.reserve(vertices);
        }
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &SheetSettings<T> {
        &self.settings
    }

    /// The mesh (pattern, positions, velocities, triangles).
    #[must_use]
    pub fn mesh(&self) -> &SheetMesh<T> {
        &self.mesh
    }

    /// The generalized-cone layer of the last frame.
    #[must_use]
    pub fn layer(&self) -> &ConeLayer<T> {
        &self.layer
    }

    /// The tears, their paths and alpha textures.
    #[must_use]
    pub fn tears(&self) -> &Tears<T> {
        &self.tears
    }

    /// Every propagation so far, in order.
    #[must_use]
    pub fn propagations(&self) -> &[Propagation<T>] {
        &self.propagations
    }

    /// The fingers.
    #[must_use]
    pub fn fingers(&self) -> &[Finger<T>] {
        &self.fingers
    }

    /// Frames stepped.
    #[must_use]
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// The model (terms, masses, held vertices).
    #[must_use]
    pub fn model(&self) -> &SheetModel<T> {
        &self.model
    }

    /// A finger pinching the sheet at pattern point `at`: the vertex there, or a new one
    /// inserted at it (snapped to a vertex or an edge within the tearing snap distance), and
    /// every vertex within [`SheetSettings::finger_radius`] of it that no other finger holds.
    /// Returns the finger's index; the finger starts where the point is.
    ///
    /// # Errors
    /// [`TearingSheetError::FingerOffSheet`], [`TearingSheetError::CoincidentFingers`] (the
    /// point's vertex is held already); the sheet is unchanged then.
    pub fn grab(&mut self, at: [T; 2]) -> Result<usize, TearingSheetError> {
        if !(at[0].is_finite() && at[1].is_finite()) || self.mesh.locate(at).is_none() {
            return Err(TearingSheetError::FingerOffSheet);
        }
        // The finger's vertex is inserted in place; anything refused after it puts the mesh
        // back (a checkpoint, not a clone: the clone would drop the mesh's reserved room).
        self.mesh.checkpoint();
        let placed = self.place_finger(at);
        if placed.is_err() {
            self.mesh.rollback();
        }
        let (vertex, pads, held) = placed?;
        self.topology_seen = self.mesh.topology_version();
        self.held = held;
        self.pads = pads;
        self.centres.push(vertex);
        self.sync_state();
        self.make_room();
        let finger = self.fingers.len();
        self.fingers.push(Finger {
            vertex,
            target: self.mesh.positions()[vertex as usize],
        });
        Ok(finger)
    }

    /// [`TearingSheet::grab`]'s edit: the vertex at `at` (inserted or snapped to) in
    /// `self.mesh`, the pads with the new finger's, the held vertices, and the model rebuilt
    /// for them. On error the model is unchanged; the mesh may hold the new vertex.
    #[allow(clippy::type_complexity)]
    fn place_finger(
        &mut self,
        at: [T; 2],
    ) -> Result<(u32, Vec<PadVertex<T>>, Vec<u32>), TearingSheetError> {
        let mesh = &mut self.mesh;
        let vertex = mesh
            .insert_at(at, T::from_f64(self.settings.tearing.snap))
            .map_err(|_| TearingSheetError::FingerOffSheet)?;
        if self.held.contains(&vertex) {
            return Err(TearingSheetError::CoincidentFingers { vertex });
        }
        let finger = self.fingers.len();
        let centre = mesh.positions()[vertex as usize];
        let mut pads = self.pads.clone();
        pads.push(PadVertex {
            vertex,
            finger,
            offset: T::Vec3::ZERO,
        });
        for i in pad_vertices(mesh, vertex, self.settings.finger_radius) {
            if i != vertex && !self.held.contains(&i) {
                pads.push(PadVertex {
                    vertex: i,
                    finger,
                    offset: mesh.positions()[i as usize] - centre,
                });
            }
        }
        let held: Vec<u32> = pads.iter().map(|h| h.vertex).collect();
        self.model.rebuild(&self.mesh, &held, &self.settings)?;
        Ok((vertex, pads, held))
    }

    /// Moves finger `index` to `target` (3D); the sheet follows at the next frame.
    ///
    /// # Errors
    /// [`TearingSheetError::NoSuchFinger`], [`TearingSheetError::NonFiniteTarget`].
    pub fn move_finger(&mut self, index: usize, target: T::Vec3) -> Result<(), TearingSheetError> {
        let finite = folio_kernels::real::vec_is_finite::<T>(target)
            && (0..3).all(|k| folio_kernels::math::abs(target.get(k)) <= T::COORD_MAX);
        if !finite {
            return Err(TearingSheetError::NonFiniteTarget);
        }
        let finger = self
            .fingers
            .get_mut(index)
            .ok_or(TearingSheetError::NoSuchFinger { index })?;
        finger.target = target;
        Ok(())
    }

    /// Lets go of finger `index` (later fingers keep their indices minus one).
    ///
    /// # Errors
    /// [`TearingSheetError::NoSuchFinger`].
    pub fn release(&mut self, index: usize) -> Result<(), TearingSheetError> {
        if index >= self.fingers.len() {
            return Err(TearingSheetError::NoSuchFinger { index });
        }
        let held: Vec<u32> = self
            .pads
            .iter()
            .filter(|h| h.finger != index)
            .map(|h| h.vertex)
            .collect();
        self.model.rebuild(&self.mesh, &held, &self.settings)?;
        self.fingers.remove(index);
        self.centres.remove(index);
        self.pads.retain(|h| h.finger != index);
        for h in &mut self.pads {
            if h.finger > index {
                h.finger -= 1;
            }
        }
        self.held = held;
        Ok(())
    }

    /// One frame (module docs).
    pub fn step(&mut self) -> FrameReport<T> {
        let mut report = FrameReport {
            status: StepStatus::Converged,
            analyses: 0,
            flips: 0,
            propagations: 0,
            last: None,
            refused: 0,
            non_finite_loads: 0,
        };
        self.physics(&mut report, true);
        if self.settings.effects.cones {
            self.layer.update(&self.mesh, &self.settings.cones);
            let flips = self.layer.remesh(&mut self.mesh, &self.settings.cones);
            if flips > 0 {
                report.flips = flips as u32;
                self.mesh_edited();
                self.layer.update(&self.mesh, &self.settings.cones);
            }
        }
        if self.settings.effects.tearing {
            for _ in 0..self.settings.max_propagations {
                self.update_gradients();
                let junctions: &[u32] = if self.settings.effects.cones {
                    &self.layer.junctions
                } else {
                    &[]
                };
                let loads = self.loads.loads(
                    self.settings.stretch_modulus.to_f64(),
                    self.settings.poisson.to_f64(),
                );
                let step = self
                    .tears
                    .step(&mut self.mesh, &loads, &self.centres, junctions);
                if step.refused.is_some() {
                    report.refused += 1;
                }
                report.non_finite_loads += step.non_finite;
                let Some(propagation) = step.propagation else {
                    break;
                };
                report.propagations += 1;
                report.last = Some(propagation);
                self.propagations.push(propagation);
                self.mesh_edited();
                self.physics(&mut report, false);
                if self.settings.effects.cones {
                    self.layer.update(&self.mesh, &self.settings.cones);
                }
            }
        }
        self.frame += 1;
        report
    }

    /// The in-plane stretching gradient of every triangle at its corners, its Eshelby
    /// tensor and its deformation gradient.
    fn update_gradients(&mut self) {
        self.model
            .triangle_loads(self.mesh.positions(), &mut self.loads);
    }

    /// The model after an edit of the mesh: rebuilt (analysis at the next step) when the
    /// connectivity changed, reshaped when only the pattern did. A model the kernels refuse
    /// (never for a mesh that passed its checks) keeps the old one, and the next step
    /// reports the mismatch as a failed step.
    fn mesh_edited(&mut self) {
        if self.topology_seen != self.mesh.topology_version() {
            if self
                .model
                .rebuild(&self.mesh, &self.held, &self.settings)
                .is_ok()
            {
                self.topology_seen = self.mesh.topology_version();
            }
        } else {
            let _ = self.model.reshape(&self.mesh, &self.settings);
        }
        self.sync_state();
    }

    /// Copies the mesh's positions and velocities into the solver state.
    fn sync_state(&mut self) {
        self.state.x.clear();
        self.state.x.extend_from_slice(self.mesh.positions());
        self.state.v.clear();
        self.state.v.extend_from_slice(self.mesh.velocities());
    }

    /// One implicit step: held vertices to their fingers, step, back into the mesh.
    fn physics(&mut self, report: &mut FrameReport<T>, first: bool) {
        let h = self.settings.time_step;
        for pad in &self.pads {
            let i = pad.vertex as usize;
            if first {
                let target = self.fingers[pad.finger].target + pad.offset;
                self.state.v[i] = (target - self.state.x[i]) * (T::ONE / h);
                self.state.x[i] = target;
            } else {
                self.state.v[i] = T::Vec3::ZERO;
            }
        }
        // A model the kernels refused at the last edit is not the mesh's: try again, and
        // take no step on a stale one (a failed step, the mesh kept as it is).
        if self.topology_seen != self.mesh.topology_version()
            && self
                .model
                .rebuild(&self.mesh, &self.held, &self.settings)
                .is_ok()
        {
            self.topology_seen = self.mesh.topology_version();
        }
        let stale = self.topology_seen != self.mesh.topology_version();
        if self.settings.hinge_bending == HingeBending::Folds {
            self.model.orient_hinges(&self.state.x);
        }
        let outcome = if stale {
            Err(())
        } else {
            self.solver
                .step(&self.model, &mut self.state)
                .map_err(|_| ())
        };
        let status = match outcome {
            Ok(r) => {
                if r.analysed {
                    report.analyses += 1;
                }
                r.status
            }
            Err(_) => StepStatus::NumericalFailure,
        };
        if !status.advanced() {
            // The state is the one before the step, plus the finger placements: keep the
            // mesh as it was.
            self.sync_state();
        } else {
            self.mesh.positions_mut().copy_from_slice(&self.state.x);
            self.mesh.velocities_mut().copy_from_slice(&self.state.v);
        }
        if (first || !status.advanced()) && report.status.advanced() {
            report.status = status;
        }
    }
}

/// The vertices of a pad of `radius` at vertex `centre`: those within that pattern
/// distance of `centre` that the sheet connects to it through such vertices, so that a pad
/// next to a tear does not hold the far lip (unless it covers the tip).
fn pad_vertices<T: Real>(mesh: &SheetMesh<T>, centre: u32, radius: T) -> Vec<u32> {
    let p = mesh.pattern()[centre as usize];
    let reach = radius * T::from_f64(1.0 + 1e-6);
    let inside = |v: u32| {
        let q = mesh.pattern()[v as usize];
        (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) <= reach * reach
    };
    let mut seen = alloc::vec![false; mesh.vertex_count()];
    let mut found = alloc::vec![centre];
    if let Some(s) = seen.get_mut(centre as usize) {
        *s = true;
    }
    let mut next = 0;
    while let Some(&v) = found.get(next) {
        next += 1;
        for h in mesh.fan_iter(v) {
            for w in mesh.triangles()[h as usize / 3] {
                if !seen[w as usize] && inside(w) {
                    seen[w as usize] = true;
                    found.push(w);
                }
            }
        }
    }
    found
}
