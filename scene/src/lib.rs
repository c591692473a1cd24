//! # folio-scene
//!
//! Folio's scene files (TOML, `docs/scenes.md`): the scene types and their validation with
//! line and column ([`scene`]), read from `toml`'s parsed document by Folio's own serde
//! deserializer ([`reader`]), the timed events and hands that drive a run ([`events`],
//! [`hands`]), the recorded fixtures and built-in scenes they name ([`fixtures`],
//! [`builtin`]), the frame clock (a frame is 1/60 s; [`clock`]), the model settings a scene
//! describes, read straight into the models' settings types: the keys are their field
//! names ([`settings`]), the older spellings read for one release ([`legacy`]), the book
//! of a DOG scene held to the book's own validation at the keys that set it ([`book`]), the
//! tearing sheet of a sheet scene ([`sheet`]), a scene name's rules ([`name`]) and short
//! numbers in messages ([`number`]). The ranges of the models' settings are the models' own
//! (each settings type's `validate`).
//!
//! Features (all default): `sheet` (the tearing sheet's scenes, [`sheet`] and [`hands`]),
//! `xpbd` (the XPBD page's scenes), `older-keys` (the older spellings of the keys),
//! `fixture-reach` (the check that a book fixture's first grab reaches the book,
//! [`reach`]) and `paper` (a DOG scene's paper, [`paper`]); the browser build
//! (`folio-web`) leaves them all out, for size (issue 23's bound): it refuses a sheet or
//! XPBD scene at its `model`, a file in the older keys at the first older table, and a
//! paper at its `paper` key.
//!
//! Layers: the models (`folio-book`, `folio-pages`, `folio-tearing`) below; the `folio`
//! command and the C API (`folio-capi`) above, both reading scenes through this crate.

extern crate alloc;

pub mod book;
pub mod builtin;
mod check;
pub mod clock;
pub mod events;
pub mod fixtures;
#[cfg(feature = "sheet")]
pub mod hands;
pub mod keys;
pub mod legacy;
pub mod name;
pub mod number;
#[cfg(feature = "paper")]
pub mod paper;
#[cfg(feature = "fixture-reach")]
pub mod reach;
pub mod reader;
pub mod scene;
pub mod settings;
#[cfg(feature = "sheet")]
pub mod sheet;
