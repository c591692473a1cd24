//! Scene files: TOML, read with serde (the format is documented in `docs/scenes.md`).
//! Every error names its line and column; a scene that does not check is never run.

use core::ops::Range;
use serde::Deserialize;
use toml::Spanned;

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
    /// The book around a DOG page (`model = "dog"` only).
    pub book: Option<Spanned<BookSection>>,
    /// The recorded input.
    pub input: Spanned<InputSection>,
    /// What `folio run` writes.
    #[serde(default)]
    pub output: OutputSection,
    /// What the run must show; `folio run` fails when it does not.
    #[serde(default)]
    pub expect: Expect,
}

/// A scene's stated expectations, checked against the run's summary.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expect {
    /// Pages left, right and held at the end (DOG book).
    pub final_pages: Option<[u32; 3]>,
    /// Upper bound on the mean max edge stretch.
    pub max_stretch_mean: Option<f64>,
    /// Upper bound on the mean RMSE edge stretch.
    pub rmse_stretch_mean: Option<f64>,
    /// Upper bound on the DOG residual after any step.
    pub dog_residual_max: Option<f64>,
    /// Upper bound on the penetration into a block after collision handling.
    pub penetration_max: Option<f64>,
    /// Most frames whose step failed (`Stalled`, a failed line search or factorization).
    pub failed_steps: Option<usize>,
}

/// The page models (issue 5's interface).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// The DOG book of seed 000 (page blocks, cover, active page).
    Dog,
    /// The cone curl of seed 001.
    Cone,
    /// The mass-spring page of seed 003.
    MassSpring,
}

impl ModelKind {
    /// The name used in scene files and reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Dog => "dog",
            Self::Cone => "cone",
            Self::MassSpring => "mass-spring",
        }
    }
}

/// The book of a DOG scene (seed 000 Sec. 3.1); omitted keys take the seed's defaults.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BookSection {
    /// Pages in the book.
    pub pages: Option<Spanned<u32>>,
    /// Pages in the left block at the start.
    pub left_pages: Option<Spanned<u32>>,
    /// Page width (page units; the seed's is 12).
    pub page_width: Option<Spanned<f64>>,
    /// Paper thickness (page units).
    pub thickness: Option<Spanned<f64>>,
    /// A hard cover.
    pub cover: Option<bool>,
}

/// The input of a scene: a named recorded fixture.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputSection {
    /// One of [`crate::fixtures::NAMES`].
    pub fixture: Spanned<String>,
    /// Pages every grab of a book fixture takes (a stack; default: the fixture's own).
    pub pages: Option<Spanned<u32>>,
}

/// What a run writes into its output folder.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Write `report.json`.
    #[serde(default = "yes")]
    pub report: bool,
}

impl Default for OutputSection {
    fn default() -> Self {
        Self { report: true }
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
    /// Parses and checks `text` (module docs).
    ///
    /// # Errors
    /// The first problem, at its line and column: TOML syntax, an unknown key or model, a
    /// wrong type, a value out of range, an input that does not fit the model.
    pub fn parse(text: &str) -> Result<Self, SceneError> {
        let scene: Self = toml::from_str(text)
            .map_err(|e| SceneError::at(text, e.span(), e.message().trim().to_string()))?;
        scene.check(text)?;
        Ok(scene)
    }

    fn check(&self, text: &str) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Some(f) = &self.frames {
            if !(1..=1_000_000).contains(f.get_ref()) {
                return bad(f.span(), "frames must be between 1 and 1000000");
            }
        }
        let model = *self.model.get_ref();
        let fixture = self.input.get_ref().fixture.clone();
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
        if let Some(pages) = &self.input.get_ref().pages {
            if crate::fixtures::kind(fixture.get_ref()) != Some(crate::fixtures::Kind::Book) {
                return bad(pages.span(), "input.pages is for book fixtures only");
            }
            if *pages.get_ref() == 0 {
                return bad(pages.span(), "input.pages must be at least 1");
            }
        }
        if let Some(book) = &self.book {
            if model != ModelKind::Dog {
                return bad(book.span(), "[book] is for model = \"dog\" only");
            }
            let b = book.get_ref();
            if let Some(p) = &b.pages {
                if !(1..=100_000).contains(p.get_ref()) {
                    return bad(p.span(), "pages must be between 1 and 100000");
                }
            }
            if let (Some(l), pages) = (
                &b.left_pages,
                b.pages.as_ref().map_or(100, |p| *p.get_ref()),
            ) {
                if *l.get_ref() > pages {
                    return bad(l.span(), "left_pages must be at most pages");
                }
            }
            for v in [&b.page_width, &b.thickness].into_iter().flatten() {
                let x = *v.get_ref();
                if !(x.is_finite() && x > 0.0) {
                    return bad(v.span(), "must be finite and > 0");
                }
            }
        }
        Ok(())
    }
}
