//! The edits a tear makes to a [`SheetMesh`] (seed `002_…` Sec. 5.3, Fig. 8, App. A).
//!
//! - [`SheetMesh::insert_in_triangle`], [`SheetMesh::insert_on_edge`] and
//!   [`SheetMesh::insert_at`]: a new vertex at a pattern point; its 3D position is the
//!   barycentric image of the point on the deformed triangle and its velocity is zero (the
//!   seed treats remeshing as static).
//! - [`SheetMesh::cut_edge`]: an interior edge becomes two boundary edges; each end on the
//!   boundary splits into two vertices, one per side (the tear lips of Fig. 8, left). Cutting
//!   an edge whose ends are both on the same boundary loop separates the sheet into two
//!   pieces (after a slit has reached across, for example).
//! - [`SheetMesh::move_vertex`]: a tear tip slides to its next position when the tear goes
//!   straight, so the old tip leaves the boundary instead of staying on it as a vertex
//!   (Fig. 8, right); the lips stay straight.
//! - [`SheetMesh::flip_edge`]: the diagonal of the quad of two triangles turns (the
//!   generalized-cone remesh).
//!
//! Every edit either succeeds with a valid manifold sheet (checked by
//! [`SheetMesh::check`]) or returns an error and leaves the sheet as it was. Edits work in
//! the mesh's own buffers (its `scratch`): within the room made by
//! [`SheetMesh::reserve`] they allocate nothing.

use folio_kernels::{Real, Vec3Ops};

use super::error::SheetError;
use super::mesh::{
    NONE, SheetMesh, dist2, inside_tolerance, longest_edge2, next, prev, signed_area,
};

/// What [`SheetMesh::cut_edge`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cut {
    /// `splits[0]` for end `a`, `splits[1]` for end `b` of the cut `(a, b)`:
    /// `(original, copy)` if that end was on the boundary and was split, `None` if it was
    /// inside the sheet (it became the tip of the slit). At both ends the copy holds the
    /// triangles on the right of the directed edge `a → b` as given to the cut, the original
    /// those on its left.
    pub splits: [Option<(u32, u32)>; 2],
}

impl Cut {
    /// The splits that happened.
    pub fn iter(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.splits.iter().flatten().copied()
    }
}

impl<T: Real> SheetMesh<T> {
    /// Inserts a vertex at pattern point `p` inside triangle `t`, splitting it into three.
    ///
    /// # Errors
    /// [`SheetError::OutsideSheet`] if `p` is not inside `t`, [`SheetError::WouldInvert`]
    /// if a new triangle would be a sliver (insert on the edge instead).
    pub fn insert_in_triangle(&mut self, t: usize, p: [T; 2]) -> Result<u32, SheetError> {
        let w = self.barycentric(t, p).ok_or(SheetError::OutsideSheet)?;
        let tol = inside_tolerance::<T>();
        if !w.iter().all(|&x| x >= tol) {
            return Err(SheetError::OutsideSheet);
        }
        let [a, b, c] = self.triangles[t];
        let v = self.pattern.len() as u32;
        let corners = [[a, b, v], [b, c, v], [c, a, v]];
        self.edit(|m| {
            m.push_vertex(p, m.map_to_3d(t, w));
            m.triangles[t] = corners[0];
            m.triangles.push(corners[1]);
            m.triangles.push(corners[2]);
        })?;
        Ok(v)
    }

    /// Inserts a vertex on the edge of half-edge `h = a → b` at $a + s (b - a)$,
    /// $0 < s < 1$, splitting the one or two triangles of the edge.
    ///
    /// # Errors
    /// [`SheetError::OutOfRange`] for a bad `h` or `s`, [`SheetError::WouldInvert`] if a
    /// new triangle would be a sliver.
    pub fn insert_on_edge(&mut self, h: u32, s: T) -> Result<u32, SheetError> {
        if h as usize >= self.twins.len() {
            return Err(SheetError::OutOfRange { field: "half_edge" });
        }
        if !(s > T::ZERO && s < T::ONE) {
            return Err(SheetError::OutOfRange { field: "s" });
        }
        let (a, b) = self.half_edge(h);
        let t = h as usize / 3;
        let c = self.half_edge(prev(h)).0;
        let g = self.twins[h as usize];
        let (pa, pb) = (self.pattern[a as usize], self.pattern[b as usize]);
        let p = [pa[0] + (pb[0] - pa[0]) * s, pa[1] + (pb[1] - pa[1]) * s];
        let (xa, xb) = (self.positions[a as usize], self.positions[b as usize]);
        let x = xa + (xb - xa) * s;
        let v = self.pattern.len() as u32;
        self.edit(|m| {
            m.push_vertex(p, x);
            m.triangles[t] = [a, v, c];
            m.triangles.push([v, b, c]);
            if g != NONE {
                let t2 = g as usize / 3;
                let d = m.half_edge(prev(g)).0;
                m.triangles[t2] = [b, v, d];
                m.triangles.push([v, a, d]);
            }
        })?;
        Ok(v)
    }

    /// A vertex at pattern point `p`, in the triangle `t` that contains it, with
    /// $r = \text{snap} \cdot \ell$ and $\ell$ the longest edge of `t`: the nearest corner of
    /// `t` if it is within $r$ of `p` (no edit); else, if the nearest edge of `t` is within
    /// $r$ of `p`, a new vertex on that edge where the line from the opposite corner
    /// through `p` meets it ([`SheetMesh::insert_on_edge`]); else a new vertex at `p`
    /// inside `t` ([`SheetMesh::insert_in_triangle`]). `snap = 0` still snaps a point that
    /// lies exactly on a corner or an edge.
    ///
    /// # Errors
    /// [`SheetError::OutOfRange`] for a negative or non-finite `snap`,
    /// [`SheetError::OutsideSheet`] when no triangle contains `p`; the errors of the
    /// insertions.
    pub fn insert_at(&mut self, p: [T; 2], snap: T) -> Result<u32, SheetError> {
        if !(snap >= T::ZERO && snap.is_finite()) {
            return Err(SheetError::OutOfRange { field: "snap" });
        }
        let (t, w) = self.locate(p).ok_or(SheetError::OutsideSheet)?;
        let tri = self.triangles[t];
        let c = tri.map(|i| self.pattern[i as usize]);
        // Squared lengths of the edges opposite each corner.
        let opposite = [dist2(c[1], c[2]), dist2(c[2], c[0]), dist2(c[0], c[1])];
        let reach2 = snap * snap * longest_edge2(c);
        let corner = (0..3).fold(0, |best, k| {
            if dist2(p, c[k]) < dist2(p, c[best]) {
                k
            } else {
                best
            }
        });
        if dist2(p, c[corner]) <= reach2 {
            return Ok(tri[corner]);
        }
        // Squared distance to the line of the edge opposite corner k: (2 A_k / |edge|)^2
        // with A_k the signed area of (p, edge), zero for a point on the line.
        let edge_dist2 = |k: usize| {
            let ak = T::TWO * signed_area(p, c[(k + 1) % 3], c[(k + 2) % 3]);
            ak * ak / opposite[k]
        };
        let k = (0..3).fold(0, |best, k| {
            if edge_dist2(k) < edge_dist2(best) {
                k
            } else {
                best
            }
        });
        if edge_dist2(k) <= reach2 {
            // Corner k is opposite the half-edge 3t + (k + 1) % 3, which runs from corner
            // (k + 1) % 3 to corner (k + 2) % 3.
            let h = (3 * t + (k + 1) % 3) as u32;
            let (wa, wb) = (w[(k + 1) % 3], w[(k + 2) % 3]);
            return self.insert_on_edge(h, wb / (wa + wb));
        }
        self.insert_in_triangle(t, p)
    }

    /// Cuts the interior edge `(a, b)` (module docs).
    ///
    /// # Errors
    /// [`SheetError::NotInteriorEdge`] if the edge does not exist or is on the boundary,
    /// [`SheetError::InteriorCut`] if neither end is on the boundary.
    pub fn cut_edge(&mut self, a: u32, b: u32) -> Result<Cut, SheetError> {
        let h = self
            .find_half_edge(a, b)
            .or_else(|| self.find_half_edge(b, a))
            .ok_or(SheetError::NotInteriorEdge { a, b })?;
        if self.twins[h as usize] == NONE {
            return Err(SheetError::NotInteriorEdge { a, b });
        }
        if !self.is_boundary(a) && !self.is_boundary(b) {
            return Err(SheetError::InteriorCut { a, b });
        }
        // From the intact adjacency: the triangles of each boundary end on the right of
        // `a → b`. A boundary fan runs counter-clockwise from the boundary, so at `a` they
        // come before the half-edge `a → b`, at `b` from the half-edge `b → a` on. The
        // triangles of both ends go into one buffer: end `slot`'s are `ranges[slot]`.
        let mut right = core::mem::take(&mut self.scratch.triangles);
        right.clear();
        let mut ranges: [Option<(u32, core::ops::Range<usize>)>; 2] = [None, None];
        for (slot, (v, w)) in [(a, b), (b, a)].into_iter().enumerate() {
            if !self.is_boundary(v) {
                continue;
            }
            let start = right.len();
            right.extend(self.fan_iter(v).map(|g| g as usize / 3));
            let fan = start..right.len();
            let Some(j) = self.fan_iter(v).position(|g| self.half_edge(g).1 == w) else {
                self.scratch.triangles = right;
                return Err(SheetError::NotInteriorEdge { a, b });
            };
            ranges[slot] = Some((
                v,
                if slot == 0 {
                    fan.start..fan.start + j
                } else {
                    fan.start + j..fan.end
                },
            ));
        }
        let mut cut = Cut { splits: [None; 2] };
        let edited = self.edit(|m| {
            for (slot, range) in ranges.iter().enumerate() {
                let Some((v, tris)) = range else {
                    continue;
                };
                let copy = m.pattern.len() as u32;
                let i = *v as usize;
                let (p, x, u) = (m.pattern[i], m.positions[i], m.velocities[i]);
                m.pattern.push(p);
                m.positions.push(x);
                m.velocities.push(u);
                for &t in &right[tris.clone()] {
                    for corner in &mut m.triangles[t] {
                        if *corner == *v {
                            *corner = copy;
                        }
                    }
                }
                cut.splits[slot] = Some((*v, copy));
            }
        });
        self.scratch.triangles = right;
        edited?;
        Ok(cut)
    }

    /// Moves vertex `v` to pattern point `p` inside its own fan (the 3D position is the
    /// barycentric image of `p` on the fan before the move, the velocity zero). Bumps
    /// [`SheetMesh::shape_version`] only: the connectivity stays.
    ///
    /// # Errors
    /// [`SheetError::OutOfRange`] for a missing vertex, [`SheetError::OutsideSheet`] if no
    /// triangle of the fan contains `p` (or `p` is not finite),
    /// [`SheetError::WouldInvert`] if a fan triangle would become clockwise or a sliver.
    pub fn move_vertex(&mut self, v: u32, p: [T; 2]) -> Result<(), SheetError> {
        if v as usize >= self.pattern.len() {
            return Err(SheetError::OutOfRange { field: "vertex" });
        }
        let tol = inside_tolerance::<T>();
        let (t, w) = self
            .fan_iter(v)
            .find_map(|h| {
                let t = h as usize / 3;
                let w = self.barycentric(t, p)?;
                (w[0] >= tol && w[1] >= tol && w[2] >= tol).then_some((t, w))
            })
            .ok_or(SheetError::OutsideSheet)?;
        for h in self.fan_iter(v) {
            let f = h as usize / 3;
            let corners =
                self.triangles[f].map(|i| if i == v { p } else { self.pattern[i as usize] });
            if !self.triangle_ok(corners) {
                return Err(SheetError::WouldInvert { index: f });
            }
        }
        let x = self.map_to_3d(t, w);
        self.pattern[v as usize] = p;
        self.positions[v as usize] = x;
        self.velocities[v as usize] = T::Vec3::ZERO;
        self.shape_version += 1;
        Ok(())
    }

    /// Flips the interior edge of half-edge `h`: triangles $(a, b, c)$ and $(b, a, d)$
    /// become $(c, a, d)$ and $(d, b, c)$.
    ///
    /// # Errors
    /// [`SheetError::NotInteriorEdge`] on the boundary, [`SheetError::WouldInvert`] when the
    /// quad is not convex enough (a new triangle would be a sliver or clockwise).
    pub fn flip_edge(&mut self, h: u32) -> Result<(), SheetError> {
        if h as usize >= self.twins.len() {
            return Err(SheetError::OutOfRange { field: "half_edge" });
        }
        let g = self.twins[h as usize];
        let (a, b) = self.half_edge(h);
        if g == NONE {
            return Err(SheetError::NotInteriorEdge { a, b });
        }
        let c = self.half_edge(next(h)).1;
        let d = self.half_edge(next(g)).1;
        if c == d || self.find_half_edge(c, d).is_some() || self.find_half_edge(d, c).is_some() {
            return Err(SheetError::WouldInvert {
                index: h as usize / 3,
            });
        }
        let (t, t2) = (h as usize / 3, g as usize / 3);
        self.edit(|m| {
            m.triangles[t] = [c, a, d];
            m.triangles[t2] = [d, b, c];
        })
    }

    fn push_vertex(&mut self, p: [T; 2], x: T::Vec3) {
        self.pattern.push(p);
        self.positions.push(x);
        self.velocities.push(T::Vec3::ZERO);
    }

    /// Applies a topology edit, checks the result and bumps the versions; restores the sheet
    /// on failure (a sliver becomes [`SheetError::WouldInvert`]).
    fn edit(&mut self, change: impl FnOnce(&mut Self)) -> Result<(), SheetError> {
        self.save();
        change(self);
        match self.check() {
            Ok(()) => {
                self.topology_version += 1;
                self.shape_version += 1;
                Ok(())
            }
            Err(e) => {
                self.restore();
                Err(match e {
                    SheetError::Degenerate { index } => SheetError::WouldInvert { index },
                    other => other,
                })
            }
        }
    }
}
