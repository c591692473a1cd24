//! The render mesh out: size query, then copy into caller buffers.

use crate::failure::Failure;
use crate::guard;
use crate::handle::FolioBookHandle;
use crate::pointer;
use crate::registry;
use crate::status::FolioStatus;

/// `n` as a `u32`; meshes have `u32` indices, so vertex and triangle counts fit.
fn count(n: usize) -> Result<u32, Failure> {
    u32::try_from(n)
        .map_err(|_| Failure::new(FolioStatus::BookError, "the mesh exceeds u32 counts"))
}

/// Writes the vertex and triangle counts of the book's current render mesh (seed `000_…`
/// Sec. 3.5): the page blocks, the cover boards, the active page and the pages in flight,
/// as built by `Book::mesh`. The buffers of `folio_book_mesh_copy` need
/// `3 * vertices` floats (positions, normals), `2 * vertices` floats (UVs) and
/// `3 * triangles` indices. The counts stay valid until the next grab, release or step.
///
/// Returns `FOLIO_STATUS_NULL_POINTER`, `FOLIO_STATUS_STALE_HANDLE`, or
/// `FOLIO_STATUS_BOOK_ERROR` if the book cannot be meshed; on failure nothing is written.
///
/// # Safety
/// `vertices` and `triangles` are NULL or valid for a write of one `uint32_t` each.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn folio_book_mesh_size(
    handle: FolioBookHandle,
    vertices: *mut u32,
    triangles: *mut u32,
) -> FolioStatus {
    guard::call("folio_book_mesh_size", || {
        pointer::check(vertices, "vertices")?;
        pointer::check(triangles, "triangles")?;
        let (v, t) = registry::with_entry(handle, |e| {
            let m = e.mesh()?;
            Ok((count(m.vertex_count())?, count(m.triangle_count())?))
        })?;
        // SAFETY: both checked non-NULL and aligned above; writable by contract.
        unsafe {
            pointer::write(vertices, v, "vertices")?;
            pointer::write(triangles, t, "triangles")
        }
    })
}

/// Copies the book's current render mesh into caller buffers (query the sizes first with
/// `folio_book_mesh_size`). Lengths are in elements, not bytes:
///
/// - `positions`: $3V$ floats, $(x, y, z)$ per vertex, book frame, page units;
/// - `normals`: $3V$ floats, unit normals;
/// - `uvs`: $2V$ floats, texture coordinates in $[0, 1]^2$;
/// - `indices`: $3T$ vertex indices, counter-clockwise seen from the side the normals
///   point to.
///
/// A buffer may be NULL with length 0 to skip it. A longer buffer is filled at its start.
///
/// Returns `FOLIO_STATUS_NULL_POINTER` (NULL with a nonzero length),
/// `FOLIO_STATUS_BUFFER_TOO_SMALL` (the message gives the length needed),
/// `FOLIO_STATUS_INVALID_ARGUMENT` (a misaligned buffer), `FOLIO_STATUS_STALE_HANDLE`,
/// `FOLIO_STATUS_BOOK_ERROR`. Every buffer is checked before any is written: on failure none
/// is.
///
/// # Safety
/// Each buffer is NULL or valid for writes of its length in elements; the buffers may not
/// overlap each other.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)] // Four (pointer, length) pairs: the C idiom.
pub unsafe extern "C" fn folio_book_mesh_copy(
    handle: FolioBookHandle,
    positions: *mut f32,
    positions_len: usize,
    normals: *mut f32,
    normals_len: usize,
    uvs: *mut f32,
    uvs_len: usize,
    indices: *mut u32,
    indices_len: usize,
) -> FolioStatus {
    guard::call("folio_book_mesh_copy", || {
        registry::with_entry(handle, |e| {
            let m = e.mesh()?;
            let (v, t) = (m.vertex_count(), m.triangle_count());
            let copy = [
                pointer::check_buffer(
                    positions,
                    positions_len,
                    3 * v,
                    true,
                    "positions",
                    "floats",
                )?,
                pointer::check_buffer(normals, normals_len, 3 * v, true, "normals", "floats")?,
                pointer::check_buffer(uvs, uvs_len, 2 * v, true, "uvs", "floats")?,
                pointer::check_buffer(indices, indices_len, 3 * t, true, "indices", "indices")?,
            ];
            // SAFETY: (all four copies) a buffer is copied only when `check_buffer` found it
            // non-NULL, aligned and at least as long as the source; by contract it is valid
            // for writes of its length; the sources are the cached mesh's vectors.
            unsafe {
                if copy[0] {
                    pointer::copy_into(positions, m.positions.as_flattened());
                }
                if copy[1] {
                    pointer::copy_into(normals, m.normals.as_flattened());
                }
                if copy[2] {
                    pointer::copy_into(uvs, m.uvs.as_flattened());
                }
                if copy[3] {
                    pointer::copy_into(indices, m.triangles.as_flattened());
                }
            }
            Ok(())
        })
    })
}
