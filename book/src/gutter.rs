//! The heavy elastica over a ground: a strip of paper rooted at a point, bending under its own
//! weight and lying one-sidedly on what is under it, settled to rest. It is how a block's top
//! page lies in the gutter (issue 42: the page near the binding as paper lies, a modelling
//! choice of Folio's; the seed's collision test of Sec. 3.4 rests the page on the corner of
//! the block's clearance band instead), and the one-dimensional reference a released page's
//! rest is measured against.
//!
//! **Folio's choice.** The top page is rooted at the hinge, free to turn there, and lies on
//! its block cut square at the binding ([`Band::open_start`]): the pages under it end at the
//! binding as it does. On the default book's settled block (50 pages, 0.375 thick, its
//! midline rising 37° from the spine) it leans on the cut's upper corner, 0.33 page units
//! from the hinge, and its chord from the hinge to a quarter of the page out stands at
//! 62.8° (card), 40.5° (novel), 39.5° (magazine) and 27.2° (bible), at 200 segments
//! (`folio-tests`' `gutter.rs`, which prints them).
//!
//! - [`ground`]: what the strip lies on ([`Ground`]): nothing ([`Air`]), a block
//!   ([`Band`]), a table ([`Level`]), or two of them ([`Both`]).
//! - [`elastica`]: the strip and its rest ([`Elastica::settle`]).

pub mod elastica;
pub mod ground;

pub use elastica::{Elastica, ElasticaError, Root, Settled};
pub use ground::{Air, Band, Both, Ground, Level, Point2};
