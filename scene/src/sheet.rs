//! The tearing sheet a scene describes (`model = "sheet"`, seed `002_…`): its settings
//! ([`crate::settings::sheet_settings`]), its mesh with the notch cut, and its hands
//! pinching it ([`crate::hands`]). Checking a scene builds all of it, so that whatever the
//! sheet would refuse is reported at its place in the file.

use core::ops::Range;

use folio_geometry::SheetMesh;
use folio_tearing::TearingError;
use folio_tearing::sheet::{SheetSettings, TearingSheet, TearingSheetError};
use toml::Spanned;

use crate::hands::{self, Hands};
use crate::scene::{HandSpec, Scene};
use crate::settings::sheet_settings;

type Problem = (Range<usize>, String);

/// The sheet's pattern size `[W, H]` (sheet units).
#[must_use]
pub fn size(scene: &Scene) -> [f64; 2] {
    let s = sheet_settings(scene);
    [s.width, s.height]
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
        None => hands::default_frames(
            hand_specs(scene)?.get_ref(),
            sheet_settings(scene).time_step,
        ),
    }
}

/// Checks a sheet scene: builds its sheet ([`setup`]) and counts its frames.
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
    let settings = sheet_settings(scene);
    settings
        .validate()
        .map_err(|e| settings_problem(scene, &e))?;
    let specs = hand_specs(scene)?;
    hands::check(specs, [settings.width, settings.height])?;
    let mut mesh = SheetMesh::rectangle(settings.width, settings.height, settings.nx, settings.ny)
        .map_err(|e| (whole_sheet(scene), format!("sheet mesh: {e}")))?;
    if let Some(notch) = scene
        .sheet
        .as_ref()
        .and_then(|s| s.get_ref().notch.as_ref())
    {
        cut_notch(&mut mesh, notch, &settings)?;
    }
    let mut sheet =
        TearingSheet::with_mesh(mesh, settings).map_err(|e| (whole_sheet(scene), e.to_string()))?;
    let hands = Hands::grab(&mut sheet, specs.get_ref(), settings.time_step)?;
    Ok((sheet, hands))
}

/// The span of `[sheet]`, else of the whole file's start.
fn whole_sheet(scene: &Scene) -> Range<usize> {
    scene.sheet.as_ref().map_or(0..0, Spanned::span)
}

/// Every scene key of the sheet's settings: the settings' name for it (as the sheet's and
/// the tearing step's errors name it), the scene key, the rule it breaks, and its span in
/// the scene (if the scene sets it).
fn keys(
    scene: &Scene,
) -> Vec<(
    &'static str,
    &'static str,
    &'static str,
    Option<Range<usize>>,
)> {
    let mut out = Vec::new();
    let sheet = scene.sheet.as_ref().map(Spanned::get_ref);
    let f = |v: Option<&Spanned<f64>>| v.map(Spanned::span);
    let n = |v: Option<&Spanned<u32>>| v.map(Spanned::span);
    if let Some(s) = sheet {
        out.extend([
            (
                "width",
                "sheet.width",
                "finite and > 0",
                f(s.width.as_ref()),
            ),
            (
                "height",
                "sheet.height",
                "finite and > 0",
                f(s.height.as_ref()),
            ),
            ("nx", "sheet.nx", "between 1 and 64", n(s.nx.as_ref())),
            ("ny", "sheet.ny", "between 1 and 64", n(s.ny.as_ref())),
            (
                "stretch_modulus",
                "sheet.stretch_modulus",
                "finite and > 0",
                f(s.stretch_modulus.as_ref()),
            ),
            (
                "poisson",
                "sheet.poisson",
                "in [0, 0.5)",
                f(s.poisson.as_ref()),
            ),
            (
                "bending",
                "sheet.bending",
                "finite and >= 0",
                f(s.bending.as_ref()),
            ),
            (
                "density",
                "sheet.density",
                "finite and > 0",
                f(s.density.as_ref()),
            ),
            ("gravity", "sheet.gravity", "finite", f(s.gravity.as_ref())),
            (
                "max_propagations",
                "sheet.max_propagations",
                "at most 64",
                n(s.max_propagations.as_ref()),
            ),
        ]);
    }
    if let Some(s) = &scene.solver {
        let h = s.get_ref().time_step.as_ref();
        out.push(("time_step", "solver.time_step", "in (0, 0.1]", f(h)));
    }
    if let Some(t) = scene.tearing.as_ref().map(Spanned::get_ref) {
        let range = "in its range";
        out.extend([
            (
                "TearSettings.thickness",
                "tearing.thickness",
                range,
                f(t.thickness.as_ref()),
            ),
            (
                "TearSettings.fracture",
                "tearing.fracture",
                range,
                f(t.fracture.as_ref()),
            ),
            (
                "TearSettings.damage",
                "tearing.damage",
                range,
                f(t.damage.as_ref()),
            ),
            (
                "TearSettings.speed",
                "tearing.speed",
                range,
                f(t.speed.as_ref()),
            ),
            (
                "TearSettings.min_step",
                "tearing.min_step",
                range,
                f(t.min_step.as_ref()),
            ),
            (
                "TearSettings.max_step",
                "tearing.max_step",
                range,
                f(t.max_step.as_ref()),
            ),
            (
                "TearSettings.turn_threshold",
                "tearing.turn_threshold",
                range,
                f(t.turn_threshold.as_ref()),
            ),
            (
                "TearSettings.snap",
                "tearing.snap",
                range,
                f(t.snap.as_ref()),
            ),
            (
                "TearSettings.texture_density",
                "tearing.texture_density",
                range,
                f(t.texture_density.as_ref()),
            ),
            (
                "DetailSettings.weight",
                "tearing.detail_weight",
                range,
                f(t.detail_weight.as_ref()),
            ),
            (
                "DetailSettings.sigma",
                "tearing.detail_sigma",
                range,
                f(t.detail_sigma.as_ref()),
            ),
        ]);
    }
    out
}

/// What a refused setting is, at the scene key that set it (module docs).
fn settings_problem(scene: &Scene, e: &TearingSheetError) -> Problem {
    let field = match *e {
        TearingSheetError::InvalidSetting { field }
        | TearingSheetError::Tearing(
            TearingError::NonFinite { field } | TearingError::OutOfRange { field, .. },
        ) => field,
        _ => "",
    };
    let known = keys(scene).into_iter().find(|k| k.0 == field);
    let message = match (*e, &known) {
        (TearingSheetError::InvalidSetting { .. }, Some((_, key, rule, _))) => {
            format!("{key} must be {rule}")
        }
        (
            TearingSheetError::Tearing(TearingError::OutOfRange {
                value, min, max, ..
            }),
            Some((_, key, _, _)),
        ) => format!("{key} = {value} is outside [{min}, {max}]"),
        (TearingSheetError::Tearing(TearingError::NonFinite { .. }), Some((_, key, _, _))) => {
            format!("{key} is not finite")
        }
        _ => e.to_string(),
    };
    let span = known
        .and_then(|k| k.3)
        .unwrap_or_else(|| whole_sheet(scene));
    (span, message)
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
