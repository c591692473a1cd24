//! Reading and checking a scene file: [`Scene::parse`] reads the TOML into the scene's types
//! ([`crate::scene`]) and holds them to every rule, calling the checkers of each part (the
//! book, the events, the hands, the sheet, the reach of a grab), which read the types and
//! not this file. Every error names its line and column; a scene that does not check is
//! never run.

use core::ops::Range;

use folio_kernels::SettingError;
use toml::Spanned;

use crate::keys::KeySpans;
use crate::reader::{self, ReadError};
use crate::scene::{
    ModelKind, Precision, Scene, SceneError, SceneNotice, all_effects, line_column,
};

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
        let schema = |e: ReadError| SceneError::at(text, e.span, e.message.trim());
        let document = crate::settings::document(text)?;
        let keys = KeySpans::of(document.doc.get_ref());
        let mut scene: Self = reader::read_table(document.doc).map_err(schema)?;
        scene.notch = document
            .notch
            .map(reader::read)
            .transpose()
            .map_err(schema)?;
        scene.keys = keys;
        scene.source = text.to_string();
        scene.notices = document
            .notices
            .into_iter()
            .map(|n| {
                let (line, column) = line_column(text, n.span.start);
                SceneNotice {
                    line,
                    column,
                    message: n.message,
                }
            })
            .collect();
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
        let sections = [
            (
                "book",
                ModelKind::Dog,
                self.book.as_ref().map(Spanned::span),
            ),
            (
                "paper",
                ModelKind::Dog,
                self.paper.as_ref().map(Spanned::span),
            ),
            (
                "spring",
                ModelKind::MassSpring,
                self.spring.as_ref().map(Spanned::span),
            ),
            (
                "xpbd",
                ModelKind::Xpbd,
                self.xpbd.as_ref().map(Spanned::span),
            ),
        ];
        for (section, owner, span) in sections {
            if let Some(span) = span.filter(|_| model != owner) {
                return bad(
                    span,
                    &format!("[{section}] is for model = \"{}\" only", owner.name()),
                );
            }
        }
        let at =
            |(span, message): (Range<usize>, String)| SceneError::at(text, Some(span), message);
        crate::settings::check_spelling(self).map_err(at)?;
        match model {
            // The book as `folio run` and the C API build it, then its first grab.
            ModelKind::Dog => {
                crate::book::check(self)?;
                #[cfg(feature = "fixture-reach")]
                crate::reach::check_reach(self).map_err(at)?;
                Ok(())
            }
            ModelKind::MassSpring => self.check_spring(),
            #[cfg(feature = "xpbd")]
            ModelKind::Xpbd => self.check_xpbd(),
            #[cfg(not(feature = "xpbd"))]
            ModelKind::Xpbd => bad(
                self.model.span(),
                "the xpbd model is not in this build (folio-scene without its `xpbd` feature)",
            ),
            _ => Ok(()),
        }
    }

    /// Refuses the keys of the sheet model in a scene of another model.
    fn check_not_sheet(&self, text: &str) -> Result<(), SceneError> {
        let (o, e) = (&self.output, &self.expect);
        let spans = [
            ("[sheet]", self.sheet.as_ref().map(Spanned::span)),
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

    fn check_effects(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let Some(list) = &self.effects else {
            return Ok(());
        };
        let mut seen: Vec<&str> = Vec::new();
        let known = all_effects();
        for e in list.get_ref() {
            let name = e.get_ref().as_str();
            let message = if !known.contains(&name) {
                format!("unknown effect `{name}`; known: {}", known.join(", "))
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
            } else {
                seen.push(name);
                continue;
            };
            return Err(SceneError::at(text, Some(e.span()), message));
        }
        Ok(())
    }

    /// The scene's own rules on settings: its frames take whole numbers of steps, and a
    /// sheet runs in `f64`.
    fn check_settings(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Some(p) = &self.precision {
            let f32_models = [ModelKind::Dog, ModelKind::MassSpring, ModelKind::Xpbd];
            if *p.get_ref() == Precision::F32 && !f32_models.contains(&model) {
                return bad(
                    p.span(),
                    "precision = \"f32\" is for the dog, mass-spring and xpbd models; a sheet \
                     scene runs in f64",
                );
            }
        }
        let seed = self.seed_fixture();
        let (key, h) = match model {
            ModelKind::Dog => (
                "book.solver.time_step",
                crate::settings::book_settings::<f64>(self)?
                    .solver
                    .time_step,
            ),
            ModelKind::MassSpring => (
                "spring.time_step",
                crate::settings::spring_settings::<f64>(self, seed)?.time_step,
            ),
            #[cfg(feature = "xpbd")]
            ModelKind::Xpbd => (
                "xpbd.time_step",
                crate::settings::xpbd_settings::<f64>(self, seed)?.time_step,
            ),
            #[cfg(feature = "sheet")]
            ModelKind::Sheet => (
                "sheet.time_step",
                crate::settings::sheet_settings(self)?.time_step,
            ),
            _ => return Ok(()),
        };
        // A frame takes a whole number of steps: the scene's own bound. The model holds the
        // step to its range (its settings' `validate`).
        match self.keys.span(key) {
            Some(span) if h.is_finite() && !crate::clock::fits_in_frame(h) => bad(
                span,
                &format!(
                    "`{key}` must be at most one frame, 1/60 s (a frame takes as many steps as \
                     keep the model on time), not {}",
                    crate::number::show(h)
                ),
            ),
            _ => Ok(()),
        }
    }

    /// The mass-spring page's settings as `folio run` builds them, checked by the page's
    /// own `validate()` at the `[spring]` key that set the refused field.
    fn check_spring(&self) -> Result<(), SceneError> {
        let s = crate::settings::spring_settings::<f64>(self, self.seed_fixture())?;
        s.validate().map_err(|e| self.refused("spring", &e))
    }

    /// The XPBD page's settings as `folio run` builds them, checked by the page's own
    /// `validate()` at the `[xpbd]` key that set the refused field.
    #[cfg(feature = "xpbd")]
    fn check_xpbd(&self) -> Result<(), SceneError> {
        let s = crate::settings::xpbd_settings::<f64>(self, self.seed_fixture())?;
        s.validate().map_err(|e| self.refused("xpbd", &e))
    }

    /// A model's refusal `e` of its `section`, at the key that set the field.
    fn refused(&self, section: &str, e: &SettingError) -> SceneError {
        let (span, message) = crate::settings::refusal(self, section, e);
        self.error(span, message)
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
