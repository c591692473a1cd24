//! The `folio` command end to end: the default run, every built-in scene against its stated
//! expectations, the tear scenes' mesh, textures and picture, `list`, `check` on the shipped
//! scene files and the documentation's examples, and malformed scenes (line and column,
//! non-zero exit, nothing half-run).

use std::path::{Path, PathBuf};

const SCENES: [&str; 10] = [
    "page-turn",
    "page-turn-mcu",
    "peek",
    "bookmark-flip",
    "stack",
    "paperback",
    "three-and-back",
    "cone-turn",
    "mass-spring-turn",
    "xpbd-turn",
];

/// The tearing sheet's built-in scenes (seed 002 Fig. 13-16).
const TEAR_SCENES: [&str; 4] = ["tear-straight", "tear-curved", "tear-zigzag", "tear-twist"];

mod common;

use common::{folio, text};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    common::scratch("cli", name)
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

/// A page turn by timed events: the fixture's grab point, over the spine, let go. (The
/// `page-turn` fixture's camera ray misses the book without gravity, whose blocks then rest
/// in another shape; `folio check` refuses that scene.)
const TURN: &str = "[[input.events]]\nframe = 30\ngrab = [11.0, 3.4]\n[[input.events]]\n\
    frame = 90\ndrag = [0.0, 8.0, 5.0]\n[[input.events]]\nframe = 130\ndrag = [-11.0, 0.5, 3.4]\n\
    [[input.events]]\nframe = 131\nrelease = true\n";

/// The scene `name` with `effects` (all of the DOG book's when `None`), 200 frames of a
/// page turn: its summary. Every variant grabs the page (no input did nothing).
fn summary_with(dir: &Path, name: &str, effects: Option<&[&str]>) -> serde_json::Value {
    let list = effects.map_or(String::new(), |e| {
        let quoted: Vec<String> = e.iter().map(|x| format!("\"{x}\"")).collect();
        format!("effects = [{}]\n", quoted.join(", "))
    });
    let scene = format!("name = \"{name}\"\nmodel = \"dog\"\nframes = 200\n{list}{TURN}");
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, scene).unwrap();
    let out = folio(dir, &["run", file.to_str().unwrap(), "--out", name]);
    assert!(out.status.success(), "{name}: {}", text(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(name).join("report.json")).unwrap())
            .unwrap();
    let summary = report["summary"].clone();
    assert_eq!(summary["health"]["input_problems"], 0, "{name}");
    assert!(
        summary["max_stretch_max"].as_f64().is_some(),
        "{name}: no page held"
    );
    summary
}

/// The page turn with and without each effect of the DOG book: what is left out shows in
/// the report as fewer terms, rows, unknowns, collision tests or snapshots.
#[test]
fn a_scene_with_and_without_each_effect() {
    let dir = scratch("effects");
    // The book's one list of its effects: a new effect lands in the match below.
    let all = folio_book::Effects::NAMES;
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

/// An RGBA8 PNG decoded: width, height, pixels.
fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buf).expect("decodes");
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Every tear scene runs (all four at once, each its own process) and meets its
/// expectations; its outputs are read back: the report's tears, the torn mesh (an OBJ
/// whose lips are extra vertices), two decodable PNG alpha textures per tear of the
/// raster's size whose left and right masks differ (there is a cut, transparent on
/// opposite sides), the picture of the torn sheet and the close-up of its torn edge.
#[test]
fn tear_scenes_write_their_mesh_textures_and_picture() {
    let dir = scratch("tears");
    let runs: Vec<_> = TEAR_SCENES
        .iter()
        .map(|name| {
            let dir = dir.clone();
            std::thread::spawn(move || (name, folio(&dir, &["run", name, "--out", name])))
        })
        .collect();
    for run in runs {
        let (name, out) = run.join().unwrap();
        println!("{}", text(&out.stdout));
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        let out = dir.join(name);
        check_outputs(&out, name);
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
                .unwrap();
        assert_eq!(report["model"], "sheet");
        let summary = &report["summary"];
        assert_eq!(summary["nonfinite_frames"], 0, "{name}");
        let lengths = summary["tear_lengths"].as_array().unwrap();
        assert!(!lengths.is_empty(), "{name}: no tear");
        let tearing = &report["tearing"];
        let tears = tearing["tears"].as_array().unwrap();
        assert_eq!(tears.len(), lengths.len(), "{name}");
        assert!(
            summary["propagations_total"].as_u64().unwrap() > 0,
            "{name}"
        );
        let per_frame: u64 = report["frames"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["propagations"].as_u64().unwrap())
            .sum();
        assert_eq!(per_frame, summary["propagations_total"].as_u64().unwrap());
        let size = tearing["texture_size"].as_array().unwrap();
        let size = [0, 1].map(|k| size[k].as_u64().unwrap() as u32);
        // The torn mesh: every face in range, more vertices than the 9 x 7 of the rectangle.
        let obj = std::fs::read_to_string(out.join("torn_sheet.obj")).unwrap();
        let count = |prefix: &str| obj.lines().filter(|l| l.starts_with(prefix)).count();
        let (vertices, faces) = (count("v "), count("f "));
        assert_eq!(count("vt "), vertices, "{name}");
        assert!(
            vertices > 63 && faces >= 96,
            "{name}: {vertices} vertices, {faces} faces"
        );
        for line in obj.lines().filter(|l| l.starts_with("f ")) {
            for corner in line.split_whitespace().skip(1) {
                let i: usize = corner.split('/').next().unwrap().parse().unwrap();
                assert!((1..=vertices).contains(&i), "{name}: {line}");
            }
        }
        // The textures of every tear.
        let mut cut = false;
        for k in 0..tears.len() {
            let [left, right] = ["left", "right"].map(|side| {
                let bytes = std::fs::read(out.join(format!("tear-{k}-{side}.png"))).unwrap();
                let (w, h, rgba) = decode_png(&bytes);
                assert_eq!([w, h], size, "{name}: tear {k} {side}");
                rgba
            });
            assert_eq!(left.len(), right.len());
            let alpha = |rgba: &[u8], i: usize| rgba[4 * i + 3];
            let pixels = left.len() / 4;
            let differ = (0..pixels).any(|i| alpha(&left, i) != alpha(&right, i));
            let only_left = (0..pixels).any(|i| alpha(&left, i) == 0 && alpha(&right, i) == 255);
            let only_right = (0..pixels).any(|i| alpha(&right, i) == 0 && alpha(&left, i) == 255);
            cut |= differ && only_left && only_right;
            // Opaque pixels show the paper, not black.
            assert!(left.chunks(4).any(|p| p[3] == 255 && p[0] > 200), "{name}");
        }
        assert!(cut, "{name}: no tear cuts its two masks apart");
        // The paper fills a good part of the picture (light pixels).
        let [share, _] = shares(&out.join("torn_sheet.png"), name);
        assert!((0.1..0.9).contains(&share), "{name}: {share}");
        // The close-up of the longest tear's edge shows paper and, beside its edge, what
        // lies behind the sheet.
        let [paper, behind] = shares(&out.join("torn_edge.png"), name);
        assert!(
            paper > 0.05 && (0.02..0.9).contains(&behind),
            "{name}: {paper} {behind}"
        );
    }
}

/// The shares of light pixels (paper) and of the background (bluish grey: blue above red
/// by 15 or more, which neither the paper nor its ink is) in the 960 x 720 picture `path`
/// of scene `name`.
fn shares(path: &Path, name: &str) -> [f64; 2] {
    let (w, h, picture) = decode_png(&std::fs::read(path).unwrap());
    assert_eq!((w, h), (960, 720), "{name}: {}", path.display());
    let count = |keep: fn(&[u8]) -> bool| picture.chunks(4).filter(|p| keep(p)).count();
    let light = count(|p| p[0] > 200 && p[1] > 200);
    let background = count(|p| i32::from(p[2]) - i32::from(p[0]) >= 15);
    let shares = [light, background].map(|n| n as f64 / f64::from(w * h));
    println!(
        "{name}: {} {:.1} % light, {:.1} % background",
        path.display(),
        100.0 * shares[0],
        100.0 * shares[1]
    );
    shares
}

#[test]
fn list_names_every_built_in_scene() {
    let out = folio(&scratch("list"), &["list"]);
    assert!(out.status.success());
    let listed = text(&out.stdout);
    for name in SCENES.iter().chain(&TEAR_SCENES) {
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
    assert!(
        files.len() >= SCENES.len() + TEAR_SCENES.len() + 2,
        "{files:?}"
    );
    let args: Vec<&str> = core::iter::once("check")
        .chain(files.iter().map(String::as_str))
        .collect();
    let out = folio(&dir, &args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // They use today's keys: no warning about an older one.
    assert!(
        !text(&out.stderr).contains("warning"),
        "{}",
        text(&out.stderr)
    );
}

/// A scene in the older keys (before the keys were the settings' field names) still checks,
/// and `check` says, at each older key, which key it is now.
#[test]
fn an_older_key_checks_with_a_warning_naming_the_new_key() {
    let dir = scratch("older");
    let file = dir.join("old.toml");
    std::fs::write(
        &file,
        "name = \"old\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n\
         [solver]\ngrid = [6, 8]\nmax_corrections = 2\n",
    )
    .unwrap();
    let out = folio(&dir, &["check", &file.display().to_string()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let said = text(&out.stderr);
    assert!(
        said.contains(
            "line 5, column 8: `solver.grid` is the older spelling of \
                       `book.quads_across` and `book.quads_along`"
        ),
        "{said}"
    );
    assert!(
        said.contains(
            "line 6, column 19: `solver.max_corrections` is the older spelling of \
                       `book.projection_iterations`"
        ),
        "{said}"
    );
}

#[test]
fn malformed_scenes_are_refused_at_their_line_and_column() {
    let dir = scratch("malformed");
    let good = "name = \"x\"\nmodel = \"cone\"\ninput = { fixture = \"page-turn-touch\" }\n";
    let dog = "name = \"x\"\nmodel = \"dog\"\ninput = { fixture = \"page-turn\" }\n";
    let events = "name = \"x\"\nmodel = \"cone\"\n[[input.events]]\nframe = 10\ngrab = [11.0, 3.0]\n[[input.events]]\nframe = 20\n";
    // A sheet with one hand; line 4 is the hand's fingers, line 5 its moves.
    let sheet = "name = \"x\"\nmodel = \"sheet\"\n[[input.hands]]\nfingers = [[4.5, 0.0]]\nmoves = [{ start = 0.0, end = 1.0, velocity = [-0.3, 0.0, 0.0] }]\n";
    let cases: [(&str, String, &str); 36] = [
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
            "tearing on the book",
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
        ("an unknown sheet key", format!("{sheet}[sheet]\ncolour = 3\n"), "line 7, column 1"),
        ("a sheet without hands", "name = \"x\"\nmodel = \"sheet\"\ninput = {}\n".into(), "line 3, column 9"),
        (
            "a sheet driven by a fixture",
            sheet.replace("[[input.hands]]", "[input]\nfixture = \"page-turn-touch\"\n[[input.hands]]"),
            "line 4, column 11",
        ),
        ("hands on a cone", sheet.replace("\"sheet\"", "\"cone\""), "line 3, column 1"),
        ("a sheet on a book", format!("{dog}[sheet]\nwidth = 3.0\n"), "line 4, column 1"),
        ("a finger off the sheet", sheet.replace("4.5, 0.0", "14.5, 0.0"), "line 4, column 12"),
        (
            "two fingers on one point",
            sheet.replace("[[4.5, 0.0]]", "[[4.5, 0.0], [4.5, 0.01]]"),
            "line 4, column 24",
        ),
        ("a move ending before it starts", sheet.replace("end = 1.0", "end = -1.0"), "line 5, column 31"),
        ("a move going nowhere", sheet.replace(", velocity = [-0.3, 0.0, 0.0]", ""), "line 5, column 10"),
        (
            "an endless move without frames",
            sheet.replace("end = 1.0, ", ""),
            "line 5, column 10",
        ),
        ("a sheet with no quads", format!("{sheet}[sheet]\nnx = 0\n"), "line 7, column 6"),
        (
            "a negative thickness",
            format!("{sheet}[tearing]\nthickness = -0.01\n"),
            "line 7, column 13",
        ),
        (
            "a notch off the grid",
            format!("{sheet}[sheet]\nnotch = [[6.0, 0.0], [6.2, 1.5]]\n"),
            "line 7, column 22",
        ),
        (
            "a notch inside the sheet",
            format!("{sheet}[sheet]\nnotch = [[6.0, 1.5], [6.0, 3.0]]\n"),
            "line 7, column 10",
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

/// A scene that names a paper runs on it, and the report gives the paper in physical units
/// with the figures worked by hand from the stock (card: 300 g/m², 380 µm, 3 GPa across
/// the grain, ν = 0.3) on an A5 page: D = E t³ / (12 (1 − ν²)), α = ρ g L³ / D, and the
/// book's clock τ = sqrt(g_b ℓ / g) with ℓ = L / 12 page units and g_b = 9.81 page units/s².
/// The card's page is stiff enough to hold within the health bounds.
#[test]
fn a_scene_on_card_reports_its_paper() {
    let dir = scratch("paper");
    let file = dir.join("card.toml");
    let scene = format!("name = \"card\"\nmodel = \"dog\"\npaper = \"card\"\nframes = 140\n{TURN}");
    std::fs::write(&file, scene).unwrap();
    let out = folio(&dir, &["run", file.to_str().unwrap(), "--out", "card"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("  paper            148 x "),
        "{}",
        text(&out.stdout)
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("card/report.json")).unwrap())
            .unwrap();
    let paper = &report["paper"];
    let get = |k: &str| paper[k].as_f64().unwrap_or_else(|| panic!("{k}: {paper}"));
    let d = 3e9 * 380e-6f64.powi(3) / (12.0 * (1.0 - 0.09));
    let alpha = 0.3 * 9.81 * 0.148f64.powi(3) / d;
    let tau = (9.81 * 0.148 / 12.0 / 9.81f64).sqrt();
    for (key, want) in [
        ("width_m", 0.148),
        ("grammage", 300.0),
        ("caliper_m", 380e-6),
        ("bending_stiffness", d),
        ("sag_number", alpha),
        ("metres_per_unit", 0.148 / 12.0),
        ("real_seconds_per_second", tau),
    ] {
        assert!(
            (get(key) / want - 1.0).abs() < 1e-9,
            "{key}: {} against {want}",
            get(key)
        );
    }
    // The Newton iterations: every awake frame counted once, at most the book's one
    // iteration per step (one step per frame at the default time step).
    let summary = &report["summary"];
    let histogram = summary["newton_iterations"]
        .as_object()
        .expect("a histogram");
    let awake: u64 = histogram.values().map(|v| v.as_u64().unwrap()).sum();
    let frames = summary["frames"].as_u64().unwrap();
    let asleep = summary["asleep_frames"].as_u64().unwrap();
    assert_eq!(awake, frames - asleep, "{histogram:?}");
    assert!(
        histogram.keys().all(|k| k == "1" || k == "0"),
        "{histogram:?}"
    );
    assert!(text(&out.stdout).contains("  Newton           iterations per awake frame"));
    // The seed's card (and a scene without a paper) has no physical size to report.
    let seed = dir.join("seed.toml");
    let scene =
        format!("name = \"seed\"\nmodel = \"dog\"\npaper = \"seed-card\"\nframes = 2\n{TURN}");
    std::fs::write(&seed, scene).unwrap();
    let out = folio(&dir, &["run", seed.to_str().unwrap(), "--out", "seed"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("seed/report.json")).unwrap())
            .unwrap();
    assert!(report.get("paper").is_none(), "{report}");
}
