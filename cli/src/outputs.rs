//! What a run writes besides `report.json`: the contact sheet (`contact_sheet.png`), the
//! animation (`animation.glb`) and the timeline (`timeline.svg`), filled frame by frame as
//! the run goes ([`Outputs::observe`]) and written at its end ([`Outputs::write`]); a sheet
//! run also writes its last frame: the torn mesh (`torn_sheet.obj`, [`crate::obj`]), every
//! tear's alpha textures (`tear-K-left.png`, `tear-K-right.png`), a picture
//! (`torn_sheet.png`) and a close-up of the longest tear's edge (`torn_edge.png`,
//! [`crate::sheet_view::edge_bounds`]), drawn with the tears' cut-outs
//! ([`crate::sheet_view`]) as the contact sheet's tiles are.

use std::path::{Path, PathBuf};

use folio_geometry::mesh::TriMesh;
use folio_tearing::Side;
use folio_tearing::sheet::TearingSheet;

use crate::error::RunError;
use crate::export::Animation;
use crate::render::{self, ContactSheet, SheetSettings, book_bounds};
use crate::report::Report;
use crate::shape::Shape;
use crate::sheet_view::{
    Cutout, SHEET_EYE, SHEET_LIGHT, edge_bounds, mesh_bounds, render_mesh, sheet_bounds, tear_png,
};
use crate::timeline::timeline_svg;
use folio_scene::scene::{ModelKind, Scene};

/// Frames per second of every scene (the animation's clock).
const FPS: f32 = 60.0;

/// The picture of a sheet run's last frame (pixels).
const PICTURE: [u32; 2] = [960, 720];

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
    /// The sheet's files: mesh, textures, picture (sheet runs).
    sheet_files: [bool; 3],
    /// The sheet at the last frame (sheet runs that write a sheet file).
    last_sheet: Option<TearingSheet<f64>>,
    /// The scene's name (file headers).
    scene: String,
    /// The render settings (paper, view) of every picture.
    settings: SheetSettings,
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
        let is_sheet = *scene.model.get_ref() == ModelKind::Sheet;
        let mut settings = SheetSettings::default();
        let bounds = if is_sheet {
            let sheet = folio_scene::settings::sheet_settings(scene).map_err(fail)?;
            settings.paper.thickness = sheet.tearing.thickness as f32;
            settings.eye = SHEET_EYE;
            settings.light = SHEET_LIGHT;
            sheet_bounds([sheet.width, sheet.height])
        } else {
            // The book's paper (its default is the renderer's 0.0075 too).
            settings.paper.thickness = scene.page_thickness() as f32;
            let [w, h] = scene.page_size();
            book_bounds(w, h)
        };
        let sheet = if o.contact_sheet {
            Some(ContactSheet::new(settings, bounds).map_err(fail)?)
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
            sheet_files: if is_sheet {
                o.sheet_files()
            } else {
                [false; 3]
            },
            last_sheet: None,
            scene: scene.name.clone(),
            settings,
            error: None,
        })
    }

    /// Called after every frame of `frames`: meshes the frames the sheet and the animation
    /// take (the last frame always goes on the sheet).
    pub fn observe(&mut self, frame: u32, frames: u32, shape: Shape<'_>) {
        if let Shape::Sheet(sheet) = shape {
            if frame + 1 == frames && self.sheet_files.contains(&true) {
                self.last_sheet = Some(sheet.clone());
            }
        }
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
                match shape {
                    Shape::Sheet(torn) => {
                        let cutout = Cutout::new(torn);
                        sheet.add_frame_cut(&self.mesh, frame, shape.thickness(), |t, uv| {
                            cutout.keep(t, uv)
                        });
                    }
                    _ => {
                        sheet.add_frame(&self.mesh, frame, shape.thickness());
                    }
                }
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
        if let Some(sheet) = &self.last_sheet {
            let frame = report.frames.len().saturating_sub(1);
            write_sheet(
                &mut written,
                dir,
                sheet,
                self.sheet_files,
                &self.settings,
                &format!(
                    "Folio: scene {}, the torn sheet after frame {frame}",
                    self.scene
                ),
            )?;
        }
        Ok(written)
    }
}

/// Writes the sheet files of `files` (mesh, textures, picture) of the last frame `sheet`
/// into `dir`, adding each to `written`; `title` heads the mesh file.
fn write_sheet(
    written: &mut Vec<(PathBuf, String)>,
    dir: &Path,
    sheet: &TearingSheet<f64>,
    files: [bool; 3],
    settings: &SheetSettings,
    title: &str,
) -> Result<(), RunError> {
    let s = sheet.settings();
    let size = [s.width, s.height];
    let [mesh, textures, picture] = files;
    if mesh {
        let path = dir.join("torn_sheet.obj");
        std::fs::write(&path, crate::obj::sheet_obj(sheet.mesh(), size, title)).map_err(fail)?;
        let m = sheet.mesh();
        written.push((
            path,
            format!(
                "{} vertices, {} triangles",
                m.vertex_count(),
                m.triangle_count()
            ),
        ));
    }
    if textures {
        for (k, tear) in sheet.tears().tears().iter().enumerate() {
            for (side, name) in [(Side::Left, "left"), (Side::Right, "right")] {
                let path = dir.join(format!("tear-{k}-{name}.png"));
                std::fs::write(&path, tear_png(&tear.alpha, side).map_err(fail)?).map_err(fail)?;
                let r = tear.alpha.raster();
                written.push((path, format!("{} x {} alpha", r.width_px(), r.height_px())));
            }
        }
    }
    if picture {
        let mut view = TriMesh::new();
        render_mesh(sheet.mesh(), size, &mut view);
        let cutout = Cutout::new(sheet);
        let settings = SheetSettings {
            tile: PICTURE,
            columns: 1,
            ..*settings
        };
        let mut draw = |settings: SheetSettings, bounds, name: &str, what: &str| {
            let (w, h, rgba) = render::picture(
                settings,
                bounds,
                &view,
                settings.paper.thickness,
                |t, uv| cutout.keep(t, uv),
            )
            .map_err(fail)?;
            let path = dir.join(name);
            std::fs::write(&path, render::encode_png(w, h, &rgba).map_err(fail)?).map_err(fail)?;
            written.push((path, format!("{w} x {h}{what}")));
            Ok::<(), RunError>(())
        };
        draw(settings, mesh_bounds(&view), "torn_sheet.png", "")?;
        if let Some(bounds) = edge_bounds(sheet) {
            // Straight at the sheet, without the table.
            let close_up = SheetSettings {
                eye: [0.0, 0.0, 1.0],
                table: false,
                ..settings
            };
            draw(
                close_up,
                bounds,
                "torn_edge.png",
                ", a close-up of the longest tear",
            )?;
        }
    }
    Ok(())
}
