//! The shape of the sheet's triangles in the pattern, and the local edge flips that keep
//! them well shaped where a tear edits the mesh (issue 22: "keep the manifold valid and the
//! triangles well shaped").
//!
//! A triangle's quality is its smallest pattern angle $\alpha_{\min}$. A flip of the
//! interior edge shared by triangles $(a, b, c)$ and $(b, a, d)$ replaces them with
//! $(c, a, d)$ and $(d, b, c)$ ([`SheetMesh::flip_edge`]); it is taken when it raises the
//! smaller $\alpha_{\min}$ of the pair. In a convex quad this is Lawson's Delaunay flip: of the
//! two diagonals, the one whose opposite angles sum to less than $\pi$ maximises the smallest
//! angle (Lawson 1977; de Berg et al., *Computational Geometry*, Thm. 9.7), so the flips
//! terminate and never lower the smallest angle of the pair. Flips change no vertex, so the
//! mesh stays as coarse as it was.

use folio_kernels::Real;

use super::mesh::{NONE, SheetMesh, corner_angle, next};

impl<T: Real> SheetMesh<T> {
    /// The smallest pattern angle of the triangle with corners `corners` (radians, in
    /// $[0, \pi/3]$ for a proper triangle).
    #[must_use]
    pub fn smallest_angle_of(corners: [[T; 2]; 3]) -> T {
        let [a, b, c] = corners;
        let (x, y, z) = (
            corner_angle(a, b, c),
            corner_angle(b, c, a),
            corner_angle(c, a, b),
        );
        let m = if y < x { y } else { x };
        if z < m { z } else { m }
    }

    /// The smallest pattern angle of triangle `t` (radians); `None` for a missing triangle.
    #[must_use]
    pub fn smallest_angle(&self, t: usize) -> Option<T> {
        let tri = self.triangles.get(t)?;
        Some(Self::smallest_angle_of(
            tri.map(|i| self.pattern[i as usize]),
        ))
    }

    /// The smallest pattern angle over all triangles (radians; $\pi$ for a mesh without one).
    #[must_use]
    pub fn worst_angle(&self) -> T {
        (0..self.triangles.len())
            .filter_map(|t| self.smallest_angle(t))
            .fold(T::PI, |m, a| if a < m { a } else { m })
    }

    /// Flips interior edges of the triangles around vertex `v` (its fan and the triangles
    /// that share an edge with it) whose pair has a smallest angle below `below` (radians),
    /// when the flip raises it (module docs), until no such flip is left or `max_flips` were
    /// made. Returns the number of flips. The sheet stays valid: each flip is checked like
    /// every edit, and one the mesh refuses is skipped.
    pub fn improve_around(&mut self, v: u32, below: T, max_flips: usize) -> usize {
        if v as usize >= self.pattern.len() {
            return 0;
        }
        let mut flips = 0;
        let mut near = core::mem::take(&mut self.scratch.triangles);
        while flips < max_flips {
            near.clear();
            for h in self.fan_iter(v) {
                let t = h as usize / 3;
                near.push(t);
                for k in 0..3 {
                    let g = self.twins[3 * t + k];
                    if g != NONE {
                        near.push(g as usize / 3);
                    }
                }
            }
            near.sort_unstable();
            near.dedup();
            let Some(h) = near.iter().find_map(|&t| self.improving_flip(t, below)) else {
                break;
            };
            if self.flip_edge(h).is_err() {
                break;
            }
            flips += 1;
        }
        self.scratch.triangles = near;
        flips
    }

    /// A half-edge of triangle `t` whose flip raises its pair's smallest angle, when that
    /// is below `below`.
    fn improving_flip(&self, t: usize, below: T) -> Option<u32> {
        (0..3).find_map(|k| {
            let h = (3 * t + k) as u32;
            let g = self.twins[h as usize];
            if g == NONE {
                return None;
            }
            let (a, b) = self.half_edge(h);
            let c = self.half_edge(next(h)).1;
            let d = self.half_edge(next(g)).1;
            let p = |i: u32| self.pattern[i as usize];
            let now = min2(
                Self::smallest_angle_of([p(a), p(b), p(c)]),
                Self::smallest_angle_of([p(b), p(a), p(d)]),
            );
            if now >= below {
                return None;
            }
            let (first, second) = ([p(c), p(a), p(d)], [p(d), p(b), p(c)]);
            if !(self.triangle_ok(first) && self.triangle_ok(second)) {
                return None;
            }
            let flipped = min2(
                Self::smallest_angle_of(first),
                Self::smallest_angle_of(second),
            );
            (flipped > now).then_some(h)
        })
    }
}

fn min2<T: Real>(a: T, b: T) -> T {
    if b < a { b } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn degrees(x: f64) -> f64 {
        x.to_degrees()
    }

    #[test]
    fn smallest_angles() {
        let h = 3f64.sqrt() / 2.0;
        let equilateral = [[0.0, 0.0], [1.0, 0.0], [0.5, h]];
        assert!((degrees(SheetMesh::smallest_angle_of(equilateral)) - 60.0).abs() < 1e-12);
        let right = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        assert!((degrees(SheetMesh::smallest_angle_of(right)) - 45.0).abs() < 1e-12);
        let mesh = SheetMesh::<f64>::rectangle(2.0, 1.0, 2, 1).unwrap();
        assert!((degrees(mesh.worst_angle()) - 45.0).abs() < 1e-12);
        assert_eq!(mesh.smallest_angle(99), None);
    }

    /// A quad split along its long diagonal into two slivers: the flip to the short
    /// diagonal is taken, the smallest angle rises from 5.7° to 45°, and a second call
    /// finds nothing to improve.
    #[test]
    fn a_sliver_pair_is_flipped_to_the_other_diagonal() {
        // Rhombus (-1, 0), (0, -0.1), (1, 0), (0, 0.1), split along (-1, 0)-(1, 0).
        let pattern = vec![[-1.0, 0.0], [0.0, -0.1], [1.0, 0.0], [0.0, 0.1]];
        let mut mesh = SheetMesh::<f64>::new(pattern, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let before = degrees(mesh.worst_angle());
        assert!((before - 5.71).abs() < 0.01, "{before}");
        let below = 10f64.to_radians();
        assert_eq!(mesh.improve_around(0, below, 8), 1);
        mesh.check().unwrap();
        let after = degrees(mesh.worst_angle());
        assert!(after > 11.0, "{after}");
        assert_eq!(mesh.improve_around(0, below, 8), 0);
        // A bound below the pair's smallest angle flips nothing.
        let mut other = SheetMesh::<f64>::new(
            vec![[-1.0, 0.0], [0.0, -0.1], [1.0, 0.0], [0.0, 0.1]],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap();
        assert_eq!(other.improve_around(0, 5f64.to_radians(), 8), 0);
        assert_eq!(other.improve_around(99, below, 8), 0);
    }

    /// On a grid whose vertices were jittered into slivers, flips around every vertex never
    /// lower the smallest angle and keep a valid sheet.
    #[test]
    fn improving_never_lowers_the_smallest_angle() {
        let mut mesh = SheetMesh::<f64>::rectangle(4.0, 4.0, 4, 4).unwrap();
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut jitter = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for v in 0..mesh.vertex_count() as u32 {
            if !mesh.is_boundary(v) {
                let p = mesh.pattern()[v as usize];
                let target = [p[0] + 0.8 * jitter(), p[1] + 0.8 * jitter()];
                let _ = mesh.move_vertex(v, target);
            }
        }
        let before = mesh.worst_angle();
        let mut flips = 0;
        for v in 0..mesh.vertex_count() as u32 {
            flips += mesh.improve_around(v, 25f64.to_radians(), 8);
        }
        mesh.check().unwrap();
        assert!(flips > 0);
        assert!(
            mesh.worst_angle() >= before,
            "{before} -> {}",
            mesh.worst_angle()
        );
    }
}
