//! Potential tearing points (seed `002_…` Sec. 4.1): the few boundary vertices where a
//! tear may start or go on, because they can concentrate stress.
//!
//! - **Tear tips** (the tips of existing tears; they are inward angles of $2\pi$);
//! - **fingers**: a finger on the boundary is itself a candidate; a finger inside the
//!   sheet gives the boundary vertex nearest to it in the pattern (a tear cannot start
//!   inside the sheet in this model: the seed puts forcing an object through the paper out of
//!   scope, Sec. 7.1);
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
/// (vertices held by fingers), `junctions`, then inward angles beyond `inward_angle`
/// radians over $\pi$; at most `limit`.
pub fn collect<T: Real>(
    out: &mut Vec<Candidate>,
    mesh: &SheetMesh<T>,
    tips: &[u32],
    fingers: &[u32],
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
        if let Some(v) = nearest_boundary(mesh, f) {
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

/// `f` if it is on the boundary, else the boundary vertex nearest to it in the pattern.
#[must_use]
pub fn nearest_boundary<T: Real>(mesh: &SheetMesh<T>, f: u32) -> Option<u32> {
    let p = *mesh.pattern().get(f as usize)?;
    if mesh.is_boundary(f) {
        return Some(f);
    }
    let mut best: Option<(T, u32)> = None;
    for v in 0..mesh.vertex_count() as u32 {
        if !mesh.is_boundary(v) {
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
