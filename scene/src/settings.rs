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
///
/// `[solver]`: `grid` sets `quads_across` and `quads_along`; `newton_tolerance` sets
/// `solver.tolerance` (Newton checks the eq. 3 residual before each iteration and stops at
/// the first iterate within it, else after `newton_iterations`); `constraint_hessian`,
/// `collision_rounds`, `krylov_restart` and `max_corrections` set their fields, and `projection = false` sets
/// `max_corrections = 0`. `newton_iterations` goes through
/// `folio_book::BookSettings::set_newton_iterations`, which also sets the refinement the
/// linear solves need for that many iterations.
///
/// Frames are in time ([`crate::clock`]): at a time step $h$ a frame takes
/// $k = \mathrm{round}(\Delta t_{\mathrm{frame}} / h) \ge 1$ steps, so the four counts the
/// book keeps in steps, `merge_frames` (slow steps before a released page merges),
/// `sleep_frames` (quiet steps before a book at rest falls asleep), `flip_frames` (steps of
/// a bookmarked page's flight) and `history_interval` (steps between bookmarking
/// snapshots), are its defaults (meant at one step per frame) times $k$: they
/// keep their meaning in seconds at any $h$.
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
        if let Some(n) = &v.newton_iterations {
            s.set_newton_iterations(*n.get_ref());
        }
        set_real(&mut s.solver.tolerance, v.newton_tolerance.as_ref());
        set(
            &mut s.solver.constraint_hessian,
            v.constraint_hessian.as_ref(),
        );
        set(&mut s.collision_rounds, v.collision_rounds.as_ref());
        set(&mut s.solver.krylov_restart, v.krylov_restart.as_ref());
        set(&mut s.max_corrections, v.max_corrections.as_ref());
        if v.projection.as_ref().is_some_and(|p| !*p.get_ref()) {
            s.max_corrections = 0;
        }
        if let Some(g) = &v.grid {
            [s.quads_across, s.quads_along] = g.get_ref().map(|q| q as usize);
        }
    }
    let k = crate::clock::steps_per_frame(s.solver.time_step.to_f64());
    s.merge_frames = s.merge_frames.saturating_mul(k);
    s.sleep_frames = s.sleep_frames.saturating_mul(k);
    s.flip_frames = s.flip_frames.saturating_mul(k);
    s.history_interval = s.history_interval.saturating_mul(k);
    s
}

/// The mass-spring settings of a scene in precision `T`: seed 003's experiment on its
/// fixture, else the defaults; its effects (gravity, the table) and solver settings (time
/// step, substeps, `grid`: particles are quads + 1). A `grid` keeps the page's total mass,
/// weight and damping (each particle's share scales by the old count over the new) and the
/// springs' stiffness; a finer grid has lighter particles, so the explicit integrator may
/// then need more substeps (the page's `validate()`, run by the scene check, says so).
#[must_use]
pub fn spring_settings<T: Real>(scene: &Scene, seed: bool) -> SpringSettings<T> {
    let mut s = if seed {
        SpringSettings::seed_experiment()
    } else {
        SpringSettings::default()
    };
    if !scene.has_effect("gravity") {
        s.particle_weight = T::ZERO;
    }
    s.floor = scene.has_effect("collisions");
    if let Some(solver) = &scene.solver {
        let v = solver.get_ref();
        set_real(&mut s.time_step, v.time_step.as_ref());
        set(&mut s.substeps, v.substeps.as_ref());
        set(&mut s.integrator, v.integrator.as_ref());
        if let Some(g) = &v.grid {
            let before = s.particles_across * s.particles_along;
            [s.particles_across, s.particles_along] = g.get_ref().map(|q| q as usize + 1);
            // The same page: its mass, weight and damping shared by more (or fewer)
            // particles; the springs keep their stiffness (a square lattice's membrane
            // stiffness does not depend on its spacing).
            let share =
                T::from_f64(before as f64 / (s.particles_across * s.particles_along) as f64);
            s.particle_mass *= share;
            s.particle_weight *= share;
            s.damping *= share;
        }
    }
    s
}

/// The XPBD page's settings of a scene in precision `T`: its defaults (on seed 003's
/// fixture, its $25 \times 25$ page of unit mass, as the cone takes there); its effects
/// (gravity, the table) and solver settings (time step, substeps, `grid`).
#[must_use]
pub fn xpbd_settings<T: Real>(scene: &Scene, seed: bool) -> XpbdSettings<T> {
    let mut s = XpbdSettings::default();
    if seed {
        (s.width, s.height) = (T::from_f64(25.0), T::from_f64(25.0));
        s.areal_density = T::from_f64(1.0 / (25.0 * 25.0));
    }
    if !scene.has_effect("gravity") {
        s.gravity = T::ZERO;
    }
    s.floor = scene.has_effect("collisions");
    if let Some(solver) = &scene.solver {
        let v = solver.get_ref();
        set_real(&mut s.time_step, v.time_step.as_ref());
        set(&mut s.substeps, v.substeps.as_ref());
        if let Some(g) = &v.grid {
            [s.quads_across, s.quads_along] = g.get_ref().map(|q| q as usize);
        }
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
    s.effects = SheetEffects::NONE;
    for name in scene.effect_names() {
        // The scene check refused every name the sheet does not have.
        s.effects.enable(&name);
    }
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
