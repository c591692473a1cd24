//! The types of a scene file (the format is documented in `docs/scenes.md`): what a scene
//! says, as read by serde through [`crate::reader`]. [`Scene::parse`] (`check.rs`)
//! reads and checks a file into them; the checkers and the drivers read these types.

use core::ops::Range;

use serde::Deserialize;
use serde::de::IgnoredAny;
use toml::Spanned;

use crate::keys::KeySpans;

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
    /// The precision the model runs in (`"f64"`, the default, or `"f32"`; dog, mass-spring
    /// and xpbd).
    pub precision: Option<Spanned<Precision>>,
    /// The DOG book (`model = "dog"` only): the keys of `folio_book::BookSettings`, read by
    /// [`crate::settings::book_settings`] in the run's precision.
    pub book: Option<Spanned<IgnoredAny>>,
    /// The DOG book's paper (`model = "dog"` only): a built-in stock's name or a
    /// `[paper]` table of figures ([`crate::paper`]), given to the book over `[book]`.
    pub paper: Option<Spanned<IgnoredAny>>,
    /// The mass-spring page (`model = "mass-spring"` only): the keys of
    /// `folio_pages::spring::SpringSettings` ([`crate::settings::spring_settings`]).
    pub spring: Option<Spanned<IgnoredAny>>,
    /// The XPBD page (`model = "xpbd"` only): the keys of `folio_pages::xpbd::XpbdSettings`
    /// ([`crate::settings::xpbd_settings`]).
    pub xpbd: Option<Spanned<IgnoredAny>>,
    /// The sheet of a tearing scene (`model = "sheet"` only): the keys of
    /// `folio_tearing::sheet::SheetSettings` with `[sheet.tearing]`
    /// ([`crate::settings::sheet_settings`]), and `notch`.
    pub sheet: Option<Spanned<IgnoredAny>>,
    /// A slit cut into the sheet before the run, written `sheet.notch`: a polyline of grid
    /// vertices from a point on the border, each segment along a grid line or a quad's
    /// diagonal (`model = "sheet"` only).
    #[serde(skip)]
    pub notch: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
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
    /// The older keys the file uses ([`crate::legacy`]): each read, at its new key.
    #[serde(skip)]
    pub notices: Vec<SceneNotice>,
    /// The file's text: the model's settings are read from it in the run's precision.
    #[serde(skip)]
    pub source: String,
}

/// An older key a scene file uses: read at its new key, for one release.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneNotice {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// Which key it is now.
    pub message: String,
}

impl core::fmt::Display for SceneNotice {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "line {}, column {}: {}",
            self.line, self.column, self.message
        )
    }
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

/// Every effect a scene may name: each model's, once, in the order of the models.
#[must_use]
pub fn all_effects() -> Vec<&'static str> {
    let mut all: Vec<&'static str> = Vec::new();
    for model in ModelKind::ALL {
        for name in model.effects() {
            if !all.contains(name) {
                all.push(name);
            }
        }
    }
    all
}

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

    /// The scene table that holds the model's settings type (`"book"` for
    /// `folio_book::BookSettings`, `"spring"`, `"xpbd"`, `"sheet"`); `None` for the cone,
    /// which takes none.
    #[must_use]
    pub fn section(self) -> Option<&'static str> {
        match self {
            Self::Dog => Some("book"),
            Self::MassSpring => Some("spring"),
            Self::Xpbd => Some("xpbd"),
            Self::Sheet => Some("sheet"),
            Self::Cone => None,
        }
    }

    /// Every model, in the order scene docs list them.
    pub const ALL: [Self; 5] = [
        Self::Dog,
        Self::Cone,
        Self::MassSpring,
        Self::Xpbd,
        Self::Sheet,
    ];

    /// The effects the model can simulate (its default set), from the model's own list.
    #[must_use]
    pub fn effects(self) -> &'static [&'static str] {
        match self {
            Self::Dog => &folio_book::Effects::NAMES,
            Self::Cone => &[],
            Self::MassSpring | Self::Xpbd => &folio_pages::PARTICLE_PAGE_EFFECTS,
            Self::Sheet => &folio_tearing::sheet::SheetEffects::NAMES,
        }
    }
}

/// The precision a model runs in (`precision`).
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

/// The side of the spine a grab takes its page from (`side = "left"` or `"right"`).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// Left of the spine: a turned page (turning back).
    Left,
    /// Right of the spine, where every model's page starts (the default).
    Right,
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
    pub side: Option<Spanned<Side>>,
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
    /// The precision the scene's model runs in (`precision`, default `f64`).
    #[must_use]
    pub fn precision(&self) -> Precision {
        self.precision
            .as_ref()
            .map_or(Precision::F64, |p| *p.get_ref())
    }

    /// A [`SceneError`] at byte range `span` of the scene's file.
    #[must_use]
    pub fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError::at(&self.source, Some(span), message)
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

    /// `true` when the input is seed 003's experiment (`fixture = "seed003-turn"`).
    pub(crate) fn seed_fixture(&self) -> bool {
        self.input
            .get_ref()
            .fixture
            .as_ref()
            .is_some_and(|f| f.get_ref() == "seed003-turn")
    }
}

#[cfg(test)]
#[path = "solver_tests.rs"]
mod solver_tests;
