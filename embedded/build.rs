//! Puts the memory map of the machine chosen by feature (`an386` or `an500`) where
//! cortex-m-rt's `link.x` looks for `memory.x`.

use std::path::PathBuf;
use std::{env, fs};

fn main() {
    let an386 = env::var_os("CARGO_FEATURE_AN386").is_some();
    let an500 = env::var_os("CARGO_FEATURE_AN500").is_some();
    let machine = match (an386, an500) {
        (true, false) => "an386",
        (false, true) => "an500",
        _ => {
            eprintln!(
                "folio-embedded: enable exactly one machine feature, `an386` (default) or \
                 `an500` (with --no-default-features)"
            );
            std::process::exit(1);
        }
    };
    let source = PathBuf::from("memory").join(format!("{machine}.x"));
    let Some(out) = env::var_os("OUT_DIR").map(PathBuf::from) else {
        eprintln!("folio-embedded: OUT_DIR is not set (run the build through cargo)");
        std::process::exit(1);
    };
    if let Err(e) = fs::copy(&source, out.join("memory.x")) {
        eprintln!("folio-embedded: cannot copy {}: {e}", source.display());
        std::process::exit(1);
    }
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=build.rs");
}
