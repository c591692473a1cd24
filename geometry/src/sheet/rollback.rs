//! A sheet mesh's room and its backups: [`SheetMesh::reserve`] makes room in the mesh and in
//! its scratch ([`super::scratch`]), [`SheetMesh::checkpoint`] and [`SheetMesh::rollback`]
//! keep and restore the caller's copy, and an edit saves and restores its own.

use folio_kernels::Real;

use super::mesh::SheetMesh;
use super::scratch::{Arrays, Slot, Way, arrays_of, room};

/// Entries reserved for a list of triangles: a longer list makes its buffer grow once.
const TRIANGLE_LIST_ROOM: usize = 256;

impl<T: Real> SheetMesh<T> {
    /// Makes room for a mesh of `vertices` vertices and `triangles` triangles in all, in the
    /// mesh and in the buffers its edits work in (module docs): edits that keep the mesh
    /// within this room allocate nothing.
    pub fn reserve(&mut self, vertices: usize, triangles: usize) {
        let (v, t) = (vertices, triangles);
        self.arrays().reserve(v, t);
        let s = &mut self.scratch;
        s.backup.arrays().reserve(v, t);
        s.checkpoint.arrays().reserve(v, t);
        room(&mut s.keys, 3 * t);
        room(&mut s.seen, v);
        room(&mut s.triangles, TRIANGLE_LIST_ROOM);
    }

    /// Remembers the sheet as it is, for [`SheetMesh::rollback`]: a change made of several
    /// edits, where a later one may refuse after an earlier one took. Within the room made
    /// by [`SheetMesh::reserve`] it allocates nothing.
    pub fn checkpoint(&mut self) {
        self.copy(Slot::Checkpoint, Way::Save);
    }

    /// Puts the sheet back as it was at the last [`SheetMesh::checkpoint`] (or as it was
    /// made, with no checkpoint taken: nothing is restored then).
    pub fn rollback(&mut self) {
        if !self.scratch.checkpoint.pattern.is_empty() {
            self.copy(Slot::Checkpoint, Way::Restore);
        }
    }

    /// Copies the arrays into the edit backup.
    pub(crate) fn save(&mut self) {
        self.copy(Slot::Edit, Way::Save);
    }

    /// Restores the arrays from the edit backup.
    pub(crate) fn restore(&mut self) {
        self.copy(Slot::Edit, Way::Restore);
    }

    /// Copies the arrays and versions between the mesh and the backup `slot`, the `way`
    /// given.
    fn copy(&mut self, slot: Slot, way: Way) {
        // Taken out (an empty backup allocates nothing) so that the mesh can lend its arrays.
        let mut b = core::mem::take(self.scratch.slot(slot));
        match way {
            Way::Save => {
                (b.topology_version, b.shape_version) = (self.topology_version, self.shape_version)
            }
            Way::Restore => {
                (self.topology_version, self.shape_version) = (b.topology_version, b.shape_version)
            }
        }
        self.arrays().copy(b.arrays(), way);
        *self.scratch.slot(slot) = b;
    }

    /// The mesh's arrays.
    fn arrays(&mut self) -> Arrays<'_, T> {
        arrays_of!(self)
    }
}
