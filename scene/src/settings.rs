//! The settings a scene describes, read straight into the models' settings types: a DOG
//! scene's `[book]` is a [`BookSettings`], a mass-spring scene's `[spring]` a
//! [`SpringSettings`], an XPBD scene's `[xpbd]` an [`XpbdSettings`] and a sheet scene's
//! `[sheet]` a [`SheetSettings`]: the keys are the types' field names (nested types are
//! nested tables: `[book.weights]`, `[book.solver]`, `[sheet.tearing.fibers]`), an omitted
//! key keeps the type's default in the run's precision, and each type's own `validate()`
//! judges the values. The scene adds only what is about scenes, each rule below. Shared by
//! the `folio` command, the browser and the C API's scene constructor.

use core::ops::Range;

use folio_book::{BookParams, BookSettings, BookUnits, Effects, Paper};
use folio_kernels::{Real, SettingError};
use folio_pages::spring::SpringSettings;
#[cfg(feature = "xpbd")]
use folio_pages::xpbd::XpbdSettings;
#[cfg(feature = "sheet")]
use folio_tearing::sheet::{SheetEffects, SheetSettings};
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use crate::legacy::{self, Notice};
use crate::reader;
use crate::scene::{ModelKind, Scene, SceneError};

/// A precision whose settings a scene reads (`f32`, `f64`): [`book_settings`],
/// [`spring_settings`] and `xpbd_settings` in that precision. They are the precision's
/// own functions, compiled once here and kept out of line: generic ones would be compiled
/// again, and inlined, in every crate that asks for settings (the browser build's size
/// bound, issue 23).
pub trait SceneReal: Real {
    /// [`book_settings`] in this precision.
    ///
    /// # Errors
    /// As [`book_settings`].
    fn book(scene: &Scene) -> Result<BookSettings<Self>, SceneError>;

    /// [`spring_settings`] in this precision.
    ///
    /// # Errors
    /// As [`spring_settings`].
    fn spring(scene: &Scene, seed: bool) -> Result<SpringSettings<Self>, SceneError>;

    /// `xpbd_settings` in this precision.
    ///
    /// # Errors
    /// As `xpbd_settings`.
    #[cfg(feature = "xpbd")]
    fn xpbd(scene: &Scene, seed: bool) -> Result<XpbdSettings<Self>, SceneError>;
}

/// [`SceneReal`] for a precision.
macro_rules! scene_real {
    ($t:ty) => {
        impl SceneReal for $t {
            #[inline(never)]
            fn book(scene: &Scene) -> Result<BookSettings<Self>, SceneError> {
                book_in(scene)
            }

            #[inline(never)]
            fn spring(scene: &Scene, seed: bool) -> Result<SpringSettings<Self>, SceneError> {
                spring_in(scene, seed)
            }

            #[cfg(feature = "xpbd")]
            #[inline(never)]
            fn xpbd(scene: &Scene, seed: bool) -> Result<XpbdSettings<Self>, SceneError> {
                xpbd_in(scene, seed)
            }
        }
    };
}

scene_real!(f64);
scene_real!(f32);

/// A scene file's document in today's keys: parsed, its older spellings rewritten
/// ([`crate::legacy`], each with its notice), and the sheet's notch taken out (a scene key
/// that is no field of [`SheetSettings`]).
pub(crate) struct Document<'t> {
    /// The document.
    pub doc: Spanned<DeTable<'t>>,
    /// One notice per older key.
    pub notices: Vec<Notice>,
    /// `sheet.notch`, if the file gives one.
    pub notch: Option<Spanned<DeValue<'t>>>,
}

/// Reads `text` as a scene document ([`Document`]).
///
/// # Errors
/// TOML syntax, or an older key that does not apply to the model, at its place.
pub(crate) fn document(text: &str) -> Result<Document<'_>, SceneError> {
    let syntax = |e: toml::de::Error| SceneError::at(text, e.span(), e.message().trim());
    let mut doc = DeTable::parse(text).map_err(syntax)?;
    let model = doc
        .get_ref()
        .get("model")
        .and_then(|m| m.get_ref().as_str().map(String::from));
    let notices = match model {
        Some(model) => legacy::modernize(&mut doc, &model)
            .map_err(|(span, message)| SceneError::at(text, Some(span), message))?,
        None => Vec::new(),
    };
    let notch = crate::keys::take(&mut doc, "sheet", "notch");
    Ok(Document {
        doc,
        notices,
        notch,
    })
}

/// The table `section` of the scene read into `S`: each key the file sets replaces the
/// field of `S::default()` (a nested table's of the nested type's default).
///
/// # Errors
/// A key that is no field of `S`, or a value of the wrong type, at its place.
fn read_section<S: DeserializeOwned + Default>(
    scene: &Scene,
    section: &str,
) -> Result<S, SceneError> {
    let text = scene.source.as_str();
    let mut document = document(text)?;
    match document.doc.get_mut().remove(section) {
        Some(value) => {
            reader::read(value).map_err(|e| SceneError::at(text, e.span, e.message.trim()))
        }
        None => Ok(S::default()),
    }
}

/// The paper of a DOG scene's book and the book units it gives ([`folio_book::BookUnits`]:
/// metres per page unit, real seconds per book second): `None` when the file names no
/// paper or names the seed's card, whose page has no physical size.
///
/// # Errors
/// As [`book_settings`].
pub fn book_paper(scene: &Scene) -> Result<Option<(Paper, BookUnits)>, SceneError> {
    let book = book_settings::<f64>(scene)?;
    let paper = paper(scene, book.params.aspect_ratio)?;
    Ok(paper.map(|p| (p, p.units(&book))))
}

/// The scene's `paper` ([`crate::paper`]) for a page of `aspect_ratio`: `None` when the
/// file names none or names the seed's card.
///
/// # Errors
/// As [`crate::paper`]'s reading, at its place.
#[cfg(feature = "paper")]
fn paper(scene: &Scene, aspect_ratio: f64) -> Result<Option<Paper>, SceneError> {
    let text = scene.source.as_str();
    let mut document = document(text)?;
    match document.doc.get_mut().remove("paper") {
        Some(value) => crate::paper::paper_of(value, aspect_ratio)
            .map_err(|(span, message)| SceneError::at(text, Some(span), message)),
        None => Ok(None),
    }
}

/// Without the `paper` feature: a scene that names a paper is refused at its key.
#[cfg(not(feature = "paper"))]
fn paper(scene: &Scene, _aspect_ratio: f64) -> Result<Option<Paper>, SceneError> {
    match &scene.paper {
        Some(at) => Err(SceneError::at(
            &scene.source,
            Some(at.span()),
            "paper is not in this build (folio-scene without its `paper` feature)",
        )),
        None => Ok(None),
    }
}

/// A field of a settings type `S` by its key, copied from another value of `S`.
pub type Field<S> = (&'static str, fn(&mut S, &S));

/// `read` (a section read over `S::default()`) with `base`'s value for each field of
/// `fields` that the file does not set under `section`: the section read over `base`.
/// `fields` lists every field where `base` differs from `S::default()`
/// (`scene/tests/documented_keys.rs` compares the two defaults field by field).
fn over<S>(mut read: S, base: &S, fields: &[Field<S>], scene: &Scene, section: &str) -> S {
    for (key, copy) in fields {
        if scene.keys.span(&format!("{section}.{key}")).is_none() {
            copy(&mut read, base);
        }
    }
    read
}

/// The fields of the book's `solver` whose book default differs from the solver's own
/// ([`BookSettings`]' `solver` docs): a `[book.solver]` table keeps the book's for them.
pub fn book_solver_fields<T: Real>() -> [Field<BookSettings<T>>; 2] {
    [
        ("solver.merit_slack", |s, b| {
            s.solver.merit_slack = b.solver.merit_slack
        }),
        ("solver.refinement_tolerance", |s, b| {
            s.solver.refinement_tolerance = b.solver.refinement_tolerance;
        }),
    ]
}

/// The fields where seed 003's experiment ([`SpringSettings::seed_experiment`]) differs
/// from the default mass-spring page.
pub fn spring_seed_fields<T: Real>() -> [Field<SpringSettings<T>>; 13] {
    [
        ("particles_across", |s, b| {
            s.particles_across = b.particles_across
        }),
        ("particles_along", |s, b| {
            s.particles_along = b.particles_along
        }),
        ("width", |s, b| s.width = b.width),
        ("height", |s, b| s.height = b.height),
        ("particle_mass", |s, b| s.particle_mass = b.particle_mass),
        ("stretch_stiffness", |s, b| {
            s.stretch_stiffness = b.stretch_stiffness
        }),
        ("shear_stiffness", |s, b| {
            s.shear_stiffness = b.shear_stiffness
        }),
        ("bend_spring_stiffness", |s, b| {
            s.bend_spring_stiffness = b.bend_spring_stiffness;
        }),
        ("damping", |s, b| s.damping = b.damping),
        ("particle_weight", |s, b| {
            s.particle_weight = b.particle_weight
        }),
        ("substeps", |s, b| s.substeps = b.substeps),
        ("floor", |s, b| s.floor = b.floor),
        ("interpolation_degree", |s, b| {
            s.interpolation_degree = b.interpolation_degree;
        }),
    ]
}

#[cfg(feature = "xpbd")]
/// The XPBD page on seed 003's fixture: a $25 \times 25$ page of unit mass (as the cone
/// takes there), the rest the defaults.
pub fn xpbd_seed<T: Real>() -> XpbdSettings<T> {
    XpbdSettings {
        width: T::from_f64(25.0),
        height: T::from_f64(25.0),
        areal_density: T::from_f64(1.0 / (25.0 * 25.0)),
        ..XpbdSettings::default()
    }
}

#[cfg(feature = "xpbd")]
/// The fields where [`xpbd_seed`] differs from the default XPBD page.
pub fn xpbd_seed_fields<T: Real>() -> [Field<XpbdSettings<T>>; 3] {
    [
        ("width", |s, b| s.width = b.width),
        ("height", |s, b| s.height = b.height),
        ("areal_density", |s, b| s.areal_density = b.areal_density),
    ]
}

/// The keys of the settings types that a scene sets in its own words: the effects
/// (`effects = [...]`, with `cover` and the table as effects too).
const SET_BY_EFFECTS: [(&str, &str); 5] = [
    ("book.effects", "the scene's `effects` list"),
    ("book.params.cover", "the `cover` effect"),
    ("spring.floor", "the `collisions` effect"),
    ("xpbd.floor", "the `collisions` effect"),
    ("sheet.effects", "the scene's `effects` list"),
];

/// Refuses a key of a settings type that the scene sets in its own words
/// ([`SET_BY_EFFECTS`]): each setting has one spelling in a scene.
///
/// # Errors
/// The span of the key and its scene spelling.
pub(crate) fn check_spelling(scene: &Scene) -> Result<(), (Range<usize>, String)> {
    for (key, instead) in SET_BY_EFFECTS {
        if let Some(span) = scene.keys.span(key) {
            return Err((span, format!("{key}: a scene writes it as {instead}")));
        }
    }
    Ok(())
}

/// The book of a DOG scene in precision `T`: its `[book]` ([`BookSettings`]) with the
/// scene's effects. The scene's own rules:
/// - without `book.params.left_pages`, half the pages start on the left;
/// - `book.params.cover` is the `cover` effect, `book.effects` the `effects` list;
/// - `book.solver.newton_iterations` without `book.solver.refinement_tolerance` sets the
///   refinement that many iterations need ([`BookSettings::set_newton_iterations`]);
/// - frames are in time ([`crate::clock`]): at a time step $h$ a frame takes
///   $k = \mathrm{round}(\Delta t_{\mathrm{frame}} / h) \ge 1$ steps, so the four counts the
///   book keeps in steps and the file does not set, `merge_frames` (slow steps before a
///   released page merges), `sleep_frames` (quiet steps before a book at rest falls
///   asleep), `flip_frames` (steps of a bookmarked page's flight) and `history_interval`
///   (steps between bookmarking snapshots), are their defaults (meant at one step per
///   frame) times $k$: they keep their meaning in seconds at any $h$.
///
/// # Errors
/// A key that is no field of [`BookSettings`], or a value of the wrong type, at its place.
pub fn book_settings<T: SceneReal>(scene: &Scene) -> Result<BookSettings<T>, SceneError> {
    T::book(scene)
}

/// [`book_settings`]' body.
fn book_in<T: Real + DeserializeOwned>(scene: &Scene) -> Result<BookSettings<T>, SceneError> {
    let book = BookSettings::<T>::default();
    let mut s = over(
        read_section(scene, "book")?,
        &book,
        &book_solver_fields(),
        scene,
        "book",
    );
    let set = |key: &str| scene.keys.span(&format!("book.{key}")).is_some();
    if let Some(paper) = paper(scene, s.params.aspect_ratio)? {
        if let Some(at) = scene.keys.span("book.weights.bend_page") {
            let message = "book.weights.bend_page: the paper sets the page's bending; \
                           leave out one of the two";
            return Err(SceneError::at(&scene.source, Some(at), message));
        }
        let asked = s.isometry_hessian;
        paper.apply(&mut s).map_err(|e| {
            let at = scene.paper.as_ref().map(Spanned::span);
            SceneError::at(&scene.source, at, e.to_string())
        })?;
        if set("isometry_hessian") {
            s.isometry_hessian = asked;
        }
    }
    if !set("params.left_pages") {
        s.params.left_pages = s.params.total_pages / 2;
    }
    s.params.cover = scene.has_effect("cover");
    s.effects = Effects::NONE;
    for name in scene.effect_names() {
        // `cover` is geometry (above); the scene check refused every unknown name.
        s.effects.enable(&name);
    }
    if set("solver.newton_iterations") && !set("solver.refinement_tolerance") {
        s.set_newton_iterations(s.solver.newton_iterations);
    }
    let k = crate::clock::steps_per_frame(s.solver.time_step.to_f64());
    for (key, count) in [
        ("merge_frames", &mut s.merge_frames),
        ("sleep_frames", &mut s.sleep_frames),
        ("flip_frames", &mut s.flip_frames),
        ("history_interval", &mut s.history_interval),
    ] {
        if !set(key) {
            *count = count.saturating_mul(k);
        }
    }
    Ok(s)
}

/// The mass-spring page of a scene in precision `T`: its `[spring]` ([`SpringSettings`])
/// over the defaults, or over seed 003's experiment on its fixture. The scene's own rules:
/// without the `gravity` effect `particle_weight` is 0; `floor` is the `collisions` effect;
/// and a file that sets `particles_across` or `particles_along` but not `particle_mass`
/// (`particle_weight`, `damping`) keeps the page's total mass (weight, damping): each
/// particle's share scales by the base's count over the new, and the springs keep their
/// stiffness (a square lattice's membrane stiffness does not depend on its spacing). A
/// finer grid has lighter particles, so the explicit integrator may then need more
/// substeps (the page's `validate()`, run by the scene check, says so).
///
/// # Errors
/// As [`book_settings`], for [`SpringSettings`].
pub fn spring_settings<T: SceneReal>(
    scene: &Scene,
    seed: bool,
) -> Result<SpringSettings<T>, SceneError> {
    T::spring(scene, seed)
}

/// [`spring_settings`]' body.
fn spring_in<T: Real + DeserializeOwned>(
    scene: &Scene,
    seed: bool,
) -> Result<SpringSettings<T>, SceneError> {
    let base = if seed {
        SpringSettings::seed_experiment()
    } else {
        SpringSettings::default()
    };
    let mut s = read_section(scene, "spring")?;
    if seed {
        s = over(s, &base, &spring_seed_fields(), scene, "spring");
    }
    let set = |key: &str| scene.keys.span(&format!("spring.{key}")).is_some();
    if set("particles_across") || set("particles_along") {
        let before = (base.particles_across * base.particles_along) as f64;
        let share = T::from_f64(before / (s.particles_across * s.particles_along) as f64);
        for (key, field) in [
            ("particle_mass", &mut s.particle_mass),
            ("particle_weight", &mut s.particle_weight),
            ("damping", &mut s.damping),
        ] {
            if !set(key) {
                *field *= share;
            }
        }
    }
    if !scene.has_effect("gravity") {
        s.particle_weight = T::ZERO;
    }
    s.floor = scene.has_effect("collisions");
    Ok(s)
}

#[cfg(feature = "xpbd")]
/// The XPBD page of a scene in precision `T`: its `[xpbd]` ([`XpbdSettings`]) over the
/// defaults, or on seed 003's fixture over its $25 \times 25$ page of unit mass (as the cone
/// takes there). Without the `gravity` effect `gravity` is 0; `floor` is the `collisions`
/// effect.
///
/// # Errors
/// As [`book_settings`], for [`XpbdSettings`].
pub fn xpbd_settings<T: SceneReal>(
    scene: &Scene,
    seed: bool,
) -> Result<XpbdSettings<T>, SceneError> {
    T::xpbd(scene, seed)
}

#[cfg(feature = "xpbd")]
/// [`xpbd_settings`]' body.
fn xpbd_in<T: Real + DeserializeOwned>(
    scene: &Scene,
    seed: bool,
) -> Result<XpbdSettings<T>, SceneError> {
    let mut s = read_section(scene, "xpbd")?;
    if seed {
        s = over(s, &xpbd_seed(), &xpbd_seed_fields(), scene, "xpbd");
    }
    if !scene.has_effect("gravity") {
        s.gravity = T::ZERO;
    }
    s.floor = scene.has_effect("collisions");
    Ok(s)
}

/// The tearing sheet of a sheet scene: its `[sheet]` ([`SheetSettings`], with
/// `[sheet.tearing]`) and its effects. Unchecked: the sheet validates them
/// ([`SheetSettings::validate`]).
///
/// # Errors
/// As [`book_settings`], for [`SheetSettings`].
#[cfg(feature = "sheet")]
pub fn sheet_settings(scene: &Scene) -> Result<SheetSettings<f64>, SceneError> {
    let mut s: SheetSettings<f64> = read_section(scene, "sheet")?;
    s.effects = SheetEffects::NONE;
    for name in scene.effect_names() {
        // The scene check refused every name the sheet does not have.
        s.effects.enable(&name);
    }
    Ok(s)
}

impl Scene {
    /// The page size `[width, height]` (page units) the scene's gestures are on: the DOG
    /// book's page ($W \times W a$, `book.params.page_width` and `aspect_ratio`), the
    /// mass-spring and XPBD pages' `width` and `height`, the cone's default page (the
    /// book's default, 12 by $12\sqrt 2$). A section that does not read gives the default
    /// (the scene check reports it).
    #[must_use]
    pub fn page_size(&self) -> [f64; 2] {
        let seed = self.seed_fixture();
        let page = match self.model.get_ref() {
            ModelKind::Dog => book_settings::<f64>(self)
                .ok()
                .map(|s| [s.params.page_width, s.params.page_height()]),
            ModelKind::MassSpring => spring_settings::<f64>(self, seed)
                .ok()
                .map(|s| [s.width, s.height]),
            #[cfg(feature = "xpbd")]
            ModelKind::Xpbd => xpbd_settings::<f64>(self, seed)
                .ok()
                .map(|s| [s.width, s.height]),
            _ => None,
        };
        page.unwrap_or_else(|| {
            let p = BookParams::default();
            [p.page_width, p.page_height()]
        })
    }

    /// The thickness of one page (page units): the DOG book's `book.params.page_thickness`,
    /// else the book's default (the renderer draws every model's paper that thick).
    #[must_use]
    pub fn page_thickness(&self) -> f64 {
        let book = (*self.model.get_ref() == ModelKind::Dog)
            .then(|| book_settings::<f64>(self).ok())
            .flatten();
        book.map_or(BookParams::default().page_thickness, |s| {
            s.params.page_thickness
        })
    }
}

/// A model's refusal of its settings, at the scene key that set the field: the key is the
/// field's path under the model's section (`book.weights.glue`); a field the file does not
/// set is reported at the section, else at the model.
pub(crate) fn refusal(scene: &Scene, section: &str, e: &SettingError) -> (Range<usize>, String) {
    let key = format!("{section}.{}", e.path);
    let span = scene
        .keys
        .span(&key)
        .or_else(|| scene.keys.span(section))
        .unwrap_or_else(|| scene.model.span());
    (span, e.named(key).to_string())
}

#[cfg(test)]
mod tests {
    use folio_book::BookSettings;
    use folio_pages::cone::ConeSettings;
    use folio_pages::spring::SpringSettings;
    use folio_tearing::sheet::SheetSettings;
    use serde::Serialize;
    use serde::de::DeserializeOwned;

    /// `value` written as TOML and read back.
    fn round_trip<S: Serialize + DeserializeOwned>(value: &S) -> S {
        let text = toml::to_string(value).expect("serializes");
        toml::from_str(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
    }

    #[test]
    fn every_settings_type_reads_back_what_it_writes() {
        let mut book = BookSettings::<f64>::default();
        book.weights.glue = 321.0;
        book.solver.newton_iterations = 2;
        book.effects.bookmarking = false;
        assert_eq!(round_trip(&book), book);
        let spring = SpringSettings::<f32> {
            substeps: 3,
            ..SpringSettings::default()
        };
        assert_eq!(round_trip(&spring), spring);
        let cone = ConeSettings::<f64>::default();
        assert_eq!(round_trip(&cone), cone);
        let xpbd = folio_pages::xpbd::XpbdSettings::<f64> {
            substeps: 96,
            spine: folio_pages::xpbd::Spine::Clamp,
            ..folio_pages::xpbd::XpbdSettings::default()
        };
        assert_eq!(round_trip(&xpbd), xpbd);
        let mut sheet = SheetSettings::<f64>::default();
        sheet.tearing.fibers.seed = 99;
        assert_eq!(round_trip(&sheet), sheet);
    }

    #[test]
    fn omitted_keys_keep_the_defaults_and_unknown_keys_are_refused() {
        let book: BookSettings<f64> =
            toml::from_str("quads_across = 12\n[solver]\ntime_step = 0.01\n")
                .expect("a partial book");
        let defaults = BookSettings::<f64>::default();
        assert_eq!(
            (book.quads_across, book.quads_along),
            (12, defaults.quads_along)
        );
        assert_eq!(book.solver.time_step, 0.01);
        assert_eq!(book.weights, defaults.weights);
        let e = toml::from_str::<SpringSettings<f64>>("stiffness = 1.0\n").expect_err("unknown");
        assert!(e.message().contains("unknown field `stiffness`"), "{e}");
    }
}
