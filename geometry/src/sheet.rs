//! The tearing sheet (seed `002_…` Sec. 3, 5.3, App. A): a coarse triangle mesh that carries
//! both the flat 2D pattern of the paper and its 3D deformed shape, with the edits a tear
//! makes and the generalized-cone layer that guides the mesh.
//!
//! - [`SheetMesh`]: vertices with pattern coordinates $(u, v)$, 3D positions and velocities;
//!   triangles counter-clockwise in the pattern; adjacency, fans and boundary loops.
//! - [`edit`]: insert a vertex in a triangle or on an edge, cut an edge (splitting its
//!   boundary end points into two tear lips), move a tear tip (removing it from the
//!   boundary, seed Fig. 8), flip an edge.
//! - [`quality`]: the triangles' smallest pattern angles and the local Delaunay flips that
//!   keep them well shaped where a tear edits the mesh.
//! - [`cones`]: flat and curved (generalized-cone) regions from the discrete curvature,
//!   ruling directions, junction points, and the remesh toward the rulings.
//!
//! Units: pattern and positions in sheet units, velocities in sheet units per second.

pub mod cones;
pub mod edit;
mod error;
mod mesh;
pub mod quality;
mod rollback;
mod scratch;

pub use cones::{ConeLayer, ConeLayerSettings, Region};
pub use edit::Cut;
pub use error::SheetError;
pub use mesh::{
    FanIter, NONE, SheetMesh, dist2 as pattern_distance2, longest_edge2, next as next_half_edge,
    prev as prev_half_edge,
};
