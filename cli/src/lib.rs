//! The library half of the `folio` command: scene files (TOML, `docs/scenes.md`), their
//! timed events and hands, the recorded fixtures and built-in scenes they name, the solver
//! settings a scene describes, and the tearing sheet of a sheet scene. The command itself (running, reports, pictures) is the
//! binary, behind the default feature `cli`; the C API uses this library without it.

extern crate alloc;

pub mod builtin;
pub mod events;
pub mod fixtures;
pub mod hands;
pub mod scene;
pub mod settings;
pub mod sheet;
