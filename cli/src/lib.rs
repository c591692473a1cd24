//! The library half of the `folio` command: scene files (TOML, `docs/scenes.md`), their
//! timed events, the recorded fixtures and built-in scenes they name, and the solver
//! settings a scene describes. The command itself (running, reports, pictures) is the
//! binary, behind the default feature `cli`; the C API uses this library without it.

extern crate alloc;

pub mod builtin;
pub mod events;
pub mod fixtures;
pub mod scene;
pub mod settings;
