//! # folio-book
//!
//! The book of seed `000_…` (Sec. 3-4), `no_std` + `alloc`, in `f32` and `f64`: the active
//! page as a discrete orthogonal geodesic net, the page blocks as planar midline curves, the
//! hard cover, all stepped by [`folio_solvers::Solver`] as one [`folio_solvers::Model`].
//!
//! - [`layout`]: the book's layout from its parameters ([`BookParams`]): page-block midlines,
//!   binding edge, hard cover.
//! - [`settings`]: [`BookSettings`] and the solver-facing [`Weights`]; [`effects`]: the
//!   effects a scene calls for ([`Effects`]), each building no term when off.
//! - [`quadrature`]: the page's bending and masses as a quadrature over the page, and the
//!   bending stiffness $D$ its weight stands for.
//! - [`model`], [`terms`]: the book as a model: nodes, masses, eliminated coordinates, the
//!   constraint and potential families of eq. 5-14.
//! - [`simulation`]: [`Book`], a frame = one implicit step plus collisions and the
//!   constraint projection; grab by ray, drag through the tent, release and merge
//!   ([`interaction`]), finger-bookmarking ([`bookmark`], feature `bookmarking`).
//! - [`gutter`]: a block's top page as a heavy elastica over its block ([`gutter::Elastica`]),
//!   the gutter as paper lies and the 1D reference of a page at rest (issue 42).
//! - [`mesh`]: the whole book as one render mesh (Sec. 3.5) from `folio_geometry::mesh`.
//! - [`script`]: recorded input ([`Script`]) for fixtures and replays.
//!
//! Layers: `folio-kernels` (per-element terms) and `folio-geometry` (grid, collision walls,
//! meshing) below, `folio-solvers` (the KKT step) beside them; the page models of
//! `folio-pages` and the scene files of `folio-scene` above.
//!
//! Features: `std` (additive), `collisions` (Sec. 3.4 and the contact springs),
//! `bookmarking` (Sec. 4.1).
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

pub mod bookmark;
mod broad_phase;
mod collide;
pub mod effects;
pub mod error;
mod flip;
pub mod friction;
mod grab;
pub mod gutter;
pub mod interaction;
pub mod layout;
mod merge;
pub mod mesh;
pub mod model;
mod outcome;
pub mod pad;
pub mod paper;
pub mod quadrature;
pub mod script;
pub mod settings;
pub mod simulation;
pub mod stock;
pub mod terms;

pub use bookmark::{Flip, History};
pub use effects::{Effects, TermCensus};
pub use error::BookError;
pub use interaction::{Ray, Tent};
pub use layout::{BlockSide, BookLayout, BookParams, MAX_EXTENT, MAX_PAGES};
pub use model::{BookTerms, Family, NodeMap};
pub use paper::{BookUnits, Paper};
pub use script::{Action, Event, Script, ScriptError};
pub use settings::{
    BookSettings, Gutter, IsometryHessian, MAX_PROJECTION_ITERATIONS, MAX_TIME_STEP,
    MICROCONTROLLER_GRID, MIN_CELL_TOLERANCES, MIN_TIME_STEP, SOFT_BEND_PAGE_MIN, WEIGHT_RANGES,
    Weights,
};
pub use simulation::{
    Book, BookStepReport, BookmarkOutcome, DragOutcome, GrabOutcome, InputOutcome, PageCounts,
    Phase,
};
pub use stock::Stock;
