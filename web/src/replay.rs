//! The step the browser is measured by: the default scene's recorded page turn (grab near the
//! right page's outer edge, swipe over the spine, let go, 750 frames), played on the DOG book
//! exactly as `folio run` plays it. The page's `?bench` mode and the native example
//! `cargo run --release -p folio-web --example native_steps` time the same calls, so the two
//! figures compare the same work.

use folio_book::{Book, Script};
use folio_scene::builtin;
use folio_scene::clock::steps_in_frame;
use folio_scene::fixtures;
use folio_scene::scene::Scene;
use folio_scene::settings::book_settings;

use crate::error::WebError;

/// The default scene's page turn, frame by frame.
pub struct Replay {
    book: Book<f64>,
    script: Script,
    frame: u32,
    steps: u64,
    failed: u64,
}

impl Replay {
    /// The default scene (`page-turn`) and its fixture, at frame 0.
    ///
    /// # Errors
    /// [`WebError`] if the built-in scene or fixture does not load (a broken build).
    pub fn new() -> Result<Self, WebError> {
        let text = builtin::scene("page-turn").ok_or_else(|| WebError::new("no page-turn"))?;
        let scene = Scene::parse(text).map_err(|e| WebError::new(e.to_string()))?;
        let fixture = fixtures::text("page-turn").ok_or_else(|| WebError::new("no fixture"))?;
        let script = Script::parse(fixture).map_err(|e| WebError::new(e.to_string()))?;
        let settings = book_settings(&scene).map_err(|e| WebError::new(e.to_string()))?;
        let book = Book::new(settings).map_err(WebError::book)?;
        Ok(Self {
            book,
            script,
            frame: 0,
            steps: 0,
            failed: 0,
        })
    }

    /// Plays the next frame: its inputs, then its steps. `false` once every frame is played
    /// (nothing is done then).
    pub fn frame(&mut self) -> bool {
        if self.frame >= self.script.frames {
            return false;
        }
        for e in self.script.events_at(self.frame) {
            if self
                .book
                .apply(self.script.camera, self.script.forward, e.action)
                .is_err()
            {
                self.failed += 1;
            }
        }
        let h = self.book.settings().solver.time_step;
        for _ in 0..steps_in_frame(self.frame, h) {
            self.steps += 1;
            match self.book.step() {
                Ok(r) if r.solver.status.advanced() => {}
                _ => self.failed += 1,
            }
        }
        self.frame += 1;
        true
    }

    /// Steps taken so far.
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Inputs refused and steps that did not advance so far.
    #[must_use]
    pub fn failed(&self) -> u64 {
        self.failed
    }

    /// Pages left, right and held now.
    #[must_use]
    pub fn counts(&self) -> [u32; 3] {
        let c = self.book.counts();
        [c.left, c.right, c.active]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The replay is the default scene's run: every frame advances and the page lands on
    /// the left, as `scenes/page-turn.toml` expects (`final_pages = [51, 49, 0]`).
    #[test]
    fn the_replay_turns_the_page() {
        let mut r = Replay::new().expect("replay");
        let mut frames = 0;
        while r.frame() {
            frames += 1;
        }
        assert_eq!(frames, 750);
        assert_eq!(r.failed(), 0);
        assert!(r.steps() >= 750);
        assert_eq!(r.counts(), [51, 49, 0]);
        assert!(!r.frame(), "done stays done");
    }
}
