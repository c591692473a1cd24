//! Shadows from the point light by a shadow map (as the seed's renderer, Sec. 4.2): the
//! depth of the nearest surface seen from the light, and a percentage-closer lookup.

use folio_geometry::mesh::TriMesh;

use super::camera::Camera;
use super::raster::{ATTRIBUTES, Corner, rasterize};
use glam::Vec3;

/// A shadow map: the nearest inverse depth per texel seen from the light (0 = nothing).
#[derive(Clone, Debug)]
pub struct ShadowMap {
    camera: Camera,
    inverse_depth: Vec<f32>,
    bias: f32,
    texel: f32,
    light: Vec3,
}

impl ShadowMap {
    /// An empty map of `resolution` x `resolution` texels for a light at `light` that frames
    /// `bounds` (what can cast or receive a shadow). Against self-shadowing ("acne") the
    /// lookup point is moved 2 texels (at the box's centre) along the surface normal
    /// towards the light, and depths within a bias of 1 texel plus $10^{-3}$ of the box's
    /// diagonal count as lit; both exceed a page's thickness, so a page does not shadow its
    /// own far side (its light reaches that side by transmission).
    #[must_use]
    pub fn new(light: Vec3, bounds: [[f32; 3]; 2], resolution: usize) -> Self {
        let resolution = resolution.max(1);
        let camera = Camera::framing(light, bounds, [resolution, resolution], 0.01);
        let [lo, hi] = bounds.map(Vec3::from);
        let centre = 0.5 * (lo + hi);
        let texel = camera.view_of(centre).z.max(0.0) / camera.focal;
        let diagonal = (hi - lo).length();
        Self {
            camera,
            inverse_depth: vec![0.0; resolution * resolution],
            bias: texel + 1e-3 * diagonal,
            texel,
            light,
        }
    }

    /// Clears the map and draws every triangle of `mesh` into it (both faces; triangles
    /// with a non-finite or out-of-range vertex are skipped).
    pub fn render(&mut self, mesh: &TriMesh) {
        self.inverse_depth.fill(0.0);
        let width = self.camera.width;
        for t in &mesh.triangles {
            let Some(corners) = corners(&self.camera, mesh, t) else {
                continue;
            };
            let depth = &mut self.inverse_depth;
            rasterize(&self.camera, &corners, false, |f| {
                let k = f.y * width + f.x;
                if f.inverse_depth > depth[k] {
                    depth[k] = f.inverse_depth;
                }
            });
        }
    }

    /// The fraction of the light reaching `p` on a surface with unit `normal` (1 lit, 0 in
    /// shadow): a 3 x 3 texel percentage-closer filter of "depth from the light $\le$
    /// nearest depth + bias" at `p` moved along $\pm$`normal` towards the light (type docs).
    /// Points outside the map or behind the light are lit.
    #[must_use]
    pub fn light_at(&self, p: Vec3, normal: Vec3) -> f32 {
        let towards = if normal.dot(self.light - p) >= 0.0 {
            2.0 * self.texel
        } else {
            -2.0 * self.texel
        };
        let v = self.camera.view_of(p + normal * towards);
        if v.z.is_nan() || v.z <= self.camera.near {
            return 1.0;
        }
        let s = self.camera.project(v);
        let (w, h) = (self.camera.width as isize, self.camera.height as isize);
        let (cx, cy) = (s[0].floor() as isize, s[1].floor() as isize);
        let mut lit = 0.0;
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (x, y) = (cx + dx, cy + dy);
                let stored = if (0..w).contains(&x) && (0..h).contains(&y) {
                    self.inverse_depth[(y * w + x) as usize]
                } else {
                    0.0
                };
                if stored <= 0.0 || v.z <= 1.0 / stored + self.bias {
                    lit += 1.0;
                }
            }
        }
        lit / 9.0
    }
}

/// The corners of triangle `t` of `mesh` seen by `camera`, with position, normal and UV
/// as attributes; `None` for an index out of range or a non-finite position.
pub fn corners(camera: &Camera, mesh: &TriMesh, t: &[u32; 3]) -> Option<[Corner; 3]> {
    let mut out = [Corner {
        view: Vec3::ZERO,
        attributes: [0.0; ATTRIBUTES],
    }; 3];
    for (corner, &index) in out.iter_mut().zip(t) {
        let i = usize::try_from(index).ok()?;
        let p = *mesh.positions.get(i)?;
        if !p.iter().all(|c| c.is_finite()) {
            return None;
        }
        let n = mesh.normals.get(i).copied().unwrap_or([0.0; 3]);
        let uv = mesh.uvs.get(i).copied().unwrap_or([0.0; 2]);
        corner.view = camera.view_of(p.into());
        corner.attributes = [p[0], p[1], p[2], n[0], n[1], n[2], uv[0], uv[1]];
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use folio_geometry::mesh::Surface;

    /// A small square hovering over the ground shadows the point under it, not one beside.
    #[test]
    fn occluder_casts_a_shadow() {
        let mut mesh = TriMesh::new();
        let p = [
            [-1.0, 2.0, -1.0],
            [-1.0, 2.0, 1.0],
            [1.0, 2.0, 1.0],
            [1.0, 2.0, -1.0],
        ];
        mesh.positions.extend(p);
        mesh.normals.extend([[0.0, 1.0, 0.0]; 4]);
        mesh.uvs.extend([[0.0; 2]; 4]);
        mesh.triangles.extend([[0, 1, 2], [0, 2, 3]]);
        mesh.surfaces.extend([Surface::Cover; 2]);
        let bounds = [[-5.0, 0.0, -5.0], [5.0, 2.0, 5.0]];
        let mut map = ShadowMap::new(Vec3::new(0.0, 20.0, 0.0), bounds, 256);
        map.render(&mesh);
        let up = Vec3::Y;
        assert_eq!(map.light_at(Vec3::ZERO, up), 0.0);
        assert_eq!(map.light_at(Vec3::new(4.0, 0.0, 4.0), up), 1.0);
        // The occluder itself is lit, on both faces (the far one by transmission).
        assert_eq!(map.light_at(Vec3::new(0.0, 2.0, 0.0), up), 1.0);
        assert_eq!(map.light_at(Vec3::new(0.0, 2.0, 0.0), Vec3::NEG_Y), 1.0);
        assert_eq!(map.light_at(Vec3::new(f32::NAN, 0.0, 0.0), up), 1.0);
    }
}
