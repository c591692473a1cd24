//! # folio-kernels
//!
//! Per-element math of Folio's paper models, generic over [`Real`] (`f32`, `f64`):
//! every constraint and potential of the DOG book model (seed `000_…`, eq. 5-14), the Provot
//! springs of the mass-spring page (seed `003_…`), the conical page curl (seed `001_…`) and
//! the triangle sheet that tears (seed `002_…`): its Saint Venant–Kirchhoff membrane
//! ([`membrane`], the in-plane stretching forces of Sec. 5.1) and its quadratic hinge
//! bending ([`hinge`]) on a flat 2D rest pattern.
//!
//! Each term evaluates on a small fixed-size local block of node positions
//! `[T::Vec3; N]` and returns values, gradients (one `Vec3` per node) and Hessians
//! (`N x N` blocks of `3 x 3` matrices) that a solver scatters into its global system.
//! Potentials implement [`Potential`], constraints implement [`Constraint`].
//!
//! Rules: no allocation, no panics, no `Result` in evaluation. Degenerate input (zero-length
//! edges, coincident points, collinear stars, the apex of a cone) takes a documented finite
//! fallback. A non-finite input coordinate makes the returned value non-finite (NaN
//! propagates); it never panics and never returns a finite-looking value. Finite output for
//! finite input is guaranteed for coordinates of magnitude at most [`Real::COORD_MAX`].
//! Constructors validate their parameters and return [`KernelError`].
//!
//! Units: lengths in page units (the seed's page width is 12), masses in page masses, time
//! in seconds. Coordinates follow seed `000_…` Sec. 3.1: X across the book, Y up (gravity
//! along −Y), Z along the binding.
#![cfg_attr(not(feature = "std"), no_std)]

pub mod binding;
pub mod cone;
pub mod contact;
pub mod curve_laplacian;
pub mod dog;
pub mod dog_laplacian;
pub mod edge_cosine;
pub mod error;
pub mod fix;
pub mod fused;
pub mod glue;
pub mod gravity;
pub mod hinge;
pub mod iso2d;
pub mod iso3d;
pub mod lanes;
pub mod math;
pub mod membrane;
pub mod positional;
pub mod real;
pub mod setting;
pub mod splitmix;
pub mod spring;
pub mod stencil;
pub mod term;

pub use error::KernelError;
pub use real::{Mat3Ops, Real, Vec3Ops};
pub use setting::{Requirement, SettingError, SettingPath, Shown};
pub use term::{Constraint, Potential};
