//! `docs/scenes.md` lists every key of the models' settings once, generated from the types:
//! each model's section (`[book]`, `[spring]`, `[xpbd]`, `[sheet]`) is its settings type,
//! a key is a field's path, its default the type's default (serialized), its meaning the
//! first paragraph of the field's doc comment in the source. A field added to a settings
//! type with its doc line reaches the scene file (serde) and this table (here); the test
//! fails while the committed table differs, and `FOLIO_BLESS=1 cargo test -p folio-scene
//! --test documented_keys` writes it.

extern crate alloc;

use alloc::collections::BTreeSet;
use std::path::{Path, PathBuf};

use folio_book::BookSettings;
use folio_pages::spring::SpringSettings;
use folio_pages::xpbd::XpbdSettings;
use folio_tearing::sheet::SheetSettings;
use serde::Serialize;
use toml::{Table, Value};

/// The repository root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The crates whose sources hold the settings types.
const CRATES: [&str; 6] = ["kernels", "geometry", "solvers", "book", "pages", "tearing"];

/// Every Rust source file of [`CRATES`], with its text.
fn sources() -> Vec<(PathBuf, String)> {
    fn walk(dir: &Path, out: &mut Vec<(PathBuf, String)>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        for path in paths {
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path).expect("a source file");
                out.push((path, text));
            }
        }
    }
    let mut out = Vec::new();
    for krate in CRATES {
        walk(&root().join(krate).join("src"), &mut out);
    }
    out
}

/// A field of a settings type: its name, its type and its doc comment's lines.
struct Field {
    name: String,
    ty: String,
    doc: Vec<String>,
}

/// The body lines of `pub {kind} {name}` in the sources, and the lines before it (its
/// attributes); `None` when no source has it, an error when two do.
fn item<'a>(
    sources: &'a [(PathBuf, String)],
    kind: &str,
    name: &str,
) -> Option<(Vec<&'a str>, Vec<&'a str>)> {
    let mut found = Vec::new();
    for (path, text) in sources {
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            let head = format!("pub {kind} {name}");
            if t.starts_with(&head) && t[head.len()..].starts_with(['<', ' ', '{']) {
                let end = lines[i..]
                    .iter()
                    .position(|l| *l == "}")
                    .map_or(lines.len(), |n| i + n);
                let start = lines[..i]
                    .iter()
                    .rposition(|l| l.trim().is_empty() || l.starts_with('}'))
                    .map_or(0, |n| n + 1);
                found.push((
                    path.clone(),
                    lines[i + 1..end].to_vec(),
                    lines[start..i].to_vec(),
                ));
            }
        }
    }
    assert!(
        found.len() <= 1,
        "two types are called {name}: {:?}",
        found.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    found.pop().map(|(_, body, attributes)| (body, attributes))
}

/// The public fields of the struct `name`, in order.
fn fields(sources: &[(PathBuf, String)], name: &str) -> Vec<Field> {
    let (body, _) = item(sources, "struct", name).unwrap_or_else(|| panic!("no struct {name}"));
    let mut out = Vec::new();
    let mut doc = Vec::new();
    for line in body {
        let t = line.trim();
        if let Some(d) = t.strip_prefix("///") {
            doc.push(d.trim().to_string());
        } else if let Some(field) = t.strip_prefix("pub ") {
            let (name, ty) = field.split_once(':').expect("name: type");
            out.push(Field {
                name: name.trim().to_string(),
                ty: ty.trim().trim_end_matches(',').to_string(),
                doc: core::mem::take(&mut doc),
            });
        } else if !t.starts_with("#[") && !t.starts_with("feature") && !t.starts_with(')') {
            doc.clear();
        }
    }
    out
}

/// The names a scene writes for the variants of the enum `name` (its serde renaming), if
/// the sources have it.
fn variants(sources: &[(PathBuf, String)], name: &str) -> Option<Vec<String>> {
    let (body, attributes) = item(sources, "enum", name)?;
    let rule = attributes
        .iter()
        .find_map(|l| l.split("rename_all = \"").nth(1))
        .and_then(|r| r.split('"').next())
        .unwrap_or("");
    let mut out = Vec::new();
    for line in body {
        let t = line.trim();
        let word: String = t.chars().take_while(char::is_ascii_alphanumeric).collect();
        let is_variant = word.chars().next().is_some_and(|c| c.is_ascii_uppercase())
            && t[word.len()..].starts_with([',', ' ', '(', '{']);
        if is_variant && !line.starts_with("        ") {
            out.push(rename(&word, rule));
        }
    }
    Some(out)
}

/// `CamelCase` under serde's `rename_all` rule.
fn rename(word: &str, rule: &str) -> String {
    let mut parts: Vec<String> = Vec::new();
    for c in word.chars() {
        if c.is_ascii_uppercase() || parts.is_empty() {
            parts.push(String::new());
        }
        parts
            .last_mut()
            .expect("a part")
            .push(c.to_ascii_lowercase());
    }
    match rule {
        "kebab-case" => parts.join("-"),
        "snake_case" => parts.join("_"),
        "lowercase" => parts.concat(),
        _ => word.to_string(),
    }
}

/// The first paragraph of a doc comment as one markdown table cell: rustdoc links become
/// their text, `|` is escaped.
fn cell(doc: &[String]) -> String {
    let paragraph: Vec<&str> = doc
        .iter()
        .map(String::as_str)
        .take_while(|l| !l.is_empty())
        .collect();
    let text = paragraph.join(" ");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(open) = rest.find("[`") {
        let Some(close) = rest[open..].find("`]").map(|c| open + c) else {
            break;
        };
        out.push_str(&rest[..open]);
        out.push_str(&rest[open + 1..close + 1]);
        rest = &rest[close + 2..];
        if rest.starts_with('(') {
            rest = rest.find(')').map_or(rest, |c| &rest[c + 1..]);
        }
    }
    out.push_str(rest);
    out.replace('|', "\\|")
}

/// A default as a scene would write it, numbers short (`1.4901161193847656e-8`, not 26
/// digits).
fn short(v: &Value) -> String {
    match v {
        Value::Float(x) if *x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) => format!("{x:e}"),
        other => other.to_string(),
    }
}

/// The base name of a type (`Weights<T>` → `Weights`).
fn base(ty: &str) -> &str {
    ty.split('<').next().unwrap_or(ty).trim()
}

/// The rows of the settings type `name` under the key prefix `prefix`, whose default is
/// `default`; `skip` lists the paths (from the section) a scene sets in its own words.
fn rows(
    sources: &[(PathBuf, String)],
    name: &str,
    prefix: &str,
    section: &str,
    default: &Table,
    skip: &[&str],
    out: &mut Vec<(String, String)>,
) {
    for f in fields(sources, name) {
        let path = if prefix.is_empty() {
            f.name.clone()
        } else {
            format!("{prefix}.{}", f.name)
        };
        if skip.contains(&path.as_str()) {
            continue;
        }
        let key = format!("{section}.{path}");
        let value = default.get(&f.name);
        if let Some(Value::Table(inner)) = value {
            out.push((key.clone(), format!("table | {}", cell(&f.doc))));
            rows(sources, base(&f.ty), &path, section, inner, skip, out);
            continue;
        }
        let shown = value.map_or("none".to_string(), |v| format!("`{}`", short(v)));
        let kinds = variants(sources, base(&f.ty))
            .map(|v| {
                let names: Vec<String> = v.iter().map(|n| format!("`\"{n}\"`")).collect();
                format!(" One of {}.", names.join(", "))
            })
            .unwrap_or_default();
        out.push((key, format!("{shown} | {}{kinds}", cell(&f.doc))));
    }
}

/// Every leaf of `table`: its path and its value.
fn leaves(table: &Table, prefix: &str, out: &mut Vec<(String, Value)>) {
    for (k, v) in table {
        let path = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            Value::Table(inner) => leaves(inner, &path, out),
            other => out.push((path, other.clone())),
        }
    }
}

/// The settings type's default as a table.
fn table_of<S: Serialize>(value: &S) -> Table {
    toml::from_str(&toml::to_string(value).expect("serializes")).expect("reads")
}

/// A model's section: its scene name, its settings type's name, its default, and the paths
/// the scene sets in its own words (the effects).
type Section = (&'static str, &'static str, Table, &'static [&'static str]);

fn sections() -> [Section; 4] {
    [
        (
            "book",
            "BookSettings",
            table_of(&BookSettings::<f64>::default()),
            &["effects", "params.cover"],
        ),
        (
            "spring",
            "SpringSettings",
            table_of(&SpringSettings::<f64>::default()),
            &["floor"],
        ),
        (
            "xpbd",
            "XpbdSettings",
            table_of(&XpbdSettings::<f64>::default()),
            &["floor"],
        ),
        (
            "sheet",
            "SheetSettings",
            table_of(&SheetSettings::<f64>::default()),
            &["effects"],
        ),
    ]
}

/// The generated table of one section.
fn generated(sources: &[(PathBuf, String)], section: &Section) -> String {
    let (name, ty, default, skip) = section;
    let mut rows_out = Vec::new();
    rows(sources, ty, "", name, default, skip, &mut rows_out);
    // Every key serde writes is a row, and every row a key serde writes (or a table, or an
    // optional field left out).
    let mut written = Vec::new();
    leaves(default, "", &mut written);
    let written: BTreeSet<String> = written
        .into_iter()
        .map(|(p, _)| p)
        .filter(|p| {
            !skip
                .iter()
                .any(|s| p == s || p.starts_with(&format!("{s}.")))
        })
        .map(|p| format!("{name}.{p}"))
        .collect();
    let listed: BTreeSet<String> = rows_out.iter().map(|(k, _)| k.clone()).collect();
    let missing: Vec<&String> = written.difference(&listed).collect();
    assert!(
        missing.is_empty(),
        "keys of [{name}] with no documented field: {missing:?}"
    );
    let mut text = String::from("| key | default | meaning |\n|---|---|---|\n");
    for (key, rest) in rows_out {
        text.push_str(&format!("| `{key}` | {rest} |\n"));
    }
    text
}

#[test]
fn the_scene_docs_list_every_settings_key_from_the_types() {
    let sources = sources();
    let file = root().join("docs/scenes.md");
    let docs = std::fs::read_to_string(&file).expect("docs/scenes.md");
    let mut updated = docs.clone();
    for section in sections() {
        let name = section.0;
        let (begin, end) = (
            format!("<!-- generated keys: {name} -->\n"),
            format!("<!-- end of generated keys: {name} -->"),
        );
        let start = updated
            .find(&begin)
            .unwrap_or_else(|| panic!("docs/scenes.md has no `{}`", begin.trim()))
            + begin.len();
        let stop = start
            + updated[start..]
                .find(&end)
                .unwrap_or_else(|| panic!("docs/scenes.md has no `{end}`"));
        updated.replace_range(start..stop, &generated(&sources, &section));
    }
    if updated != docs {
        if std::env::var_os("FOLIO_BLESS").is_some() {
            std::fs::write(&file, &updated).expect("writes docs/scenes.md");
        } else {
            panic!(
                "docs/scenes.md's key tables differ from the settings types: run \
                 `FOLIO_BLESS=1 cargo test -p folio-scene --test documented_keys` and commit"
            );
        }
    }
}

/// Every leaf path where `a` and `b` differ.
fn differing<S: Serialize>(a: &S, b: &S) -> BTreeSet<String> {
    let ([mut x, mut y], [ta, tb]) = ([Vec::new(), Vec::new()], [table_of(a), table_of(b)]);
    leaves(&ta, "", &mut x);
    leaves(&tb, "", &mut y);
    let value =
        |v: &[(String, Value)], k: &str| v.iter().find(|(p, _)| p == k).map(|(_, v)| v.clone());
    x.iter()
        .chain(&y)
        .map(|(p, _)| p.clone())
        .filter(|p| value(&x, p) != value(&y, p))
        .collect()
}

/// The fields a base is patched with (`folio_scene::settings`' rule for a default that is
/// not the type's own) are exactly those where `base` differs from `plain`, and patching
/// `plain` with them gives `base`.
fn patched_by<S: Serialize + PartialEq + core::fmt::Debug + Copy>(
    base: S,
    plain: S,
    fields: &[folio_scene::settings::Field<S>],
) {
    let listed: BTreeSet<String> = fields.iter().map(|(k, _)| (*k).to_string()).collect();
    assert_eq!(differing(&base, &plain), listed);
    let mut patched = plain;
    for (_, copy) in fields {
        copy(&mut patched, &base);
    }
    assert_eq!(patched, base);
}

/// A default that is not its type's own (the book's solver, seed 003's pages) is patched
/// field by field over what serde reads: every field where the two differ, and no other.
#[test]
fn every_default_that_differs_from_its_types_is_patched() {
    fn both<T: folio_kernels::Real + Serialize>() {
        use folio_scene::settings::{
            book_solver_fields, spring_seed_fields, xpbd_seed, xpbd_seed_fields,
        };
        let book = BookSettings::<T>::default();
        let solver_only = BookSettings {
            solver: folio_solvers::settings::Settings::default(),
            ..book
        };
        patched_by(book, solver_only, &book_solver_fields());
        let spring = SpringSettings::<T>::seed_experiment();
        patched_by(spring, SpringSettings::default(), &spring_seed_fields());
        patched_by(
            xpbd_seed::<T>(),
            XpbdSettings::default(),
            &xpbd_seed_fields(),
        );
    }
    both::<f64>();
    both::<f32>();
}
