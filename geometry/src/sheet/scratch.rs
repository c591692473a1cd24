//! [`Scratch`]: the working buffers of a `SheetMesh`'s edits and checks, kept between
//! them so that an edit allocates nothing once `SheetMesh::reserve` has made room (a tear
//! edits the mesh inside a frame, and frames do not allocate: DESIGN.md).
//!
//! A clone of a mesh starts with empty buffers: they hold nothing between two calls, so only
//! their capacity is lost, and a cloned mesh is set up again with `SheetMesh::reserve`.

use alloc::vec::Vec;

use folio_kernels::Real;

/// A copy of the mesh's arrays and versions: before the running edit (restored when the
/// edited mesh fails its check), or at the caller's checkpoint
/// (`SheetMesh::checkpoint`).
#[derive(Debug)]
pub(crate) struct Backup<T: Real> {
    pub topology_version: u64,
    pub shape_version: u64,
    pub pattern: Vec<[T; 2]>,
    pub positions: Vec<T::Vec3>,
    pub velocities: Vec<T::Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub twins: Vec<u32>,
    pub outgoing: Vec<u32>,
}

/// Working buffers of the edits (module docs).
#[derive(Debug)]
pub(crate) struct Scratch<T: Real> {
    pub backup: Backup<T>,
    /// The caller's checkpoint, for a change made of several edits.
    pub checkpoint: Backup<T>,
    /// `(low end, high end, half-edge)` of every half-edge: the adjacency rebuild's sort.
    pub keys: Vec<(u32, u32, u32)>,
    /// Triangles per vertex: the manifold check's count.
    pub seen: Vec<usize>,
    /// A list of triangles: those near a vertex (`SheetMesh::improve_around`), the fans
    /// a cut moves to the new vertices (`SheetMesh::cut_edge`).
    pub triangles: Vec<usize>,
}

impl<T: Real> Default for Backup<T> {
    fn default() -> Self {
        Self {
            topology_version: 0,
            shape_version: 0,
            pattern: Vec::new(),
            positions: Vec::new(),
            velocities: Vec::new(),
            triangles: Vec::new(),
            twins: Vec::new(),
            outgoing: Vec::new(),
        }
    }
}

impl<T: Real> Default for Scratch<T> {
    fn default() -> Self {
        Self {
            backup: Backup::default(),
            checkpoint: Backup::default(),
            keys: Vec::new(),
            seen: Vec::new(),
            triangles: Vec::new(),
        }
    }
}

impl<T: Real> Scratch<T> {
    /// The backup `slot`.
    pub(super) fn slot(&mut self, slot: Slot) -> &mut Backup<T> {
        match slot {
            Slot::Edit => &mut self.backup,
            Slot::Checkpoint => &mut self.checkpoint,
        }
    }
}

impl<T: Real> Clone for Scratch<T> {
    /// Empty buffers (module docs): scratch carries no state from one call to the next.
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// The arrays a mesh and each of its backups hold, borrowed: what is done to all of them
/// alike is written once.
pub(super) struct Arrays<'a, T: Real> {
    pub pattern: &'a mut Vec<[T; 2]>,
    pub positions: &'a mut Vec<T::Vec3>,
    pub velocities: &'a mut Vec<T::Vec3>,
    pub triangles: &'a mut Vec<[u32; 3]>,
    pub twins: &'a mut Vec<u32>,
    pub outgoing: &'a mut Vec<u32>,
}

/// The [`Arrays`] of a mesh or a backup, which name their arrays alike.
macro_rules! arrays_of {
    ($owner:expr) => {
        Arrays {
            pattern: &mut $owner.pattern,
            positions: &mut $owner.positions,
            velocities: &mut $owner.velocities,
            triangles: &mut $owner.triangles,
            twins: &mut $owner.twins,
            outgoing: &mut $owner.outgoing,
        }
    };
}
pub(super) use arrays_of;

impl<T: Real> Arrays<'_, T> {
    /// Room for a mesh of `v` vertices and `t` triangles.
    pub(super) fn reserve(self, v: usize, t: usize) {
        room(self.pattern, v);
        room(self.positions, v);
        room(self.velocities, v);
        room(self.outgoing, v);
        room(self.triangles, t);
        room(self.twins, 3 * t);
    }

    /// Copies every array between the mesh's (`self`) and a backup's (`kept`), the `way`
    /// given.
    pub(super) fn copy(self, kept: Arrays<'_, T>, way: Way) {
        copy_between(self.pattern, kept.pattern, way);
        copy_between(self.positions, kept.positions, way);
        copy_between(self.velocities, kept.velocities, way);
        copy_between(self.triangles, kept.triangles, way);
        copy_between(self.twins, kept.twins, way);
        copy_between(self.outgoing, kept.outgoing, way);
    }
}

impl<T: Real> Backup<T> {
    /// The backup's arrays.
    pub(super) fn arrays(&mut self) -> Arrays<'_, T> {
        arrays_of!(self)
    }
}

/// Which of the scratch's backups a copy uses.
#[derive(Clone, Copy, Debug)]
pub(super) enum Slot {
    /// The running edit's backup.
    Edit,
    /// The caller's checkpoint.
    Checkpoint,
}

/// Which way a copy runs.
#[derive(Clone, Copy, Debug)]
pub(super) enum Way {
    /// From the mesh into the backup.
    Save,
    /// From the backup into the mesh.
    Restore,
}

/// Copies one array between the mesh (`live`) and a backup (`kept`) the `way` given.
fn copy_between<E: Copy>(live: &mut Vec<E>, kept: &mut Vec<E>, way: Way) {
    match way {
        Way::Save => copy_into(kept, live),
        Way::Restore => copy_into(live, kept),
    }
}

/// Replaces `to`'s contents with `from`'s, within `to`'s capacity when it suffices.
pub(crate) fn copy_into<E: Copy>(to: &mut Vec<E>, from: &[E]) {
    to.clear();
    to.extend_from_slice(from);
}

/// Capacity for `total` elements in `v`.
pub(crate) fn room<E>(v: &mut Vec<E>, total: usize) {
    v.reserve(total.saturating_sub(v.len()));
}
