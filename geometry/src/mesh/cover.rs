//! A hard-cover board's mesh (seed `000_…` Sec. 3.1 and 3.5): a box under the board's top
//! edge, extruded along Z.

use super::error::{MeshError, check_non_negative, check_positive, check_vector};
use super::trimesh::{Surface, TriMesh};
use super::vector::{add, dot, lift, scale, sub, unit};

/// Appends a hard-cover board (`Cover`): a box under the segment `from -> to` (XY, the
/// board's top edge), `thickness` deep on the side `down` points to, spanning
/// $z \in [-o, h + o]$ ($o$ = `overhang`, $h$ = `height`).
///
/// With $u = (\text{to} - \text{from}) / \lVert\cdot\rVert$ and $d$ the unit part of `down`
/// perpendicular to $u$ (so the box is rectangular even for a slanted `down`), the profile is
/// `from`, `to`, `to` $+ t d$, `from` $+ t d$. Six faces, each with its own four vertices
/// (UVs $(0,0), (1,0), (1,1), (0,1)$ at its corners) and its outward normal: top $-d$,
/// bottom $d$, ends $\mp u$, caps ∓Z: 24 vertices and 12 triangles.
///
/// Fallbacks: `from == to` takes $u = +X$ (a box of zero length, finite); a `down` that is
/// zero or parallel to the segment takes $d = (u_y, -u_x)$, the clockwise perpendicular
/// (−Y for $u = +X$).
///
/// # Errors
/// [`MeshError::OutOfRange`] for a non-finite or too large `from` / `to`, a non-finite
/// `down` or a negative `overhang`; [`MeshError::NonPositive`] for `thickness` or `height`
/// not positive; [`MeshError::TooManyVertices`] if `out` would exceed `u32` indices. On error
/// `out` is unchanged.
pub fn cover_mesh(
    out: &mut TriMesh,
    from: [f64; 2],
    to: [f64; 2],
    down: [f64; 2],
    thickness: f64,
    height: f64,
    overhang: f64,
) -> Result<(), MeshError> {
    check_vector("from", from, true)?;
    check_vector("to", to, true)?;
    check_vector("down", down, false)?;
    check_positive("thickness", thickness)?;
    check_positive("height", height)?;
    check_non_negative("overhang", overhang)?;
    out.reserve_for(24, 12)?;

    let u = unit(sub(to, from)).unwrap_or([1.0, 0.0]);
    let d = unit(sub(down, scale(u, dot(down, u)))).unwrap_or([u[1], -u[0]]);
    let depth = scale(d, thickness);
    // Profile edges: top (from -> to), far end, bottom, near end; each with its outward normal.
    let profile = [from, to, add(to, depth), add(from, depth)];
    let outward = [scale(d, -1.0), u, d, scale(u, -1.0)];
    let (z0, z1) = (-overhang, height + overhang);
    for (k, normal) in outward.into_iter().enumerate() {
        let (a, b) = (profile[k], profile[(k + 1) % 4]);
        let face = [lift(a, z0), lift(b, z0), lift(b, z1), lift(a, z1)];
        out.push_planar_quad(face, lift(normal, 0.0), Surface::Cover);
    }
    for (z, normal_z) in [(z0, -1.0), (z1, 1.0)] {
        let face = profile.map(|p| lift(p, z));
        out.push_planar_quad(face, [0.0, 0.0, normal_z], Surface::Cover);
    }
    Ok(())
}
