//! The `folio` command end to end: the default run, every built-in scene against its stated
//! expectations, `list`, `check` on the shipped scene files and the documentation's
//! examples, and malformed scenes (line and column, non-zero exit, nothing half-run).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENES: [&str; 6] = [
    "page-turn",
    "peek",
    "bookmark-flip",
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
}

#[test]
fn every_built_in_scene_meets_its_expectations() {
    let dir = scratch("builtin");
    for name in &SCENES[1..] {
        let out = folio(&dir, &["run", name, "--out", name]);
        println!("{}", text(&out.stdout));
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        assert!(dir.join(name).join("report.json").is_file(), "{name}");
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
    let cases: [(&str, String, &str); 9] = [
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
