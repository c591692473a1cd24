//! [`Scratch`]: the working buffers of a [`SheetMesh`]'s edits and checks, kept between
//! them so that an edit allocates nothing once [`SheetMesh::reserve`] has made room (a tear
//! edits the mesh inside a frame, and frames do not allocate: DESIGN.md).
//!
//! A clone of a mesh starts with empty buffers: they hold nothing between two calls, so only
//! their capacity is lost, and a cloned mesh is set up again with [`SheetMesh::reserve`].

use alloc::vec::Vec;

use folio_kernels::Real;

use super::mesh::SheetMesh;

/// A copy of the mesh's arrays and versions: before the running edit (restored when the
/// edited mesh fails its check), or at the caller's checkpoint
/// ([`SheetMesh::checkpoint`]).
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
    /// A list of triangles: those near a vertex ([`SheetMesh::improve_around`]), the fans
    /// a cut moves to the new vertices ([`SheetMesh::cut_edge`]).
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

impl<T: Real> Clone for Scratch<T> {
    /// Empty buffers (module docs): scratch carries no state from one call to the next.
    fn clone(&self) -> Self {
        Self::default()
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

/// Entries reserved for a list of triangles: a longer list makes its buffer grow once.
const TRIANGLE_LIST_ROOM: usize = 256;

impl<T: Real> SheetMesh<T> {
    /// Makes room for a mesh of `vertices` vertices and `triangles` triangles in all, in the
    /// mesh and in the buffers its edits work in (module docs): edits that keep the mesh
    /// within this room allocate nothing.
    pub fn reserve(&mut self, vertices: usize, triangles: usize) {
        let (v, t) = (vertices, triangles);
        room(&mut self.pattern, v);
        room(&mut self.positions, v);
        room(&mut self.velocities, v);
        room(&mut self.outgoing, v);
        room(&mut self.triangles, t);
        room(&mut self.twins, 3 * t);
        let s = &mut self.scratch;
        for b in [&mut s.backup, &mut s.checkpoint] {
            room(&mut b.pattern, v);
            room(&mut b.positions, v);
            room(&mut b.velocities, v);
            room(&mut b.outgoing, v);
            room(&mut b.triangles, t);
            room(&mut b.twins, 3 * t);
        }
        room(&mut s.keys, 3 * t);
        room(&mut s.seen, v);
        room(&mut s.triangles, TRIANGLE_LIST_ROOM);
    }

    /// Remembers the sheet as it is, for [`SheetMesh::rollback`]: a change made of several
    /// edits, where a later one may refuse after an earlier one took. Within the room made
    /// by [`SheetMesh::reserve`] it allocates nothing.
    pub fn checkpoint(&mut self) {
        let mut b = core::mem::take(&mut self.scratch.checkpoint);
        self.copy_to(&mut b);
        self.scratch.checkpoint = b;
    }

    /// Puts the sheet back as it was at the last [`SheetMesh::checkpoint`] (or as it was
    /// made, with no checkpoint taken: nothing is restored then).
    pub fn rollback(&mut self) {
        let b = core::mem::take(&mut self.scratch.checkpoint);
        if !b.pattern.is_empty() {
            self.copy_from(&b);
        }
        self.scratch.checkpoint = b;
    }

    /// Copies the arrays into the edit backup.
    pub(crate) fn save(&mut self) {
        let mut b = core::mem::take(&mut self.scratch.backup);
        self.copy_to(&mut b);
        self.scratch.backup = b;
    }

    /// Restores the arrays from the edit backup.
    pub(crate) fn restore(&mut self) {
        let b = core::mem::take(&mut self.scratch.backup);
        self.copy_from(&b);
        self.scratch.backup = b;
    }

    fn copy_to(&self, b: &mut Backup<T>) {
        b.topology_version = self.topology_version;
        b.shape_version = self.shape_version;
        copy_into(&mut b.pattern, &self.pattern);
        copy_into(&mut b.positions, &self.positions);
        copy_into(&mut b.velocities, &self.velocities);
        copy_into(&mut b.triangles, &self.triangles);
        copy_into(&mut b.twins, &self.twins);
        copy_into(&mut b.outgoing, &self.outgoing);
    }

    fn copy_from(&mut self, b: &Backup<T>) {
        self.topology_version = b.topology_version;
        self.shape_version = b.shape_version;
        copy_into(&mut self.pattern, &b.pattern);
        copy_into(&mut self.positions, &b.positions);
        copy_into(&mut self.velocities, &b.velocities);
        copy_into(&mut self.triangles, &b.triangles);
        copy_into(&mut self.twins, &b.twins);
        copy_into(&mut self.outgoing, &b.outgoing);
    }
}
