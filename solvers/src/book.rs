//! The book of seed `000_…` (Sec. 3-4) on the solver: the model (nodes, masses, constraints,
//! potentials), interaction (grab, drag through the tent, release, merge), collision
//! handling, and the quality measures of Sec. 5.
//!
//! It lives in `folio-solvers` because it is a [`crate::Model`] driven by [`crate::Solver`]:
//! its geometry (grids, layout, collision walls, meshing) comes from `folio-geometry` below.

pub mod bookmark;
pub mod effects;
pub mod error;
pub mod interaction;
pub mod mesh;
pub mod model;
pub mod script;
pub mod settings;
pub mod simulation;
pub mod terms;

pub use bookmark::{Flip, History};
pub use effects::{Effects, TermCensus};
pub use error::BookError;
pub use interaction::{Ray, Tent};
pub use model::{BookTerms, Family, NodeMap};
pub use script::{Action, Event, Script, ScriptError};
pub use settings::{BookSettings, Weights};
pub use simulation::{
    Book, BookStepReport, BookmarkOutcome, DragOutcome, GrabOutcome, InputOutcome, PageCounts,
    Phase,
};
