//! The atlas's declared variants: what each knob is set to, and the scene file that sets it.
//!
//! A variant is the scene it is measured on with a few keys set: the page model (`model`),
//! `precision`, and the knobs of the model's settings (`docs/scenes.md`: the grid, the
//! time step, Newton's iterations and tolerance, the constraint Hessian, collision rounds,
//! the projection, substeps, the mass-spring integrator), each at its key in the model's
//! section. Everything else is the scene's own: its input, its book, its frames. A variant
//! of another model than the scene's drops the scene's model sections, `precision` and
//! `effects`: that model runs its defaults on the same input.

use toml::{Table, Value};

/// One point of the atlas: a label and the keys it sets.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// Short label (plots, tables): `"8x11"`, `"newton 2"`, `"f32"`.
    pub label: String,
    /// The page model (`"dog"`, `"cone"`, `"mass-spring"`, `"xpbd"`).
    pub model: String,
    /// The scene keys it sets (paths from the scene's root), in order.
    pub keys: Vec<(String, Value)>,
}

/// The knob values a variant is built from (module docs; `None` keeps the scene's).
#[derive(Clone, Copy, Debug, Default)]
pub struct Knobs {
    /// `grid`: quads across x along.
    pub grid: Option<[i64; 2]>,
    /// `precision = "f32"`.
    pub f32: bool,
    /// Steps per 1/60 s frame (`time_step` = 1/60 s over it).
    pub steps: Option<i64>,
    /// `newton_iterations`.
    pub newton: Option<i64>,
    /// Newton's `tolerance` (`book.solver.tolerance`).
    pub tolerance: Option<f64>,
    /// `constraint_hessian = true`.
    pub hessian: bool,
    /// `collision_rounds`.
    pub collision_rounds: Option<i64>,
    /// `projection = false`.
    pub no_projection: bool,
    /// `substeps`.
    pub substeps: Option<i64>,
    /// `integrator = "implicit-euler"` (mass-spring).
    pub implicit: bool,
}

impl Knobs {
    /// The scene keys of these knobs on `model` (paths from the scene's root: a model's
    /// settings are its section's keys, `book.quads_across`, `spring.substeps`).
    fn keys(self, model: &str) -> Vec<(String, Value)> {
        let kind = folio_scene::scene::ModelKind::ALL
            .into_iter()
            .find(|m| m.name() == model);
        let section = kind.and_then(|m| m.section()).unwrap_or(model);
        let at = |key: &str| format!("{section}.{key}");
        let dog = model == "dog";
        let mut out: Vec<(String, Value)> = Vec::new();
        if let Some(grid) = self.grid {
            // A mass-spring page counts particles, one more than quads.
            let (names, extra) = match model {
                "mass-spring" => (["particles_across", "particles_along"], 1),
                _ => (["quads_across", "quads_along"], 0),
            };
            for (name, quads) in names.into_iter().zip(grid) {
                out.push((at(name), (quads + extra).into()));
            }
        }
        if self.f32 {
            out.push(("precision".into(), "f32".into()));
        }
        let solver = |key: &str| {
            if dog {
                at(&format!("solver.{key}"))
            } else {
                at(key)
            }
        };
        if let Some(k) = self.steps {
            out.push((solver("time_step"), Value::Float(FRAME / k as f64)));
        }
        if let Some(n) = self.newton {
            out.push((solver("newton_iterations"), n.into()));
        }
        if let Some(t) = self.tolerance {
            out.push((solver("tolerance"), t.into()));
        }
        if self.hessian {
            out.push((solver("constraint_hessian"), true.into()));
        }
        if let Some(r) = self.collision_rounds {
            out.push((at("collision_rounds"), r.into()));
        }
        if self.no_projection {
            out.push((at("projection_iterations"), 0.into()));
        }
        if let Some(n) = self.substeps {
            out.push((at("substeps"), n.into()));
        }
        if self.implicit {
            out.push((at("integrator"), "implicit-euler".into()));
        }
        out
    }

    /// The variant of `model` with these knobs, labelled by what they change.
    #[must_use]
    pub fn variant(self, model: &str) -> Variant {
        let mut parts = Vec::new();
        if let Some([a, b]) = self.grid {
            parts.push(format!("{a}x{b}"));
        }
        if self.f32 {
            parts.push("f32".into());
        }
        if let Some(k) = self.steps {
            parts.push(format!("h/{k}"));
        }
        if let Some(n) = self.newton {
            parts.push(format!("newton {n}"));
        }
        if let Some(t) = self.tolerance {
            parts.push(format!("tol {t:e}"));
        }
        if self.hessian {
            parts.push("hessian".into());
        }
        if let Some(r) = self.collision_rounds {
            parts.push(format!("{r} collision rounds"));
        }
        if self.no_projection {
            parts.push("no projection".into());
        }
        if let Some(n) = self.substeps {
            parts.push(format!("{n} substeps"));
        }
        if self.implicit {
            parts.push("implicit".into());
        }
        let knobs = if parts.is_empty() {
            "default".to_string()
        } else {
            parts.join(", ")
        };
        Variant {
            label: format!("{model} {knobs}"),
            model: model.to_string(),
            keys: self.keys(model),
        }
    }
}

/// The frame (seconds): a variant's time step is the frame over its steps per frame.
const FRAME: f64 = 1.0 / 60.0;

/// The grid of the reference, and of its refinement (quads across x along). A 24 x 33
/// reference refined to 32 x 44 at four steps a frame took 5 to 6 s a frame with the page
/// held (Newton with the constraint Hessian, 4 to 9 iterations a step): over an hour for
/// the default scene.
pub const REFERENCE_GRIDS: [[i64; 2]; 2] = [[16, 22], [24, 33]];

/// The reference's steps per frame, and its refinement's.
pub const REFERENCE_STEPS: [i64; 2] = [2, 4];

/// Newton's tolerance of the reference (KKT residual of seed `000_…` eq. 3).
pub const REFERENCE_TOLERANCE: f64 = 1e-10;

/// Newton's most iterations per step of the reference.
pub const REFERENCE_NEWTON: i64 = 20;

/// The reference of the atlas (`refined = false`), or the reference refined once more:
/// the DOG book in `f64` on a fine grid, a short time step, Newton to a KKT residual of
/// [`REFERENCE_TOLERANCE`] (at most [`REFERENCE_NEWTON`] iterations a step) with the
/// constraint Hessian: without $\sum_l \lambda_l \nabla^2 C_l$ the iteration is not
/// Newton's on the KKT system and does not converge on a held page (on the page turn at
/// 8 x 11, 20 iterations left eq. 3 residuals of 0.02 to 0.2; with it, 4 to 9 iterations
/// reach 1e-10).
#[must_use]
pub fn reference(refined: bool) -> Variant {
    let k = usize::from(refined);
    let mut v = Knobs {
        grid: Some(REFERENCE_GRIDS[k]),
        steps: Some(REFERENCE_STEPS[k]),
        newton: Some(REFERENCE_NEWTON),
        tolerance: Some(REFERENCE_TOLERANCE),
        hessian: true,
        ..Knobs::default()
    }
    .variant("dog");
    v.label = if refined {
        "reference, refined".into()
    } else {
        "reference".into()
    };
    v
}

/// The declared variants for a scene of `model` (`"dog"` for the book's scenes; a page
/// model's scene, driven by touch input, also compares the other page models on the same
/// input). The first is the scene as written.
#[must_use]
pub fn declared(model: &str) -> Vec<Variant> {
    let none = Knobs::default();
    let dog = |k: Knobs| k.variant("dog");
    let mut out = Vec::new();
    // The scene's own model at its defaults first; on another model's scene, the DOG
    // page at its defaults too, so the two compare at equal knobs.
    if model != "dog" {
        out.push(none.variant(model));
    }
    out.push(dog(none));
    out.extend([
        dog(Knobs {
            grid: Some([6, 8]),
            ..none
        }),
        dog(Knobs {
            grid: Some([12, 16]),
            ..none
        }),
        dog(Knobs {
            grid: Some([16, 22]),
            ..none
        }),
        dog(Knobs {
            newton: Some(2),
            ..none
        }),
        dog(Knobs {
            hessian: true,
            ..none
        }),
        dog(Knobs {
            newton: Some(2),
            hessian: true,
            ..none
        }),
        // Issue 42's Newton rows: 3 and 4 iterations (with the Hessian: without it the
        // iteration is not Newton's), and Newton to a tolerance under the reference's cap.
        dog(Knobs {
            newton: Some(3),
            hessian: true,
            ..none
        }),
        dog(Knobs {
            newton: Some(4),
            hessian: true,
            ..none
        }),
        dog(Knobs {
            newton: Some(REFERENCE_NEWTON),
            tolerance: Some(1e-3),
            hessian: true,
            ..none
        }),
        dog(Knobs {
            newton: Some(REFERENCE_NEWTON),
            tolerance: Some(1e-6),
            hessian: true,
            ..none
        }),
        dog(Knobs { f32: true, ..none }),
        // The microcontroller book (`page-turn-mcu`): f32 on the coarse grid.
        dog(Knobs {
            grid: Some(folio_book::MICROCONTROLLER_GRID.map(|q| q as i64)),
            f32: true,
            ..none
        }),
        dog(Knobs {
            steps: Some(2),
            ..none
        }),
        dog(Knobs {
            collision_rounds: Some(1),
            ..none
        }),
        dog(Knobs {
            no_projection: true,
            ..none
        }),
        dog(Knobs {
            grid: Some([12, 16]),
            newton: Some(2),
            ..none
        }),
        dog(Knobs {
            grid: Some([12, 16]),
            steps: Some(2),
            ..none
        }),
    ]);
    if model != "dog" {
        let xpbd_fine_substeps =
            4 * i64::from(folio_pages::xpbd::XpbdSettings::<f64>::default().substeps);
        let others = [
            none.variant("cone"),
            none.variant("mass-spring"),
            // Particles 4 times lighter on the same springs: twice the frequency, so twice
            // the default 8 substeps keeps the explicit integrator's margin.
            Knobs {
                grid: Some([16, 22]),
                substeps: Some(16),
                ..none
            }
            .variant("mass-spring"),
            Knobs {
                implicit: true,
                ..none
            }
            .variant("mass-spring"),
            none.variant("xpbd"),
            // Four times the substeps: the default's bias (h omega_max)^2 a sixteenth, and
            // on a grid twice as fine the default's h omega_max (the stiffest bending mode's
            // frequency grows as the inverse square of the spacing).
            Knobs {
                substeps: Some(xpbd_fine_substeps),
                ..none
            }
            .variant("xpbd"),
            Knobs {
                grid: Some([16, 22]),
                substeps: Some(xpbd_fine_substeps),
                ..none
            }
            .variant("xpbd"),
        ];
        // The scene's own model as written is the first variant already.
        let first = out[0].clone();
        out.extend(others.into_iter().filter(|v| *v != first));
    }
    out
}

/// The scene's model on the grid `grid` (quads across x along), all else as written. The
/// mass-spring page's particles get lighter on a finer grid while its springs keep their
/// stiffness, so its frequency grows as $\sqrt{N}$ with the particle count $N$: its
/// substeps grow alike from the default's, keeping the explicit integrator's margin.
#[must_use]
pub fn on_grid(model: &str, grid: [i64; 2]) -> Variant {
    let substeps = (model == "mass-spring").then(|| {
        let d = folio_pages::spring::SpringSettings::<f64>::default();
        let n = ((grid[0] + 1) * (grid[1] + 1)) as f64;
        let ratio = (n / (d.particles_across * d.particles_along) as f64).sqrt();
        (f64::from(d.substeps) * ratio.max(1.0)).ceil() as i64
    });
    Knobs {
        grid: Some(grid),
        substeps,
        ..Knobs::default()
    }
    .variant(model)
}

/// The scene file of `variant` on the scene `base` (a parsed scene file): `name` becomes
/// `name`, `model` the variant's, `description` says which variant of the base it is, its
/// keys are set; a variant of another model than the scene's drops the base's model
/// sections (`[book]`, `[spring]`, `[xpbd]`), its `precision` and `effects` first.
#[must_use]
pub fn scene_text(base: &Table, variant: &Variant, name: &str) -> String {
    let mut table = base.clone();
    let same_model = table.get("model").and_then(Value::as_str) == Some(variant.model.as_str());
    if !same_model {
        for key in ["book", "spring", "xpbd", "precision", "effects"] {
            table.remove(key);
        }
    }
    table.insert("name".into(), name.into());
    table.insert("model".into(), variant.model.as_str().into());
    // The base's description names the base's model: say which variant this is.
    let description = match table.get("description").and_then(Value::as_str) {
        Some(d) => format!("atlas variant {} of: {d}", variant.label),
        None => format!("atlas variant {}", variant.label),
    };
    table.insert("description".into(), description.into());
    for (path, value) in &variant.keys {
        set(&mut table, path, value.clone());
    }
    toml::to_string(&table).unwrap_or_default()
}

/// Sets the dotted `path` of `table` to `value`, creating its tables.
fn set(table: &mut Table, path: &str, value: Value) {
    match path.split_once('.') {
        None => {
            table.insert(path.into(), value);
        }
        Some((head, rest)) => {
            let inner = table
                .entry(head)
                .or_insert_with(|| Value::Table(Table::new()));
            if let Value::Table(inner) = inner {
                set(inner, rest, value);
            }
        }
    }
}

/// A file-name-safe form of `label` (`"dog 12x16, newton 2"` → `"dog-12x16-newton-2"`).
#[must_use]
pub fn slug(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}
