//! The `folio` command end to end: the default run, every built-in scene against its stated
//! expectations, `list`, `check` on the shipped scene files and the documentation's
//! examples, and malformed scenes (line and column, non-zero exit, nothing half-run).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENES: [&str; 7] = [
    "page-turn",
    "peek",
    "bookmark-flip",
    "stack",
    "paperback",
    "cone-turn",
    "mass-spring-turn",
];

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("folio-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn folio(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_folio"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("folio runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn no_arguments_runs_the_default_scene() {
    let dir = scratch("default");
    let out = folio(&dir, &[]);
    println!("{}", text(&out.stdout));
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("scene page-turn") && stdout.contains("expectations     met"));
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("out/page-turn/report.json")).unwrap(),
    )
    .unwrap();
    let summary = &report["summary"];
    for key in [
        "frames",
        "step_ms_median",
        "step_ms_p99",
        "max_stretch_mean",
        "rmse_stretch_mean",
        "dog_residual_max",
        "penetration_max",
        "nonfinite_frames",
        "status_counts",
        "effects",
    ] {
        assert!(!summary[key].is_null(), "summary.{key} missing");
    }
    assert_eq!(summary["frames"], 750);
    assert_eq!(report["frames"].as_array().unwrap().len(), 750);
    check_outputs(&dir.join("out/page-turn"), "page-turn");
}

#[test]
fn every_built_in_scene_meets_its_expectations() {
    let dir = scratch("builtin");
    for name in &SCENES[1..] {
        let out = folio(&dir, &["run", name, "--out", name]);
        println!("{}", text(&out.stdout));
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        check_outputs(&dir.join(name), name);
    }
}

/// The files a run writes: the report, a PNG contact sheet that shows the page, a binary
/// glTF, an SVG timeline.
fn check_outputs(dir: &Path, name: &str) {
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let png = std::fs::read(dir.join("contact_sheet.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{name}: a PNG");
    let glb = std::fs::read(dir.join("animation.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF", "{name}: a binary glTF");
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
        glb.len()
    );
    let svg = std::fs::read_to_string(dir.join("timeline.svg")).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
        "{name}"
    );
    // The page shows: every built-in scene turns or lifts a page in some tiles (a book at
    // rest would show 0 % page), and the book or page fills a good part of every tile.
    let summary = &report["summary"];
    let page = summary["page_coverage"].as_f64().unwrap();
    let paper = summary["paper_coverage"].as_f64().unwrap();
    println!("{name}: contact sheet {page:.3} page, {paper:.3} paper");
    assert!((0.01..0.5).contains(&page), "{name}: page coverage {page}");
    assert!(
        (0.1..0.6).contains(&paper),
        "{name}: paper coverage {paper}"
    );
}

/// The scene `name` with `effects` (all of the DOG book's when `None`), 200 frames of the
/// page turn: its summary.
fn summary_with(dir: &Path, name: &str, effects: Option<&[&str]>) -> serde_json::Value {
    let list = effects.map_or(String::new(), |e| {
        let quoted: Vec<String> = e.iter().map(|x| format!("\"{x}\"")).collect();
        format!("effects = [{}]\n", quoted.join(", "))
    });
    let scene = format!(
        "name = \"{name}\"\nmodel = \"dog\"\nframes = 200\n{list}input = {{ fixture = \"page-turn\" }}\n"
    );
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, scene).unwrap();
    let out = folio(dir, &["run", file.to_str().unwrap(), "--out", name]);
    assert!(out.status.success(), "{name}: {}", text(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(name).join("report.json")).unwrap())
            .unwrap();
    report["summary"].clone()
}

/// The page turn with and without each effect of the DOG book: what is left out shows in
/// the report as fewer terms, rows, unknowns, collision tests or snapshots.
#[test]
fn a_scene_with_and_without_each_effect() {
    let dir = scratch("effects");
    let all = [
        "gravity",
        "glue",
        "collisions",
        "cover",
        "blocks",
        "bookmarking",
    ];
    let full = summary_with(&dir, "all", None);
    let named = summary_with(&dir, "all-named", Some(&all));
    for key in [
        "effects",
        "dofs_max",
        "constraint_rows_max",
        "terms_max",
        "final_pages",
    ] {
        assert_eq!(
            named[key], full[key],
            "naming every effect is the default: {key}"
        );
    }
    let get = |s: &serde_json::Value, k: &str| s[k].as_u64().unwrap_or_else(|| panic!("{k}: {s}"));
    for effect in all {
        let rest: Vec<&str> = all
            .iter()
            .copied()
            .filter(|e| *e != effect && !(effect == "blocks" && *e == "glue"))
            .collect();
        let without = summary_with(&dir, &format!("no-{effect}"), Some(&rest));
        let listed: Vec<&str> = without["effects"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e.as_str().unwrap())
            .collect();
        assert_eq!(listed, rest, "{effect}");
        assert_eq!(without["nonfinite_frames"], 0, "{effect}");
        let fewer = |k: &str| get(&without, k) < get(&full, k);
        match effect {
            "gravity" | "glue" => assert!(fewer("terms_max"), "{effect}: {without}"),
            "collisions" => assert_eq!(get(&without, "contact_tests_total"), 0),
            "cover" | "blocks" => {
                assert!(
                    fewer("dofs_max") && fewer("constraint_rows_max"),
                    "{effect}: {without}"
                );
            }
            "bookmarking" => {
                assert_eq!(get(&without, "snapshots_total"), 0);
                assert!(get(&full, "snapshots_total") > 0);
            }
            _ => unreachable!(),
        }
    }
}

#[test]
fn list_names_every_built_in_scene() {
    let out = folio(&scratch("list"), &["list"]);
    assert!(out.status.success());
    let listed = text(&out.stdout);
    for name in SCENES {
        assert!(
            listed.lines().any(|l| l.starts_with(name)),
            "{name} not listed"
        );
    }
}

#[test]
fn check_accepts_the_shipped_scenes_and_the_documented_examples() {
    let dir = scratch("check");
    let mut files: Vec<String> = std::fs::read_dir(repo().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path().display().to_string())
        .collect();
    // Every ```toml block of docs/scenes.md is a scene.
    let docs = std::fs::read_to_string(repo().join("docs/scenes.md")).unwrap();
    for (k, block) in docs.split("```toml").skip(1).enumerate() {
        let scene = block.split("```").next().unwrap();
        let file = dir.join(format!("doc_{k}.toml"));
        std::fs::write(&file, scene).unwrap();
        files.push(file.display().to_string());
    }
    assert!(files.len() >= SCENES.len() + 2, "{files:?}");
    let args: Vec<&str> = core::iter::once("check")
        .chain(files.iter().map(String::as_str))
        .collect();
    let out = folio(&dir, &args);
    assert!(out.status.success(), "{}", text(&out.stderr));
}

#[test]
fn malformed_scenes_are_refused_at_their_line_and_column() {
    let dir = scratch("malformed");
    let good = "name = \"x\"\nmodel = \"cone\"\ninput = { fixture = \"page-turn-touch\" }\n";
    let dog = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
    let events = "name = \"x\"\nmodel = \"cone\"\n[[input.events]]\nframe = 10\ngrab = [11.0, 3.0]\n[[input.events]]\nframe = 20\n";
    let cases: [(&str, String, &str); 22] = [
        ("unknown key", format!("{good}colour = 3\n"), "line 4, column 1"),
        ("unknown model", good.replace("\"cone\"", "\"paper\""), "line 2, column 9"),
        ("syntax", format!("{good}frames = \n"), "line 4"),
        ("frames out of range", format!("{good}frames = 0\n"), "line 4, column 10"),
        ("wrong type", format!("{good}frames = \"ten\"\n"), "line 4, column 10"),
        (
            "book fixture on a cone",
            good.replace("page-turn-touch", "page-turn"),
            "line 3, column 21",
        ),
        ("unknown fixture", good.replace("page-turn-touch", "nope"), "line 3, column 21"),
        (
            "a stack on a touch fixture",
            good.replace("\"page-turn-touch\" }", "\"page-turn-touch\", pages = 3 }"),
            "line 3, column 48",
        ),
        (
            "left pages above pages",
            "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n[book]\npages = 10\nleft_pages = 11\n".to_string(),
            "line 6, column 14",
        ),
        (
            "unknown effect",
            format!("effects = [\"blocks\", \"magnetism\"]\n{dog}"),
            "line 1, column 22",
        ),
        (
            "an effect the model lacks",
            format!("effects = [\"gravity\"]\n{good}"),
            "line 1, column 12",
        ),
        (
            "tearing is not there yet",
            format!("effects = [\"tearing\"]\n{dog}"),
            "line 1, column 12",
        ),
        (
            "an effect named twice",
            format!("effects = [\"blocks\", \"blocks\"]\n{dog}"),
            "line 1, column 22",
        ),
        (
            "glue without blocks",
            format!("effects = [\"glue\"]\n{dog}"),
            "line 1, column 12",
        ),
        ("weights on a cone", format!("{good}[weights]\npull = 1.0\n"), "line 4, column 1"),
        ("a negative weight", format!("{dog}[weights]\npull = -1.0\n"), "line 5, column 8"),
        ("a zero time step", format!("{dog}[solver]\ntime_step = 0.0\n"), "line 5, column 13"),
        (
            "substeps on the book",
            format!("{dog}[solver]\nsubsteps = 4\n"),
            "line 5, column 12",
        ),
        ("an event without action", events.to_string(), "line 6, column 1"),
        (
            "no tiles on the sheet",
            format!("{good}[output]\nsheet_tiles = 0\n"),
            "line 5, column 15",
        ),
        (
            "a grab off the page",
            events.replace("[11.0, 3.0]", "[13.0, 3.0]") + "drag = [0.0, 1.0, 3.0]\n",
            "line 5, column 8",
        ),
        (
            "frames going back",
            events.replace("frame = 20", "frame = 5\nrelease = true"),
            "line 6, column 1",
        ),
    ];
    for (what, scene, place) in cases {
        let file = dir.join("bad.toml");
        std::fs::write(&file, &scene).unwrap();
        let check = folio(&dir, &["check", "bad.toml"]);
        let stderr = text(&check.stderr);
        println!("{what}: {stderr}");
        assert_eq!(check.status.code(), Some(1), "{what}");
        assert!(
            stderr.contains(place),
            "{what}: expected {place} in {stderr}"
        );
        // Nothing half-run: `run` refuses before creating any output.
        let run = folio(&dir, &["run", "bad.toml", "--out", "never"]);
        assert_eq!(run.status.code(), Some(1), "{what}");
        assert!(!dir.join("never").exists(), "{what}");
    }
    let usage = folio(&dir, &["frobnicate"]);
    assert_eq!(usage.status.code(), Some(2));
}
