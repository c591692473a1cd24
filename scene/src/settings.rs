//! The solver settings a scene describes: the DOG book's (book, effects, weights, solver),
//! the mass-spring and XPBD pages' (effects, solver) and the tearing sheet's (sheet, tearing,
//! effects, solver). Shared by the `folio` command and the C API's scene constructor.

use folio_book::{BookSettings, Effects};
use folio_kernels::Real;
use folio_pages::spring::SpringSettings;
use folio_pages::xpbd::XpbdSettings;
use folio_tearing::sheet::{SheetEffects, SheetSettings};

use crate::scene::Scene;

/// The book settings of a DOG scene in precision `T`: its book, effects, weights and
/// solver settings (the rest are the book's defaults in `T`).
#[must_use]
pub fn book_settings<T: Real>(scene: &Scene) -> BookSettings<T> {
    let mut s = BookSettings::default();
    if let Some(book) = &scene.book {
        s.params = *book.get_ref();
        if scene.keys.span("book.left_pages").is_none() {
            s.params.left_pages = s.params.total_pages / 2;
        }
    }
    s.params.cover = scene.has_effect("cover");
    s.effects = Effects::NONE;
    for name in scene.effect_names() {
        // `cover` is geometry (above); the scene check refused every unknown name.
        s.effects.enable(&name);
    }
    if let Some(w) = &scene.weights {
        s.weights = w.get_ref().map(T::from_f64);
    }
    if let Some(solver) = &scene.solver {
        let v = solver.get_ref();
        set_real(&mut s.solver.time_step, v.time_step.as_ref());
        set(
            &mut s.solver.newton_iterations,
            v.newton_iterations.as_ref(),
        );
        set(&mut s.max_corrections, v.max_corrections.as_ref());
    }
    s
}

/// The mass-spring settings of a scene: seed 003's experiment on its fixture, else the
/// defaults; its effects (gravity, the table) and solver settings.
#[must_use]
pub fn spring_settings(scene: &Scene, seed: bool) -> SpringSettings<f64> {
    let mut s = if seed {
        SpringSettings::seed_experiment()
    } else {
        SpringSettings::default()
    };
    if !scene.has_effect("gravity") {
        s.particle_weight = 0.0;
    }
    s.floor = scene.has_effect("collisions");
    if let Some(solver) = &scene.solver {
        let v = solver.get_ref();
        set(&mut s.time_step, v.time_step.as_ref());
        set(&mut s.substeps, v.substeps.as_ref());
    }
    s
}

/// The XPBD page's settings of a scene: its defaults (on seed 003's fixture, its
/// $25 \times 25$ page of unit mass, as the cone takes there); its effects (gravity, the
/// table) and solver settings (time step, substeps).
#[must_use]
pub fn xpbd_settings(scene: &Scene, seed: bool) -> XpbdSettings<f64> {
    let mut s = XpbdSettings::default();
    if seed {
        (s.width, s.height) = (25.0, 25.0);
        s.areal_density = 1.0 / (25.0 * 25.0);
    }
    if !scene.has_effect("gravity") {
        s.gravity = 0.0;
    }
    s.floor = scene.has_effect("collisions");
    if let Some(solver) = &scene.solver {
        let v = solver.get_ref();
        set(&mut s.time_step, v.time_step.as_ref());
        set(&mut s.substeps, v.substeps.as_ref());
    }
    s
}

/// The tearing sheet's settings of a sheet scene: its `[sheet]` (a [`SheetSettings`]) with
/// its `[tearing]` (a `TearSettings`), its effects and its time step. Unchecked: the sheet
/// validates them ([`SheetSettings::validate`]).
#[must_use]
pub fn sheet_settings(scene: &Scene) -> SheetSettings<f64> {
    let mut s = scene
        .sheet
        .as_ref()
        .map_or_else(SheetSettings::default, |v| *v.get_ref());
    if let Some(tearing) = &scene.tearing {
        s.tearing = *tearing.get_ref();
    }
    s.effects = SheetEffects {
        gravity: scene.has_effect("gravity"),
        bending: scene.has_effect("bending"),
        cones: scene.has_effect("cones"),
        tearing: scene.has_effect("tearing"),
    };
    if let Some(solver) = &scene.solver {
        set(&mut s.time_step, solver.get_ref().time_step.as_ref());
    }
    s
}

/// Overwrites `field` with the scene's value in precision `T`, if it gives one.
fn set_real<T: Real>(field: &mut T, value: Option<&toml::Spanned<f64>>) {
    if let Some(v) = value {
        *field = T::from_f64(*v.get_ref());
    }
}

/// Overwrites `field` with the scene's value, if it gives one.
fn set<V: Copy>(field: &mut V, value: Option<&toml::Spanned<V>>) {
    if let Some(v) = value {
        *field = *v.get_ref();
    }
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
