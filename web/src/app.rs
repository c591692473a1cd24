//! The interactive book: a [`Model`] seen by a [`Camera`], driven by pointer events in
//! screen pixels, meshed into [`Buffers`] after every frame, and counted, so that a bad frame
//! never looks like a good one.
//!
//! A pointer that goes down on a page grabs it by the ray through the pixel and drags it
//! (the book through its drag plane and tent, seed `000_…` Sec. 3.3); one that goes down off
//! the book turns the view. Letting go releases the page, which falls, settles and merges.

use folio_geometry::mesh::TriMesh;
use folio_scene::scene::{ModelKind, Scene};
use glam::DVec3;

use crate::buffers::Buffers;
use crate::camera::Camera;
use crate::error::WebError;
use crate::model::{Grab, Model, mesh_is_finite};

/// What the pointer is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Pointer {
    /// Up.
    Idle,
    /// Holding a page.
    Holding,
    /// Turning the view; the last pixel.
    Orbiting([f64; 2]),
}

/// Counters of a session: what ran, and what went wrong.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Frames advanced.
    pub frames: u64,
    /// Model steps taken.
    pub steps: u64,
    /// Steps refused or not advanced.
    pub failed_steps: u64,
    /// Frames whose mesh was not finite or could not be built (the buffers keep the last
    /// good mesh).
    pub bad_frames: u64,
    /// Pointer inputs the model refused.
    pub refused_inputs: u64,
    /// The active page's stretch after the last frame (0 with none).
    pub stretch: f64,
    /// The largest stretch of any frame.
    pub max_stretch: f64,
}

/// The interactive simulation (module docs).
pub struct App {
    model: Model,
    camera: Camera,
    mesh: TriMesh,
    buffers: Buffers,
    pointer: Pointer,
    tally: Tally,
    table: f32,
    reach: f32,
    stage: [[f64; 3]; 2],
    effects: Vec<String>,
    kind: ModelKind,
}

impl App {
    /// The scene `text` (TOML, `docs/scenes.md`), its effects replaced by `effects` when
    /// given (names the model has), on a `viewport` (CSS pixels). The scene's input and
    /// outputs are ignored: the pointer is the input.
    ///
    /// # Errors
    /// [`WebError`] with the scene's line and column for text that does not parse or check,
    /// for an effect the model has not, or a model the browser build does not run.
    pub fn new(
        text: &str,
        effects: Option<&[String]>,
        viewport: [f64; 2],
    ) -> Result<Self, WebError> {
        let mut scene = Scene::parse(text).map_err(|e| WebError::new(e.to_string()))?;
        if let Some(list) = effects {
            set_effects(&mut scene, list)?;
        }
        let mut model = Model::from_scene(&scene)?;
        let mut mesh = TriMesh::new();
        model.mesh(&mut mesh)?;
        let mut bounds = bounds(&mesh).ok_or_else(|| WebError::new("the first mesh is empty"))?;
        let [w, h] = model.page_size();
        // Room above the book for a page standing over the spine.
        bounds[1][1] += 0.8 * w;
        let reach = w.max(h) as f32;
        let table = bounds[0][1] as f32 - 1e-3 * reach;
        let mut buffers = Buffers::default();
        buffers.fill(&mesh, table, reach);
        Ok(Self {
            camera: Camera::framing(bounds, viewport),
            model,
            mesh,
            buffers,
            pointer: Pointer::Idle,
            tally: Tally::default(),
            table,
            reach,
            stage: bounds,
            effects: scene.effect_names(),
            kind: *scene.model.get_ref(),
        })
    }

    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The camera.
    #[must_use]
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Sets the viewport (CSS pixels).
    pub fn resize(&mut self, viewport: [f64; 2]) {
        self.camera.resize(viewport);
    }

    /// The render buffers of the last good frame.
    #[must_use]
    pub fn buffers(&self) -> &Buffers {
        &self.buffers
    }

    /// The counters.
    #[must_use]
    pub fn tally(&self) -> &Tally {
        &self.tally
    }

    /// The effects the model can simulate (every name the panel may offer).
    #[must_use]
    pub fn available_effects(&self) -> &'static [&'static str] {
        self.kind.effects()
    }

    /// The effects simulated.
    #[must_use]
    pub fn effects(&self) -> &[String] {
        &self.effects
    }

    /// A pointer goes down at pixel `(x, y)`: grabs `pages` pages under it, or starts
    /// turning the view if it misses the book.
    pub fn pointer_down(&mut self, x: f64, y: f64, pages: u32) -> Grab {
        let Some((origin, direction)) = self.camera.ray(x, y) else {
            self.tally.refused_inputs += 1;
            return Grab::Missed;
        };
        let forward = self.camera.frame().forward;
        let grab = match self.model.grab(origin, direction, forward, pages) {
            Ok(g) => g,
            Err(_) => {
                self.tally.refused_inputs += 1;
                Grab::Missed
            }
        };
        self.pointer = match grab {
            Grab::Held => Pointer::Holding,
            Grab::Missed | Grab::NotEnoughPages => Pointer::Orbiting([x, y]),
        };
        grab
    }

    /// The pointer moves to `(x, y)`: drags the held page, or turns the view.
    pub fn pointer_move(&mut self, x: f64, y: f64) {
        match self.pointer {
            Pointer::Idle => {}
            Pointer::Holding => {
                let ok = self
                    .camera
                    .ray(x, y)
                    .is_some_and(|(o, d)| self.model.drag(o, d).is_ok());
                if !ok {
                    self.tally.refused_inputs += 1;
                }
            }
            Pointer::Orbiting(last) => {
                if x.is_finite() && y.is_finite() {
                    self.camera.orbit(x - last[0], y - last[1]);
                    self.pointer = Pointer::Orbiting([x, y]);
                }
            }
        }
    }

    /// The pointer goes up: a held page is let go.
    pub fn pointer_up(&mut self) {
        if self.pointer == Pointer::Holding {
            self.model.release();
        }
        self.pointer = Pointer::Idle;
    }

    /// Finger-bookmarking (see [`Model::bookmark`]).
    pub fn bookmark(&mut self, add: bool) -> &'static str {
        self.model.bookmark(add)
    }

    /// Advances one frame and meshes it. `false` if a step failed or the frame could not
    /// be meshed finite; such a frame is counted, and the buffers keep the last good mesh.
    pub fn advance(&mut self) -> bool {
        let outcome = self.model.advance();
        self.tally.frames += 1;
        self.tally.steps += u64::from(outcome.steps);
        self.tally.failed_steps += u64::from(outcome.failed);
        let meshed = self.model.mesh(&mut self.mesh).is_ok() && mesh_is_finite(&self.mesh);
        let stretch = self.model.stretch().unwrap_or(0.0);
        if meshed && stretch.is_finite() {
            self.buffers.fill(&self.mesh, self.table, self.reach);
            self.tally.stretch = stretch;
            self.tally.max_stretch = self.tally.max_stretch.max(stretch);
        } else {
            self.tally.bad_frames += 1;
        }
        meshed && stretch.is_finite() && outcome.failed == 0
    }

    /// The box the camera frames (min and max corners, page units): the first mesh, with
    /// room above it for a page standing over the spine; what casts and receives shadows.
    #[must_use]
    pub fn stage(&self) -> [[f64; 3]; 2] {
        self.stage
    }

    /// The highest vertex of the last good mesh (page units; the table is below it).
    #[must_use]
    pub fn top(&self) -> f64 {
        self.buffers
            .positions
            .chunks_exact(3)
            .map(|p| f64::from(p[1]))
            .fold(f64::from(self.table), f64::max)
    }

    /// The held point (book frame), if any.
    #[must_use]
    pub fn held_position(&self) -> Option<DVec3> {
        self.model.held_position()
    }
}

/// Replaces the scene's effects by `list`, each a name its model has.
fn set_effects(scene: &mut Scene, list: &[String]) -> Result<(), WebError> {
    let model: ModelKind = *scene.model.get_ref();
    let known = model.effects();
    if let Some(bad) = list.iter().find(|e| !known.contains(&e.as_str())) {
        return Err(WebError::new(format!(
            "the {} model has no effect `{bad}` (it has: {})",
            model.name(),
            known.join(", ")
        )));
    }
    let names = list
        .iter()
        .map(|e| toml::Spanned::new(0..0, e.clone()))
        .collect();
    scene.effects = Some(toml::Spanned::new(0..0, names));
    Ok(())
}

/// The min and max corners of `mesh`'s vertices, `None` for an empty or non-finite mesh.
fn bounds(mesh: &TriMesh) -> Option<[[f64; 3]; 2]> {
    let mut b = [[f64::MAX; 3], [f64::MIN; 3]];
    for p in &mesh.positions {
        for k in 0..3 {
            let v = f64::from(p[k]);
            b[0][k] = b[0][k].min(v);
            b[1][k] = b[1][k].max(v);
        }
    }
    (!mesh.positions.is_empty() && b.iter().flatten().all(|v| v.is_finite())).then_some(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn book() -> App {
        let text = folio_scene::builtin::scene("page-turn").expect("scene");
        App::new(text, None, [1000.0, 640.0]).expect("app")
    }

    /// A pointer on the right page near its outer edge, dragged across the spine and let
    /// go, turns the page: the counts go from 50/50 to 51/49, and no frame is bad. The
    /// points are where the camera sees the right and left pages, so this is the browser
    /// test's gesture without the browser.
    #[test]
    fn a_dragged_page_merges_into_the_left_block() {
        let mut app = book();
        let c = app.model().counts().expect("a book");
        assert_eq!((c.left, c.right), (50, 50));
        let [w, h] = app.model().page_size();
        let top = app.top();
        let at = |x: f64| {
            app.camera()
                .project(DVec3::new(x, top, 0.5 * h))
                .expect("in view")
        };
        let (from, to) = (at(0.9 * w), at(-0.9 * w));
        assert_eq!(app.pointer_down(from[0], from[1], 1), Grab::Held);
        for k in 1..=60 {
            let s = f64::from(k) / 60.0;
            app.pointer_move(
                from[0] + s * (to[0] - from[0]),
                from[1] + s * (to[1] - from[1]),
            );
            app.advance();
        }
        for _ in 0..600 {
            if app.held_position().is_some_and(|p| p.x < -0.5 * w) {
                break;
            }
            app.advance();
        }
        app.pointer_up();
        for _ in 0..1200 {
            app.advance();
            if app.model().counts().is_some_and(|c| c.active == 0) {
                break;
            }
        }
        let c = app.model().counts().expect("a book");
        assert_eq!(
            (c.left, c.right, c.active),
            (51, 49, 0),
            "{:?}",
            app.tally()
        );
        let t = app.tally();
        assert_eq!((t.failed_steps, t.bad_frames, t.refused_inputs), (0, 0, 0));
        assert!(
            t.max_stretch > 0.0 && t.max_stretch < 0.2,
            "{}",
            t.max_stretch
        );
    }

    /// A pointer off the book turns the view instead of grabbing.
    #[test]
    fn a_pointer_off_the_book_orbits() {
        let mut app = book();
        let before = *app.camera();
        assert_eq!(app.pointer_down(2.0, 2.0, 1), Grab::Missed);
        app.pointer_move(50.0, 30.0);
        app.pointer_up();
        assert_ne!(app.camera().yaw, before.yaw);
        assert_eq!(app.model().phase(), "at-rest");
    }

    /// Bad input is refused with a message, and counted, not a panic.
    #[test]
    fn bad_input_is_refused() {
        let text = folio_scene::builtin::scene("page-turn").expect("scene");
        let e = App::new("model = 3", None, [100.0, 100.0])
            .err()
            .expect("refused");
        assert!(e.message.contains("line 1"), "{e}");
        let e = App::new(text, Some(&["tearing".into()]), [100.0, 100.0])
            .err()
            .expect("refused");
        assert!(e.message.contains("no effect `tearing`"), "{e}");
        let sheet = folio_scene::builtin::scene("tear-straight").expect("scene");
        let e = App::new(sheet, None, [100.0, 100.0])
            .err()
            .expect("refused");
        // Refused by the scene reader when it is built without the sheet (as for the
        // browser), else by the model: either way the message says so.
        assert!(e.message.contains("sheet model is not in"), "{e}");
        let mut app = book();
        app.pointer_down(f64::NAN, 1.0, 1);
        assert_eq!(app.tally().refused_inputs, 1);
    }

    /// The page models run behind the same pointer: the cone and the mass-spring page are
    /// grabbed where they are seen, dragged and let go, every frame finite.
    #[test]
    fn the_page_models_follow_the_pointer() {
        for name in ["cone-turn", "mass-spring-turn"] {
            let text = folio_scene::builtin::scene(name).expect("scene");
            let mut app = App::new(text, None, [1000.0, 640.0]).expect("app");
            let [w, h] = app.model().page_size();
            let at = |x: f64, y: f64| {
                app.camera()
                    .project(DVec3::new(x, y, 0.5 * h))
                    .expect("in view")
            };
            let (from, to) = (at(0.9 * w, 0.0), at(-0.9 * w, 0.1 * w));
            assert_eq!(app.pointer_down(from[0], from[1], 1), Grab::Held, "{name}");
            for k in 1..=90 {
                let s = f64::from(k) / 90.0;
                app.pointer_move(
                    from[0] + s * (to[0] - from[0]),
                    from[1] + s * (to[1] - from[1]),
                );
                app.advance();
            }
            app.pointer_up();
            for _ in 0..120 {
                app.advance();
            }
            let t = app.tally();
            assert_eq!((t.bad_frames, t.refused_inputs), (0, 0), "{name}: {t:?}");
            let mean_x: f32 = app
                .buffers()
                .positions
                .chunks_exact(3)
                .map(|p| p[0])
                .sum::<f32>()
                / app.buffers().vertex_count() as f32;
            assert!(
                mean_x < 0.0,
                "{name}: the page went over the spine ({mean_x})"
            );
        }
    }
}
