//! Scene files: TOML, parsed by `toml` and read with serde through [`crate::reader`] (the
//! format is documented in `docs/scenes.md`).
//! Every error names its line and column; a scene that does not check is never run.

use core::ops::Range;

use folio_book::{BookParams, Weights};
use folio_tearing::TearSettings;
use folio_tearing::sheet::SheetSettings;
use serde::Deserialize;
use toml::Spanned;
use toml::de::DeTable;

use crate::keys::{self, KeySpans};
use crate::reader::{self, ReadError};

/// A scene: which page model, which book or page, which input, for how long.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name (file names, reports).
    pub name: String,
    /// One line for `folio list`.
    #[serde(default)]
    pub description: String,
    /// The page model.
    pub model: Spanned<ModelKind>,
    /// Frames to run (60 per second); default: the input's own length.
    pub frames: Option<Spanned<u32>>,
    /// The effects to simulate (default: every effect the model has; see
    /// [`ModelKind::effects`]). An effect left out contributes no term and no work.
    pub effects: Option<Spanned<Vec<Spanned<String>>>>,
    /// The book around a DOG page (`model = "dog"` only): the keys of [`BookParams`]
    /// (omitted keys keep its defaults; without `left_pages`, half the pages start on the
    /// left), except `cover`, which is the `cover` effect.
    pub book: Option<Spanned<BookParams>>,
    /// The sheet of a tearing scene (`model = "sheet"` only): the keys of
    /// [`SheetSettings`] (omitted keys keep its defaults), except `tearing` (the scene's
    /// `[tearing]`), `time_step` (`solver.time_step`) and `effects` (the scene's list).
    pub sheet: Option<Spanned<SheetSettings<f64>>>,
    /// A slit cut into the sheet before the run, written `sheet.notch`: a polyline of grid
    /// vertices from a point on the border, each segment along a grid line or a quad's
    /// diagonal (`model = "sheet"` only).
    #[serde(skip)]
    pub notch: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
    /// The tearing step's parameters (`model = "sheet"` only): the keys of
    /// [`TearSettings`], with `[tearing.fibers]` and `[tearing.detail]`.
    pub tearing: Option<Spanned<TearSettings>>,
    /// Potential weights of the DOG book (`model = "dog"` only): the keys of [`Weights`],
    /// each in $[0, 10^9]$.
    pub weights: Option<Spanned<Weights<f64>>>,
    /// Time step and solver settings.
    pub solver: Option<Spanned<SolverSection>>,
    /// The input: a recorded fixture or timed events.
    pub input: Spanned<InputSection>,
    /// What `folio run` writes.
    #[serde(default)]
    pub output: OutputSection,

    /// What the run must show; `folio run` fails when it does not.
    #[serde(default)]
    pub expect: Expect,

    /// Where each key of the file sits (errors of a model's `validate()` point there).
    #[serde(skip)]
    pub keys: KeySpans,
}

/// A scene's stated expectations, checked against the run's summary. The per-frame bounds
/// (`max_stretch`, `dog_residual_max`, `penetration_max`, `failed_steps`) replace the
/// health bounds every run is held to (defaults: 10 % stretch, a DOG residual of 1e-2,
/// one page thickness of penetration, no failed step).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expect {
    /// Pages left, right and held at the end (DOG book).
    pub final_pages: Option<[u32; 3]>,
    /// Upper bound on every frame's max edge stretch (default 0.1).
    pub max_stretch: Option<f64>,
    /// Upper bound on the mean max edge stretch.
    pub max_stretch_mean: Option<f64>,
    /// Upper bound on the mean RMSE edge stretch.
    pub rmse_stretch_mean: Option<f64>,
    /// Upper bound on the DOG residual after any step (default 1e-2).
    pub dog_residual_max: Option<f64>,
    /// Upper bound on the penetration into a block after collision handling (default: one
    /// page thickness).
    pub penetration_max: Option<f64>,
    /// Most frames whose step failed (`Stalled`, non-finite input, a failed line search or
    /// factorization, a refused step; default 0).
    pub failed_steps: Option<usize>,
    /// Lower bound on the length of the longest tear in the pattern (sheet units; sheet).
    pub tear_length_min: Option<Spanned<f64>>,
    /// Why the first tear started (sheet): `"inward-angle"`, `"junction"`, `"finger"`.
    pub tear_start: Option<Spanned<TearStart>>,
}

/// The kind of potential tearing point a tear starts at (seed `002_…` Sec. 4.1).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum TearStart {
    /// A boundary vertex with an inward angle (a notch).
    InwardAngle,
    /// A junction point of flat and curved regions.
    Junction,
    /// A finger, or the boundary vertex nearest to one.
    Finger,
}

impl TearStart {
    /// The name used in scene files and reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::InwardAngle => "inward-angle",
            Self::Junction => "junction",
            Self::Finger => "finger",
        }
    }
}

/// The page models (issue 5's interface).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum ModelKind {
    /// The DOG book of seed 000 (page blocks, cover, active page).
    Dog,
    /// The cone curl of seed 001.
    Cone,
    /// The mass-spring page of seed 003.
    MassSpring,
    /// The position-based page: XPBD distance and isometric bending constraints.
    Xpbd,
    /// The tearing sheet of seed 002, held and pulled by hands.
    Sheet,
}

pub use crate::limits::MAX_WEIGHT;

/// Every effect a scene may name.
pub const EFFECTS: [&str; 9] = [
    "gravity",
    "glue",
    "collisions",
    "cover",
    "blocks",
    "bookmarking",
    "bending",
    "cones",
    "tearing",
];

impl ModelKind {
    /// The name used in scene files and reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Dog => "dog",
            Self::Cone => "cone",
            Self::MassSpring => "mass-spring",
            Self::Xpbd => "xpbd",
            Self::Sheet => "sheet",
        }
    }

    /// The effects the model can simulate (its default set).
    #[must_use]
    pub fn effects(self) -> &'static [&'static str] {
        match self {
            Self::Dog => &[
                "gravity",
                "glue",
                "collisions",
                "cover",
                "blocks",
                "bookmarking",
            ],
            Self::Cone => &[],
            Self::MassSpring | Self::Xpbd => &["gravity", "collisions"],
            Self::Sheet => &["gravity", "bending", "cones", "tearing"],
        }
    }
}

/// Time step and solver settings; omitted keys keep the model's defaults.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// Time step (seconds; DOG, mass-spring, xpbd and sheet).
    pub time_step: Option<Spanned<f64>>,
    /// Newton iterations per step (DOG; the seed's one).
    pub newton_iterations: Option<Spanned<u32>>,
    /// Constraint projection iterations after a step (DOG; 0 is the seed's plain step).
    pub max_corrections: Option<Spanned<u32>>,
    /// Substeps per step (mass-spring, 1 to 64; xpbd, 1 to 1024).
    pub substeps: Option<Spanned<u32>>,
    /// Quads of the page `[across, along]` (across from the spine, along it), each
    /// [`GRID_RANGE`] (dog, mass-spring: particles are quads + 1, xpbd).
    pub grid: Option<Spanned<[u32; 2]>>,
    /// The precision the model runs in (dog, mass-spring, xpbd; default `"f64"`).
    pub precision: Option<Spanned<Precision>>,
    /// The eq. 3 residual at which Newton stops iterating (dog; finite, >= 0).
    pub newton_tolerance: Option<Spanned<f64>>,
    /// Include the constraint Hessian in the KKT matrix (dog; default false, the seed's).
    pub constraint_hessian: Option<Spanned<bool>>,
    /// Restart length of the KKT refinement's GMRES in `f32` (dog, 1 to 50; default 10): its
    /// basis holds one more vector of the KKT order than this.
    pub krylov_restart: Option<Spanned<u32>>,
    /// Collision detect/resolve rounds per step (dog, 1 to 16; default 3, the seed's).
    pub collision_rounds: Option<Spanned<u32>>,
    /// The constraint projection after a step (dog; default true; `false` is
    /// `max_corrections = 0`).
    pub projection: Option<Spanned<bool>>,
    /// The mass-spring page's integrator: `"semi-implicit-euler"` (the seed's, default) or
    /// `"implicit-euler"` (mass-spring only).
    pub integrator: Option<Spanned<folio_pages::spring::Integrator>>,
}

/// The quads a page may have across and along (`solver.grid`), each.
pub const GRID_RANGE: core::ops::RangeInclusive<u32> = 2..=64;

/// The precision a model runs in (`solver.precision`).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// `f64`, the reference (default).
    #[default]
    F64,
    /// `f32`, the microcontroller path.
    F32,
}

impl Precision {
    /// The name used in scene files and reports (`"f64"`, `"f32"`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::F64 => "f64",
            Self::F32 => "f32",
        }
    }
}

/// The input of a scene: a named recorded fixture, or timed events.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputSection {
    /// One of [`crate::fixtures::NAMES`].
    pub fixture: Option<Spanned<String>>,
    /// Pages every grab of a book fixture takes (a stack; default: the fixture's own).
    pub pages: Option<Spanned<u32>>,
    /// Timed events: gestures in sequence (a grab, drags, a release, the next grab) in page
    /// coordinates.
    pub events: Option<Spanned<Vec<Spanned<EventSpec>>>>,
    /// The hands holding a sheet (`model = "sheet"` only).
    pub hands: Option<Spanned<Vec<Spanned<HandSpec>>>>,
}

/// One hand holding the sheet (`[[input.hands]]`): its fingers pinch the sheet at the
/// start, move with the hand as one rigid body, and let go together.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandSpec {
    /// The pattern points `[u, v]` (sheet units) the fingers pinch, one or more.
    pub fingers: Spanned<Vec<Spanned<[f64; 2]>>>,
    /// How the hand moves: segments in time order, the hand still between them.
    #[serde(default)]
    pub moves: Vec<Spanned<MoveSpec>>,
    /// When the hand lets go (seconds; default: it holds to the end).
    pub release: Option<Spanned<f64>>,
}

/// One segment of a hand's motion (`moves = [{ ... }]`): from `start` to `end` the hand
/// translates at `velocity` and turns at `spin` about its centre (the mean of its
/// fingers, moving with it).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveSpec {
    /// Start (seconds).
    pub start: Spanned<f64>,
    /// End (seconds; default: the end of the run).
    pub end: Option<Spanned<f64>>,
    /// Velocity `[x, y, z]` (sheet units per second; x along u, y along v, z out of the
    /// flat sheet).
    pub velocity: Option<Spanned<[f64; 3]>>,
    /// Angular velocity `[x, y, z]` (radians per second, right-handed about the axis).
    pub spin: Option<Spanned<[f64; 3]>>,
}

/// One timed input event (`[[input.events]]`): when (`frame` or `time`) and what (`grab`,
/// `drag` or `release`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventSpec {
    /// The frame (60 per second) before whose step the event applies.
    pub frame: Option<Spanned<u32>>,
    /// The same in seconds (rounded to the nearest frame).
    pub time: Option<Spanned<f64>>,
    /// Grab the page at material point `[u, v]` (page units: across from the spine, along
    /// it) of the page on `side`.
    pub grab: Option<Spanned<[f64; 2]>>,
    /// The side of the spine a grab takes its page from (default `"right"`; grabs only).
    pub side: Option<Spanned<crate::events::Side>>,
    /// Pages a grab takes at once, a stack (default 1; grabs only, DOG book only).
    pub pages: Option<Spanned<u32>>,
    /// The finger reaches `[x, y, z]` (page frame: x across the book from the spine, y up,
    /// z along the spine) at this frame, moving in a straight line from where it was.
    pub drag: Option<Spanned<[f64; 3]>>,
    /// Let go (`release = true`).
    pub release: Option<Spanned<bool>>,
}

/// What a run writes into its output folder.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Write `report.json`.
    #[serde(default = "yes")]
    pub report: bool,
    /// Write `contact_sheet.png`.
    #[serde(default = "yes")]
    pub contact_sheet: bool,
    /// Tiles on the contact sheet, spread evenly over the run (1 to 256; default 16).
    pub sheet_tiles: Option<Spanned<u32>>,
    /// Write `animation.glb`.
    #[serde(default = "yes")]
    pub animation: bool,
    /// Frames between two frames of the animation (1 to 1000; default 5).
    pub animation_every: Option<Spanned<u32>>,
    /// Write `timeline.svg`.
    #[serde(default = "yes")]
    pub timeline: bool,
    /// Write the torn sheet's mesh `torn_sheet.obj` (sheet; default true).
    pub mesh: Option<Spanned<bool>>,
    /// Write every tear's alpha textures `tear-K-left.png`, `tear-K-right.png` (sheet;
    /// default true).
    pub textures: Option<Spanned<bool>>,
    /// Write the picture of the last frame `torn_sheet.png` and the close-up of its
    /// longest tear's edge `torn_edge.png` (sheet; default true).
    pub picture: Option<Spanned<bool>>,
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            report: true,
            contact_sheet: true,
            sheet_tiles: None,
            animation: true,
            animation_every: None,
            timeline: true,
            mesh: None,
            textures: None,
            picture: None,
        }
    }
}

impl OutputSection {
    /// Tiles on the contact sheet.
    #[must_use]
    pub fn tiles(&self) -> u32 {
        self.sheet_tiles.as_ref().map_or(16, |v| *v.get_ref())
    }

    /// Frames between two animation frames.
    #[must_use]
    pub fn every(&self) -> u32 {
        self.animation_every.as_ref().map_or(5, |v| *v.get_ref())
    }

    /// Whether a sheet run writes its torn mesh, its tear textures and its picture.
    #[must_use]
    pub fn sheet_files(&self) -> [bool; 3] {
        [&self.mesh, &self.textures, &self.picture].map(|v| v.as_ref().is_none_or(|v| *v.get_ref()))
    }
}

fn yes() -> bool {
    true
}

/// Why a scene does not check: a message at a line and column (1-based).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// 1-based line (0 when the error has no place in the file).
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What is wrong.
    pub message: String,
}

impl core::fmt::Display for SceneError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.message)
        } else {
            write!(
                f,
                "line {}, column {}: {}",
                self.line, self.column, self.message
            )
        }
    }
}

impl core::error::Error for SceneError {}

impl SceneError {
    /// An error at byte range `span` of `text`.
    #[must_use]
    pub fn at(text: &str, span: Option<Range<usize>>, message: impl Into<String>) -> Self {
        let (line, column) = span.map_or((0, 0), |s| line_column(text, s.start));
        Self {
            line,
            column,
            message: message.into(),
        }
    }
}

/// 1-based line and column of byte `offset` in `text`.
#[must_use]
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

impl Scene {
    /// Parses and checks the bytes of a scene file: as [`Scene::parse`], after checking
    /// that they are UTF-8.
    ///
    /// # Errors
    /// Bytes that are not UTF-8, at the line and column of the first bad byte, with its
    /// byte offset; else as [`Scene::parse`].
    pub fn parse_bytes(bytes: &[u8]) -> Result<Self, SceneError> {
        match core::str::from_utf8(bytes) {
            Ok(text) => Self::parse(text),
            Err(e) => {
                let at = e.valid_up_to();
                // The valid prefix places the bad byte.
                let valid = core::str::from_utf8(&bytes[..at]).unwrap_or_default();
                let (line, column) = line_column(valid, at);
                Err(SceneError {
                    line,
                    column,
                    message: format!(
                        "the file is not UTF-8: byte {at} (0-based) starts an invalid sequence"
                    ),
                })
            }
        }
    }

    /// Parses and checks `text` (module docs).
    ///
    /// # Errors
    /// The first problem, at its line and column: TOML syntax, an unknown key or model, a
    /// wrong type, a value out of range, an input that does not fit the model.
    pub fn parse(text: &str) -> Result<Self, SceneError> {
        let syntax = |e: toml::de::Error| SceneError::at(text, e.span(), e.message().trim());
        let schema = |e: ReadError| SceneError::at(text, e.span, e.message.trim());
        let mut doc = DeTable::parse(text).map_err(syntax)?;
        let notch = keys::take(&mut doc, "sheet", "notch");
        let keys = KeySpans::of(doc.get_ref());
        let mut scene: Self = reader::read_table(doc).map_err(schema)?;
        scene.notch = notch.map(reader::read).transpose().map_err(schema)?;
        scene.keys = keys;
        scene.check(text)?;
        Ok(scene)
    }

    fn check(&self, text: &str) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Err(message) = crate::name::check(&self.name) {
            return bad(self.keys.span("name").unwrap_or(0..0), &message);
        }
        if let Some(f) = &self.frames {
            if !(1..=1_000_000).contains(f.get_ref()) {
                return bad(f.span(), "frames must be between 1 and 1000000");
            }
        }
        let model = *self.model.get_ref();
        self.check_input(text, model)?;
        self.check_effects(text, model)?;
        self.check_settings(text, model)?;
        if model == ModelKind::Sheet {
            #[cfg(feature = "sheet")]
            crate::sheet::check(self)
                .map_err(|(span, message)| SceneError::at(text, Some(span), message))?;
            #[cfg(not(feature = "sheet"))]
            return bad(
                self.model.span(),
                "the sheet model is not in this build (folio-scene without its `sheet` feature)",
            );
        } else {
            self.check_not_sheet(text)?;
        }
        let e = &self.expect;
        let bounds = [
            ("expect.max_stretch", e.max_stretch),
            ("expect.max_stretch_mean", e.max_stretch_mean),
            ("expect.rmse_stretch_mean", e.rmse_stretch_mean),
            ("expect.dog_residual_max", e.dog_residual_max),
            ("expect.penetration_max", e.penetration_max),
        ];
        for (key, v) in bounds {
            if v.is_some_and(|v| !(v.is_finite() && v >= 0.0)) {
                let span = self.keys.span(key).unwrap_or(0..0);
                return bad(span, &format!("{key} must be finite and >= 0"));
            }
        }
        let o = &self.output;
        if let Some(v) = &o.sheet_tiles {
            if !(1..=256).contains(v.get_ref()) {
                return bad(v.span(), "output.sheet_tiles must be between 1 and 256");
            }
        }
        if let Some(v) = &o.animation_every {
            if !(1..=1000).contains(v.get_ref()) {
                return bad(
                    v.span(),
                    "output.animation_every must be between 1 and 1000",
                );
            }
        }
        if let Some(book) = &self.book {
            if model != ModelKind::Dog {
                return bad(book.span(), "[book] is for model = \"dog\" only");
            }
        }
        let at =
            |(span, message): (Range<usize>, String)| SceneError::at(text, Some(span), message);
        match model {
            // The book as `folio run` and the C API build it, then its first grab.
            ModelKind::Dog => {
                let checked = crate::book::check(self);
                #[cfg(feature = "fixture-reach")]
                let checked = checked.and_then(|()| crate::reach::check_reach(self));
                checked.map_err(at)
            }
            ModelKind::MassSpring => self.check_spring().map_err(at),
            ModelKind::Xpbd => self.check_xpbd().map_err(at),
            _ => Ok(()),
        }
    }

    /// Refuses the keys of the sheet model in a scene of another model.
    fn check_not_sheet(&self, text: &str) -> Result<(), SceneError> {
        let (o, e) = (&self.output, &self.expect);
        let spans = [
            ("[sheet]", self.sheet.as_ref().map(Spanned::span)),
            ("[tearing]", self.tearing.as_ref().map(Spanned::span)),
            ("sheet.notch", self.notch.as_ref().map(Spanned::span)),
            ("output.mesh", o.mesh.as_ref().map(Spanned::span)),
            ("output.textures", o.textures.as_ref().map(Spanned::span)),
            ("output.picture", o.picture.as_ref().map(Spanned::span)),
            (
                "expect.tear_length_min",
                e.tear_length_min.as_ref().map(Spanned::span),
            ),
            (
                "expect.tear_start",
                e.tear_start.as_ref().map(Spanned::span),
            ),
        ];
        match spans.into_iter().find_map(|(key, span)| Some((key, span?))) {
            Some((key, span)) => Err(SceneError::at(
                text,
                Some(span),
                format!("{key} is for model = \"sheet\" only"),
            )),
            None => Ok(()),
        }
    }

    /// The precision the scene's model runs in (`solver.precision`, default `f64`).
    #[must_use]
    pub fn precision(&self) -> Precision {
        self.solver
            .as_ref()
            .and_then(|s| s.get_ref().precision.as_ref())
            .map_or(Precision::F64, |p| *p.get_ref())
    }

    /// The page size `[width, height]` (page units): every model's page is
    /// $W \times W\sqrt 2$, $W$ = `book.page_width` (default 12).
    #[must_use]
    pub fn page_size(&self) -> [f64; 2] {
        let w = self
            .book
            .as_ref()
            .map_or(BookParams::default().page_width, |b| b.get_ref().page_width);
        [w, w * core::f64::consts::SQRT_2]
    }

    /// The effects the run simulates: the scene's list, else every effect of the model.
    #[must_use]
    pub fn effect_names(&self) -> Vec<String> {
        match &self.effects {
            Some(list) => list.get_ref().iter().map(|e| e.get_ref().clone()).collect(),
            None => self
                .model
                .get_ref()
                .effects()
                .iter()
                .map(|e| (*e).to_string())
                .collect(),
        }
    }

    /// `true` when the run simulates `effect`.
    #[must_use]
    pub fn has_effect(&self, effect: &str) -> bool {
        self.effect_names().iter().any(|e| e == effect)
    }

    fn check_effects(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let Some(list) = &self.effects else {
            return Ok(());
        };
        let mut seen: Vec<&str> = Vec::new();
        for e in list.get_ref() {
            let name = e.get_ref().as_str();
            let message = if !EFFECTS.contains(&name) {
                format!("unknown effect `{name}`; known: {}", EFFECTS.join(", "))
            } else if !model.effects().contains(&name) {
                let has = model.effects();
                format!(
                    "the {} model does not simulate `{name}` (it has: {})",
                    model.name(),
                    if has.is_empty() {
                        "none".to_string()
                    } else {
                        has.join(", ")
                    }
                )
            } else if seen.contains(&name) {
                format!("effect `{name}` named twice")
            } else if name == "glue" && !self.has_effect("blocks") {
                "`glue` joins the two blocks: it needs `blocks`".to_string()
            } else {
                seen.push(name);
                continue;
            };
            return Err(SceneError::at(text, Some(e.span()), message));
        }
        Ok(())
    }

    fn check_settings(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Some(w) = &self.weights {
            if model != ModelKind::Dog {
                return bad(w.span(), "[weights] is for model = \"dog\" only");
            }
            for (key, v) in w.get_ref().named() {
                if let Err(message) = crate::limits::weight(key, v) {
                    let span = self.keys.span(key).unwrap_or_else(|| w.span());
                    return bad(span, &message);
                }
            }
        }
        let Some(section) = &self.solver else {
            return Ok(());
        };
        if model == ModelKind::Cone {
            return bad(
                section.span(),
                "[solver] is for the dog, mass-spring, xpbd and sheet models",
            );
        }
        let s = section.get_ref();
        if let Some(h) = &s.time_step {
            // A finite step above a frame is told the scene's bound, not the book's.
            if h.get_ref().is_finite() && !crate::clock::fits_in_frame(*h.get_ref()) {
                return bad(
                    h.span(),
                    &format!(
                        "solver.time_step must be at most one frame, 1/60 s (a frame takes \
                         as many steps as keep the model on time), not {}",
                        crate::number::show(*h.get_ref())
                    ),
                );
            }
            if let Err(message) = crate::limits::time_step(*h.get_ref()) {
                return bad(h.span(), &message);
            }
        }
        self.check_new_solver_keys(text, model, s)?;
        let dog_only = [
            ("newton_iterations", &s.newton_iterations, 1..=20),
            ("max_corrections", &s.max_corrections, 0..=50),
            ("collision_rounds", &s.collision_rounds, 1..=16),
            ("krylov_restart", &s.krylov_restart, 1..=50),
        ];
        for (name, v, range) in dog_only {
            let Some(v) = v else { continue };
            if model != ModelKind::Dog {
                return bad(
                    v.span(),
                    &format!("solver.{name} is for model = \"dog\" only"),
                );
            }
            if !range.contains(v.get_ref()) {
                let (lo, hi) = (range.start(), range.end());
                return bad(
                    v.span(),
                    &format!("solver.{name} must be between {lo} and {hi}"),
                );
            }
        }
        if let Some(v) = &s.integrator {
            if model != ModelKind::MassSpring {
                return bad(
                    v.span(),
                    "solver.integrator is for model = \"mass-spring\" only",
                );
            }
        }
        if let Some(v) = &s.substeps {
            let most = match model {
                ModelKind::MassSpring => 64,
                ModelKind::Xpbd => folio_pages::xpbd::MAX_SUBSTEPS,
                _ => {
                    return bad(
                        v.span(),
                        "solver.substeps is for model = \"mass-spring\" or \"xpbd\" only",
                    );
                }
            };
            if !(1..=most).contains(v.get_ref()) {
                return bad(
                    v.span(),
                    &format!("solver.substeps must be between 1 and {most}"),
                );
            }
        }
        Ok(())
    }

    /// The keys of `[solver]` that set the page's resolution and precision and the DOG
    /// solver's tolerance, Hessian and projection: each for the models it applies to, in
    /// range, at its own key.
    fn check_new_solver_keys(
        &self,
        text: &str,
        model: ModelKind,
        s: &SolverSection,
    ) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Some(g) = &s.grid {
            match model {
                ModelKind::Dog | ModelKind::MassSpring | ModelKind::Xpbd => {}
                ModelKind::Sheet => {
                    return bad(
                        g.span(),
                        "solver.grid is for the dog, mass-spring and xpbd models; a sheet \
                         sets its quads with sheet.nx and sheet.ny",
                    );
                }
                _ => {
                    return bad(
                        g.span(),
                        "solver.grid is for the dog, mass-spring and xpbd models",
                    );
                }
            }
            if !g.get_ref().iter().all(|q| GRID_RANGE.contains(q)) {
                let (lo, hi) = (GRID_RANGE.start(), GRID_RANGE.end());
                return bad(
                    g.span(),
                    &format!(
                        "solver.grid = [across, along] quads, each between {lo} and {hi}, \
                         not {:?}",
                        g.get_ref()
                    ),
                );
            }
        }
        if let Some(p) = &s.precision {
            if model == ModelKind::Sheet && *p.get_ref() == Precision::F32 {
                return bad(
                    p.span(),
                    "solver.precision = \"f32\" is for the dog, mass-spring and xpbd models; \
                     a sheet scene runs in f64",
                );
            }
        }
        if let Some(t) = &s.newton_tolerance {
            if model != ModelKind::Dog {
                return bad(
                    t.span(),
                    "solver.newton_tolerance is for model = \"dog\" only",
                );
            }
            let t_value = *t.get_ref();
            if !(t_value.is_finite() && t_value >= 0.0) {
                return bad(
                    t.span(),
                    &format!(
                        "solver.newton_tolerance must be finite and >= 0, not {}",
                        crate::number::show(t_value)
                    ),
                );
            }
        }
        let flags = [
            ("constraint_hessian", &s.constraint_hessian),
            ("projection", &s.projection),
        ];
        for (name, v) in flags {
            if let Some(v) = v.as_ref().filter(|_| model != ModelKind::Dog) {
                return bad(
                    v.span(),
                    &format!("solver.{name} is for model = \"dog\" only"),
                );
            }
        }
        if let (Some(p), Some(m)) = (&s.projection, &s.max_corrections) {
            let (on, corrections) = (*p.get_ref(), *m.get_ref());
            if on != (corrections > 0) {
                let message = if on {
                    "solver.projection = true needs solver.max_corrections of at least 1 \
                     (max_corrections = 0 switches the projection off)"
                } else {
                    "solver.projection = false switches the projection off: leave out \
                     solver.max_corrections (or set it to 0)"
                };
                return bad(p.span(), message);
            }
        }
        Ok(())
    }

    /// The mass-spring page's settings as `folio run` builds them, checked by the page's
    /// own `validate()` (reported at `[solver]`, the only keys a scene sets).
    fn check_spring(&self) -> Result<(), (Range<usize>, String)> {
        let checked = crate::settings::spring_settings::<f64>(self, self.seed_fixture()).validate();
        self.refused_settings("mass-spring", checked)
    }

    /// The XPBD page's settings as `folio run` builds them, checked by the page's own
    /// `validate()` (reported at `[solver]`, the only keys a scene sets).
    fn check_xpbd(&self) -> Result<(), (Range<usize>, String)> {
        let checked = crate::settings::xpbd_settings::<f64>(self, self.seed_fixture()).validate();
        self.refused_settings("xpbd", checked)
    }

    /// A page model's refusal of its settings, reported at `[solver]` (or the input).
    fn refused_settings(
        &self,
        model: &str,
        checked: Result<(), folio_pages::PageError>,
    ) -> Result<(), (Range<usize>, String)> {
        checked.map_err(|e| {
            let span = self
                .solver
                .as_ref()
                .map_or(self.input.span(), Spanned::span);
            (span, format!("the {model} page refuses its settings: {e}"))
        })
    }

    /// `true` when the input is seed 003's experiment (`fixture = "seed003-turn"`).
    fn seed_fixture(&self) -> bool {
        self.input
            .get_ref()
            .fixture
            .as_ref()
            .is_some_and(|f| f.get_ref() == "seed003-turn")
    }

    fn check_input(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        let input = self.input.get_ref();
        if model == ModelKind::Sheet {
            let given = [
                input.fixture.as_ref().map(Spanned::span),
                input.events.as_ref().map(Spanned::span),
                input.pages.as_ref().map(Spanned::span),
            ];
            if let Some(span) = given.into_iter().flatten().next() {
                return bad(
                    span,
                    "a sheet is held by [[input.hands]], not a fixture or events",
                );
            }
            return match &input.hands {
                Some(_) => Ok(()),
                None => bad(self.input.span(), "a sheet scene needs [[input.hands]]"),
            };
        }
        if let Some(hands) = &input.hands {
            return bad(hands.span(), "input.hands is for model = \"sheet\" only");
        }
        let fixture = match (&input.fixture, &input.events) {
            (Some(f), None) => f,
            (None, Some(events)) => {
                if let Some(pages) = &input.pages {
                    return bad(pages.span(), "input.pages is for book fixtures only");
                }
                return crate::events::check(events, self.page_size(), model)
                    .map_err(|(span, message)| SceneError::at(text, Some(span), message));
            }
            _ => {
                return bad(
                    self.input.span(),
                    "input needs either `fixture` or `events`, not both",
                );
            }
        };
        match crate::fixtures::kind(fixture.get_ref()) {
            None => {
                let names = crate::fixtures::NAMES.join(", ");
                return bad(fixture.span(), &format!("unknown fixture; known: {names}"));
            }
            Some(crate::fixtures::Kind::Book) if model != ModelKind::Dog => {
                return bad(
                    fixture.span(),
                    "a book fixture (camera rays on the whole book) needs model = \"dog\"",
                );
            }
            Some(_) if fixture.get_ref() == "seed003-turn" && model == ModelKind::Dog => {
                return bad(
                    fixture.span(),
                    "seed003-turn is on seed 003's 25 x 25 page; the DOG book's page is 12 wide",
                );
            }
            Some(_) => {}
        }
        if let Some(pages) = &input.pages {
            if crate::fixtures::kind(fixture.get_ref()) != Some(crate::fixtures::Kind::Book) {
                return bad(pages.span(), "input.pages is for book fixtures only");
            }
            if *pages.get_ref() == 0 {
                return bad(pages.span(), "input.pages must be at least 1");
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "solver_tests.rs"]
mod solver_tests;
