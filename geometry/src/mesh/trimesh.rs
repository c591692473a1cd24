//! The render mesh ([`TriMesh`]) and the few ways the builders append to it: a vertex, a
//! triangle, a quad, a strip of quads between two rows of vertices, a fan, a planar face.

use alloc::vec::Vec;

use super::error::MeshError;
use super::vector::{cross, dot, sub};

/// Which surface a triangle belongs to (selects material and texture).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// The active page's front (the side its vertex normals point to).
    PageFront,
    /// The active page's back.
    PageBack,
    /// The rim joining the active page's front and back along its border.
    PageEdge,
    /// A page block's top (the offset curve of its midline, with the rounded binding).
    BlockTop,
    /// A page block's bottom (its midline, extruded).
    BlockBottom,
    /// A page block's side faces: the fore-edge, the binding face and the two end caps.
    BlockEdge,
    /// A hard-cover board.
    Cover,
}

/// A triangle mesh for rendering, in `f32` (GPU-ready). Vertices are not shared between
/// surfaces, so every vertex has the normal of its own surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions (page units).
    pub positions: Vec<[f32; 3]>,
    /// Vertex normals, unit length.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates in $[0, 1]^2$.
    pub uvs: Vec<[f32; 2]>,
    /// Vertex indices, counter-clockwise seen from the side the normals point to.
    pub triangles: Vec<[u32; 3]>,
    /// The surface of each triangle.
    pub surfaces: Vec<Surface>,
}

impl TriMesh {
    /// An empty mesh.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Removes every vertex and triangle, keeping the allocated storage for reuse.
    pub fn clear(&mut self) {
        self.positions.clear();
        self.normals.clear();
        self.uvs.clear();
        self.triangles.clear();
        self.surfaces.clear();
    }

    /// Number of vertices.
    #[inline]
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[inline]
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Reserves room for `vertices` more vertices and `triangles` more triangles; fails if
    /// the vertex count would exceed `u32::MAX` or the storage cannot be allocated. Every
    /// builder calls this before appending, so that the index casts below are exact.
    pub(super) fn reserve_for(
        &mut self,
        vertices: usize,
        triangles: usize,
    ) -> Result<(), MeshError> {
        let needed = self.vertex_count().saturating_add(vertices);
        let too_many = MeshError::TooManyVertices { needed };
        if u32::try_from(needed).is_err() {
            return Err(too_many);
        }
        self.positions.try_reserve(vertices).map_err(|_| too_many)?;
        self.normals.try_reserve(vertices).map_err(|_| too_many)?;
        self.uvs.try_reserve(vertices).map_err(|_| too_many)?;
        self.triangles
            .try_reserve(triangles)
            .map_err(|_| too_many)?;
        self.surfaces.try_reserve(triangles).map_err(|_| too_many)
    }

    /// Appends a vertex (cast to `f32`, UV clamped to $[0, 1]^2$) and returns its index.
    pub(super) fn push_vertex(
        &mut self,
        position: [f64; 3],
        normal: [f64; 3],
        uv: [f64; 2],
    ) -> usize {
        let index = self.vertex_count();
        self.positions.push(position.map(|c| c as f32));
        self.normals.push(normal.map(|c| c as f32));
        self.uvs.push(uv.map(|c| c.clamp(0.0, 1.0) as f32));
        index
    }

    /// Appends the triangle `[a, b, c]` (vertex indices, in this winding).
    pub(super) fn push_triangle(&mut self, vertices: [usize; 3], surface: Surface) {
        // `reserve_for` bounded every index by `u32::MAX`.
        self.triangles
            .push(vertices.map(|v| u32::try_from(v).unwrap_or(u32::MAX)));
        self.surfaces.push(surface);
    }

    /// Appends the quad `a, b, c, d` (in this cyclic order) as triangles `(a, b, c)`, `(a, c, d)`.
    pub(super) fn push_quad(&mut self, [a, b, c, d]: [usize; 4], surface: Surface) {
        self.push_triangle([a, b, c], surface);
        self.push_triangle([a, c, d], surface);
    }

    /// Appends the strip of quads between the vertex rows `a .. a + len` and `b .. b + len`:
    /// quad $k$ is $(a_k, a_{k+1}, b_{k+1}, b_k)$.
    pub(super) fn push_strip(&mut self, a: usize, b: usize, len: usize, surface: Surface) {
        for k in 0..len.saturating_sub(1) {
            self.push_quad([a + k, a + k + 1, b + k + 1, b + k], surface);
        }
    }

    /// Appends the fan from vertex `apex` to the row `row .. row + len`: triangle $m$ is
    /// $(\text{apex}, r_{m+1}, r_m)$, wound like [`TriMesh::push_strip`] with a row that
    /// collapsed to the apex.
    pub(super) fn push_fan(&mut self, apex: usize, row: usize, len: usize, surface: Surface) {
        for m in 0..len.saturating_sub(1) {
            self.push_triangle([apex, row + m + 1, row + m], surface);
        }
    }

    /// Appends a planar face with corners `corners` (in cyclic order) and the outward unit
    /// `normal`, with UVs $(0,0), (1,0), (1,1), (0,1)$ at the corners; the winding is chosen
    /// so that the face is counter-clockwise seen from `normal`.
    pub(super) fn push_planar_quad(
        &mut self,
        corners: [[f64; 3]; 4],
        normal: [f64; 3],
        surface: Surface,
    ) {
        const UV: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let first = self.vertex_count();
        for (corner, uv) in corners.into_iter().zip(UV) {
            self.push_vertex(corner, normal, uv);
        }
        let [a, b, c, _] = corners;
        let facing = dot(cross(sub(b, a), sub(c, a)), normal);
        let quad = if facing >= 0.0 {
            [0, 1, 2, 3]
        } else {
            [0, 3, 2, 1]
        };
        self.push_quad(quad.map(|k| first + k), surface);
    }

    /// Reverses the winding of every triangle from index `first` on (for a mirror image).
    pub(super) fn reverse_winding_from(&mut self, first: usize) {
        if let Some(triangles) = self.triangles.get_mut(first..) {
            for t in triangles {
                t.swap(1, 2);
            }
        }
    }
}
