//! # folio-web
//!
//! Folio in a browser (issue 23): the DOG book of seed `000_…` and the cheaper page models
//! behind a small [`mod@wasm_bindgen`] API for `web/static/index.html`, which draws them with
//! WebGL2 and the translucent paper shading of seed `000_…` eq. 15-17. The page grabs,
//! drags and lets go of pages with a mouse or a finger; everything it shows is computed by
//! the library's own models ([`model`]), not a second simulation.
//!
//! - [`Folio`]: a scene (TOML) in, pointer events in screen pixels, one frame per call of
//!   [`Folio::advance`], the mesh out as flat arrays that JavaScript views in place on the
//!   module's memory, and a status line of counters ([`app::Tally`]).
//! - [`Bench`]: the default scene's recorded page turn, frame by frame, to time a step in
//!   the browser against the same calls natively (`examples/native_steps.rs`).
//!
//! Build and serve: `web/build.sh` (README, "In a browser"). The module is built for
//! `wasm32-unknown-unknown`; on the host the same code runs the native tests and bench.

pub mod app;
pub mod buffers;
pub mod camera;
pub mod error;
pub mod model;
pub mod replay;

use core::fmt::Write as _;

use wasm_bindgen::prelude::*;

use crate::app::App;
use crate::model::Grab;
use crate::replay::Replay;

/// The interactive book of a scene (crate docs).
#[wasm_bindgen]
pub struct Folio {
    app: App,
}

#[wasm_bindgen]
impl Folio {
    /// The scene `toml` on a `width` x `height` viewport (CSS pixels). `effects`, when
    /// given, is a comma-separated list that replaces the scene's effects (`""` for none).
    ///
    /// # Errors
    /// A JavaScript `Error` whose message says what is wrong (the scene's line and column
    /// for bad TOML, an unknown effect, a model the browser build does not run).
    #[wasm_bindgen(constructor)]
    pub fn new(
        toml: &str,
        effects: Option<String>,
        width: f64,
        height: f64,
    ) -> Result<Folio, JsError> {
        let list: Option<Vec<String>> = effects.map(|e| {
            e.split(',')
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect()
        });
        App::new(toml, list.as_deref(), [width, height])
            .map(|app| Self { app })
            .map_err(|e| JsError::new(&e.message))
    }

    /// The text of a built-in scene (`page-turn`, `cone-turn`, `mass-spring-turn`, ...).
    #[must_use]
    pub fn builtin(name: &str) -> Option<String> {
        folio_scene::builtin::scene(name).map(String::from)
    }

    /// The effects this scene's model can simulate, comma-separated.
    #[must_use]
    pub fn model_effects(&self) -> String {
        self.app.available_effects().join(",")
    }

    /// Sets the viewport (CSS pixels).
    pub fn resize(&mut self, width: f64, height: f64) {
        self.app.resize([width, height]);
    }

    /// A pointer goes down at pixel `(x, y)` (CSS pixels from the canvas' top left):
    /// grabs `pages` pages there (`"held"`), or, off the book, starts turning the view
    /// (`"missed"`, `"not-enough-pages"`).
    pub fn pointer_down(&mut self, x: f64, y: f64, pages: u32) -> String {
        match self.app.pointer_down(x, y, pages.max(1)) {
            Grab::Held => "held",
            Grab::Missed => "missed",
            Grab::NotEnoughPages => "not-enough-pages",
        }
        .into()
    }

    /// The pointer moves to `(x, y)`.
    pub fn pointer_move(&mut self, x: f64, y: f64) {
        self.app.pointer_move(x, y);
    }

    /// The pointer goes up: a held page is let go.
    pub fn pointer_up(&mut self) {
        self.app.pointer_up();
    }

    /// Finger-bookmarking: one more page into the grip (`add`) or one back out. Says what
    /// happened (`"started"`, `"nothing is held"`, ...).
    pub fn bookmark(&mut self, add: bool) -> String {
        self.app.bookmark(add).into()
    }

    /// Advances one frame (1/60 s of model time) and meshes it. `false` when a step failed
    /// or the frame was not finite; the status counts it.
    pub fn advance(&mut self) -> bool {
        self.app.advance()
    }

    /// The clip-space matrix (16 floats, column-major) the page draws with.
    #[must_use]
    pub fn view_projection(&self) -> Vec<f32> {
        self.app.camera().view_projection().to_vec()
    }

    /// The eye position (3 floats, book frame).
    #[must_use]
    pub fn eye(&self) -> Vec<f32> {
        self.app
            .camera()
            .frame()
            .eye
            .to_array()
            .map(|v| v as f32)
            .to_vec()
    }

    /// The pixel where the book-frame point `(x, y, z)` is seen (2 numbers), or nothing
    /// behind the eye.
    #[must_use]
    pub fn project(&self, x: f64, y: f64, z: f64) -> Option<Vec<f64>> {
        let p = glam::DVec3::new(x, y, z);
        self.app.camera().project(p).map(|s| s.to_vec())
    }

    /// The highest point of the mesh (page units): the top of the thicker block at rest.
    #[must_use]
    pub fn top(&self) -> f64 {
        self.app.top()
    }

    /// The box the camera frames, which the page's shadow map frames too: its min corner
    /// then its max corner (6 numbers, page units; [`App::stage`]).
    #[must_use]
    pub fn stage(&self) -> Vec<f64> {
        self.app.stage().concat()
    }

    /// Where `positions` starts in the module's memory (bytes): $3V$ floats.
    #[must_use]
    pub fn positions_ptr(&self) -> usize {
        self.app.buffers().positions.as_ptr() as usize
    }

    /// Where `normals` starts: $3V$ floats.
    #[must_use]
    pub fn normals_ptr(&self) -> usize {
        self.app.buffers().normals.as_ptr() as usize
    }

    /// Where `uvs` starts: $2V$ floats.
    #[must_use]
    pub fn uvs_ptr(&self) -> usize {
        self.app.buffers().uvs.as_ptr() as usize
    }

    /// Where the material codes start: $V$ floats ([`buffers::Material`]).
    #[must_use]
    pub fn materials_ptr(&self) -> usize {
        self.app.buffers().materials.as_ptr() as usize
    }

    /// Where the indices start: $3T$ `u32`.
    #[must_use]
    pub fn indices_ptr(&self) -> usize {
        self.app.buffers().indices.as_ptr() as usize
    }

    /// Vertices $V$.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.app.buffers().vertex_count()
    }

    /// Indices $3T$.
    #[must_use]
    pub fn index_count(&self) -> usize {
        self.app.buffers().indices.len()
    }

    /// The state as JSON: the model, its phase, page counts (the book), the held point,
    /// the page size, the effects, and the counters of [`app::Tally`].
    #[must_use]
    pub fn status(&self) -> String {
        status_json(&self.app)
    }
}

/// [`Folio::status`].
fn status_json(app: &App) -> String {
    let t = app.tally();
    let m = app.model();
    let mut s = String::with_capacity(384);
    let _ = write!(
        s,
        "{{\"model\":\"{}\",\"phase\":\"{}\"",
        m.name(),
        m.phase()
    );
    if let Some(c) = m.counts() {
        let _ = write!(
            s,
            ",\"left\":{},\"right\":{},\"active\":{}",
            c.left, c.right, c.active
        );
    }
    match app.held_position() {
        Some(p) => {
            let _ = write!(s, ",\"held\":[{},{},{}]", num(p.x), num(p.y), num(p.z));
        }
        None => s.push_str(",\"held\":null"),
    }
    let [w, h] = m.page_size();
    let _ = write!(s, ",\"page\":[{},{}]", num(w), num(h));
    let effects: Vec<String> = app.effects().iter().map(|e| format!("\"{e}\"")).collect();
    let _ = write!(s, ",\"effects\":[{}]", effects.join(","));
    let _ = write!(
        s,
        ",\"frames\":{},\"steps\":{},\"failedSteps\":{},\"badFrames\":{},\"refusedInputs\":{},\"stretch\":{},\"maxStretch\":{}}}",
        t.frames,
        t.steps,
        t.failed_steps,
        t.bad_frames,
        t.refused_inputs,
        num(t.stretch),
        num(t.max_stretch)
    );
    s
}

/// `v` as a JSON number (`null` if not finite: JSON has no NaN).
fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v}")
    } else {
        "null".into()
    }
}

/// The default scene's recorded page turn, to time a step (crate docs).
#[wasm_bindgen]
pub struct Bench {
    replay: Replay,
}

#[wasm_bindgen]
impl Bench {
    /// At frame 0.
    ///
    /// # Errors
    /// A JavaScript `Error` if the built-in scene does not load (a broken build).
    #[wasm_bindgen(constructor)]
    pub fn new() -> Result<Bench, JsError> {
        Replay::new()
            .map(|replay| Self { replay })
            .map_err(|e| JsError::new(&e.message))
    }

    /// Plays the next frame; `false` when every frame is played.
    pub fn frame(&mut self) -> bool {
        self.replay.frame()
    }

    /// Steps taken.
    #[must_use]
    pub fn steps(&self) -> f64 {
        self.replay.steps() as f64
    }

    /// Inputs refused and steps not advanced.
    #[must_use]
    pub fn failed(&self) -> f64 {
        self.replay.failed() as f64
    }

    /// Pages left, right and held.
    #[must_use]
    pub fn counts(&self) -> Vec<u32> {
        self.replay.counts().to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The status is JSON with the fields the page and the browser test read.
    #[test]
    fn the_status_is_json() {
        let text = folio_scene::builtin::scene("page-turn").expect("scene");
        let app = App::new(text, None, [640.0, 480.0]).expect("app");
        let s = status_json(&app);
        for key in [
            "\"model\":\"dog\"",
            "\"left\":50",
            "\"right\":50",
            "\"held\":null",
            "\"badFrames\":0",
            "\"effects\":[",
        ] {
            assert!(s.contains(key), "{key} in {s}");
        }
        assert!(s.starts_with('{') && s.ends_with('}'));
        assert_eq!(num(f64::NAN), "null");
    }
}
