//! Runs on the host before the firmware builds:
//!
//! 1. puts the memory map of the machine chosen by feature (`an386` or `an500`) where
//!    cortex-m-rt's `link.x` looks for `memory.x`;
//! 2. compiles the page-turn fixture (`tests/fixtures/page_turn.input`) to the binary form of
//!    `src/fixture_format.rs` (`page_turn.bin` in `OUT_DIR`, which `src/fixture.rs` includes),
//!    so the firmware parses no text and no floats.
//!
//! The fixture is parsed by `folio_book::Script::parse` itself: `book/src/script.rs` is
//! compiled into this build script as a module (it needs only `core` and `alloc`), so the
//! firmware plays exactly the values the host tests play, without building the book and its
//! solver for the host.

extern crate alloc;

#[allow(dead_code)]
#[path = "src/fixture_format.rs"]
mod fixture_format;
// The book's `std` feature (an `Error` impl) is no feature of this package.
#[allow(dead_code, unexpected_cfgs)]
#[path = "../book/src/script.rs"]
mod script;

use std::path::{Path, PathBuf};
use std::{env, fs};

use script::{Action, Script};

/// The recorded page turn (text).
const FIXTURE: &str = "../tests/fixtures/page_turn.input";

/// Prints `message` and stops the build.
fn fail(message: &str) -> ! {
    eprintln!("folio-embedded: {message}");
    std::process::exit(1);
}

/// Copies `memory/<machine>.x` to `out/memory.x`.
fn memory_map(out: &Path) {
    let an386 = env::var_os("CARGO_FEATURE_AN386").is_some();
    let an500 = env::var_os("CARGO_FEATURE_AN500").is_some();
    let machine = match (an386, an500) {
        (true, false) => "an386",
        (false, true) => "an500",
        _ => fail(
            "enable exactly one machine feature, `an386` (default) or `an500` (with \
             --no-default-features)",
        ),
    };
    let source = PathBuf::from("memory").join(format!("{machine}.x"));
    if let Err(e) = fs::copy(&source, out.join("memory.x")) {
        fail(&format!("cannot copy {}: {e}", source.display()));
    }
}

/// Appends the little-endian bits of each of `v`.
fn put_f64s(bytes: &mut Vec<u8>, v: [f64; 3]) {
    for x in v {
        bytes.extend_from_slice(&x.to_bits().to_le_bytes());
    }
}

/// `script` in the binary form of `src/fixture_format.rs`.
fn encode(script: &Script) -> Vec<u8> {
    use fixture_format::{BOOKMARK_ADD, BOOKMARK_REMOVE, DRAG, GRAB, HEADER_BYTES, RELEASE};
    let events = u32::try_from(script.events.len())
        .unwrap_or_else(|_| fail("the fixture has more than 2^32 events"));
    let mut bytes = Vec::with_capacity(HEADER_BYTES + 33 * script.events.len());
    bytes.extend_from_slice(&script.frames.to_le_bytes());
    bytes.extend_from_slice(&events.to_le_bytes());
    put_f64s(&mut bytes, script.camera);
    put_f64s(&mut bytes, script.forward);
    for event in &script.events {
        bytes.extend_from_slice(&event.frame.to_le_bytes());
        match event.action {
            Action::Grab { direction, pages } => {
                bytes.push(GRAB);
                put_f64s(&mut bytes, direction);
                bytes.extend_from_slice(&pages.to_le_bytes());
            }
            Action::Drag { direction } => {
                bytes.push(DRAG);
                put_f64s(&mut bytes, direction);
            }
            Action::Release => bytes.push(RELEASE),
            Action::BookmarkAdd => bytes.push(BOOKMARK_ADD),
            Action::BookmarkRemove => bytes.push(BOOKMARK_REMOVE),
        }
    }
    bytes
}

/// Parses the fixture and writes its binary form to `out/page_turn.bin`.
fn fixture(out: &Path) {
    let text = fs::read_to_string(FIXTURE)
        .unwrap_or_else(|e| fail(&format!("cannot read {FIXTURE}: {e}")));
    let script = Script::parse(&text).unwrap_or_else(|e| fail(&format!("{FIXTURE}: {e}")));
    let target = out.join("page_turn.bin");
    if let Err(e) = fs::write(&target, encode(&script)) {
        fail(&format!("cannot write {}: {e}", target.display()));
    }
}

fn main() {
    let Some(out) = env::var_os("OUT_DIR").map(PathBuf::from) else {
        fail("OUT_DIR is not set (run the build through cargo)");
    };
    memory_map(&out);
    fixture(&out);
    println!("cargo:rustc-link-search={}", out.display());
    for path in [
        "memory",
        "build.rs",
        "src/fixture_format.rs",
        FIXTURE,
        "../book/src/script.rs",
    ] {
        println!("cargo:rerun-if-changed={path}");
    }
}
