//! Folio's C API: the DOG book of seed `000_…` behind opaque handles, for C programs such
//! as an e-reader's page renderer. The header is `include/folio.h`, generated from this
//! crate by cbindgen (`tests/header.rs` keeps it in sync).
//!
//! # Shape of the API
//!
//! - **Versioned, prefixed symbols.** Every exported symbol starts with `folio_`, every type
//!   with `Folio`, every constant with `FOLIO_`. [`folio_api_version`] returns the library's
//!   [`FOLIO_API_VERSION`]; a program compares it with the header's at startup (the rule
//!   is in the constant's docs).
//! - **Handles, not pointers.** A book is a [`FolioBookHandle`], a 64-bit value naming a slot
//!   of a global registry and the serial number of the book created in it. A destroyed,
//!   never-created or zero handle is detected and answered with
//!   [`FolioStatus::StaleHandle`]; it is never dereferenced.
//! - **Status codes.** Every fallible function returns a [`FolioStatus`]. On failure a
//!   message for the calling thread is kept until its next call and read with
//!   [`folio_last_error_message`].
//! - **No unwinding across the boundary.** Every body runs under
//!   [`std::panic::catch_unwind`]; a panic becomes [`FolioStatus::Panic`] and the book it
//!   happened in answers [`FolioStatus::Poisoned`] until it is destroyed.
//! - **Inputs are plain integers and floats.** Sides, precisions and effect flags are
//!   `uint32_t` values with named constants, and [`FolioBookSettings`] holds only integers
//!   and doubles, so every bit pattern a C caller can pass is defined behaviour in Rust and
//!   is checked (a Rust `enum` or `bool` read from an out-of-range C value would not be).
//!   Enums appear only in outputs.
//! - **Thread safety.** Any function may be called from any thread. Calls on one book are
//!   serialized by a lock per book; calls on different books run in parallel.
//!
//! # Units and frames
//!
//! Lengths are page units (the seed's page is 12 wide), times seconds. The book frame has X
//! across the open book (the binding near $x = 0$, the right block at $x > 0$), Y up and Z
//! along the binding ($0 \le z \le H$, $H$ the page height).
//!
//! # Safety of this crate
//!
//! The workspace denies `unsafe_code`; a C API cannot avoid it, because it reads and writes
//! through the caller's raw pointers. It is allowed here, at the crate root. Raw memory is
//! touched only by the checked helpers of the private module `pointer` (a read, a write, a
//! copy, each after a NULL, alignment and length check) and where
//! [`folio_book_create_from_scene`] reads the caller's C string; the other `unsafe` blocks
//! call those helpers. Every `unsafe` block states why it is sound in a `// SAFETY:`
//! comment, and every exported function that takes a pointer is an `unsafe extern "C" fn`
//! whose `# Safety` section states what the caller guarantees.
#![allow(unsafe_code)] // C ABI: raw caller pointers (see "Safety of this crate" above).
// The crate needs std (threads, locks, unwinding); prefer `core`/`alloc` paths where they exist.
extern crate alloc;

// The modules in the header's order (cbindgen follows the declarations; one comment per
// module keeps rustfmt from sorting them).
// FOLIO_API_VERSION and folio_api_version.
mod version;
// FolioStatus and folio_status_name.
mod status;
// The thread's last error, and folio_last_error_message.
mod error_message;
mod last_error;
// FolioBookSettings, precisions, effect flags.
mod settings;
// FolioBookHandle.
mod handle;
// FolioSide.
mod side;
// folio_book_create, folio_book_destroy.
mod create;
// folio_book_create_from_scene.
mod scene;
// folio_book_grab, folio_book_drag, folio_book_release.
mod input;
// FolioStepReport, and folio_book_step.
mod step;
mod step_report;
// folio_book_mesh_size, folio_book_mesh_copy.
mod mesh;
// The page's nodes and the held node.
mod nodes;
// Internals.
mod any_book;
mod entry;
mod failure;
mod guard;
mod pointer;
mod registry;

pub use create::{folio_book_create, folio_book_destroy};
pub use error_message::folio_last_error_message;
pub use handle::FolioBookHandle;
pub use input::{folio_book_drag, folio_book_grab, folio_book_release};
pub use mesh::{folio_book_mesh_copy, folio_book_mesh_size};
pub use nodes::{folio_book_held_position, folio_book_page_grid, folio_book_page_positions};
pub use scene::folio_book_create_from_scene;
pub use settings::{
    FOLIO_EFFECT_BLOCKS, FOLIO_EFFECT_BOOKMARKING, FOLIO_EFFECT_COLLISIONS, FOLIO_EFFECT_GLUE,
    FOLIO_EFFECT_GRAVITY, FOLIO_EFFECTS_ALL, FOLIO_PRECISION_F32, FOLIO_PRECISION_F64,
    FolioBookSettings, FolioEffects, FolioPrecision, folio_book_settings_default,
};
pub use side::{FOLIO_SIDE_LEFT, FOLIO_SIDE_NONE, FOLIO_SIDE_RIGHT, FolioSide};
pub use status::{FolioStatus, folio_status_name};
pub use step::folio_book_step;
pub use step_report::{FolioPhase, FolioStepReport, FolioStepStatus};
pub use version::{FOLIO_API_VERSION, folio_api_version};
