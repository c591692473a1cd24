//! How a tearing sheet is shown (seed `002_…` Sec. 6.2): its render mesh in the stage's
//! frame with both sides, the cut-outs its tears' alpha textures make in it, and those
//! textures as images.
//!
//! **Frame.** The sheet is simulated with $x$ along $u$, $y$ along $v$ (up the held sheet)
//! and $z$ out of the flat sheet, towards the viewer; the stage ([`crate::render`]) has $Y$
//! up too, so the sheet is drawn where it is, held upright over the floor (the stage's table
//! at the bottom of the framed box), seen from in front, a little above and to the right
//! ([`SHEET_EYE`]) and lit from above-left-front ([`SHEET_LIGHT`]); gravity, when simulated,
//! pulls down in the picture.
//!
//! **Texture coordinates.** The front shows the printed page ([`page_albedo`]) with its head
//! at the sheet's top edge: $\mathrm{uv} = (u / W,\ 1 - v / H)$; the back mirrors $u$, as
//! [`folio_geometry::mesh::page_mesh`] lays out a page's back. The tear textures are images
//! of the pattern, top row at $v = H$ ([`folio_tearing::AlphaPair::to_rgba`]).
//!
//! **Cut-outs.** A triangle on the left lip of a tear is drawn with $T_{\text{left}}$, one
//! on the right lip with $T_{\text{right}}$ (Sec. 6.2): transparent beyond the tear's
//! detail path. The lip of a triangle is the side of the tear path's nearest segment its
//! pattern centroid lies on; a branch only cuts the triangles on the side of its parent it
//! leaves to (its masks are copies of that side's). Far from a tear both masks are opaque,
//! so the side chosen there does not matter. A sample is drawn where every mask that
//! applies to its triangle is at least half opaque.

use std::io;

use folio_geometry::SheetMesh;
use folio_geometry::mesh::{Surface, TriMesh};
use folio_kernels::Vec3Ops;
use folio_tearing::sheet::TearingSheet;
use folio_tearing::{AlphaPair, Side, Tear};

use crate::render::encode_png;
use crate::render::shading::srgb;
use crate::render::texture::{self, page_albedo};

/// Alpha at or above which a mask keeps a sample.
const KEEP_ALPHA: u8 = 128;

/// Direction from the framed box's centre to the eye: in front of the sheet, a little
/// above and to the right.
pub const SHEET_EYE: [f32; 3] = [0.3, 0.35, 1.0];
/// Direction from the framed box's centre to the light: above, left, in front.
pub const SHEET_LIGHT: [f32; 3] = [-0.5, 0.9, 0.9];

/// The box a contact sheet of a `[W, H]` sheet frames: the sheet upright, with room for
/// hands that pull it a fifth of its width sideways, a quarter of its height down and out
/// of its plane.
#[must_use]
pub fn sheet_bounds(size: [f64; 2]) -> [[f32; 3]; 2] {
    let [w, h] = size.map(|v| v as f32);
    let depth = 0.2 * w.max(h);
    [[-0.2 * w, -0.25 * h, -depth], [1.2 * w, 1.1 * h, depth]]
}

/// The box around every finite vertex of `mesh`, grown by 5 % of its diagonal on each side
/// (a unit box at the origin for a mesh without one).
#[must_use]
pub fn mesh_bounds(mesh: &TriMesh) -> [[f32; 3]; 2] {
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in mesh
        .positions
        .iter()
        .filter(|p| p.iter().all(|c| c.is_finite()))
    {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        return [[0.0; 3], [1.0; 3]];
    }
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f32>().sqrt();
    let pad = 0.05 * diagonal.max(1e-3);
    [lo.map(|v| v - pad), hi.map(|v| v + pad)]
}

/// Appends the render mesh of `sheet` (pattern `[W, H]` = `size`) to `out` (module docs):
/// its front (`PageFront`, triangles `0..n` of those appended, normals on the side of $+z$
/// for the flat sheet) and its back (`PageBack`, triangles `n..2n`, the same triangles
/// wound the other way), with area-weighted vertex normals. The lips of a tear are
/// separate vertices, so the tear shows as a gap where they move apart.
pub fn render_mesh(sheet: &SheetMesh<f64>, size: [f64; 2], out: &mut TriMesh) {
    let [w, h] = size;
    let positions: Vec<[f64; 3]> = sheet
        .positions()
        .iter()
        .map(|x| [x.x(), x.y(), x.z()])
        .collect();
    let mut normals = vec![[0.0f64; 3]; positions.len()];
    for t in sheet.triangles() {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let (e1, e2) = (sub(b, a), sub(c, a));
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for &i in t {
            for k in 0..3 {
                normals[i as usize][k] += n[k];
            }
        }
    }
    let first = out.positions.len() as u32;
    let count = positions.len() as u32;
    for (side, sign) in [(0u32, 1.0f64), (1, -1.0)] {
        for ((p, n), q) in positions.iter().zip(&normals).zip(sheet.pattern()) {
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let unit = if length > 0.0 && length.is_finite() {
                n.map(|c| sign * c / length)
            } else {
                [0.0, 0.0, sign]
            };
            let u = q[0] / w;
            let u = if side == 0 { u } else { 1.0 - u };
            out.positions.push(p.map(|c| c as f32));
            out.normals.push(unit.map(|c| c as f32));
            out.uvs
                .push([u, 1.0 - q[1] / h].map(|c| c.clamp(0.0, 1.0) as f32));
        }
    }
    for (surface, offset) in [(Surface::PageFront, 0), (Surface::PageBack, count)] {
        for t in sheet.triangles() {
            let [a, b, c] = t.map(|i| first + offset + i);
            out.triangles
                .push(if offset == 0 { [a, b, c] } else { [a, c, b] });
            out.surfaces.push(surface);
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The side of the path of `tear` pattern point `p` is on: of the path's segment nearest to
/// it (`None` for a path without a segment).
fn side_of(path: &[[f64; 2]], p: [f64; 2]) -> Option<Side> {
    let mut best: Option<(f64, Side)> = None;
    for w in path.windows(2) {
        let (a, b) = (w[0], w[1]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let r = [p[0] - a[0], p[1] - a[1]];
        let len2 = e[0] * e[0] + e[1] * e[1];
        let s = if len2 > 0.0 {
            ((r[0] * e[0] + r[1] * e[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = [r[0] - s * e[0], r[1] - s * e[1]];
        let distance = d[0] * d[0] + d[1] * d[1];
        let side = if e[0] * r[1] - e[1] * r[0] >= 0.0 {
            Side::Left
        } else {
            Side::Right
        };
        if best.is_none_or(|(bd, _)| distance < bd) {
            best = Some((distance, side));
        }
    }
    best.map(|b| b.1)
}

/// Half the side of the box a close-up of a torn edge frames, sheet units: 1.2 units
/// across, about 2 cm of a page 21 cm wide, the span of seed `002_…`'s Fig. 20.
pub const CLOSE_UP_HALF_SIDE: f64 = 0.6;

/// The box a close-up of `sheet`'s torn edge frames: a cube of side
/// $2 \times$ [`CLOSE_UP_HALF_SIDE`] centred on the 3D position of the sheet vertex nearest,
/// in the pattern, to the middle (by length) of the longest tear's path. `None` when no
/// tear has a segment of positive length or that vertex's position is not finite.
#[must_use]
pub fn edge_bounds(sheet: &TearingSheet<f64>) -> Option<[[f32; 3]; 2]> {
    let length = |path: &[[f64; 2]]| -> f64 {
        path.windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum()
    };
    let longest = sheet
        .tears()
        .tears()
        .iter()
        .map(|tear| (length(&tear.path), &tear.path))
        .filter(|(l, _)| *l > 0.0)
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    let (total, path) = longest;
    let mut left = 0.5 * total;
    let mut middle = path[0];
    for w in path.windows(2) {
        let step = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        if step >= left && step > 0.0 {
            let t = left / step;
            middle = [0, 1].map(|k| w[0][k] + t * (w[1][k] - w[0][k]));
            break;
        }
        left -= step;
        middle = w[1];
    }
    let mesh = sheet.mesh();
    let nearest = mesh
        .pattern()
        .iter()
        .map(|q| (q[0] - middle[0]).hypot(q[1] - middle[1]))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))?
        .0;
    let x = mesh.positions()[nearest];
    let centre = [x.x(), x.y(), x.z()];
    if !centre.iter().all(|c| c.is_finite()) {
        return None;
    }
    let r = CLOSE_UP_HALF_SIDE;
    Some([
        centre.map(|c| (c - r) as f32),
        centre.map(|c| (c + r) as f32),
    ])
}

/// The cut-outs of a sheet's tears on its render mesh ([`render_mesh`]; module docs).
pub struct Cutout<'a> {
    /// Sheet triangles `n`: render triangles `0..n` are the front, `n..2n` the back.
    triangles: usize,
    size: [f64; 2],
    /// The masks that apply to each sheet triangle.
    masks: Vec<Vec<&'a [u8]>>,
    /// The tears' raster (shared by all).
    raster: folio_tearing::detail::Raster,
}

impl<'a> Cutout<'a> {
    /// The cut-outs of `sheet`'s tears.
    #[must_use]
    pub fn new(sheet: &'a TearingSheet<f64>) -> Self {
        let mesh = sheet.mesh();
        let settings = sheet.settings();
        let tears: &[Tear<f64>] = sheet.tears().tears();
        let masks = mesh
            .triangles()
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.pattern()[i as usize]);
                let centroid = [0, 1].map(|k| (a[k] + b[k] + c[k]) / 3.0);
                tears
                    .iter()
                    .filter(|tear| {
                        // A branch cuts only its parent's lip it leaves to.
                        tear.parent.is_none_or(|parent| {
                            let parent = &tears[parent].path;
                            let leaves_to = tear.path.get(1).and_then(|&q| side_of(parent, q));
                            leaves_to.is_some() && leaves_to == side_of(parent, centroid)
                        })
                    })
                    .filter_map(|tear| {
                        side_of(&tear.path, centroid).map(|side| tear.alpha.mask(side))
                    })
                    .collect()
            })
            .collect();
        Self {
            triangles: mesh.triangle_count(),
            size: [settings.width, settings.height],
            masks,
            raster: *sheet.tears().raster(),
        }
    }

    /// Whether render triangle `t` is drawn at texture coordinates `uv`.
    #[must_use]
    pub fn keep(&self, t: usize, uv: [f32; 2]) -> bool {
        let (sheet_triangle, back) = if t < self.triangles {
            (t, false)
        } else if t < 2 * self.triangles {
            (t - self.triangles, true)
        } else {
            return true;
        };
        let masks = &self.masks[sheet_triangle];
        if masks.is_empty() {
            return true;
        }
        let u = if back { 1.0 - uv[0] } else { uv[0] };
        let p = [
            f64::from(u) * self.size[0],
            (1.0 - f64::from(uv[1])) * self.size[1],
        ];
        let Some(k) = self.raster.index(self.raster.pixel_of(p)) else {
            return true;
        };
        masks
            .iter()
            .all(|m| m.get(k).is_none_or(|&a| a >= KEEP_ALPHA))
    }
}

/// The printed page's colour (sRGB) at the centre of raster pixel `(i, j)` of `alpha`'s
/// raster (module docs).
fn page_colour(alpha: &AlphaPair, i: u32, j: u32) -> [u8; 3] {
    let r = alpha.raster();
    let [u, v] = r.center((i, j));
    let uv = [u / r.sheet_width(), 1.0 - v / r.sheet_height()].map(|c| c as f32);
    page_albedo(texture::Side::Front, uv).map(|c| (srgb(c) * 255.0).round() as u8)
}

/// The tear texture $T_{\text{paper}}$ masked by the mask of `side` of `alpha`
/// ([`AlphaPair::to_rgba`] over the printed page) encoded as a PNG of the raster's size.
///
/// # Errors
/// The encoder's error.
pub fn tear_png(alpha: &AlphaPair, side: Side) -> io::Result<Vec<u8>> {
    let r = alpha.raster();
    let rgba = alpha.to_rgba(|i, j| page_colour(alpha, i, j), side);
    encode_png(r.width_px(), r.height_px(), &rgba)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_side_is_that_of_the_nearest_segment() {
        // Up, then right: (0,0) -> (0,2) -> (2,2).
        let path = [[0.0, 0.0], [0.0, 2.0], [2.0, 2.0]];
        assert_eq!(side_of(&path, [-1.0, 1.0]), Some(Side::Left));
        assert_eq!(side_of(&path, [1.0, 1.0]), Some(Side::Right));
        assert_eq!(side_of(&path, [1.0, 3.0]), Some(Side::Left));
        assert_eq!(side_of(&path[..1], [1.0, 3.0]), None);
    }

    /// The flat sheet faces the viewer: normals +z, the front wound counter-clockwise seen
    /// from +z, the back the other way; the printed page's head at the top edge.
    #[test]
    fn the_flat_sheet_faces_the_viewer() {
        let sheet = SheetMesh::<f64>::rectangle(12.0, 9.0, 2, 2).unwrap();
        let mut out = TriMesh::new();
        render_mesh(&sheet, [12.0, 9.0], &mut out);
        let n = sheet.triangle_count();
        assert_eq!(out.triangle_count(), 2 * n);
        assert_eq!(out.vertex_count(), 2 * sheet.vertex_count());
        for (k, t) in out.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|i| out.positions[i as usize]);
            let towards = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            assert_eq!(towards > 0.0, k < n, "triangle {k}");
        }
        assert_eq!(out.normals[0], [0.0, 0.0, 1.0]);
        // Vertex 0 is the pattern's (0, 0): the bottom-left corner, uv (0, 1); its back
        // copy mirrors u.
        assert_eq!(out.positions[0], [0.0, 0.0, 0.0]);
        assert_eq!(out.uvs[0], [0.0, 1.0]);
        assert_eq!(out.uvs[sheet.vertex_count()], [1.0, 1.0]);
    }
}
