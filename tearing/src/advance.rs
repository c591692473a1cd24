//! One propagation of a tear on the sheet mesh (seed `002_…` Sec. 5.2 "Griffith", 5.3,
//! Fig. 8): the tip moves from $p$ to $p_{\text{next}} = p + s\thinspace t$ in the pattern.
//!
//! - **Straight on** (the tip of a tear whose direction turns by at most the threshold):
//!   the tip vertex itself slides to $p_{\text{next}}$ ([`SheetMesh::move_vertex`]); the old
//!   tip position leaves the boundary and the lips stay straight (Fig. 8, right). If the
//!   slide would invert a triangle, the tear splits instead.
//! - **Split** (a new tear, or a turn): a vertex $q$ is made at $p_{\text{next}}$ — inside the
//!   triangle of the fan of $p$ that contains the direction $t$, or where the segment leaves
//!   that triangle through its far edge (so a step crosses at most one triangle), snapped onto
//!   an edge or a vertex when within the snap distance — and the edge $(p, q)$ is cut:
//!   $p$ becomes two lips (Fig. 8, left) and $q$ the new tip.
//! - **Separation**: when $q$ lies on the sheet's boundary, the cut splits it too and the
//!   piece between the two tear paths comes off; the tear ends.

use folio_geometry::SheetMesh;
use folio_geometry::sheet::{Cut, SheetError, next_half_edge};
use folio_kernels::Real;

/// How the mesh changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Edit {
    /// The tip slid on (Fig. 8, right); no topology change.
    Moved,
    /// The tip split into two lips and a new tip was made (Fig. 8, left).
    Split,
    /// The tear reached the boundary: the tip's edge was cut at both ends.
    Separated,
}

/// The outcome of [`advance`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Advance {
    /// What was done.
    pub edit: Edit,
    /// The new tip (`None` after a separation).
    pub tip: Option<u32>,
    /// The lips made by the cut (none for a slide).
    pub cut: Option<Cut>,
}

/// Advances the tear at boundary vertex `p` by `length` along the unit pattern direction
/// `t` (module docs); `straight` allows the slide. `snap` is the snap distance relative to a
/// triangle's longest edge ([`SheetMesh::insert_at`]); on the far edge it is relative to
/// that edge's length.
///
/// # Errors
/// [`SheetError::OutsideSheet`] when no triangle of the fan of `p` contains the direction
/// `t` (it points out of the sheet), the errors of the edits otherwise. The mesh is unchanged
/// on error.
pub fn advance<T: Real>(
    mesh: &mut SheetMesh<T>,
    p: u32,
    t: [T; 2],
    length: T,
    straight: bool,
    snap: T,
) -> Result<Advance, SheetError> {
    let origin = *mesh
        .pattern()
        .get(p as usize)
        .ok_or(SheetError::OutOfRange { field: "p" })?;
    let target = [origin[0] + t[0] * length, origin[1] + t[1] * length];
    if straight && mesh.move_vertex(p, target).is_ok() {
        return Ok(Advance {
            edit: Edit::Moved,
            tip: Some(p),
            cut: None,
        });
    }
    // A split is two edits (the new vertex, then the cut); the second may refuse after the
    // first took: put the sheet back as it was.
    let backup = mesh.clone();
    let result = split(mesh, p, t, length, snap, origin, target);
    if result.is_err() {
        *mesh = backup;
    }
    result
}

/// The split of [`advance`]: the new tip `q` at `target` (or where the step leaves the wedge
/// triangle), then the cut of `(p, q)`.
fn split<T: Real>(
    mesh: &mut SheetMesh<T>,
    p: u32,
    t: [T; 2],
    length: T,
    snap: T,
    origin: [T; 2],
    target: [T; 2],
) -> Result<Advance, SheetError> {
    let (h, exit) = wedge(mesh, p, t).ok_or(SheetError::OutsideSheet)?;
    let q = if length < exit * (T::ONE - snap) {
        let tri = h as usize / 3;
        match mesh.insert_in_triangle(tri, target) {
            Ok(q) => q,
            Err(_) => mesh.insert_at(target, snap)?,
        }
    } else {
        // The far edge b → c of the wedge triangle (p, b, c) is the half-edge after h.
        let far = next_half_edge(h);
        let (b, c) = mesh.half_edge(far);
        let (pb, pc) = (mesh.pattern()[b as usize], mesh.pattern()[c as usize]);
        let s = crossing(origin, t, pb, pc).unwrap_or(T::HALF);
        if s < snap {
            b
        } else if s > T::ONE - snap {
            c
        } else {
            mesh.insert_on_edge(far, s)?
        }
    };
    if q == p {
        return Err(SheetError::OutOfRange { field: "length" });
    }
    let ends_on_boundary = mesh.is_boundary(q);
    let cut = mesh.cut_edge(p, q)?;
    Ok(Advance {
        edit: if ends_on_boundary {
            Edit::Separated
        } else {
            Edit::Split
        },
        tip: (!ends_on_boundary).then_some(q),
        cut: Some(cut),
    })
}

/// The half-edge `p → b` of the fan triangle $(p, b, c)$ whose corner at `p` contains the
/// direction `t`, and the distance along `t` from `p` to its far edge `(b, c)`.
#[must_use]
pub fn wedge<T: Real>(mesh: &SheetMesh<T>, p: u32, t: [T; 2]) -> Option<(u32, T)> {
    let o = mesh.pattern()[p as usize];
    let cross = |a: [T; 2], b: [T; 2]| a[0] * b[1] - a[1] * b[0];
    mesh.fan_iter(p).find_map(|h| {
        let (_, b) = mesh.half_edge(h);
        let c = mesh.half_edge(next_half_edge(h)).1;
        let (pb, pc) = (mesh.pattern()[b as usize], mesh.pattern()[c as usize]);
        let eb = [pb[0] - o[0], pb[1] - o[1]];
        let ec = [pc[0] - o[0], pc[1] - o[1]];
        // Counter-clockwise triangle: t is inside the corner when it is left of eb and
        // right of ec.
        if cross(eb, t) >= T::ZERO && cross(t, ec) >= T::ZERO {
            let s = crossing(o, t, pb, pc)?;
            let hit = [pb[0] + (pc[0] - pb[0]) * s, pb[1] + (pc[1] - pb[1]) * s];
            let d = [hit[0] - o[0], hit[1] - o[1]];
            Some((h, folio_kernels::math::sqrt(d[0] * d[0] + d[1] * d[1])))
        } else {
            None
        }
    })
}

/// Parameter $s \in [0, 1]$ where the ray $o + \lambda t$ ($\lambda > 0$) crosses segment
/// $b \to c$.
fn crossing<T: Real>(o: [T; 2], t: [T; 2], b: [T; 2], c: [T; 2]) -> Option<T> {
    let e = [c[0] - b[0], c[1] - b[1]];
    let den = t[0] * e[1] - t[1] * e[0];
    if den == T::ZERO {
        return None;
    }
    let w = [b[0] - o[0], b[1] - o[1]];
    let lambda = (w[0] * e[1] - w[1] * e[0]) / den;
    let s = (w[0] * t[1] - w[1] * t[0]) / den;
    (lambda > T::ZERO && s >= T::ZERO && s <= T::ONE).then_some(s)
}
