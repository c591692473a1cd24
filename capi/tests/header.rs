//! `include/folio.h` is what cbindgen generates from this crate now. The header is generated
//! in memory with cbindgen as a library (CI needs no cbindgen binary) and compared with the
//! committed file; `FOLIO_BLESS=1` rewrites the file instead.

use std::path::Path;

/// The command that regenerates the header.
const BLESS: &str = "FOLIO_BLESS=1 cargo test -p folio-capi --test header";

fn generate(crate_dir: &Path) -> String {
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml"))
        .expect("capi/cbindgen.toml parses");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(crate_dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen generates the header");
    let mut out = Vec::new();
    bindings.write(&mut out);
    String::from_utf8(out).expect("the header is UTF-8")
}

#[test]
fn header_is_up_to_date() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = crate_dir.join("include/folio.h");
    let generated = generate(crate_dir);
    if std::env::var_os("FOLIO_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/folio.h");
        eprintln!("wrote {}", path.display());
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != generated {
        let first = committed
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(generated.lines().count()));
        panic!(
            "capi/include/folio.h is out of date (first difference at line {}: committed {:?}, \
             generated {:?}).\nRegenerate it with:\n    {BLESS}",
            first + 1,
            committed.lines().nth(first).unwrap_or("<end of file>"),
            generated.lines().nth(first).unwrap_or("<end of file>"),
        );
    }
}

/// `folio_status_name` spells every status as the header does, with the header's value.
#[test]
fn status_names_match_the_header() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let header = generate(crate_dir);
    let mut code = 0;
    loop {
        // SAFETY: `folio_status_name` returns a static NUL-terminated string.
        #[allow(unsafe_code)]
        let name = unsafe { std::ffi::CStr::from_ptr(folio_capi::folio_status_name(code)) };
        let name = name.to_str().unwrap();
        if name == "FOLIO_STATUS_UNKNOWN" {
            break;
        }
        assert!(
            header.contains(&format!("    {name} = {code},")),
            "{name} = {code} is not in the header"
        );
        code += 1;
    }
    let defined = header.matches("    FOLIO_STATUS_").count();
    assert_eq!(
        code as usize, defined,
        "every status of the header has a name"
    );
}
