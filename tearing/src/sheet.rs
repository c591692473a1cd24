//! The tearing sheet of seed `002_…`: a coarse triangle sheet of paper held by fingers,
//! simulated by the implicit step with in-plane stretching and bending, remeshed toward its
//! generalized cones, and torn (feature `tearing`).
//!
//! - [`SheetSettings`]: the sheet, its material and the effects a scene calls for.
//! - [`SheetModel`]: the [`folio_solvers::Model`] of the sheet (membranes, hinges, gravity;
//!   fingers eliminate the coordinates they hold).
//! - [`TearingSheet`]: one frame = physics, cone layer and remesh, tearing with a
//!   relaxation step after each propagation ([`FrameReport`]).

mod error;
mod model;
mod settings;
mod simulation;

pub use error::TearingSheetError;
pub use model::SheetModel;
pub use settings::{HingeBending, SheetEffects, SheetSettings};
pub use simulation::{Finger, FrameReport, TearingSheet};
