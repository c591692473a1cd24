//! The active page's quad grid (seed `000_…` Sec. 3.1-3.2): vertex `(i, j)` has index
//! `i + nx * j`, `i` across the page (X at rest, `i = 0` at the binding) and `j` along the
//! binding (Z). Each vertex is classified by its grid neighbours into an inner star (four
//! neighbours, three DOG constraints), a boundary star (three, one constraint) or a corner
//! (two, none); the grid edges carry the isometry terms (eq. 13).

use alloc::vec::Vec;
use folio_kernels::Real;

/// A vertex's star with its neighbours in the order the DOG kernels expect.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Star {
    /// `[p0, xf, yf, xb, yb]`: x-forward, y-forward, x-back, y-back.
    Inner([usize; 5]),
    /// `[p0, a, b, c]`: three consecutive neighbours counter-clockwise, the missing one after `c`.
    Boundary([usize; 4]),
    /// A corner vertex (two neighbours, no DOG constraint).
    Corner(usize),
}

/// An `nx x nz` vertex grid (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QuadGrid {
    /// Vertices across the page (along X at rest).
    pub nx: usize,
    /// Vertices along the binding (Z).
    pub nz: usize,
}

impl QuadGrid {
    /// A grid of `quads_x x quads_z` quads; `None` unless both are at least 1.
    #[must_use]
    pub fn new(quads_x: usize, quads_z: usize) -> Option<Self> {
        (quads_x >= 1 && quads_z >= 1).then_some(Self {
            nx: quads_x + 1,
            nz: quads_z + 1,
        })
    }

    /// Number of vertices.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.nx * self.nz
    }

    /// `true` for a grid without vertices (never, for a grid from [`QuadGrid::new`]).
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The surface of grid `nodes` (one point per vertex, index order) at the material
    /// point `at` $= (u, v)$ of a grid whose rest spacing is `spacing` $= (h_u, h_v)$: the
    /// bilinear interpolation of its cell,
    /// $(1-b)\bigl((1-a)p_{ij} + a\,p_{i+1,j}\bigr) + b\bigl((1-a)p_{i,j+1} + a\,p_{i+1,j+1}\bigr)$
    /// with $i = \lfloor u/h_u \rfloor$, $a = u/h_u - i$ (and $j$, $b$ along $v$). A point
    /// beyond the last cell extrapolates it. `nodes` must hold [`QuadGrid::len`] points.
    #[must_use]
    pub fn bilinear<T: Real>(&self, nodes: &[T::Vec3], spacing: [f64; 2], at: [f64; 2]) -> T::Vec3 {
        let fu = (at[0] / spacing[0]).max(0.0);
        let fv = (at[1] / spacing[1]).max(0.0);
        let i = (fu as usize).min(self.nx.saturating_sub(2));
        let j = (fv as usize).min(self.nz.saturating_sub(2));
        let (a, b) = (T::from_f64(fu - i as f64), T::from_f64(fv - j as f64));
        let node = |i: usize, j: usize| nodes[self.index(i, j)];
        let bottom = node(i, j) * (T::ONE - a) + node(i + 1, j) * a;
        let top = node(i, j + 1) * (T::ONE - a) + node(i + 1, j + 1) * a;
        bottom * (T::ONE - b) + top * b
    }

    /// Index of vertex `(i, j)`.
    #[inline]
    #[must_use]
    pub fn index(&self, i: usize, j: usize) -> usize {
        i + self.nx * j
    }

    /// `(i, j)` of vertex `k`.
    #[inline]
    #[must_use]
    pub fn coords(&self, k: usize) -> (usize, usize) {
        (k % self.nx, k / self.nx)
    }

    /// The neighbour of `(i, j)` at offset `(di, dj)`, if it exists.
    fn neighbour(&self, i: usize, j: usize, di: isize, dj: isize) -> Option<usize> {
        let a = i.checked_add_signed(di)?;
        let b = j.checked_add_signed(dj)?;
        (a < self.nx && b < self.nz).then(|| self.index(a, b))
    }

    /// The star of vertex `(i, j)`.
    #[must_use]
    pub fn star(&self, i: usize, j: usize) -> Star {
        let ring = [
            self.neighbour(i, j, 1, 0),
            self.neighbour(i, j, 0, 1),
            self.neighbour(i, j, -1, 0),
            self.neighbour(i, j, 0, -1),
        ];
        let c = self.index(i, j);
        match ring {
            [Some(xf), Some(yf), Some(xb), Some(yb)] => Star::Inner([c, xf, yf, xb, yb]),
            _ => match ring.iter().position(Option::is_none) {
                Some(missing) if ring.iter().filter(|q| q.is_some()).count() == 3 => {
                    // Rotate the ring so that the missing neighbour comes last.
                    let k = (missing + 1) % 4;
                    let at = |m: usize| ring[(k + m) % 4].unwrap_or(c);
                    Star::Boundary([c, at(0), at(1), at(2)])
                }
                _ => Star::Corner(c),
            },
        }
    }

    /// Every vertex's star, in index order.
    #[must_use]
    pub fn stars(&self) -> Vec<Star> {
        (0..self.len())
            .map(|k| {
                let (i, j) = self.coords(k);
                self.star(i, j)
            })
            .collect()
    }

    /// Every grid edge `[a, b]` with `a < b`: first the edges along X (row by row), then along Z.
    #[must_use]
    pub fn edges(&self) -> Vec<[usize; 2]> {
        let mut out = Vec::with_capacity(self.edge_count());
        for j in 0..self.nz {
            for i in 0..self.nx - 1 {
                out.push([self.index(i, j), self.index(i + 1, j)]);
            }
        }
        for j in 0..self.nz - 1 {
            for i in 0..self.nx {
                out.push([self.index(i, j), self.index(i, j + 1)]);
            }
        }
        out
    }

    /// Number of grid edges.
    #[must_use]
    pub fn edge_count(&self) -> usize {
        (self.nx - 1) * self.nz + self.nx * (self.nz - 1)
    }

    /// `true` for a vertex on the grid's border.
    #[must_use]
    pub fn is_border(&self, i: usize, j: usize) -> bool {
        i == 0 || j == 0 || i + 1 == self.nx || j + 1 == self.nz
    }

    /// The vertices one ring in from the border (seed `000_…` Sec. 3.3: grabbing them avoids
    /// the smoothness artifacts of positional targets on the boundary), in index order.
    /// Empty when the grid has fewer than three vertices in a direction.
    #[must_use]
    pub fn second_ring(&self) -> Vec<usize> {
        if self.nx < 3 || self.nz < 3 {
            return Vec::new();
        }
        (0..self.len())
            .filter(|&k| {
                let (i, j) = self.coords(k);
                let inside = i >= 1 && j >= 1 && i + 2 <= self.nx && j + 2 <= self.nz;
                inside && (i == 1 || j == 1 || i + 2 == self.nx || j + 2 == self.nz)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{QuadGrid, Star};

    /// 3 x 2 quads: vertices 0-3 on row `j = 0`, 4-7 on `j = 1`, 8-11 on `j = 2`.
    fn grid() -> QuadGrid {
        QuadGrid::new(3, 2).unwrap()
    }

    #[test]
    fn index_and_coords_are_inverse() {
        let g = grid();
        assert_eq!((g.nx, g.nz, g.len()), (4, 3, 12));
        assert_eq!(g.index(2, 1), 6);
        assert_eq!(g.coords(6), (2, 1));
        for k in 0..g.len() {
            let (i, j) = g.coords(k);
            assert!(i < g.nx && j < g.nz);
            assert_eq!(g.index(i, j), k);
        }
        assert_eq!(QuadGrid::new(0, 2), None);
        assert_eq!(QuadGrid::new(2, 0), None);
    }

    /// Corners have two neighbours, edge vertices three (counter-clockwise, the missing one
    /// after the last), inner vertices four in the order x-forward, y-forward, x-back, y-back.
    #[test]
    fn stars_at_corners_edges_and_inside() {
        let g = grid();
        for (i, j) in [(0, 0), (3, 0), (0, 2), (3, 2)] {
            assert_eq!(
                g.star(i, j),
                Star::Corner(g.index(i, j)),
                "corner ({i}, {j})"
            );
        }
        assert_eq!(g.star(1, 0), Star::Boundary([1, 2, 5, 0]), "bottom edge");
        assert_eq!(g.star(3, 1), Star::Boundary([7, 11, 6, 3]), "right edge");
        assert_eq!(g.star(1, 2), Star::Boundary([9, 8, 5, 10]), "top edge");
        assert_eq!(g.star(0, 1), Star::Boundary([4, 0, 5, 8]), "left edge");
        assert_eq!(g.star(1, 1), Star::Inner([5, 6, 9, 4, 1]));
        assert_eq!(g.star(2, 1), Star::Inner([6, 7, 10, 5, 2]));
        let stars = g.stars();
        let count = |f: fn(&Star) -> bool| stars.iter().filter(|s| f(s)).count();
        assert_eq!(count(|s| matches!(s, Star::Inner(_))), 2);
        assert_eq!(count(|s| matches!(s, Star::Boundary(_))), 6);
        assert_eq!(count(|s| matches!(s, Star::Corner(_))), 4);
        for (k, s) in stars.iter().enumerate() {
            let (i, j) = g.coords(k);
            assert_eq!(*s, g.star(i, j));
            assert_eq!(g.is_border(i, j), !matches!(s, Star::Inner(_)));
        }
    }

    #[test]
    fn edges_join_grid_neighbours() {
        let g = grid();
        let edges = g.edges();
        assert_eq!(edges.len(), g.edge_count());
        assert_eq!(edges.len(), 3 * 3 + 4 * 2);
        assert_eq!(edges[0], [0, 1]);
        assert_eq!(edges[9], [0, 4]);
        for [a, b] in edges {
            let ((ia, ja), (ib, jb)) = (g.coords(a), g.coords(b));
            assert!(a < b);
            assert_eq!(ib - ia + jb - ja, 1, "edge [{a}, {b}]");
        }
    }

    /// On 4 x 4 quads the second ring is the 8 vertices around the centre.
    #[test]
    fn second_ring() {
        let g = QuadGrid::new(4, 4).unwrap();
        assert_eq!(g.second_ring(), [6, 7, 8, 11, 13, 16, 17, 18]);
        assert!(QuadGrid::new(1, 4).unwrap().second_ring().is_empty());
    }
}
