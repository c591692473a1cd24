//! [`SheetModel`]: the sheet as a [`Model`] of the implicit step (seed `002_…` Sec. 5.1,
//! "the standard FEM used by the physical simulation step"):
//! $$V(x) = \sum_{t} V^{\text{membrane}}_t(x) + w_b \sum_{e} V^{\text{hinge}}_e(x) + g \sum_i m_i\thinspace y_i,$$
//! one [`Membrane`] per triangle (Saint Venant–Kirchhoff on the pattern, stiff: paper barely
//! stretches), one [`Hinge`] per interior edge (the quadratic bending of a flat-rest sheet),
//! gravity when on. Masses are lumped: a third of each triangle's pattern area times the
//! density at each corner. A finger holds its vertex: all three coordinates are eliminated
//! and follow the finger (DESIGN.md: fixed coordinates are eliminated, not constrained).
//!
//! The terms are rebuilt from the mesh when its shape changes (a tip slides: new rest
//! shapes, same stencils); the topology version changes only when the mesh's connectivity or
//! the set of held vertices does, and only then does the solver re-run its analysis.

use alloc::vec::Vec;

use folio_geometry::SheetMesh;
use folio_geometry::sheet::{NONE, next_half_edge};
use folio_kernels::gravity::Gravity;
use folio_kernels::hinge::Hinge;
use folio_kernels::membrane::Membrane;
use folio_kernels::{Potential, Real, SettingError};

use super::error::TearingSheetError;
use super::settings::SheetSettings;
use crate::release::LoadBuffers;
use folio_solvers::model::{Model, PotentialSet, TermVisitor};
use folio_solvers::room::Room;

/// The sheet's terms, masses and held vertices (module docs).
#[derive(Clone, Debug)]
pub struct SheetModel<T: Real> {
    version: u64,
    terms: Terms<T>,
    /// Where a rebuild fills the new terms before they replace [`SheetModel::terms`] (so a
    /// rebuild the kernels refuse leaves the model unchanged); it keeps the old terms'
    /// buffers, and the next rebuild refills them without allocating.
    spare: Terms<T>,
}

/// What [`SheetModel`] sums: the held vertices, the lumped masses and the terms.
#[derive(Clone, Debug)]
struct Terms<T: Real> {
    held: Vec<bool>,
    masses: Vec<T>,
    membranes: PotentialSet<T, Membrane<T>, 3>,
    hinges: PotentialSet<T, Hinge<T>, 4>,
    gravity: PotentialSet<T, Gravity<T>, 1>,
}

impl<T: Real> SheetModel<T> {
    /// The model of `mesh` with the vertices `held` by fingers.
    ///
    /// # Errors
    /// [`TearingSheetError::Kernel`] for a triangle or hinge the kernels refuse.
    pub fn new(
        mesh: &SheetMesh<T>,
        held: &[u32],
        settings: &SheetSettings<T>,
    ) -> Result<Self, TearingSheetError> {
        let mut model = Self {
            version: 0,
            terms: Terms::empty(settings),
            spare: Terms::empty(settings),
        };
        model.rebuild(mesh, held, settings)?;
        Ok(model)
    }

    /// Makes room for a mesh of `vertices` vertices and `triangles` triangles in all: a
    /// rebuild or reshape within it allocates nothing.
    pub fn reserve(&mut self, vertices: usize, triangles: usize) {
        self.terms.reserve(vertices, triangles);
        self.spare.reserve(vertices, triangles);
    }

    /// Rebuilds every term from `mesh` and `held` and bumps the topology version (call it
    /// after a topology edit or a change of fingers). On error the model is unchanged.
    ///
    /// # Errors
    /// As [`SheetModel::new`].
    pub fn rebuild(
        &mut self,
        mesh: &SheetMesh<T>,
        held: &[u32],
        settings: &SheetSettings<T>,
    ) -> Result<(), TearingSheetError> {
        let n = mesh.vertex_count();
        let spare = &mut self.spare;
        spare.held.clear();
        spare.held.resize(n, false);
        for &v in held {
            if let Some(h) = spare.held.get_mut(v as usize) {
                *h = true;
            }
        }
        spare.fill(mesh, settings)?;
        core::mem::swap(&mut self.terms, &mut self.spare);
        self.version += 1;
        Ok(())
    }

    /// Rebuilds the terms' rest shapes and the masses from the mesh's pattern, keeping the
    /// stencils and the topology version (after a tip slid). On error the model is
    /// unchanged.
    ///
    /// # Errors
    /// As [`SheetModel::new`].
    pub fn reshape(
        &mut self,
        mesh: &SheetMesh<T>,
        settings: &SheetSettings<T>,
    ) -> Result<(), TearingSheetError> {
        self.spare.held.clear();
        self.spare.held.extend_from_slice(&self.terms.held);
        self.spare.fill(mesh, settings)?;
        core::mem::swap(&mut self.terms, &mut self.spare);
        Ok(())
    }

    /// The membrane kernel of every triangle, in triangle order.
    #[must_use]
    pub fn membranes(&self) -> &PotentialSet<T, Membrane<T>, 3> {
        &self.terms.membranes
    }

    /// What the tearing step reads of every triangle at positions `x`, into `buffers`
    /// (cleared first): the stretching gradient at its corners, its Eshelby tensor
    /// ([`Membrane::eshelby`]), its deformation gradient and its stress; and which vertices
    /// are held.
    pub fn triangle_loads(&self, x: &[T::Vec3], buffers: &mut LoadBuffers<T>) {
        buffers.gradients.clear();
        buffers.eshelby.clear();
        buffers.deformations.clear();
        buffers.stresses.clear();
        buffers.prescribed.clear();
        buffers.prescribed.extend_from_slice(&self.terms.held);
        for term in self.terms.membranes.terms() {
            let local = term.nodes.map(|i| x[i as usize]);
            buffers.gradients.push(term.kernel.gradient(&local));
            buffers.eshelby.push(term.kernel.eshelby(&local));
            let (f0, f1) = term.kernel.deformation_gradient(&local);
            buffers.deformations.push([f0, f1]);
            buffers.stresses.push(term.kernel.stress(&local));
        }
    }

    /// Points every hinge's normal along its two triangles' mean normal at positions `x`
    /// ([`Hinge::orient`]): called at the start of each step, so that the bending counts
    /// only the hinges' folds, not in-plane deformation.
    pub fn orient_hinges(&mut self, x: &[T::Vec3]) {
        for term in self.terms.hinges.terms_mut() {
            let local = term.nodes.map(|i| x[i as usize]);
            term.kernel.orient(&local);
        }
    }

    /// The hinges (interior edges).
    #[must_use]
    pub fn hinges(&self) -> &PotentialSet<T, Hinge<T>, 4> {
        &self.terms.hinges
    }

    /// `true` when `node` is held by a finger.
    #[must_use]
    pub fn is_held(&self, node: usize) -> bool {
        self.terms.held.get(node).copied().unwrap_or(false)
    }
}

impl<T: Real> Terms<T> {
    /// No vertex, no term; the hinges weighted by the settings' bending modulus.
    fn empty(settings: &SheetSettings<T>) -> Self {
        Self {
            held: Vec::new(),
            masses: Vec::new(),
            membranes: PotentialSet::new(T::ONE),
            hinges: PotentialSet::new(settings.bending),
            gravity: PotentialSet::new(T::ONE),
        }
    }

    /// Room for `vertices` vertices and `triangles` triangles (at most three hinges per
    /// triangle, one gravity term per vertex).
    fn reserve(&mut self, vertices: usize, triangles: usize) {
        self.held.room_for(vertices);
        self.masses.room_for(vertices);
        self.membranes.reserve(triangles);
        self.hinges.reserve(3 * triangles);
        self.gravity.reserve(vertices);
    }

    /// Fills the masses and terms of `mesh` (the held vertices are set by the caller).
    fn fill(
        &mut self,
        mesh: &SheetMesh<T>,
        settings: &SheetSettings<T>,
    ) -> Result<(), TearingSheetError> {
        let n = mesh.vertex_count();
        self.masses.clear();
        self.masses.resize(n, T::ZERO);
        self.membranes.reset(T::ONE);
        self.hinges.reset(settings.bending);
        self.gravity.reset(T::ONE);
        let p = mesh.pattern();
        let third = T::ONE / T::from_f64(3.0);
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let corners = tri.map(|i| p[i as usize]);
            let membrane = Membrane::new(corners, settings.stretch_modulus, settings.poisson)
                .map_err(|_| TearingSheetError::Kernel { index: t })?
                .with_law(settings.membrane_law());
            self.membranes.push(membrane, *tri);
            let share = mesh.pattern_area(t) * settings.density * third;
            for &i in tri {
                self.masses[i as usize] += share;
            }
        }
        if settings.effects.bending {
            for h in 0..3 * mesh.triangle_count() as u32 {
                let g = mesh.twin(h);
                if g == NONE || g < h {
                    continue;
                }
                let (a, b) = mesh.half_edge(h);
                let c = mesh.half_edge(next_half_edge(h)).1;
                let d = mesh.half_edge(next_half_edge(g)).1;
                let nodes = [a, b, c, d];
                let hinge = Hinge::new(nodes.map(|i| p[i as usize])).map_err(|_| {
                    TearingSheetError::Kernel {
                        index: h as usize / 3,
                    }
                })?;
                self.hinges.push(hinge, nodes);
            }
        }
        if settings.effects.gravity {
            for (i, &m) in self.masses.iter().enumerate() {
                let term = Gravity::new(settings.gravity, m)
                    .map_err(|_| SettingError::new("gravity", "finite"))?;
                self.gravity.push(term, [i as u32]);
            }
        }
        Ok(())
    }
}

impl<T: Real> Model<T> for SheetModel<T> {
    fn topology_version(&self) -> u64 {
        self.version
    }

    fn node_count(&self) -> usize {
        self.terms.masses.len()
    }

    fn is_fixed(&self, node: usize, _axis: usize) -> bool {
        self.is_held(node)
    }

    fn mass(&self, node: usize) -> T {
        self.terms.masses.get(node).copied().unwrap_or(T::ZERO)
    }

    fn visit_terms<V: TermVisitor<T>>(&self, visitor: &mut V) {
        visitor.potentials(&self.terms.membranes);
        visitor.potentials(&self.terms.hinges);
        visitor.potentials(&self.terms.gravity);
    }
}
