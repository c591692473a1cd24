//! # folio-solvers
//!
//! Folio's sparse KKT machinery and the implicit-Euler SQP step of seed `000_…` (Sec. 3.1,
//! eq. 2-4), `no_std` + `alloc`, in `f32` and `f64`.
//!
//! - [`model`]: what a model provides ([`Model`]): nodes, masses, eliminated coordinates,
//!   and term families ([`PotentialSet`], [`ConstraintSet`]) over `folio-kernels` terms.
//! - [`pattern`]: the upper-triangle KKT pattern and every term's scatter map, built once.
//! - [`ordering`], [`symbolic`]: the fill-reducing order and the indices-only analysis,
//!   rebuilt only when the model's topology version changes.
//! - [`ldlt`], [`kkt`]: the numeric $LDL^\top$ with sign-aware regularization on the reused
//!   analysis, and the refined solve.
//! - [`nested_dissection`]: the split order of a two-thread factorization
//!   ([`Parallelism`]).
//! - [`normal_equations`]: $J W^{-1} J^\top$, the constraint projection's reduced system.
//! - [`step`]: [`Solver::step`], one time step with a [`StepReport`].
//! - [`matrix_market`]: export of the assembled KKT matrix.
//! - [`ring`]: [`Ring`], a fixed-capacity history of states (the models' recordings).
//! - [`banded`]: [`banded::Banded`], a banded SPD matrix and its Cholesky factor, for the
//!   Newton systems of curves.
//!
//! It holds no model: anything that implements [`Model`] can be stepped, and the KKT
//! machinery ([`pattern`], [`symbolic`], [`ldlt`], [`kkt`]) is usable on its own for any
//! symmetric quasi-definite system with known pivot signs. The models live above it: the
//! DOG book in `folio-book`, the page models in `folio-pages`, the tearing sheet in
//! `folio-tearing`. It depends on `folio-kernels` alone (and faer for the AMD ordering).
//!
//! Setup allocates; a step on an analysed topology does not (a test with a counting
//! allocator holds this).
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

mod assembly;
pub mod banded;
#[cfg(test)]
mod chain;
pub mod error;
pub mod gmres;
pub mod index;
pub mod kkt;
pub mod ldlt;
pub mod matrix_market;
pub mod model;
pub mod nested_dissection;
pub mod normal_equations;
pub mod ordering;
pub mod pattern;
pub mod report;
pub mod ring;
pub mod room;
pub mod settings;
mod slots;
pub mod step;
pub mod symbolic;
pub mod vector;

pub use error::SolverError;
pub use kkt::Kkt;
pub use model::{ConstraintSet, Model, PotentialSet, Term, TermVisitor};
pub use ordering::Ordering;
pub use report::{StepReport, StepStatus};
pub use ring::Ring;
pub use settings::{Convexify, Parallelism, Settings};
pub use step::{Correction, Pins, Solver, State};
