//! # folio-geometry
//!
//! Geometry of Folio's book (seed `000_…` Sec. 3): `no_std` + `alloc`.
//!
//! - [`grid`]: the active page's DOG quad grid, its stars and edges.
//! - [`collision`]: the 2D collision projection of Sec. 3.4.
//! - [`mesh`]: the triangle mesh for rendering of Sec. 3.5.
//! - [`sheet`]: the tearing sheet of seed `002_…`: a coarse triangle mesh with its 2D
//!   pattern, the edits of a tear, and the generalized-cone layer.
//!
//! Axes (seed Sec. 3.1): X across the open book, Y up (pages stack along Y, gravity is −Y),
//! Z along the binding. Lengths in page units (a page is 12 wide by default).
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

pub mod collision;
pub mod grid;
pub mod mesh;
pub mod sheet;

pub use collision::{Bounds, Contacts, Corner, Floor, Obstacle, Wall};
pub use grid::{QuadGrid, Star};
pub use mesh::BlockSide;
pub use sheet::{SheetError, SheetMesh};
