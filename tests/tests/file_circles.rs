//! No crate's files import each other in a circle (issue 41, "schema apart from drivers"):
//! within each crate, the files form a ladder, each importing only files below it, so that
//! a file can be read and changed knowing only what it imports.
//!
//! A file's imports are the modules its code names through `crate::` (and `super::`, as
//! seen from its module); comment lines and a file's own `mod tests` block are left out, so
//! a doc link or a test that reads its parent is not an import. A circle is a strongly
//! connected set of two or more modules (Tarjan).
//!
//! Circles not yet broken would be listed in [`KNOWN`] (none are), so that the test fails on
//! any new circle and on a listed circle that is gone (then delete its line): the list only
//! shrinks.

extern crate alloc;

use alloc::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The workspace's crates (their `src/`).
const CRATES: [&str; 13] = [
    "kernels", "geometry", "solvers", "book", "pages", "tearing", "scene", "cli", "capi",
    "counting", "web", "bench", "tests",
];

/// The circles not yet broken, as `crate: module, module, ...` (sorted): none left.
const KNOWN: [&str; 0] = [];

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of `file` under `src` (`a::b`; the crate root is empty).
fn module_of(src: &Path, file: &Path) -> String {
    let relative = file
        .strip_prefix(src)
        .expect("under src")
        .with_extension("");
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("lib" | "main" | "mod")
    ) {
        parts.pop();
    }
    parts.join("::")
}

/// The identifier paths that follow `prefix` in `code` (`crate::a::b` gives `a::b`).
fn paths_after(code: &str, prefix: &str) -> Vec<String> {
    code.match_indices(prefix)
        .filter(|(at, _)| {
            // A whole word: not `foo_crate::`.
            code[..*at]
                .chars()
                .next_back()
                .is_none_or(|c| !(c.is_alphanumeric() || c == '_'))
        })
        .map(|(at, _)| {
            code[at + prefix.len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect::<String>()
                .trim_end_matches(':')
                .to_owned()
        })
        .collect()
}

/// The longest module path of `modules` that starts `path` (`a::b::Item` gives `a::b`).
fn module_in(modules: &BTreeSet<String>, path: &str) -> Option<String> {
    let parts: Vec<&str> = path.split("::").collect();
    (1..=parts.len())
        .rev()
        .map(|k| parts[..k].join("::"))
        .find(|m| modules.contains(m))
}

/// The import graph of one crate's files.
fn imports(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    sources(src, &mut files);
    let by_module: BTreeMap<String, PathBuf> = files
        .iter()
        .map(|f| (module_of(src, f), f.clone()))
        .collect();
    let modules: BTreeSet<String> = by_module.keys().cloned().collect();
    let mut graph = BTreeMap::new();
    for (module, file) in &by_module {
        let text = fs::read_to_string(file).expect("readable source");
        let code: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        let code = code.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
        let mut deps = BTreeSet::new();
        for path in paths_after(code, "crate::") {
            deps.extend(module_in(&modules, &path));
        }
        let parent = module.rsplit_once("::").map_or("", |(p, _)| p);
        for path in paths_after(code, "super::") {
            let full = if parent.is_empty() {
                path
            } else {
                format!("{parent}::{path}")
            };
            deps.extend(module_in(&modules, &full));
        }
        deps.remove(module);
        graph.insert(module.clone(), deps);
    }
    graph
}

/// The strongly connected sets of two or more modules (Tarjan), each sorted.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Walk<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Walk<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in self.graph.get(v).into_iter().flatten() {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut set = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    set.push(w.to_owned());
                    if w == v {
                        break;
                    }
                }
                if set.len() > 1 {
                    set.sort();
                    self.found.push(set);
                }
            }
        }
    }
    let mut walk = Walk {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in graph.keys() {
        if !walk.index.contains_key(v.as_str()) {
            walk.visit(v);
        }
    }
    walk.found
}

#[test]
fn no_crate_has_a_new_circle_of_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut found = BTreeSet::new();
    for name in CRATES {
        for set in circles(&imports(&root.join(name).join("src"))) {
            found.insert(format!("{name}: {}", set.join(", ")));
        }
    }
    let known: BTreeSet<String> = KNOWN.iter().map(|s| (*s).to_owned()).collect();
    let new: Vec<&String> = found.difference(&known).collect();
    let gone: Vec<&String> = known.difference(&found).collect();
    assert!(
        new.is_empty(),
        "files that import each other in a circle: {new:#?}"
    );
    assert!(
        gone.is_empty(),
        "circles broken: delete them from KNOWN: {gone:#?}"
    );
}

/// The finder sees a circle through `crate::` and one through `super::`, and not an import
/// written in a comment or a test block.
#[test]
fn the_finder_sees_circles_and_only_imports() {
    let dir = std::env::temp_dir().join(format!("folio-circles-{}", std::process::id()));
    let src = dir.join("src");
    fs::create_dir_all(src.join("deep")).unwrap();
    let write = |name: &str, text: &str| fs::write(src.join(name), text).unwrap();
    write("lib.rs", "mod a;\nmod b;\nmod c;\nmod deep;\n");
    write("a.rs", "use crate::b::Thing;\n");
    write("b.rs", "pub struct Thing;\nfn f() { crate::a::g(); }\n");
    write(
        "c.rs",
        "// use crate::a;\n#[cfg(test)]\nmod tests {\n    use crate::deep::x;\n}\n",
    );
    write("deep/mod.rs", "mod x;\nmod y;\n");
    write("deep/x.rs", "use super::y::Y;\n");
    write("deep/y.rs", "use crate::deep::x::X;\nuse crate::c;\n");
    let found = circles(&imports(&src));
    fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        found,
        [vec!["a", "b"], vec!["deep::x", "deep::y"]]
            .map(|v| v.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>())
    );
}
