//! The contact sheet (`contact_sheet.png`): frames of a run rendered by a small software
//! rasterizer into tiles laid out in rows, with the translucent page shading of seed
//! `000_…` Sec. 4.2 (eq. 15-17, [`shading`]) and a procedural page texture ([`texture`]).
//!
//! Book coordinates (page units): X across the book with the binding near $x = 0$, Y up
//! (the book lies on a table at the bottom of the bounds), Z along the binding from the
//! head ($z = 0$) to the foot ($z = H$). Every tile is seen by the same perspective camera
//! ([`camera`]): from above, in front of the foot edge and a little to the right, fitted so
//! that the bounds fill the tile. A point light above-left-front casts shadows
//! ([`shadow`]) onto a table. Meshes are drawn with a z-buffer and back-face culling (the
//! mesh builders wind every triangle counter-clockwise seen from its normal's side and
//! mesh both sides of a page), at `supersample`² samples per pixel.

pub mod camera;
pub mod error;
pub mod font;
pub mod raster;
pub mod shading;
pub mod shadow;
pub mod span;
pub mod stage;
pub mod texture;
pub mod vector;

use std::io;
use std::path::Path;

use folio_geometry::mesh::TriMesh;
use glam::Vec3;

pub use error::RenderError;
pub use shading::Paper;

use stage::Stage;

/// Largest tile side (pixels).
pub const MAX_TILE_SIZE: u32 = 4096;
/// Most tiles per row.
pub const MAX_COLUMNS: u32 = 64;
/// Largest supersampling factor per axis.
pub const MAX_SUPERSAMPLE: u32 = 4;
/// Most tiles on one sheet; [`ContactSheet::add_frame`] refuses more.
pub const MAX_TILES: usize = 4096;

/// Colour of the frame-number labels' text and box.
const LABEL: ([u8; 3], [u8; 3]) = ([20, 20, 24], [236, 234, 226]);
/// Colour of the 1-pixel line between tiles and of empty cells.
const GUTTER: [u8; 3] = [40, 42, 48];

/// Direction from the framed box's centre to the eye for a book: above, in front (+Z,
/// beyond the page's foot) and a little to the right, so both page blocks and a turning
/// page standing over the spine are seen.
pub const BOOK_EYE: [f32; 3] = [0.25, 1.0, 0.8];
/// Direction from the framed box's centre to the light for a book: above, left, in front.
pub const BOOK_LIGHT: [f32; 3] = [-0.55, 1.0, 0.45];

/// How the sheet is laid out and rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SheetSettings {
    /// Tile size (width, height) in pixels, each in $[1, 4096]$. Default 320 x 240.
    pub tile: [u32; 2],
    /// Tiles per row, in $[1, 64]$. Default 4.
    pub columns: u32,
    /// Samples per pixel along each axis (anti-aliasing), in $[1, 4]$. Default 2.
    pub supersample: u32,
    /// The paper's optics ([`Paper`]); its thickness is one page's.
    pub paper: Paper,
    /// Direction from the framed box's centre to the eye (unnormalized, finite, not zero).
    /// Default [`BOOK_EYE`].
    pub eye: [f32; 3],
    /// Direction from the framed box's centre to the point light (unnormalized, finite,
    /// not zero). Default [`BOOK_LIGHT`].
    pub light: [f32; 3],
    /// Whether the table is drawn under the framed box. Default true; a close-up that
    /// frames part of an upright sheet leaves it out, or its plane would hide the sheet
    /// below the box.
    pub table: bool,
}

impl Default for SheetSettings {
    fn default() -> Self {
        Self {
            tile: [320, 240],
            columns: 4,
            supersample: 2,
            paper: Paper::default(),
            eye: BOOK_EYE,
            light: BOOK_LIGHT,
            table: true,
        }
    }
}

/// A default framing for [`ContactSheet::new`] of a book with pages `page_width` x
/// `page_height` (page units): X in $[-W, W]$, Y in $[0, 0.75 W]$, Z in $[0, H]$. A page
/// standing over the spine can rise to $W$; seen from above its top still falls inside
/// the tile (the recorded page turn peaks at $y \approx 0.8 W$), and a box of full
/// height would leave the book small.
#[must_use]
pub fn book_bounds(page_width: f64, page_height: f64) -> [[f32; 3]; 2] {
    let (w, h) = (page_width as f32, page_height as f32);
    [[-w, 0.0, 0.0], [w, 0.75 * w, h]]
}

/// The stage of `settings` framing `bounds`, once both are checked.
fn stage(settings: &SheetSettings, bounds: [[f32; 3]; 2]) -> Result<Stage, RenderError> {
    let [w, h] = settings.tile;
    if !(1..=MAX_TILE_SIZE).contains(&w) || !(1..=MAX_TILE_SIZE).contains(&h) {
        return Err(RenderError::TileSize {
            tile: settings.tile,
        });
    }
    if !(1..=MAX_COLUMNS).contains(&settings.columns) {
        return Err(RenderError::Columns {
            columns: settings.columns,
        });
    }
    if !(1..=MAX_SUPERSAMPLE).contains(&settings.supersample) {
        return Err(RenderError::Supersample {
            supersample: settings.supersample,
        });
    }
    if let Some(field) = settings.paper.invalid_field() {
        return Err(RenderError::Paper { field });
    }
    for (axis, (&lo, &hi)) in bounds[0].iter().zip(&bounds[1]).enumerate() {
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(RenderError::Bounds { axis });
        }
    }
    for (field, d) in [("eye", settings.eye), ("light", settings.light)] {
        let d = Vec3::from(d);
        if !(d.is_finite() && d.length() > 0.0) {
            return Err(RenderError::Direction { field });
        }
    }
    Ok(Stage::new(
        bounds,
        [w as usize, h as usize],
        settings.supersample as usize,
        settings.paper,
        [settings.eye, settings.light].map(Vec3::from),
        settings.table,
    ))
}

/// One picture of `mesh` framed by `bounds`, a single tile of `settings` (no label, no
/// gutter; `columns` unused), drawn as [`ContactSheet::add_frame_cut`] draws a tile: pages
/// `thickness` thick, samples where `keep` fails cut away. Returns `(width, height, RGBA8)`.
///
/// # Errors
/// [`RenderError`] as [`ContactSheet::new`].
pub fn picture(
    settings: SheetSettings,
    bounds: [[f32; 3]; 2],
    mesh: &TriMesh,
    thickness: f32,
    keep: impl Fn(usize, [f32; 2]) -> bool,
) -> Result<(u32, u32, Vec<u8>), RenderError> {
    let mut stage = stage(&settings, bounds)?;
    let image = stage.render(mesh, thickness, keep);
    Ok((settings.tile[0], settings.tile[1], image.rgba))
}

/// An RGBA8 image (`width` x `height`, rows top first) encoded as a PNG.
///
/// # Errors
/// The encoder's error as an [`io::Error`] (also for a buffer of the wrong size).
pub fn encode_png(width: u32, height: u32, rgba: &[u8]) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgba)?;
        writer.finish()?;
    }
    Ok(bytes)
}

/// A contact sheet being filled tile by tile (module docs).
#[derive(Clone, Debug)]
pub struct ContactSheet {
    settings: SheetSettings,
    stage: Stage,
    tiles: Vec<Vec<u8>>,
    page_samples: u64,
    paper_samples: u64,
    samples: u64,
}

impl ContactSheet {
    /// An empty sheet whose camera frames `bounds` (min and max corners, book coordinates;
    /// see [`book_bounds`]).
    ///
    /// # Errors
    /// [`RenderError`] for a setting out of its documented range or bounds that are not
    /// finite with min <= max.
    pub fn new(settings: SheetSettings, bounds: [[f32; 3]; 2]) -> Result<Self, RenderError> {
        let stage = stage(&settings, bounds)?;
        Ok(Self {
            settings,
            stage,
            tiles: Vec::new(),
            page_samples: 0,
            paper_samples: 0,
            samples: 0,
        })
    }

    /// Renders `mesh` into the next tile, labelled with `frame` in its top-left corner, with
    /// the active page `thickness` thick (page units; a stack of $k$ pages is $k$ pages
    /// thick; zero, negative or non-finite counts as one page, so that
    /// `book.active_thickness()` can be passed as it is, also without an active page).
    /// Returns `false` (and draws nothing) when the sheet already holds [`MAX_TILES`].
    /// Triangles with a non-finite or out-of-range vertex are skipped.
    pub fn add_frame(&mut self, mesh: &TriMesh, frame: u32, thickness: f64) -> bool {
        self.add_frame_cut(mesh, frame, thickness, |_, _| true)
    }

    /// [`ContactSheet::add_frame`] with cut-outs: a sample of triangle `t` at texture
    /// coordinates `uv` is drawn only where `keep(t, uv)` holds
    /// ([`stage::Stage::render`]).
    pub fn add_frame_cut(
        &mut self,
        mesh: &TriMesh,
        frame: u32,
        thickness: f64,
        keep: impl Fn(usize, [f32; 2]) -> bool,
    ) -> bool {
        let thickness = if thickness.is_finite() && thickness > 0.0 {
            thickness as f32
        } else {
            self.settings.paper.thickness
        };
        if self.tiles.len() >= MAX_TILES {
            return false;
        }
        let image = self.stage.render(mesh, thickness, keep);
        let mut rgba = image.rgba;
        let [w, h] = self.settings.tile.map(|v| v as usize);
        // A 1-pixel gutter on the right and bottom edges separates the tiles.
        for y in 0..h {
            for x in 0..w {
                if x + 1 == w || y + 1 == h {
                    let k = 4 * (y * w + x);
                    rgba[k..k + 3].copy_from_slice(&GUTTER);
                }
            }
        }
        let scale = (h / 120).max(1);
        font::draw_number(&mut rgba, w, [3, 3], frame, scale, LABEL.0, LABEL.1);
        self.tiles.push(rgba);
        self.page_samples += image.page_samples;
        self.paper_samples += image.paper_samples;
        self.samples += image.samples;
        true
    }

    /// Tiles rendered so far.
    #[must_use]
    pub fn tiles(&self) -> usize {
        self.tiles.len()
    }

    /// Fraction of all samples of all tiles that show a page surface (`PageFront`,
    /// `PageBack`, `PageEdge`); 0 for an empty sheet.
    #[must_use]
    pub fn coverage(&self) -> f64 {
        self.fraction(self.page_samples)
    }

    /// Fraction of all samples of all tiles that show paper: a page surface or a block's
    /// top; 0 for an empty sheet.
    #[must_use]
    pub fn paper_coverage(&self) -> f64 {
        self.fraction(self.paper_samples)
    }

    /// `count` over all samples drawn (0 for an empty sheet).
    fn fraction(&self, count: u64) -> f64 {
        if self.samples == 0 {
            0.0
        } else {
            count as f64 / self.samples as f64
        }
    }

    /// The sheet as an RGBA8 image `(width, height, pixels)`: `columns` tiles per row, as
    /// many rows as needed (at least one), cells without a tile in the gutter colour.
    #[must_use]
    pub fn to_rgba(&self) -> (u32, u32, Vec<u8>) {
        let [tw, th] = self.settings.tile.map(|v| v as usize);
        let columns = self.settings.columns as usize;
        let rows = self.tiles.len().div_ceil(columns).max(1);
        let (width, height) = (tw * columns, th * rows);
        let mut rgba = vec![255u8; 4 * width * height];
        for pixel in rgba.chunks_exact_mut(4) {
            pixel[..3].copy_from_slice(&GUTTER);
        }
        for (k, tile) in self.tiles.iter().enumerate() {
            let (cx, cy) = (k % columns, k / columns);
            for y in 0..th {
                let src = &tile[4 * y * tw..4 * (y + 1) * tw];
                let start = 4 * ((cy * th + y) * width + cx * tw);
                rgba[start..start + 4 * tw].copy_from_slice(src);
            }
        }
        // Both sides fit in u32: at most 64 x 4096 wide, 4096 x 4096 high.
        let dim = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        (dim(width), dim(height), rgba)
    }

    /// The sheet encoded as a PNG (8-bit RGBA).
    ///
    /// # Errors
    /// The encoder's error as an [`io::Error`].
    pub fn encode_png(&self) -> io::Result<Vec<u8>> {
        let (width, height, rgba) = self.to_rgba();
        encode_png(width, height, &rgba)
    }

    /// Writes the sheet to `path` as a PNG ([`ContactSheet::encode_png`]).
    ///
    /// # Errors
    /// The encoder's or the file system's error.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        std::fs::write(path, self.encode_png()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use folio_geometry::QuadGrid;
    use folio_geometry::mesh::page_mesh;

    fn small() -> SheetSettings {
        SheetSettings {
            tile: [96, 72],
            columns: 3,
            ..SheetSettings::default()
        }
    }

    /// A flat page (the seed's size, 12 x 17) on the right half of the book.
    fn flat_page() -> TriMesh {
        let grid = QuadGrid::new(8, 11).unwrap();
        let h = 12.0 * core::f64::consts::SQRT_2;
        let positions: Vec<[f64; 3]> = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                [12.0 * i as f64 / 8.0, 0.1, h * j as f64 / 11.0]
            })
            .collect();
        let mut mesh = TriMesh::new();
        page_mesh(&mut mesh, grid, &positions, 0.0075, 12.0).unwrap();
        mesh
    }

    /// The page seen from above covers a plausible share of the tile: it is a quarter of
    /// the framed box's top face, and the box's height adds to the framed area.
    #[test]
    fn flat_page_covers_a_plausible_fraction() {
        let mut sheet = ContactSheet::new(small(), book_bounds(12.0, 17.0)).unwrap();
        assert!(sheet.add_frame(&flat_page(), 0, 0.0));
        let c = sheet.coverage();
        assert!((0.12..0.5).contains(&c), "coverage {c}");
        assert_eq!(sheet.tiles(), 1);
    }

    #[test]
    fn empty_mesh_covers_nothing() {
        let mut sheet = ContactSheet::new(small(), book_bounds(12.0, 17.0)).unwrap();
        assert_eq!(sheet.coverage(), 0.0);
        assert!(sheet.add_frame(&TriMesh::new(), 0, 0.0));
        assert_eq!(sheet.coverage(), 0.0);
    }

    /// The PNG decodes to `columns` tiles across and one row per `columns` tiles.
    #[test]
    fn png_decodes_to_the_sheet_size() {
        let mut sheet = ContactSheet::new(small(), book_bounds(12.0, 17.0)).unwrap();
        let page = flat_page();
        for frame in 0..4 {
            assert!(sheet.add_frame(&page, frame, 0.0075));
        }
        let bytes = sheet.encode_png().unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes.as_slice()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (3 * 96, 2 * 72));
        assert_eq!(info.color_type, png::ColorType::Rgba);
        let (w, h, rgba) = sheet.to_rgba();
        assert_eq!((w, h), (info.width, info.height));
        assert_eq!(&buf[..rgba.len()], &rgba[..]);
        // Written to a file, the same bytes.
        let dir = std::env::temp_dir().join(format!("folio-render-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("sheet.png");
        sheet.write_png(&path).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), sheet.encode_png().unwrap());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Degenerate and NaN triangles are skipped without a panic; the rest still renders.
    #[test]
    fn degenerate_and_nan_triangles_do_not_panic() {
        let mut mesh = flat_page();
        let n = mesh.vertex_count() as u32;
        mesh.positions.push([f32::NAN, 0.0, 0.0]);
        mesh.positions.push([1.0, 1.0, 1.0]);
        mesh.normals.extend([[0.0, 1.0, 0.0]; 2]);
        mesh.uvs.extend([[0.5, 0.5]; 2]);
        let surface = folio_geometry::mesh::Surface::PageFront;
        for t in [[n, n + 1, 0], [n + 1, n + 1, n + 1], [0, 1, 99_999]] {
            mesh.triangles.push(t);
            mesh.surfaces.push(surface);
        }
        // A zero-length normal and a NaN UV on a valid triangle.
        mesh.normals[0] = [0.0; 3];
        mesh.uvs[1] = [f32::NAN, 0.0];
        let mut sheet = ContactSheet::new(small(), book_bounds(12.0, 17.0)).unwrap();
        assert!(sheet.add_frame(&mesh, 7, f64::NAN));
        assert!(sheet.coverage() > 0.1);
    }

    #[test]
    fn bad_settings_are_typed_errors() {
        let b = book_bounds(12.0, 17.0);
        let bad = |s: SheetSettings| ContactSheet::new(s, b).unwrap_err();
        let d = SheetSettings::default();
        assert_eq!(
            bad(SheetSettings { tile: [0, 10], ..d }),
            RenderError::TileSize { tile: [0, 10] }
        );
        assert_eq!(
            bad(SheetSettings { columns: 0, ..d }),
            RenderError::Columns { columns: 0 }
        );
        assert_eq!(
            bad(SheetSettings {
                supersample: 9,
                ..d
            }),
            RenderError::Supersample { supersample: 9 }
        );
        let paper = Paper {
            roughness: 0.0,
            ..Paper::default()
        };
        assert_eq!(
            bad(SheetSettings { paper, ..d }),
            RenderError::Paper { field: "roughness" }
        );
        assert_eq!(
            bad(SheetSettings { eye: [0.0; 3], ..d }),
            RenderError::Direction { field: "eye" }
        );
        let nan = [[0.0, f32::NAN, 0.0], [1.0, 1.0, 1.0]];
        assert_eq!(
            ContactSheet::new(d, nan).unwrap_err(),
            RenderError::Bounds { axis: 1 }
        );
    }
}
