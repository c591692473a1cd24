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
//!
//! **Keeping the triangles well shaped** ([`crate::TipRemesh::Shaped`]; issue 22). A step is
//! often much shorter than the mesh's edges (0.05-0.6 against 1.5 on the default sheet),
//! and the seed's edits then leave slivers: the first step from a notch made a triangle
//! of 0.16°, a tear that starts along the border one of 0.6°. With `shaped`:
//!
//! - after every edit the triangles around the tip are flipped toward better shape
//!   ([`SheetMesh::improve_around`], pairs below [`WELL_SHAPED`]);
//! - a slide whose target lies beyond the far edge of its wedge triangle flips that edge
//!   first, so the fan reaches on; a slide that would leave a fan triangle below half
//!   [`WELL_SHAPED`] and worse than now (a tip pressing toward the border) splits instead;
//! - a split's target within the snap distance of the wedge's far edge, relative to that
//!   edge's length, goes onto it; one within the snap distance of a border edge at the tip
//!   (relative to the wedge triangle's longest edge) is refused, as a tear cannot run along
//!   the border (snapped onto it, its cut would be a border edge); one within the snap
//!   distance of the wedge triangle's other corners becomes that corner. Other edges at the
//!   tip do not snap: that would turn every short step onto a mesh edge;
//! - the tip slides, even where the tear turns, while its straight segment from the lips'
//!   last kink is shorter than half the longest edge of its fan (the caller's `straight`);
//!   the path still records every step, the mesh's crack bends every half edge or more.

use folio_geometry::SheetMesh;
use folio_geometry::sheet::{
    Cut, NONE, SheetError, longest_edge2, next_half_edge, pattern_distance2 as dist2,
    prev_half_edge,
};
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
/// that edge's length. `shaped` keeps the triangles well shaped (module docs).
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
    shaped: bool,
) -> Result<Advance, SheetError> {
    let origin = *mesh
        .pattern()
        .get(p as usize)
        .ok_or(SheetError::OutOfRange { field: "p" })?;
    let target = [origin[0] + t[0] * length, origin[1] + t[1] * length];
    // The seed's slide is one edit, refused whole.
    if straight && !shaped && mesh.move_vertex(p, target).is_ok() {
        return Ok(Advance {
            edit: Edit::Moved,
            tip: Some(p),
            cut: None,
        });
    }
    // A shaped slide may flip edges first, and a split is two edits (the new vertex, then
    // the cut); a later edit may refuse after an earlier one took: put the sheet back as it
    // was.
    mesh.checkpoint();
    let result = if straight && shaped && slide(mesh, p, t, length, target) {
        Ok(Advance {
            edit: Edit::Moved,
            tip: Some(p),
            cut: None,
        })
    } else {
        split(mesh, p, t, length, snap, origin, target, shaped)
    };
    match &result {
        Ok(a) => {
            if let (Some(tip), true) = (a.tip, shaped) {
                mesh.improve_around(tip, T::from_f64(WELL_SHAPED), MAX_QUALITY_FLIPS);
            }
        }
        Err(_) => mesh.rollback(),
    }
    result
}

/// Smallest pattern angle (radians, 10°) below which the triangles around a new or moved
/// tip are flipped toward better shape ([`SheetMesh::improve_around`]).
///
/// Measured on `refining_the_mesh_keeps_the_path` (16 and 32 quads across): the largest
/// distance between the two paths is 1.5 % of their length without these flips, 0.8-0.9 %
/// with a bound of 5° or 10°, and 4.1 % with 15° (11 % with 20°): flipping the fair
/// triangles around a tip too changes the disk's discretization near the crack, on the
/// coarse mesh more than on the fine one.
pub const WELL_SHAPED: f64 = 10.0 * core::f64::consts::PI / 180.0;

/// Most flips per propagation, to open a slide's way or to reshape the tip's triangles.
const MAX_QUALITY_FLIPS: usize = 8;

/// Slides tip `p` to `target` ($p + \text{length}\, t$): when the target lies beyond the far
/// edge of the fan triangle that holds the direction `t`, that edge is flipped first (if it
/// is inside the sheet), so the fan reaches on toward the target instead of squeezing its
/// triangles against the edge. `false` when the slide is refused (the caller splits).
fn slide<T: Real>(mesh: &mut SheetMesh<T>, p: u32, t: [T; 2], length: T, target: [T; 2]) -> bool {
    for _ in 0..MAX_QUALITY_FLIPS {
        if !keeps_shape(mesh, p, target) {
            return false;
        }
        if mesh.move_vertex(p, target).is_ok() {
            return true;
        }
        let Some((h, exit)) = wedge(mesh, p, t) else {
            return false;
        };
        if exit >= length || mesh.flip_edge(next_half_edge(h)).is_err() {
            return false;
        }
    }
    keeps_shape(mesh, p, target) && mesh.move_vertex(p, target).is_ok()
}

/// The far corner $b$ or $c$ of the wedge triangle $(p, b, c)$ of half-edge `h` within
/// `snap` times the triangle's longest edge of `target`, the nearer if both are.
fn near_corner<T: Real>(mesh: &SheetMesh<T>, h: u32, target: [T; 2], snap: T) -> Option<u32> {
    let reach2 = snap * snap * longest_edge_of(mesh, h);
    let (_, b) = mesh.half_edge(h);
    let c = mesh.half_edge(next_half_edge(h)).1;
    let d = |v: u32| dist2(mesh.pattern()[v as usize], target);
    let nearer = if d(c) < d(b) { c } else { b };
    (d(nearer) <= reach2).then_some(nearer)
}

/// The squared length of the longest edge of the triangle of half-edge `h`.
fn longest_edge_of<T: Real>(mesh: &SheetMesh<T>, h: u32) -> T {
    longest_edge2(mesh.triangles()[h as usize / 3].map(|i| mesh.pattern()[i as usize]))
}

/// Whether `target`, in the wedge triangle $(p, b, c)$ of half-edge `h` $= p \to b$, lies
/// within `snap` times that triangle's longest edge of one of its edges at $p$ that is on
/// the sheet's border (measured across the edge, where the target projects onto it).
fn along_border<T: Real>(mesh: &SheetMesh<T>, h: u32, target: [T; 2], snap: T) -> bool {
    let reach2 = snap * snap * longest_edge_of(mesh, h);
    // The edges at p: p → b (h) and c → p (the half-edge before h).
    [h, prev_half_edge(h)].into_iter().any(|e| {
        if mesh.twin(e) != NONE {
            return false;
        }
        let (a, b) = mesh.half_edge(e);
        let (pa, pb) = (mesh.pattern()[a as usize], mesh.pattern()[b as usize]);
        // Squared distance from the target to the edge's line, (2 area / |edge|)^2, where
        // the target projects onto the edge itself.
        let (e, r) = (
            [pb[0] - pa[0], pb[1] - pa[1]],
            [target[0] - pa[0], target[1] - pa[1]],
        );
        let cross = e[0] * r[1] - e[1] * r[0];
        let along = e[0] * r[0] + e[1] * r[1];
        let length2 = dist2(pa, pb);
        length2 > T::ZERO
            && along >= T::ZERO
            && along <= length2
            && cross * cross <= reach2 * length2
    })
}

/// Whether moving vertex `p` to `target` leaves every triangle of its fan with a smallest
/// angle of at least half [`WELL_SHAPED`], or no worse than the fan's worst now (a tip
/// that slides toward an edge it cannot flip, the sheet's border, squeezes the triangles
/// between: it splits onto that edge instead).
fn keeps_shape<T: Real>(mesh: &SheetMesh<T>, p: u32, target: [T; 2]) -> bool {
    let floor = T::from_f64(0.5 * WELL_SHAPED);
    let (mut now, mut moved) = (T::PI, T::PI);
    for h in mesh.fan_iter(p) {
        let tri = mesh.triangles()[h as usize / 3];
        let corners = tri.map(|i| mesh.pattern()[i as usize]);
        let shifted = tri.map(|i| {
            if i == p {
                target
            } else {
                mesh.pattern()[i as usize]
            }
        });
        let (a, b) = (
            SheetMesh::smallest_angle_of(corners),
            SheetMesh::smallest_angle_of(shifted),
        );
        now = if a < now { a } else { now };
        moved = if b < moved { b } else { moved };
    }
    moved >= floor || moved >= now
}

/// The split of [`advance`]: the new tip `q` at `target` (or where the step leaves the wedge
/// triangle), then the cut of `(p, q)`.
#[allow(clippy::too_many_arguments)]
fn split<T: Real>(
    mesh: &mut SheetMesh<T>,
    p: u32,
    t: [T; 2],
    length: T,
    snap: T,
    origin: [T; 2],
    target: [T; 2],
    shaped: bool,
) -> Result<Advance, SheetError> {
    let (h, exit) = wedge(mesh, p, t).ok_or(SheetError::OutsideSheet)?;
    // The far edge b → c of the wedge triangle (p, b, c) is the half-edge after h; a target
    // within the snap distance of it (relative to its length) goes onto it.
    let far = next_half_edge(h);
    let (b, c) = mesh.half_edge(far);
    let (pb, pc) = (mesh.pattern()[b as usize], mesh.pattern()[c as usize]);
    let far_length = folio_kernels::math::sqrt(dist2(pb, pc));
    let inside = if shaped {
        length < exit - snap * far_length
    } else {
        length < exit * (T::ONE - snap)
    };
    let q = if inside {
        if shaped && along_border(mesh, h, target, snap) {
            return Err(SheetError::NotInteriorEdge { a: p, b: p });
        }
        match near_corner(mesh, h, target, snap).filter(|_| shaped) {
            Some(q) => q,
            None => match mesh.insert_in_triangle(h as usize / 3, target) {
                Ok(q) => q,
                Err(_) => mesh.insert_at(target, snap)?,
            },
        }
    } else {
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
