//! Potential tearing points (seed `002_…` Sec. 4.1): the few boundary vertices where a
//! tear may start or go on, because they can concentrate stress.
//!
//! - **Tear tips** (the tips of existing tears; they are inward angles of $2\pi$);
//! - **fingers**: a finger on the boundary is itself a candidate; a finger inside the
//!   sheet gives the boundary vertex nearest to it in the pattern (a tear cannot start
//!   inside the sheet in this model: the seed puts forcing an object through the paper out of
//!   scope, Sec. 7.1). Vertices marked `prescribed` (a finger's pad, for an estimator that
//!   leaves them out) are passed over for the nearest boundary vertex that is not: the
//!   edge of the grip;
//! - **junction points** where flat and curved regions meet the boundary
//!   ([`folio_geometry::sheet::ConeLayer`]);
//! - **inward angles**: boundary vertices whose pattern angle exceeds $\pi$ by more than
//!   [`crate::TearSettings::inward_angle`].
//!
//! Each vertex appears once, with the first of these kinds that applies; the list is cut to
//! [`crate::TearSettings::max_candidates`] in that order.

use alloc::vec::Vec;

use folio_geometry::SheetMesh;
use folio_kernels::Real;

/// Why a vertex is a potential tearing point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    /// The tip of an existing tear ($d_p = D$ in eq. 3).
    Tip,
    /// A finger, or the boundary vertex nearest to one.
    Finger,
    /// A junction of regions on the boundary.
    Junction,
    /// An inward angle of the boundary.
    InwardAngle,
}

/// A potential tearing point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Candidate {
    /// The boundary vertex.
    pub vertex: u32,
    /// Why it is one.
    pub kind: Kind,
}

/// Collects the candidates of `mesh` into `out` (module docs): `tips` of tears, `fingers`
/// (vertices held by fingers; per vertex, `prescribed` marks those to pass over, empty for
/// none), `junctions`, then inward angles beyond `inward_angle` radians over $\pi$; at
/// most `limit`.
#[allow(clippy::too_many_arguments)]
pub fn collect<T: Real>(
    out: &mut Vec<Candidate>,
    mesh: &SheetMesh<T>,
    tips: &[u32],
    fingers: &[u32],
    prescribed: &[bool],
    junctions: &[u32],
    inward_angle: T,
    limit: usize,
) {
    out.clear();
    let add = |out: &mut Vec<Candidate>, vertex: u32, kind: Kind| {
        if out.len() < limit && mesh.is_boundary(vertex) && !out.iter().any(|c| c.vertex == vertex)
        {
            out.push(Candidate { vertex, kind });
        }
    };
    for &v in tips {
        add(out, v, Kind::Tip);
    }
    for &f in fingers {
        if let Some(v) = nearest_boundary(mesh, f, prescribed) {
            add(out, v, Kind::Finger);
        }
    }
    for &v in junctions {
        add(out, v, Kind::Junction);
    }
    let bound = T::PI + inward_angle;
    for v in 0..mesh.vertex_count() as u32 {
        if mesh.is_boundary(v) && mesh.pattern_angle(v) > bound {
            add(out, v, Kind::InwardAngle);
        }
    }
}

/// `f` if it is on the boundary and not `prescribed`, else the boundary vertex nearest to
/// it in the pattern that is not `prescribed` (per vertex; empty for none).
#[must_use]
pub fn nearest_boundary<T: Real>(mesh: &SheetMesh<T>, f: u32, prescribed: &[bool]) -> Option<u32> {
    let p = *mesh.pattern().get(f as usize)?;
    let free = |v: u32| !prescribed.get(v as usize).copied().unwrap_or(false);
    if mesh.is_boundary(f) && free(f) {
        return Some(f);
    }
    let mut best: Option<(T, u32)> = None;
    for v in 0..mesh.vertex_count() as u32 {
        if !mesh.is_boundary(v) || !free(v) {
            continue;
        }
        let q = mesh.pattern()[v as usize];
        let d = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]);
        if best.is_none_or(|(b, _)| d < b) {
            best = Some((d, v));
        }
    }
    best.map(|(_, v)| v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A finger on the border is its own candidate, unless its vertex is held (a pad):
    /// then the nearest free border vertex, the edge of the grip.
    #[test]
    fn a_held_finger_gives_the_edge_of_its_grip() {
        let mesh = SheetMesh::<f64>::rectangle(4.0, 2.0, 4, 2).unwrap();
        // Vertex i + 5 j is at (i, j).
        assert_eq!(nearest_boundary(&mesh, 2, &[]), Some(2));
        let mut held = alloc::vec![false; mesh.vertex_count()];
        held[2] = true;
        held[3] = true;
        assert_eq!(nearest_boundary(&mesh, 2, &held), Some(1));
        assert_eq!(
            nearest_boundary(&mesh, 7, &[]),
            Some(2),
            "inside: the nearest border"
        );
    }
}
