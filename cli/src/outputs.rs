//! What a run writes besides `report.json`: the contact sheet (`contact_sheet.png`), the
//! animation (`animation.glb`) and the timeline (`timeline.svg`), filled frame by frame as
//! the run goes ([`Outputs::observe`]) and written at its end ([`Outputs::write`]).

use std::path::{Path, PathBuf};

use folio_geometry::mesh::TriMesh;

use crate::export::Animation;
use crate::render::{ContactSheet, SheetSettings, book_bounds};
use crate::run::{Report, RunError, Shape};
use crate::timeline::timeline_svg;
use folio::scene::Scene;

/// Frames per second of every scene (the animation's clock).
const FPS: f32 = 60.0;

/// The outputs of one run (module docs).
pub struct Outputs {
    sheet: Option<ContactSheet>,
    /// Tiles the sheet should hold, spread evenly over the run.
    tiles: u32,
    animation: Option<Animation>,
    /// Frames between two animation frames.
    every: u32,
    timeline: bool,
    mesh: TriMesh,
    /// The first error met while observing (the run goes on; writing reports it).
    error: Option<RunError>,
}

fn fail(e: impl core::fmt::Display) -> RunError {
    RunError(e.to_string())
}

impl Outputs {
    /// The outputs `scene` asks for.
    ///
    /// # Errors
    /// A contact sheet or animation that cannot be set up.
    pub fn new(scene: &Scene) -> Result<Self, RunError> {
        let o = &scene.output;
        let [w, h] = scene.page_size();
        let sheet = if o.contact_sheet {
            let mut settings = SheetSettings::default();
            settings.paper.thickness = scene
                .book
                .as_ref()
                .and_then(|b| b.get_ref().thickness.as_ref())
                .map_or(settings.paper.thickness, |t| *t.get_ref() as f32);
            Some(ContactSheet::new(settings, book_bounds(w, h)).map_err(fail)?)
        } else {
            None
        };
        let animation = if o.animation {
            Some(Animation::new(FPS).map_err(fail)?)
        } else {
            None
        };
        Ok(Self {
            sheet,
            tiles: o.tiles().max(1),
            animation,
            every: o.every().max(1),
            timeline: o.timeline,
            mesh: TriMesh::new(),
            error: None,
        })
    }

    /// Called after every frame of `frames`: meshes the frames the sheet and the animation
    /// take (the last frame always goes on the sheet).
    pub fn observe(&mut self, frame: u32, frames: u32, shape: Shape<'_>) {
        // Tiles at frames 0, s, 2s, ... and the last frame: at most `tiles` in all.
        let stride = match self.tiles {
            0 | 1 => frames.max(1),
            t => frames.saturating_sub(1).div_ceil(t - 1).max(1),
        };
        let on_sheet = self.sheet.is_some() && (frame % stride == 0 || frame + 1 == frames);
        let in_animation = self.animation.is_some() && frame % self.every == 0;
        if !(on_sheet || in_animation) || self.error.is_some() {
            return;
        }
        self.mesh.clear();
        if let Err(e) = shape.mesh(&mut self.mesh) {
            self.error = Some(RunError(format!("frame {frame}: {e}")));
            return;
        }
        if on_sheet {
            if let Some(sheet) = &mut self.sheet {
                sheet.add_frame(&self.mesh, frame, shape.thickness());
            }
        }
        if in_animation {
            if let Some(animation) = &mut self.animation {
                if let Err(e) = animation.add_frame(frame, &self.mesh) {
                    self.error = Some(RunError(format!("frame {frame}: {e}")));
                }
            }
        }
    }

    /// The contact sheet, if the scene asked for one.
    #[must_use]
    pub fn sheet(&self) -> Option<&ContactSheet> {
        self.sheet.as_ref()
    }

    /// Writes every output into `dir`; returns the files written, each with what it holds.
    ///
    /// # Errors
    /// An error met while observing, or a file that cannot be written.
    pub fn write(self, dir: &Path, report: &Report) -> Result<Vec<(PathBuf, String)>, RunError> {
        if let Some(e) = self.error {
            return Err(e);
        }
        std::fs::create_dir_all(dir).map_err(fail)?;
        let mut written = Vec::new();
        if let Some(sheet) = &self.sheet {
            let path = dir.join("contact_sheet.png");
            sheet.write_png(&path).map_err(fail)?;
            written.push((path, format!("{} tiles", sheet.tiles())));
        }
        if let Some(animation) = &self.animation {
            let path = dir.join("animation.glb");
            std::fs::write(&path, animation.to_glb()).map_err(fail)?;
            written.push((path, format!("{} frames", animation.frames())));
        }
        if self.timeline {
            let steps: Vec<f64> = report.frames.iter().map(|f| f.step_ms).collect();
            let stretch: Vec<Option<f64>> = report.frames.iter().map(|f| f.max_stretch).collect();
            let path = dir.join("timeline.svg");
            std::fs::write(&path, timeline_svg(&steps, &stretch)).map_err(fail)?;
            written.push((path, format!("{} frames", steps.len())));
        }
        Ok(written)
    }
}
