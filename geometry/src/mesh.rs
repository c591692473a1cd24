//! Triangle meshes for rendering the book (seed `000_…` Sec. 3.5 "Meshing", Fig. 9).
//!
//! The simulation state becomes geometry by normal offsetting and extrusion:
//!
//! - [`page_mesh`]: the active page's nodes offset by $\pm t/2$ along the vertex normals
//!   (front and back), joined by a rim; each grid row is length-adapted to the page width.
//! - [`block_mesh`]: a page block's planar midline offset in XY by the block thickness, with
//!   several offset directions at the binding node ("upsampling at binding": a rounded
//!   profile) and the top curve length-adapted to the midline ("segment length adaptation":
//!   the sheared fore-edge), extruded along Z.
//! - [`cover_mesh`]: a hard-cover board as a box.
//!
//! Every builder appends to a [`TriMesh`] (f32 positions, unit normals, UVs in $[0, 1]^2$,
//! counter-clockwise triangles seen from the side the normals point to, one [`Surface`] per
//! triangle). Builders validate their input first and return a [`MeshError`] without touching
//! the mesh; valid but degenerate input (coincident nodes, collinear differences, folded
//! polylines) takes the documented fallback of each function and never yields NaN.
//! The f64 geometry behind the page and block meshes is public ([`PageSurfaces`],
//! [`BlockCurves`], [`adapt_length`]) so that it can be inspected and tested before the cast
//! to f32. The builders allocate temporary f64 storage proportional to their input.

mod adapt;
mod block;
mod cover;
mod error;
mod page;
mod trimesh;
mod vector;

pub use adapt::{MIN_END_FRACTION, adapt_length};
pub use block::{BlockCurves, BlockProfile, BlockSide, block_mesh};
pub use cover::cover_mesh;
pub use error::MeshError;
pub use page::{PageSurfaces, page_mesh};
pub use trimesh::{Surface, TriMesh};

/// Largest magnitude (page units) of an input coordinate or length the builders accept
/// (larger ones give [`MeshError::CoordinateTooLarge`] or [`MeshError::OutOfRange`]), so
/// that every output coordinate stays finite after the cast to `f32`
/// (`f32::MAX` $\approx 3.4 \cdot 10^{38}$).
pub const MAX_COORDINATE: f64 = 1e20;
