//! # folio-tearing
//!
//! Interactive paper tearing after seed `002_…` (Schreck, Rohmer, Hahmann, *Interactive
//! paper tearing*), `no_std` + `alloc`: the tearing sheet's physics and the tearing itself.
//!
//! - [`candidates`]: the potential tearing points (Sec. 4.1).
//! - [`fiber`]: the seeded Perlin fiber texture $T_{\text{fibers}}(u, v)$ (Sec. 4.2).
//! - [`split`]: the force split, release rate and direction (Sec. 5.1-5.2, eq. 4-6).
//! - [`release`]: the energy a tear releases over a disk of fixed size, the $J$-integral
//!   (independent of the mesh).
//! - [`advance`]: one propagation on the sheet mesh, split or slide (Sec. 5.3, Fig. 8).
//! - [`tears`]: [`Tears`], the tearing step: fracture energy (eq. 3), Griffith (eq. 1),
//!   propagation, the tears' paths and textures.
//! - [`detail`]: the stochastic detail path between two tear tips (Sec. 6.1, eq. 7).
//! - [`texture`]: the left and right alpha textures cut along a detail path (Sec. 6.2).
//! - [`settings`]: the settings of the tearing step, [`TearSettings`].
//! - [`sheet`]: the sheet's physics: [`sheet::SheetModel`] (membranes, hinges, gravity,
//!   fingers) stepped by `folio-solvers`, and [`sheet::TearingSheet`], a frame of physics,
//!   cone remesh and tearing.
//!
//! Layers: `folio-kernels` (membrane and hinge terms), `folio-geometry` (the sheet mesh, its
//! edits and the cone layer) and `folio-solvers` (the implicit step) below.
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

pub mod advance;
pub mod candidates;
pub mod detail;
pub mod fiber;
pub mod mixity;
pub mod release;
pub mod settings;
pub mod sheet;
pub mod split;
pub mod tears;
pub mod texture;

pub use advance::Edit;
pub use candidates::{Candidate, Kind};
pub use release::{LoadBuffers, TriangleLoads};
pub use settings::{Estimator, TearSettings, TipRemesh};
pub use split::Split;
pub use tears::{Evaluation, Propagation, Tear, TearStep, Tears};
pub use texture::{AlphaPair, PathProfile, Side};
