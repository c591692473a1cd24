//! Reading and checking a scene file: [`Scene::parse`] reads the TOML into the scene's types
//! ([`crate::scene`]) and holds them to every rule, calling the checkers of each part (the
//! book, the events, the hands, the sheet, the reach of a grab), which read the types and
//! not this file. Every error names its line and column; a scene that does not check is
//! never run.

use core::ops::Range;

use folio_kernels::{SettingError, Shown};
use toml::Spanned;
use toml::de::DeTable;

use crate::keys::{self, KeySpans};
use crate::reader::{self, ReadError};
use crate::scene::{
    GRID_RANGE, ModelKind, Precision, Scene, SceneError, SolverSection, all_effects, line_column,
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

    fn check_effects(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let Some(list) = &self.effects else {
            return Ok(());
        };
        let mut seen: Vec<&str> = Vec::new();
        for e in list.get_ref() {
            let name = e.get_ref().as_str();
            let known = all_effects();
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

    fn check_settings(&self, text: &str, model: ModelKind) -> Result<(), SceneError> {
        let bad =
            |span: Range<usize>, message: &str| Err(SceneError::at(text, Some(span), message));
        if let Some(w) = &self.weights {
            // The book holds them to their ranges (`crate::book`).
            if model != ModelKind::Dog {
                return bad(w.span(), "[weights] is for model = \"dog\" only");
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
            // A frame takes a whole number of steps: the scene's own bound. The model holds
            // the step to its range (its settings' `validate`).
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
        }
        self.check_new_solver_keys(text, model, s)?;
        // The book holds these to their ranges (`crate::book`).
        let dog_only = [
            (
                "newton_iterations",
                s.newton_iterations.as_ref().map(Spanned::span),
            ),
            (
                "max_corrections",
                s.max_corrections.as_ref().map(Spanned::span),
            ),
            (
                "collision_rounds",
                s.collision_rounds.as_ref().map(Spanned::span),
            ),
            (
                "krylov_restart",
                s.krylov_restart.as_ref().map(Spanned::span),
            ),
            (
                "newton_tolerance",
                s.newton_tolerance.as_ref().map(Spanned::span),
            ),
            (
                "constraint_hessian",
                s.constraint_hessian.as_ref().map(Spanned::span),
            ),
            ("projection", s.projection.as_ref().map(Spanned::span)),
        ];
        for (name, span) in dog_only {
            if let Some(span) = span.filter(|_| model != ModelKind::Dog) {
                return bad(span, &format!("solver.{name} is for model = \"dog\" only"));
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
        // The page model holds them to its range (`refused_settings`).
        if let Some(v) = &s.substeps {
            if !matches!(model, ModelKind::MassSpring | ModelKind::Xpbd) {
                return bad(
                    v.span(),
                    "solver.substeps is for model = \"mass-spring\" or \"xpbd\" only",
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

    /// A page model's refusal of its settings, at the `[solver]` key that set the field
    /// (`grid` sets the page's particles or quads), else at `[solver]` (or the input) for a
    /// field the scene does not set.
    fn refused_settings(
        &self,
        model: &str,
        checked: Result<(), SettingError>,
    ) -> Result<(), (Range<usize>, String)> {
        const SCENE_KEYS: [(&str, &str); 7] = [
            ("particles_across", "solver.grid"),
            ("particles_along", "solver.grid"),
            ("quads_across", "solver.grid"),
            ("quads_along", "solver.grid"),
            ("time_step", "solver.time_step"),
            ("substeps", "solver.substeps"),
            ("integrator", "solver.integrator"),
        ];
        checked.map_err(|e| {
            let not = e
                .value
                .map(|v| format!(", not {}", Shown(v)))
                .unwrap_or_default();
            let key = SCENE_KEYS
                .iter()
                .find(|(field, _)| e.path.is(field))
                .map(|(_, key)| *key);
            if let Some(at) = key.and_then(|k| self.keys.span(k)) {
                let key = key.unwrap_or_default();
                return (
                    at,
                    format!(
                        "{key}: the {model} page's {} must be {}{not}",
                        e.path, e.requirement
                    ),
                );
            }
            let span = self
                .solver
                .as_ref()
                .map_or(self.input.span(), Spanned::span);
            (span, format!("the {model} page refuses its settings: {e}"))
        })
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
