//! [`SheetMesh`]: the coarse triangle mesh of a sheet of paper, in its flat pattern and in
//! 3D, with half-edge adjacency, vertex fans and boundary loops.
//!
//! Half-edge `h = 3t + k` of triangle `t = [a, b, c]` runs from corner `k` to corner
//! `k + 1 (mod 3)`; its twin runs the other way in the neighbouring triangle, or is [`NONE`]
//! on the boundary. Triangles are counter-clockwise in the pattern. The adjacency is rebuilt
//! after every topology edit (allocation-free otherwise); the edits bump
//! [`SheetMesh::topology_version`], and edits that move a vertex in the pattern bump
//! [`SheetMesh::shape_version`].

use alloc::vec::Vec;

use folio_kernels::{Real, Vec3Ops, math};

use super::error::SheetError;
use super::scratch::Scratch;

/// "No half-edge": the twin of a boundary half-edge.
pub const NONE: u32 = u32::MAX;

/// Smallest pattern area of a triangle, relative to its squared longest edge, that
/// [`SheetMesh::check`] and the edits accept: every angle of an accepted triangle is above
/// $\arcsin(2 \cdot 10^{-3}) \approx 0.11°$ (its height over the longest edge $\ell$ is
/// above $2 \cdot 10^{-3} \ell$, and the other edges are at most $\ell$ long).
pub(crate) const MIN_RELATIVE_AREA: f64 = 1e-3;

/// A sheet: pattern coordinates, 3D positions and velocities per vertex, and triangles
/// (module docs).
#[derive(Clone, Debug)]
pub struct SheetMesh<T: Real> {
    pub(crate) pattern: Vec<[T; 2]>,
    pub(crate) positions: Vec<T::Vec3>,
    pub(crate) velocities: Vec<T::Vec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
    /// Twin of each half-edge, or [`NONE`].
    pub(crate) twins: Vec<u32>,
    /// One half-edge leaving each vertex: the boundary one (no twin) if the vertex is on the
    /// boundary, so that a counter-clockwise walk from it visits the whole fan.
    pub(crate) outgoing: Vec<u32>,
    pub(crate) topology_version: u64,
    pub(crate) shape_version: u64,
    /// Working buffers of the edits ([`super::scratch`]).
    pub(crate) scratch: Scratch<T>,
}

impl<T: Real> SheetMesh<T> {
    /// A sheet from its pattern and triangles, lying flat at $(u, v, 0)$ at rest.
    ///
    /// # Errors
    /// As [`SheetMesh::check`].
    pub fn new(pattern: Vec<[T; 2]>, triangles: Vec<[u32; 3]>) -> Result<Self, SheetError> {
        let positions = pattern
            .iter()
            .map(|p| T::Vec3::new(p[0], p[1], T::ZERO))
            .collect();
        let velocities = alloc::vec![T::Vec3::ZERO; pattern.len()];
        let mut mesh = Self {
            pattern,
            positions,
            velocities,
            triangles,
            twins: Vec::new(),
            outgoing: Vec::new(),
            topology_version: 0,
            shape_version: 0,
            scratch: Scratch::default(),
        };
        mesh.check()?;
        Ok(mesh)
    }

    /// A `width` x `height` rectangle of `nx` x `ny` quads, each split into two triangles,
    /// the diagonals mirrored about $u = W/2$ and alternating by row (so the mesh is
    /// symmetric about the vertical centre line when `nx` is even). Vertex `i + (nx+1) j`
    /// is at $(iW/n_x,\ jH/n_y)$.
    ///
    /// # Errors
    /// [`SheetError::OutOfRange`] for a non-finite or non-positive size, or `nx`, `ny`
    /// outside 1..=1024.
    pub fn rectangle(width: T, height: T, nx: usize, ny: usize) -> Result<Self, SheetError> {
        let positive = |x: T| x.is_finite() && x > T::ZERO && x <= T::COORD_MAX;
        if !positive(width) {
            return Err(SheetError::OutOfRange { field: "width" });
        }
        if !positive(height) {
            return Err(SheetError::OutOfRange { field: "height" });
        }
        if !(1..=1024).contains(&nx) {
            return Err(SheetError::OutOfRange { field: "nx" });
        }
        if !(1..=1024).contains(&ny) {
            return Err(SheetError::OutOfRange { field: "ny" });
        }
        let mut pattern = Vec::with_capacity((nx + 1) * (ny + 1));
        for j in 0..=ny {
            for i in 0..=nx {
                pattern.push([
                    width * T::from_f64(i as f64 / nx as f64),
                    height * T::from_f64(j as f64 / ny as f64),
                ]);
            }
        }
        let id = |i: usize, j: usize| (i + (nx + 1) * j) as u32;
        let mut triangles = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if (2 * i < nx) != (j % 2 == 1) {
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                } else {
                    triangles.push([a, b, d]);
                    triangles.push([b, c, d]);
                }
            }
        }
        Self::new(pattern, triangles)
    }

    /// Pattern coordinates $(u, v)$ of every vertex (sheet units).
    #[must_use]
    pub fn pattern(&self) -> &[[T; 2]] {
        &self.pattern
    }

    /// 3D positions (sheet units).
    #[must_use]
    pub fn positions(&self) -> &[T::Vec3] {
        &self.positions
    }

    /// 3D positions, mutable (the physics writes them; the pattern stays).
    pub fn positions_mut(&mut self) -> &mut [T::Vec3] {
        &mut self.positions
    }

    /// Velocities (sheet units per second).
    #[must_use]
    pub fn velocities(&self) -> &[T::Vec3] {
        &self.velocities
    }

    /// Velocities, mutable.
    pub fn velocities_mut(&mut self) -> &mut [T::Vec3] {
        &mut self.velocities
    }

    /// Triangles, counter-clockwise in the pattern.
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.pattern.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Changes with every edit of the connectivity (insert, cut, flip): the physics re-runs
    /// its symbolic analysis when it does, and only then.
    #[must_use]
    pub fn topology_version(&self) -> u64 {
        self.topology_version
    }

    /// Changes with every edit of the pattern (including topology edits): the rest shapes of
    /// the triangles must be rebuilt when it does.
    #[must_use]
    pub fn shape_version(&self) -> u64 {
        self.shape_version
    }

    /// Start and end vertex of half-edge `h`.
    #[inline]
    #[must_use]
    pub fn half_edge(&self, h: u32) -> (u32, u32) {
        let (t, k) = (h as usize / 3, h as usize % 3);
        let tri = self.triangles[t];
        (tri[k], tri[(k + 1) % 3])
    }

    /// Twin of half-edge `h`, or [`NONE`] on the boundary.
    #[inline]
    #[must_use]
    pub fn twin(&self, h: u32) -> u32 {
        self.twins[h as usize]
    }

    /// The half-edge `a → b`, if the sheet has it.
    #[must_use]
    pub fn find_half_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.fan_iter(a).find(|&h| self.half_edge(h).1 == b)
    }

    /// `true` when `v` is on the sheet's boundary.
    #[must_use]
    pub fn is_boundary(&self, v: u32) -> bool {
        self.outgoing
            .get(v as usize)
            .is_some_and(|&h| h != NONE && self.twins[h as usize] == NONE)
    }

    /// The half-edges leaving `v`, one per triangle of its fan, counter-clockwise (for a
    /// boundary vertex, starting at the boundary edge that has the sheet on its left).
    pub fn fan_iter(&self, v: u32) -> FanIter<'_, T> {
        let start = self.outgoing.get(v as usize).copied().unwrap_or(NONE);
        FanIter {
            mesh: self,
            start,
            next: start,
        }
    }

    /// Sum of the pattern angles at `v` over its fan (radians): $2\pi$ inside the sheet,
    /// $\pi$ on a straight boundary, above $\pi$ at an inward angle, $2\pi$ at a tear tip.
    #[must_use]
    pub fn pattern_angle(&self, v: u32) -> T {
        let mut sum = T::ZERO;
        for h in self.fan_iter(v) {
            let (_, b) = self.half_edge(h);
            let c = self.half_edge(prev(h)).0;
            sum += corner_angle(
                self.pattern[v as usize],
                self.pattern[b as usize],
                self.pattern[c as usize],
            );
        }
        sum
    }

    /// For a boundary vertex `v`: its two boundary neighbours `(next, previous)` along the
    /// boundary loop (the sheet on the left when walking `previous → v → next`).
    #[must_use]
    pub fn boundary_neighbours(&self, v: u32) -> Option<(u32, u32)> {
        if !self.is_boundary(v) {
            return None;
        }
        let first = self.outgoing[v as usize];
        let last = self.fan_iter(v).last()?;
        Some((self.half_edge(first).1, self.half_edge(prev(last)).0))
    }

    /// The boundary loops, each a list of vertices in order with the sheet on the left.
    #[must_use]
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        let mut seen = alloc::vec![false; self.twins.len()];
        let mut loops = Vec::new();
        for h0 in 0..self.twins.len() {
            if self.twins[h0] != NONE || seen[h0] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut h = h0 as u32;
            while !seen[h as usize] {
                seen[h as usize] = true;
                let (a, b) = self.half_edge(h);
                cycle.push(a);
                h = self.outgoing[b as usize];
                if h == NONE || self.twins[h as usize] != NONE {
                    break;
                }
            }
            loops.push(cycle);
        }
        loops
    }

    /// Signed pattern area of triangle `t` (positive when counter-clockwise).
    #[must_use]
    pub fn pattern_area(&self, t: usize) -> T {
        let [a, b, c] = self.triangles[t].map(|i| self.pattern[i as usize]);
        signed_area(a, b, c)
    }

    /// The triangle containing pattern point `p` and the barycentric coordinates of `p` in
    /// it (each at least $-\max(10^{-9}, 64\varepsilon)$, so that a point on an edge is found
    /// in f32 as well), or `None` outside the sheet.
    #[must_use]
    pub fn locate(&self, p: [T; 2]) -> Option<(usize, [T; 3])> {
        let tol = inside_tolerance::<T>();
        (0..self.triangles.len()).find_map(|t| {
            let w = self.barycentric(t, p)?;
            (w[0] >= tol && w[1] >= tol && w[2] >= tol).then_some((t, w))
        })
    }

    /// Barycentric coordinates of pattern point `p` in triangle `t` (`None` if it is
    /// degenerate or `t` does not exist). Each is the ratio of a sub-triangle's signed area to
    /// the triangle's, so it is exactly zero for a point on the line of the opposite edge
    /// (they sum to one up to rounding).
    #[must_use]
    pub fn barycentric(&self, t: usize, p: [T; 2]) -> Option<[T; 3]> {
        let [a, b, c] = self.triangles.get(t)?.map(|i| self.pattern[i as usize]);
        let area = signed_area(a, b, c);
        if !positive(area) {
            return None;
        }
        Some([
            signed_area(p, b, c) / area,
            signed_area(a, p, c) / area,
            signed_area(a, b, p) / area,
        ])
    }

    /// The 3D point of triangle `t` at barycentric coordinates `w` (the pattern-to-3D map).
    #[must_use]
    pub fn map_to_3d(&self, t: usize, w: [T; 3]) -> T::Vec3 {
        let [a, b, c] = self.triangles[t].map(|i| self.positions[i as usize]);
        a * w[0] + b * w[1] + c * w[2]
    }

    /// Checks that the sheet is a valid manifold with boundary: indices in range, every value
    /// finite, every triangle counter-clockwise and not a sliver in the pattern, every edge
    /// in at most two triangles with opposite directions, every vertex in exactly one fan.
    /// Rebuilds the adjacency on success.
    ///
    /// # Errors
    /// The first violation found ([`SheetError`]).
    pub fn check(&mut self) -> Result<(), SheetError> {
        let n = self.pattern.len();
        if n >= NONE as usize || 3 * self.triangles.len() >= NONE as usize {
            return Err(SheetError::TooLarge);
        }
        if self.positions.len() != n || self.velocities.len() != n {
            return Err(SheetError::OutOfRange { field: "positions" });
        }
        for i in 0..n {
            let p = self.pattern[i];
            let finite = p[0].is_finite()
                && p[1].is_finite()
                && folio_kernels::real::vec_is_finite::<T>(self.positions[i])
                && folio_kernels::real::vec_is_finite::<T>(self.velocities[i]);
            if !finite {
                return Err(SheetError::NonFinite { index: i });
            }
        }
        for (t, tri) in self.triangles.iter().enumerate() {
            if tri.iter().any(|&i| i as usize >= n) {
                return Err(SheetError::BadIndex { index: t });
            }
            if !self.triangle_ok(tri.map(|i| self.pattern[i as usize])) {
                return Err(SheetError::Degenerate { index: t });
            }
        }
        self.rebuild_adjacency()?;
        let mut seen = core::mem::take(&mut self.scratch.seen);
        seen.clear();
        seen.resize(n, 0);
        for tri in &self.triangles {
            for &i in tri {
                seen[i as usize] += 1;
            }
        }
        let bad = seen
            .iter()
            .enumerate()
            .find(|&(v, &count)| count == 0 || self.fan_iter(v as u32).count() != count);
        let result = match bad {
            Some((index, _)) => Err(SheetError::NonManifoldVertex { index }),
            None => Ok(()),
        };
        self.scratch.seen = seen;
        result
    }

    /// `true` for a counter-clockwise pattern triangle above the sliver bound.
    pub(crate) fn triangle_ok(&self, [a, b, c]: [[T; 2]; 3]) -> bool {
        let area = signed_area(a, b, c);
        let longest = dist2(a, b).max_of(dist2(b, c)).max_of(dist2(c, a));
        area > T::from_f64(MIN_RELATIVE_AREA) * longest
    }

    /// Twins and outgoing half-edges from the triangles.
    pub(crate) fn rebuild_adjacency(&mut self) -> Result<(), SheetError> {
        let m = 3 * self.triangles.len();
        let mut keys = core::mem::take(&mut self.scratch.keys);
        keys.clear();
        for h in 0..m as u32 {
            let (a, b) = self.half_edge(h);
            keys.push((a.min(b), a.max(b), h));
        }
        keys.sort_unstable();
        let paired = self.pair_twins(&keys);
        self.scratch.keys = keys;
        paired?;
        self.outgoing.clear();
        self.outgoing.resize(self.pattern.len(), NONE);
        for h in 0..m as u32 {
            let a = self.half_edge(h).0 as usize;
            if self.outgoing[a] == NONE || self.twins[h as usize] == NONE {
                self.outgoing[a] = h;
            }
        }
        Ok(())
    }

    /// Twins from the half-edges sorted by their ends (`(low, high, half-edge)`).
    fn pair_twins(&mut self, keys: &[(u32, u32, u32)]) -> Result<(), SheetError> {
        self.twins.clear();
        self.twins.resize(keys.len(), NONE);
        for same in keys.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let (a, b) = (same[0].0, same[0].1);
            match *same {
                [_] => {}
                [(_, _, h), (_, _, g)] => {
                    if self.half_edge(h).0 == self.half_edge(g).0 {
                        return Err(SheetError::NonManifoldEdge { a, b });
                    }
                    self.twins[h as usize] = g;
                    self.twins[g as usize] = h;
                }
                _ => return Err(SheetError::NonManifoldEdge { a, b }),
            }
        }
        Ok(())
    }
}

/// Walks the fan of a vertex (see [`SheetMesh::fan_iter`]).
pub struct FanIter<'a, T: Real> {
    mesh: &'a SheetMesh<T>,
    start: u32,
    next: u32,
}

impl<T: Real> Iterator for FanIter<'_, T> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        let h = self.next;
        if h == NONE {
            return None;
        }
        let t = self.mesh.twins[prev(h) as usize];
        self.next = if t == self.start { NONE } else { t };
        Some(h)
    }
}

/// `x > 0`, `false` for NaN.
#[inline]
#[must_use]
pub(crate) fn positive<T: Real>(x: T) -> bool {
    x > T::ZERO
}

/// How far below zero a barycentric coordinate may be for a point to count as inside a
/// triangle: $-\max(10^{-9}, 64\varepsilon)$.
#[inline]
#[must_use]
pub(crate) fn inside_tolerance<T: Real>() -> T {
    let tol = T::from_f64(1e-9);
    let rounding = T::from_f64(64.0) * T::EPSILON;
    -(if rounding > tol { rounding } else { tol })
}

/// The half-edge before `h` in its triangle (it ends where `h` starts).
#[inline]
#[must_use]
pub fn prev(h: u32) -> u32 {
    if h % 3 == 0 { h + 2 } else { h - 1 }
}

/// The half-edge after `h` in its triangle.
#[inline]
#[must_use]
pub fn next(h: u32) -> u32 {
    if h % 3 == 2 { h - 2 } else { h + 1 }
}

/// The signed area $\tfrac12 (b - a) \times (c - a)$ of a pattern triangle.
#[inline]
#[must_use]
pub(crate) fn signed_area<T: Real>(a: [T; 2], b: [T; 2], c: [T; 2]) -> T {
    T::HALF * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// Squared distance of two pattern points (squared sheet units).
#[inline]
#[must_use]
pub fn dist2<T: Real>(a: [T; 2], b: [T; 2]) -> T {
    let (du, dv) = (b[0] - a[0], b[1] - a[1]);
    du * du + dv * dv
}

/// The squared length of the longest edge of the pattern triangle with corners `c`.
#[inline]
#[must_use]
pub fn longest_edge2<T: Real>(c: [[T; 2]; 3]) -> T {
    [dist2(c[1], c[2]), dist2(c[2], c[0]), dist2(c[0], c[1])]
        .into_iter()
        .fold(T::ZERO, |m, x| if x > m { x } else { m })
}

/// The pattern angle at `a` of the triangle corner `(a, b, c)`, in $[0, \pi]$.
#[must_use]
pub(crate) fn corner_angle<T: Real>(a: [T; 2], b: [T; 2], c: [T; 2]) -> T {
    let (e, f) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    let cross = e[0] * f[1] - e[1] * f[0];
    let dot = e[0] * f[0] + e[1] * f[1];
    math::abs(math::atan2(cross, dot))
}

/// `max` for [`Real`] (NaN-free inputs).
trait MaxOf {
    fn max_of(self, other: Self) -> Self;
}

impl<T: Real> MaxOf for T {
    #[inline]
    fn max_of(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
}
