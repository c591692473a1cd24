//! The mesh as the page's WebGL2 buffers: flat vertex arrays the page reads in place, through
//! typed-array views on the module's memory (`Float32Array(memory.buffer, ptr, len)`), plus
//! a table under the book.
//!
//! Each vertex carries a material code ([`Material`]) that tells the fragment shader which
//! page texture to read and how to shade it: the meshes never share a vertex between two
//! surfaces, so a triangle's surface is its vertices'.

use folio_geometry::mesh::{Surface, TriMesh};

/// What a vertex is made of, as the shader reads it (`float` codes 0 to 6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Material {
    /// The active page's front (its recto when it lies on the right).
    PageFront = 0,
    /// The active page's back.
    PageBack = 1,
    /// The left block's top page (a verso).
    LeftTop = 2,
    /// The right block's top page (a recto).
    RightTop = 3,
    /// Page edges: the active page's rim, a block's fore-edge, binding face and ends.
    Edges = 4,
    /// Cover cloth: the boards and the blocks' undersides.
    Cover = 5,
    /// The table.
    Table = 6,
}

impl Material {
    /// The material of a triangle of `surface` whose first vertex has `x` (left of the
    /// spine for $x < 0$).
    #[must_use]
    pub fn of(surface: Surface, x: f32) -> Self {
        match surface {
            Surface::PageFront => Self::PageFront,
            Surface::PageBack => Self::PageBack,
            Surface::BlockTop if x < 0.0 => Self::LeftTop,
            Surface::BlockTop => Self::RightTop,
            Surface::PageEdge | Surface::BlockEdge => Self::Edges,
            Surface::BlockBottom | Surface::Cover => Self::Cover,
        }
    }
}

/// Interleaving-free vertex arrays and triangle indices, reused frame to frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Buffers {
    /// $(x, y, z)$ per vertex (book frame, page units).
    pub positions: Vec<f32>,
    /// Unit normal per vertex.
    pub normals: Vec<f32>,
    /// Texture coordinates per vertex, $[0, 1]^2$.
    pub uvs: Vec<f32>,
    /// [`Material`] code per vertex.
    pub materials: Vec<f32>,
    /// Three vertex indices per triangle, counter-clockwise seen from the normal's side.
    pub indices: Vec<u32>,
}

impl Buffers {
    /// Fills the buffers from `mesh`, then adds the table: a square of side
    /// `4 * reach` centred under the book at height `table`, facing up.
    pub fn fill(&mut self, mesh: &TriMesh, table: f32, reach: f32) {
        self.positions.clear();
        self.normals.clear();
        self.uvs.clear();
        self.materials.clear();
        self.indices.clear();
        self.positions.extend(mesh.positions.iter().flatten());
        self.normals.extend(mesh.normals.iter().flatten());
        self.uvs.extend(mesh.uvs.iter().flatten());
        self.materials
            .resize(mesh.positions.len(), Material::Edges as u8 as f32);
        for (t, surface) in mesh.triangles.iter().zip(&mesh.surfaces) {
            let x = mesh.positions.get(t[0] as usize).map_or(0.0, |p| p[0]);
            let code = f32::from(Material::of(*surface, x) as u8);
            for &v in t {
                if let Some(m) = self.materials.get_mut(v as usize) {
                    *m = code;
                }
            }
        }
        self.indices.extend(mesh.triangles.iter().flatten());
        let base = mesh.positions.len() as u32;
        let r = 2.0 * reach;
        for (x, z) in [(-r, -r), (r, -r), (r, r), (-r, r)] {
            self.positions.extend([x, table, z + 0.5 * reach]);
            self.normals.extend([0.0, 1.0, 0.0]);
            self.uvs.extend([0.0, 0.0]);
            self.materials.push(f32::from(Material::Table as u8));
        }
        // Counter-clockwise seen from above (+Y): (-r,-r) -> (-r,r) -> (r,r).
        self.indices
            .extend([base, base + 3, base + 2, base, base + 2, base + 1]);
    }

    /// Vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.materials.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every vertex gets its triangle's material, the table comes last and faces up, and
    /// every index names a vertex.
    #[test]
    fn a_mesh_fills_the_buffers() {
        let mesh = TriMesh {
            positions: vec![[-1.0, 0.0, 0.0], [-1.0, 0.0, 1.0], [-2.0, 0.0, 0.0]],
            normals: vec![[0.0, 1.0, 0.0]; 3],
            uvs: vec![[0.0, 0.0]; 3],
            triangles: vec![[0, 1, 2]],
            surfaces: vec![Surface::BlockTop],
        };
        let mut b = Buffers::default();
        b.fill(&mesh, -0.5, 10.0);
        assert_eq!(b.vertex_count(), 7);
        assert_eq!(
            &b.materials[..3],
            &[2.0; 3],
            "left of the spine: the left top"
        );
        assert_eq!(&b.materials[3..], &[6.0; 4]);
        assert!(b.indices.iter().all(|&i| (i as usize) < b.vertex_count()));
        // The table's first triangle, seen from above, turns counter-clockwise.
        let p = |i: u32| {
            let k = 3 * i as usize;
            [b.positions[k], b.positions[k + 2]]
        };
        let [a, c, d] = [p(b.indices[3]), p(b.indices[4]), p(b.indices[5])];
        // Looking down -Y with X right and Z towards the viewer: counter-clockwise has a
        // negative (x, z) cross product.
        let cross = (c[0] - a[0]) * (d[1] - a[1]) - (c[1] - a[1]) * (d[0] - a[0]);
        assert!(cross < 0.0, "{cross}");
        b.fill(&mesh, -0.5, 10.0);
        assert_eq!(b.vertex_count(), 7, "a refill replaces");
    }
}
