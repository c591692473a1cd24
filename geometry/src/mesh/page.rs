//! The active page's mesh (seed `000_…` Sec. 3.5): its nodes offset by half the thickness
//! along the vertex normals on both sides, each grid row length-adapted to the page width,
//! and a rim joining the two sides along the grid border.

use alloc::vec::Vec;

use super::adapt::adapt_length;
use super::error::{MeshError, check_points, check_positive};
use super::trimesh::{Surface, TriMesh};
use super::vector::{add, cross, fill_gaps, scale, sub, unit, unit_above};
use crate::grid::QuadGrid;

/// Two grid differences whose unit directions span less than this sine give no normal.
const PARALLEL_SINE: f64 = 1e-12;

/// The normal of a page lying flat with `i` along +X and `j` along +Z; taken when no vertex
/// of the page has a normal.
const FLAT_NORMAL: [f64; 3] = [0.0, 1.0, 0.0];

/// The active page's two offset surfaces in `f64` (seed `000_…` Sec. 3.5), indexed like the
/// grid (vertex `(i, j)` at `i + nx * j`):
/// $$f_k = p_k + \tfrac{t}{2} n_k, \qquad b_k = p_k - \tfrac{t}{2} n_k,$$
/// then, in every row $j$ (the edge chain from the binding $i = 0$ to the outer edge), on each
/// surface, the outer vertex is moved by [`adapt_length`] so that the row is `page_width` long.
///
/// The vertex normal is $n = (\partial_j p \times \partial_i p) / \lVert\cdot\rVert$ with
/// central differences $\partial_i p = p_{i+1,j} - p_{i-1,j}$ (one-sided at the border), so a
/// page lying flat with $i$ along +X and $j$ along +Z has $n = +Y$. Fallback: where the two
/// differences are zero or parallel (coincident or collinear nodes: the sine of their angle
/// is below $10^{-12}$) the vertex takes the normal of the nearest earlier vertex in index
/// order that has one (the first such normal for the vertices before it), and +Y if no
/// vertex has one.
#[derive(Clone, Debug, PartialEq)]
pub struct PageSurfaces {
    grid: QuadGrid,
    normals: Vec<[f64; 3]>,
    front: Vec<[f64; 3]>,
    back: Vec<[f64; 3]>,
}

impl PageSurfaces {
    /// The surfaces of the page with node `positions` on `grid` (type docs).
    ///
    /// # Errors
    /// [`MeshError::TooFewNodes`] for a grid with fewer than 2 x 2 vertices,
    /// [`MeshError::TooManyVertices`] if `nx * nz` overflows, [`MeshError::PositionCount`]
    /// unless `positions.len() == nx * nz`, [`MeshError::NonFinite`] and
    /// [`MeshError::CoordinateTooLarge`] for a bad position, [`MeshError::NonPositive`] and
    /// [`MeshError::OutOfRange`] for a bad `thickness` or `page_width`.
    pub fn new(
        grid: QuadGrid,
        positions: &[[f64; 3]],
        thickness: f64,
        page_width: f64,
    ) -> Result<Self, MeshError> {
        check_grid(grid, positions)?;
        check_positive("thickness", thickness)?;
        check_positive("page_width", page_width)?;
        let normals = vertex_normals(grid, positions);
        let offset = |sign: f64| -> Vec<[f64; 3]> {
            let mut surface: Vec<[f64; 3]> = positions
                .iter()
                .zip(&normals)
                .map(|(&p, &n)| add(p, scale(n, sign * 0.5 * thickness)))
                .collect();
            for row in surface.chunks_exact_mut(grid.nx) {
                adapt_length(row, page_width);
            }
            surface
        };
        let front = offset(1.0);
        let back = offset(-1.0);
        Ok(Self {
            grid,
            normals,
            front,
            back,
        })
    }

    /// The grid.
    #[must_use]
    pub fn grid(&self) -> QuadGrid {
        self.grid
    }

    /// Unit vertex normals $n_k$ (pointing to the front).
    #[must_use]
    pub fn normals(&self) -> &[[f64; 3]] {
        &self.normals
    }

    /// Front vertices $f_k$ (after length adaptation).
    #[must_use]
    pub fn front(&self) -> &[[f64; 3]] {
        &self.front
    }

    /// Back vertices $b_k$ (after length adaptation).
    #[must_use]
    pub fn back(&self) -> &[[f64; 3]] {
        &self.back
    }

    /// Appends the front, the back and the rim to `out` ([`page_mesh`]).
    fn append(&self, out: &mut TriMesh) -> Result<(), MeshError> {
        let QuadGrid { nx, nz } = self.grid;
        // Validated: nx, nz >= 2 and nx * nz fits; the sums below are of the same order.
        let vertices = 2 * nx * nz + 4 * (nx + nz);
        let triangles = 4 * (nx - 1) * (nz - 1) + 4 * (nx + nz - 2);
        out.reserve_for(vertices, triangles)?;
        self.push_side(out, true);
        self.push_side(out, false);
        for side in RimSide::ALL {
            self.push_rim_side(out, side);
        }
        Ok(())
    }

    /// Appends the front (`front`) or the back. UVs: front $u = i/(n_x-1)$,
    /// $v = j/(n_z-1)$; the back mirrors $u \to 1 - u$, so that a texture reads correctly
    /// seen from the back (the binding is then on the right, as on a verso page).
    fn push_side(&self, out: &mut TriMesh, front: bool) {
        let QuadGrid { nx, nz } = self.grid;
        let (points, sign, surface) = if front {
            (&self.front, 1.0, Surface::PageFront)
        } else {
            (&self.back, -1.0, Surface::PageBack)
        };
        let first = out.vertex_count();
        for (k, (&p, &n)) in points.iter().zip(&self.normals).enumerate() {
            let (i, j) = self.grid.coords(k);
            let u = i as f64 / (nx - 1) as f64;
            let u = if front { u } else { 1.0 - u };
            out.push_vertex(p, scale(n, sign), [u, j as f64 / (nz - 1) as f64]);
        }
        for j in 0..nz - 1 {
            let (lower, upper) = (first + nx * j, first + nx * (j + 1));
            // Front quads run (i,j), (i,j+1), (i+1,j+1), (i+1,j): counter-clockwise about n.
            let (a, b) = if front {
                (upper, lower)
            } else {
                (lower, upper)
            };
            out.push_strip(a, b, nx, surface);
        }
    }

    /// Appends the rim along one side of the grid border: a strip between the front and the
    /// back border vertices. Rim normal $\hat n \times \tau$ with $\tau$ the border tangent
    /// (central difference of the mid-surface along the border, in the loop order of
    /// [`RimSide`]), i.e. perpendicular to the rim and pointing away from the page; fallback:
    /// the side's outward direction of a page lying flat (−Z, +X, +Z, −X).
    /// UVs: $u$ along the side, $v = 1$ on the front and $0$ on the back.
    fn push_rim_side(&self, out: &mut TriMesh, side: RimSide) {
        let len = side.len(self.grid);
        let normal = |k: usize| {
            let mid = |k: usize| {
                let g = side.vertex(self.grid, k);
                add(self.front[g], self.back[g])
            };
            let tangent = sub(mid((k + 1).min(len - 1)), mid(k.saturating_sub(1)));
            let n = self.normals[side.vertex(self.grid, k)];
            unit(cross(n, tangent)).unwrap_or(side.flat_outward())
        };
        let mut rows = [0; 2];
        for (row, (points, v)) in rows.iter_mut().zip([(&self.front, 1.0), (&self.back, 0.0)]) {
            *row = out.vertex_count();
            for k in 0..len {
                let u = k as f64 / (len - 1) as f64;
                out.push_vertex(points[side.vertex(self.grid, k)], normal(k), [u, v]);
            }
        }
        out.push_strip(rows[0], rows[1], len, Surface::PageEdge);
    }
}

/// A side of the grid border, traversed so that the four sides form one loop,
/// counter-clockwise seen from the front.
#[derive(Clone, Copy)]
enum RimSide {
    /// $j = 0$, $i$ increasing.
    Start,
    /// $i = n_x - 1$ (the outer edge), $j$ increasing.
    Outer,
    /// $j = n_z - 1$, $i$ decreasing.
    End,
    /// $i = 0$ (the binding), $j$ decreasing.
    Binding,
}

impl RimSide {
    const ALL: [Self; 4] = [Self::Start, Self::Outer, Self::End, Self::Binding];

    /// Vertices along the side.
    fn len(self, grid: QuadGrid) -> usize {
        match self {
            Self::Start | Self::End => grid.nx,
            Self::Outer | Self::Binding => grid.nz,
        }
    }

    /// Grid index of the side's `k`-th vertex in loop order.
    fn vertex(self, grid: QuadGrid, k: usize) -> usize {
        let QuadGrid { nx, nz } = grid;
        match self {
            Self::Start => grid.index(k, 0),
            Self::Outer => grid.index(nx - 1, k),
            Self::End => grid.index(nx - 1 - k, nz - 1),
            Self::Binding => grid.index(0, nz - 1 - k),
        }
    }

    /// Outward direction of the side for a page lying flat (i along +X, j along +Z).
    fn flat_outward(self) -> [f64; 3] {
        match self {
            Self::Start => [0.0, 0.0, -1.0],
            Self::Outer => [1.0, 0.0, 0.0],
            Self::End => [0.0, 0.0, 1.0],
            Self::Binding => [-1.0, 0.0, 0.0],
        }
    }
}

/// `Ok` for a grid of at least 2 x 2 vertices with `nx * nz` valid positions.
fn check_grid(grid: QuadGrid, positions: &[[f64; 3]]) -> Result<(), MeshError> {
    let QuadGrid { nx, nz } = grid;
    if nx < 2 || nz < 2 {
        return Err(MeshError::TooFewNodes { found: nx.min(nz) });
    }
    let expected = nx
        .checked_mul(nz)
        .filter(|&n| n <= usize::MAX / 8)
        .ok_or(MeshError::TooManyVertices { needed: usize::MAX })?;
    if positions.len() != expected {
        return Err(MeshError::PositionCount {
            expected,
            found: positions.len(),
        });
    }
    check_points(positions)
}

/// Unit vertex normals with the fallback of [`PageSurfaces`].
fn vertex_normals(grid: QuadGrid, positions: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let raw: Vec<Option<[f64; 3]>> = (0..grid.len())
        .map(|k| {
            let (i, j) = grid.coords(k);
            let at = |i: usize, j: usize| positions[grid.index(i, j)];
            let di = sub(at((i + 1).min(grid.nx - 1), j), at(i.saturating_sub(1), j));
            let dj = sub(at(i, (j + 1).min(grid.nz - 1)), at(i, j.saturating_sub(1)));
            unit_above(cross(unit(dj)?, unit(di)?), PARALLEL_SINE)
        })
        .collect();
    fill_gaps(&raw, FLAT_NORMAL)
}

/// Appends the active page (seed `000_…` Sec. 3.5): the front (`PageFront`) and back
/// (`PageBack`) offset surfaces of [`PageSurfaces`] and the rim (`PageEdge`) joining them along
/// the grid border.
///
/// Front vertices carry the normals $n_k$, back vertices $-n_k$; UVs: front
/// $u = i/(n_x-1)$, $v = j/(n_z-1)$, back $u = 1 - i/(n_x-1)$ (mirrored, so that the texture
/// reads correctly from its side). Each side of the rim has its own vertices with the normal
/// perpendicular to the rim, pointing away from the page. Counts: $2 n_x n_z + 4(n_x + n_z)$
/// vertices and $4 (n_x-1)(n_z-1) + 4(n_x + n_z - 2)$ triangles.
///
/// # Errors
/// As [`PageSurfaces::new`], and [`MeshError::TooManyVertices`] if `out` would exceed `u32`
/// indices. On error `out` is unchanged.
pub fn page_mesh(
    out: &mut TriMesh,
    grid: QuadGrid,
    positions: &[[f64; 3]],
    thickness: f64,
    page_width: f64,
) -> Result<(), MeshError> {
    PageSurfaces::new(grid, positions, thickness, page_width)?.append(out)
}
