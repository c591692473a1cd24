//! What a handle names: the book and its render mesh, cached between the size query and the
//! copy.

use folio_geometry::mesh::TriMesh;

use crate::any_book::AnyBook;
use crate::failure::Failure;
use crate::status::FolioStatus;
use crate::step_report::FolioStepReport;

/// A live book of the registry.
#[derive(Debug)]
pub(crate) struct Entry {
    /// The book.
    pub book: AnyBook,
    /// [`folio_book::Book::mesh`] of the current state, when `mesh_fresh`.
    mesh: TriMesh,
    /// `false` after anything that may change the mesh (grab, release, step).
    mesh_fresh: bool,
}

impl Entry {
    /// A book with no mesh built yet.
    pub fn new(book: AnyBook) -> Self {
        Self {
            book,
            mesh: TriMesh::new(),
            mesh_fresh: false,
        }
    }

    /// Marks the cached mesh out of date; every call that can move or add geometry calls it.
    pub fn touch(&mut self) {
        self.mesh_fresh = false;
    }

    /// One step (see `folio_book_step`).
    pub fn step(&mut self) -> Result<FolioStepReport, Failure> {
        self.touch();
        self.book.step().map_err(Failure::book)
    }

    /// The mesh of the current state, built now if it is out of date (the storage of the
    /// previous mesh is reused).
    ///
    /// # Errors
    /// `BOOK_ERROR` when the book cannot be meshed (a non-finite node).
    pub fn mesh(&mut self) -> Result<&TriMesh, Failure> {
        if !self.mesh_fresh {
            self.mesh.clear();
            self.book.mesh(&mut self.mesh).map_err(|e| {
                Failure::new(FolioStatus::BookError, format!("cannot mesh the book: {e}"))
            })?;
            self.mesh_fresh = true;
        }
        Ok(&self.mesh)
    }
}
