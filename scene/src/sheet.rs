//! The tearing sheet a scene describes (`model = "sheet"`, seed `002_…`): its settings
//! ([`crate::settings::sheet_settings`]), its mesh with the notch cut, and its hands
//! pinching it ([`crate::hands`]). Checking a scene builds all of it, so that whatever the
//! sheet would refuse is reported at its place in the file.

use core::ops::Range;

use folio_geometry::SheetMesh;
use folio_tearing::sheet::{SheetSettings, TearingSheet};
use toml::Spanned;

use crate::clock::FRAME_SECONDS;
use crate::hands::{self, Hands};
use crate::scene::{HandSpec, Scene};
use crate::settings::sheet_settings;

type Problem = (Range<usize>, String);

/// The sheet's settings, or where they do not read.
fn read(scene: &Scene) -> Result<SheetSettings<f64>, Problem> {
    sheet_settings(scene).map_err(|e| {
        let span = scene.sheet.as_ref().map_or(0..0, Spanned::span);
        (span, e.message)
    })
}

/// The hands of a sheet scene.
fn hand_specs(scene: &Scene) -> Result<&Spanned<Vec<Spanned<HandSpec>>>, Problem> {
    scene.input.get_ref().hands.as_ref().ok_or_else(|| {
        (
            scene.input.span(),
            "a sheet scene needs [[input.hands]]".into(),
        )
    })
}

/// The frames a sheet scene runs: its `frames`, else the hands' ([`hands::default_frames`]).
///
/// # Errors
/// A scene without `frames` whose hands move without end, or without hands.
pub fn frames(scene: &Scene) -> Result<u32, Problem> {
    match &scene.frames {
        Some(f) => Ok(*f.get_ref()),
        None => hands::default_frames(hand_specs(scene)?.get_ref(), FRAME_SECONDS),
    }
}

/// Checks a sheet scene: each setting in its one place, then builds its sheet ([`setup`])
/// and counts its frames.
///
/// # Errors
/// As [`setup`] and [`frames`].
pub fn check(scene: &Scene) -> Result<(), Problem> {
    setup(scene)?;
    frames(scene).map(|_| ())
}

/// The sheet of a scene at rest with its notch cut, and its hands pinching it: the
/// settings are validated, then the hands ([`hands::check`]), the notch and the grabs.
///
/// # Errors
/// The span of the setting, notch point, hand or finger the sheet refuses, and why.
pub fn setup(scene: &Scene) -> Result<(TearingSheet<f64>, Hands), Problem> {
    let settings = read(scene)?;
    settings
        .validate()
        .map_err(|e| crate::settings::refusal(scene, "sheet", &e))?;
    let specs = hand_specs(scene)?;
    hands::check(specs, [settings.width, settings.height])?;
    let mut mesh = SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)
        .map_err(|e| (whole_sheet(scene), format!("sheet mesh: {e}")))?;
    if let Some(notch) = &scene.notch {
        cut_notch(&mut mesh, notch, &settings)?;
    }
    let mut sheet =
        TearingSheet::with_mesh(mesh, settings).map_err(|e| (whole_sheet(scene), e.to_string()))?;
    let hands = Hands::grab(&mut sheet, specs.get_ref(), FRAME_SECONDS)?;
    Ok((sheet, hands))
}

/// The span of `[sheet]`, else of the whole file's start.
fn whole_sheet(scene: &Scene) -> Range<usize> {
    scene.sheet.as_ref().map_or(0..0, Spanned::span)
}

/// Cuts the notch polyline `notch` into the rectangle `mesh` of `settings` (its points
/// grid vertices, the first on the border, each segment along a grid line or a diagonal).
fn cut_notch(
    mesh: &mut SheetMesh<f64>,
    notch: &Spanned<Vec<Spanned<[f64; 2]>>>,
    settings: &SheetSettings<f64>,
) -> Result<(), Problem> {
    let (nx, ny) = (settings.nx, settings.ny);
    let spacing = [settings.width / nx as f64, settings.height / ny as f64];
    let points = notch.get_ref();
    if points.len() < 2 {
        return Err((notch.span(), "a notch needs at least two points".into()));
    }
    let mut grid = Vec::with_capacity(points.len());
    for p in points {
        let [u, v] = *p.get_ref();
        let (i, j) = ((u / spacing[0]).round(), (v / spacing[1]).round());
        let on_vertex = (u - i * spacing[0]).abs() <= 1e-6 * spacing[0]
            && (v - j * spacing[1]).abs() <= 1e-6 * spacing[1]
            && (0.0..=nx as f64).contains(&i)
            && (0.0..=ny as f64).contains(&j);
        if !on_vertex {
            return Err((
                p.span(),
                format!(
                    "a notch point must be a vertex of the {nx} x {ny} grid (spacing {} x {})",
                    spacing[0], spacing[1]
                ),
            ));
        }
        grid.push((i as i64, j as i64));
    }
    let (i0, j0) = grid[0];
    if !(i0 == 0 || j0 == 0 || i0 == nx as i64 || j0 == ny as i64) {
        return Err((
            points[0].span(),
            "a notch starts on the sheet's border".into(),
        ));
    }
    let id = |(i, j): (i64, i64)| (i + (nx as i64 + 1) * j) as u32;
    for (k, pair) in grid.windows(2).enumerate() {
        let ((a, b), span) = ((pair[0], pair[1]), points[k + 1].span());
        let (di, dj) = (b.0 - a.0, b.1 - a.1);
        let n = di.abs().max(dj.abs());
        if n == 0 || !(di == 0 || dj == 0 || di.abs() == dj.abs()) {
            return Err((
                span,
                "a notch segment runs along a grid line or a quad's diagonal to another point"
                    .into(),
            ));
        }
        for s in 0..n {
            let from = (a.0 + s * di / n, a.1 + s * dj / n);
            let to = (a.0 + (s + 1) * di / n, a.1 + (s + 1) * dj / n);
            mesh.cut_edge(id(from), id(to)).map_err(|e| {
                let at = |(i, j): (i64, i64)| {
                    format!("({}, {})", i as f64 * spacing[0], j as f64 * spacing[1])
                };
                (
                    span.clone(),
                    format!(
                        "the notch cannot be cut from {} to {}: {e}",
                        at(from),
                        at(to)
                    ),
                )
            })?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::scene::Scene;

    const SHEET: &str = "name = \"x\"\nmodel = \"sheet\"\nframes = 2\n\
        [[input.hands]]\nfingers = [[4.5, 0.0]]\n";

    /// The line and column of the error of `extra` appended to a valid sheet scene.
    fn refused(extra: &str) -> (usize, usize, String) {
        let e = Scene::parse(&format!("{SHEET}{extra}")).expect_err(extra);
        (e.line, e.column, e.message)
    }

    #[test]
    fn the_settings_types_are_the_scene_keys() {
        let text = format!(
            "{SHEET}[sheet]\nnx = 4\nnotch = [[6.0, 0.0], [6.0, 1.5]]\ntime_step = 0.01\n\
             [sheet.cones]\nflip_margin = 0.25\n[sheet.tearing]\nsnap = 0.2\n\
             [sheet.tearing.fibers]\nseed = 7\n[sheet.tearing.detail]\nsigma = 0.3\n"
        );
        let scene = Scene::parse(&text).unwrap();
        assert!(scene.notices.is_empty(), "{:?}", scene.notices);
        let s = crate::settings::sheet_settings(&scene).unwrap();
        assert_eq!(s.time_step, 0.01);
        let defaults = folio_tearing::sheet::SheetSettings::<f64>::default();
        assert_eq!((s.nx, s.ny), (4, defaults.ny));
        assert_eq!(s.cones.flip_margin, 0.25);
        assert_eq!(s.tearing.snap, 0.2);
        assert_eq!(s.tearing.fibers.seed, 7);
        assert_eq!(s.tearing.detail.sigma, 0.3);
        assert_eq!(s.tearing.detail.weight, defaults.tearing.detail.weight);
        assert_eq!(scene.notch.as_ref().map(|n| n.get_ref().len()), Some(2));
    }

    #[test]
    fn the_older_tearing_table_reads_at_its_new_key() {
        let text = format!("{SHEET}[tearing]\nsnap = 0.2\n[solver]\ntime_step = 0.01\n");
        let scene = Scene::parse(&text).unwrap();
        let s = crate::settings::sheet_settings(&scene).unwrap();
        assert_eq!((s.tearing.snap, s.time_step), (0.2, 0.01));
        let said: Vec<&str> = scene.notices.iter().map(|n| n.message.as_str()).collect();
        assert_eq!(said.len(), 2, "{said:?}");
        assert!(said[0].contains("`sheet.tearing`"), "{said:?}");
        assert!(said[1].contains("`sheet.time_step`"), "{said:?}");
    }

    #[test]
    fn a_refused_setting_is_reported_at_its_key() {
        let (line, column, message) = refused("[sheet.cones]\nflip_margin = 2.0\n");
        assert_eq!((line, column), (7, 15), "{message}");
        assert!(
            message.contains("`sheet.cones.flip_margin` must be in [0, 1]"),
            "{message}"
        );
        let (line, column, message) = refused("[sheet.tearing.detail]\nweight = 1.5\n");
        assert_eq!((line, column), (7, 10), "{message}");
        assert_eq!(
            message,
            "`sheet.tearing.detail.weight` must be in [0, 1], not 1.5"
        );
        let (line, column, message) = refused("[sheet]\nheight = -1.0\n");
        assert_eq!((line, column), (7, 10), "{message}");
        assert_eq!(message, "`sheet.height` must be finite and > 0, not -1");
    }

    #[test]
    fn unknown_and_misplaced_keys_are_refused_at_their_place() {
        let (line, column, message) = refused("[sheet.tearing.fibers]\ncolour = 1\n");
        assert_eq!((line, column), (7, 1), "{message}");
        assert!(message.contains("unknown field `colour`"), "{message}");
        let (line, _, message) = refused("[sheet.tearing]\nsnap = 0.1\n[tearing]\nsnap = 0.2\n");
        assert_eq!(line, 8, "{message}");
        assert!(
            message.contains("older spelling and its new one"),
            "{message}"
        );
        // A table is placed at its header.
        let (line, _, message) = refused("[sheet.effects]\ngravity = true\n");
        assert_eq!(line, 6, "{message}");
        assert!(message.contains("`effects` list"), "{message}");
    }
}
