//! The generalized-cone layer of the sheet (seed `002_…` Sec. 3 and 5, Fig. 3, after its
//! crumpling model [SRH+15]): a deformed sheet of paper is a union of flat regions and
//! curved regions that are generalized cones (ruled, developable). This module estimates
//! that layer from the coarse mesh and remeshes the mesh toward it.
//!
//! **Curvature per triangle.** With $\theta_e$ the signed dihedral angle of interior edge $e$
//! (positive when the surface turns toward the normal of the counter-clockwise pattern
//! orientation, [`dihedral`]; zero on the boundary), $\ell_e$ its pattern length and
//! $\hat n_e$ the unit pattern normal of the edge, the triangle's pattern shape operator is
//! $$S_t = \frac{1}{A_t} \sum_{e \in t} \frac{\theta_e\thinspace\ell_e}{2}\thinspace \hat n_e \hat n_e^\top$$
//! (the edge-based discrete shape operator, not given in the seed; a 2x2 symmetric matrix,
//! units 1/length, $A_t$ the pattern area). It is exact on triangles whose edges all lie
//! inside the sheet when the mesh follows the rulings: on a cylinder meshed by quads with
//! edges along its rulings every quad is planar and $S_t = \kappa\thinspace b b^\top$ exactly ($b$
//! across the rulings). On a coarse mesh it is then averaged, weighted by pattern area, over
//! the triangle and its edge neighbours, using only *complete* triangles (no edge on the
//! boundary: a boundary edge has no dihedral angle, so such a triangle misses the bending
//! across it and would read flat along a bent rim); a triangle with no complete one among
//! them averages the complete triangles two steps away, and failing that all of its
//! neighbours. The eigenvalue of largest magnitude $\kappa_1$ of the average is the bending;
//! the eigenvector of the other one is the **ruling** direction (along which a developable
//! surface is straight).
//!
//! **Regions.** A triangle is [`Region::Flat`] when $|\kappa_1|$ is below
//! [`ConeLayerSettings::flat_curvature`], otherwise curved with the sign of $\kappa_1$
//! ([`Region::Convex`], [`Region::Concave`]): two cones bent in opposite directions, as in the
//! twist of seed Fig. 13, are different regions.
//!
//! **Junction points.** Region borders run along mesh edges, so they meet the boundary at
//! vertices: a boundary vertex whose fan holds more than one region is a junction point
//! (seed Sec. 4.1). Because the remesh turns edges toward the rulings, the borders between a
//! cone and a flat region follow rulings, as the seed's layer has them.
//!
//! **Remesh** ([`ConeLayer::remesh`]): passes over the interior edges between two curved
//! triangles, until a pass flips nothing (at most eight); an edge is flipped when the other
//! diagonal of its quad follows the mean ruling of the two triangles better by
//! [`ConeLayerSettings::flip_margin`] in $|\cos|$ (hysteresis, so that the mesh does not flip back
//! and forth between frames), and the two new triangles take that mean ruling. A flip that
//! would make a sliver or a clockwise triangle is skipped. The vertex count never changes,
//! so the mesh stays as coarse as it was (seed Sec. 7.6: about a hundred triangles).

use alloc::vec::Vec;

use folio_kernels::{Real, Vec3Ops, math};

use super::mesh::{NONE, SheetMesh, next, positive};
use super::scratch::room;

/// Weight of a triangle's own estimate in the averaging, relative to a neighbour of the same
/// area (1: a plain area-weighted mean; measured on a cylinder at an angle to the grid, the
/// per-triangle spread of the curvature is ±21 % with 1 and ±26 % with 3).
const SELF_WEIGHT: f64 = 1.0;

/// Most passes of [`ConeLayer::remesh`] (each flips every edge that qualifies; the passes
/// stop at the first that flips nothing).
const MAX_REMESH_PASSES: usize = 8;

/// The region of a triangle (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// No bending above the threshold.
    Flat,
    /// A cone bending toward the sheet's normal ($\kappa_1 > 0$).
    Convex,
    /// A cone bending away from the sheet's normal ($\kappa_1 < 0$).
    Concave,
}

/// Thresholds of the cone layer.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeLayerSettings<T: Real> {
    /// Curvature magnitude (1 / sheet unit) below which a triangle is flat.
    pub flat_curvature: T,
    /// Improvement in $|\cos|$ between the edge and the ruling that a flip needs, in
    /// $[0, 1]$.
    pub flip_margin: T,
}

impl<T: Real> Default for ConeLayerSettings<T> {
    /// Flat below a curvature of 0.05 (a radius of 20 sheet units), flips for an
    /// improvement of 0.2 in $|\cos|$.
    fn default() -> Self {
        Self {
            flat_curvature: T::from_f64(0.05),
            flip_margin: T::from_f64(0.2),
        }
    }
}

/// The estimated layer of a sheet: one region, curvature and ruling per triangle, and the
/// junction points (module docs).
#[derive(Clone, Debug, Default)]
pub struct ConeLayer<T: Real> {
    /// Region of each triangle.
    pub regions: Vec<Region>,
    /// $\kappa_1$ of each triangle (1 / sheet unit).
    pub curvature: Vec<T>,
    /// Unit ruling direction of each triangle in the pattern (meaningless for flat ones).
    pub rulings: Vec<[T; 2]>,
    /// Boundary vertices where regions meet.
    pub junctions: Vec<u32>,
    shape: Vec<[T; 3]>,
    /// [`SheetMesh::topology_version`] of the mesh at the last update.
    topology: Option<u64>,
    /// The remesh's working copy of the rulings (the flipped pairs take their mean ruling).
    remesh_rulings: Vec<[T; 2]>,
    /// The remesh's flags: triangle `t` was curved at the last update.
    remesh_curved: Vec<bool>,
}

impl<T: Real> ConeLayer<T> {
    /// Makes room for a mesh of `vertices` vertices and `triangles` triangles in all: an
    /// update or remesh within it allocates nothing.
    pub fn reserve(&mut self, vertices: usize, triangles: usize) {
        room(&mut self.regions, triangles);
        room(&mut self.curvature, triangles);
        room(&mut self.rulings, triangles);
        room(&mut self.shape, triangles);
        room(&mut self.remesh_rulings, triangles);
        room(&mut self.remesh_curved, triangles);
        room(&mut self.junctions, vertices);
    }

    /// The layer of `mesh` as it is deformed now.
    #[must_use]
    pub fn of(mesh: &SheetMesh<T>, settings: &ConeLayerSettings<T>) -> Self {
        let mut layer = Self::default();
        layer.update(mesh, settings);
        layer
    }

    /// Re-estimates the layer of `mesh` into the existing buffers (no allocation once they
    /// have grown to the mesh's size).
    pub fn update(&mut self, mesh: &SheetMesh<T>, settings: &ConeLayerSettings<T>) {
        let n = mesh.triangle_count();
        self.topology = Some(mesh.topology_version());
        self.shape.clear();
        self.shape.extend((0..n).map(|t| shape_operator(mesh, t)));
        // One pass of area-weighted averaging (module docs, "Curvature per triangle"): over
        // the complete triangles among t and its edge neighbours; for a triangle with none,
        // over the complete ones two steps away; failing that over all of t's neighbours.
        self.curvature.clear();
        self.rulings.clear();
        self.regions.clear();
        let self_weight = T::from_f64(SELF_WEIGHT);
        for t in 0..n {
            let mut sum = [T::ZERO; 3];
            let mut weight = T::ZERO;
            let mut add = |s: usize, c: T| {
                let a = mesh.pattern_area(s) * c;
                for (acc, x) in sum.iter_mut().zip(self.shape[s]) {
                    *acc += x * a;
                }
                weight += a;
            };
            let mut any = false;
            if complete(mesh, t) {
                add(t, self_weight);
                any = true;
            }
            for s in neighbours(mesh, t).into_iter().flatten() {
                if complete(mesh, s) {
                    add(s, T::ONE);
                    any = true;
                }
            }
            if !any {
                // At most 3 neighbours with 2 further neighbours each.
                let mut ring = [usize::MAX; 6];
                let mut len = 0;
                for s in neighbours(mesh, t).into_iter().flatten() {
                    for r in neighbours(mesh, s).into_iter().flatten() {
                        if r != t && complete(mesh, r) && !ring[..len].contains(&r) && len < 6 {
                            ring[len] = r;
                            len += 1;
                        }
                    }
                }
                for &r in &ring[..len] {
                    add(r, T::ONE);
                    any = true;
                }
            }
            if !any {
                add(t, self_weight);
                for s in neighbours(mesh, t).into_iter().flatten() {
                    add(s, T::ONE);
                }
            }
            let s = sum.map(|x| x / weight);
            let (kappa, ruling) = principal(s);
            self.curvature.push(kappa);
            self.rulings.push(ruling);
            self.regions
                .push(if math::abs(kappa) < settings.flat_curvature {
                    Region::Flat
                } else if kappa > T::ZERO {
                    Region::Convex
                } else {
                    Region::Concave
                });
        }
        self.junctions.clear();
        // Room for every vertex as a junction, so that more junctions in a later frame do not
        // grow the buffer.
        self.junctions.reserve(mesh.vertex_count());
        for v in 0..mesh.vertex_count() as u32 {
            if !mesh.is_boundary(v) {
                continue;
            }
            let mut fan = mesh.fan_iter(v).map(|h| self.regions[h as usize / 3]);
            if let Some(first) = fan.next() {
                if fan.any(|r| r != first) {
                    self.junctions.push(v);
                }
            }
        }
    }

    /// Edge flips toward the rulings (module docs); returns the number of flips. Does
    /// nothing when `mesh` is not the mesh of the last [`ConeLayer::update`] (its topology
    /// changed since). Re-estimates nothing itself: call [`ConeLayer::update`] after it when
    /// flips happened.
    ///
    /// Works in buffers of the layer: no allocation once they have grown to the mesh's size,
    /// except in the flips themselves (a topology edit). A flip whose new triangles
    /// $(c, a, d)$, $(d, b, c)$ would be clockwise or slivers in the pattern is skipped
    /// before the mesh is asked (the mesh would refuse it the same way, after copying itself).
    pub fn remesh(&mut self, mesh: &mut SheetMesh<T>, settings: &ConeLayerSettings<T>) -> usize {
        let n = mesh.triangle_count();
        if self.topology != Some(mesh.topology_version()) || self.rulings.len() != n {
            return 0;
        }
        let rulings = &mut self.remesh_rulings;
        rulings.clear();
        rulings.extend_from_slice(&self.rulings);
        let curved = &mut self.remesh_curved;
        curved.clear();
        curved.extend(self.regions.iter().map(|&r| r != Region::Flat));
        let mut flips = 0;
        for _ in 0..MAX_REMESH_PASSES {
            let mut pass = 0;
            for h in 0..3 * n as u32 {
                let g = mesh.twin(h);
                if g == NONE || g < h {
                    continue;
                }
                let (t, t2) = (h as usize / 3, g as usize / 3);
                if !curved[t] || !curved[t2] {
                    continue;
                }
                let (r1, r2) = (rulings[t], rulings[t2]);
                let s = if r1[0] * r2[0] + r1[1] * r2[1] < T::ZERO {
                    -T::ONE
                } else {
                    T::ONE
                };
                let ruling = [r1[0] + s * r2[0], r1[1] + s * r2[1]];
                let (a, b) = mesh.half_edge(h);
                let c = mesh.half_edge(next(h)).1;
                let d = mesh.half_edge(next(g)).1;
                let p = |i: u32| mesh.pattern()[i as usize];
                let now = abs_cos(ruling, p(a), p(b));
                let flipped = abs_cos(ruling, p(c), p(d));
                if flipped > now + settings.flip_margin
                    && mesh.triangle_ok([p(c), p(a), p(d)])
                    && mesh.triangle_ok([p(d), p(b), p(c)])
                    && mesh.flip_edge(h).is_ok()
                {
                    // The two new triangles (same indices) get the mean ruling of the pair
                    // (|r1 + s r2| >= 1 since the two are unit and s r2 . r1 >= 0).
                    let len = math::sqrt(ruling[0] * ruling[0] + ruling[1] * ruling[1]);
                    let r = [ruling[0] / len, ruling[1] / len];
                    rulings[t] = r;
                    rulings[t2] = r;
                    pass += 1;
                }
            }
            flips += pass;
            if pass == 0 {
                break;
            }
        }
        flips
    }
}

/// The triangles across the three edges of triangle `t` (`None` across the boundary).
fn neighbours<T: Real>(mesh: &SheetMesh<T>, t: usize) -> [Option<usize>; 3] {
    core::array::from_fn(|k| {
        let g = mesh.twin((3 * t + k) as u32);
        (g != NONE).then_some(g as usize / 3)
    })
}

/// `true` when all three edges of triangle `t` are inside the sheet, so that its shape
/// operator sees the bending across each of them.
fn complete<T: Real>(mesh: &SheetMesh<T>, t: usize) -> bool {
    (0..3).all(|k| mesh.twin((3 * t + k) as u32) != NONE)
}

/// $|\cos|$ of the angle between `ruling` and the pattern segment `a → b`.
fn abs_cos<T: Real>(ruling: [T; 2], a: [T; 2], b: [T; 2]) -> T {
    let e = [b[0] - a[0], b[1] - a[1]];
    let den =
        math::sqrt((e[0] * e[0] + e[1] * e[1]) * (ruling[0] * ruling[0] + ruling[1] * ruling[1]));
    if den > T::ZERO {
        math::abs(e[0] * ruling[0] + e[1] * ruling[1]) / den
    } else {
        T::ZERO
    }
}

/// The unit 3D normal of triangle `t` (zero for a degenerate one).
fn normal<T: Real>(mesh: &SheetMesh<T>, t: usize) -> T::Vec3 {
    let [a, b, c] = mesh.triangles()[t].map(|i| mesh.positions()[i as usize]);
    let n = (b - a).cross(c - a);
    let len = math::length::<T>(n);
    if len > T::ZERO {
        n * (T::ONE / len)
    } else {
        T::Vec3::ZERO
    }
}

/// The signed dihedral angle at the edge of half-edge `h` (radians, in $(-\pi, \pi]$; zero on
/// the boundary): positive when the two triangles turn toward their normals (the normal of
/// the counter-clockwise pattern orientation), as $\theta_e$ of the module docs. The same for
/// `h` and its twin. Zero for a half-edge the mesh does not have.
#[must_use]
pub fn dihedral<T: Real>(mesh: &SheetMesh<T>, h: u32) -> T {
    if h as usize >= 3 * mesh.triangle_count() {
        return T::ZERO;
    }
    let g = mesh.twin(h);
    if g == NONE {
        return T::ZERO;
    }
    let (n1, n2) = (normal(mesh, h as usize / 3), normal(mesh, g as usize / 3));
    let (a, b) = mesh.half_edge(h);
    let e = mesh.positions()[b as usize] - mesh.positions()[a as usize];
    let len = math::length::<T>(e);
    if !positive(len) {
        return T::ZERO;
    }
    // e runs along the edge as triangle 1 (counter-clockwise) runs it, so n1 x e points into
    // triangle 1. A neighbour turned toward n1 by φ has its normal tilted toward triangle 1
    // by φ: n2 = cos φ n1 + sin φ (n1 x e)/|e|, and (n2 x n1) . e / |e| = sin φ.
    math::atan2(n2.cross(n1).dot(e) / len, n1.dot(n2))
}

/// $S_t$ of the module docs as `[s_uu, s_uv, s_vv]`.
fn shape_operator<T: Real>(mesh: &SheetMesh<T>, t: usize) -> [T; 3] {
    let area = mesh.pattern_area(t);
    let mut s = [T::ZERO; 3];
    if !positive(area) {
        return s;
    }
    for k in 0..3 {
        let h = (3 * t + k) as u32;
        let theta = dihedral(mesh, h);
        let (a, b) = mesh.half_edge(h);
        let (pa, pb) = (mesh.pattern()[a as usize], mesh.pattern()[b as usize]);
        let e = [pb[0] - pa[0], pb[1] - pa[1]];
        let len = math::sqrt(e[0] * e[0] + e[1] * e[1]);
        if !positive(len) {
            continue;
        }
        let n = [e[1] / len, -e[0] / len];
        let w = theta * len * T::HALF / area;
        s[0] += w * n[0] * n[0];
        s[1] += w * n[0] * n[1];
        s[2] += w * n[1] * n[1];
    }
    s
}

/// The eigenvalue of largest magnitude of the symmetric 2x2 `[a, b, c]` (= `[[a, b], [b,
/// c]]`) and the unit eigenvector of the other eigenvalue (the ruling).
fn principal<T: Real>([a, b, c]: [T; 3]) -> (T, [T; 2]) {
    let mean = (a + c) * T::HALF;
    let half = (a - c) * T::HALF;
    let r = math::sqrt(half * half + b * b);
    let (l1, l2) = (mean + r, mean - r);
    let (big, small) = if math::abs(l1) >= math::abs(l2) {
        (l1, l2)
    } else {
        (l2, l1)
    };
    // Eigenvector of `small`: (b, small - a) or (small - c, b), whichever is longer.
    let v1 = [b, small - a];
    let v2 = [small - c, b];
    let n1 = v1[0] * v1[0] + v1[1] * v1[1];
    let n2 = v2[0] * v2[0] + v2[1] * v2[1];
    let (v, n) = if n1 >= n2 { (v1, n1) } else { (v2, n2) };
    if n > T::ZERO {
        let len = math::sqrt(n);
        (big, [v[0] / len, v[1] / len])
    } else {
        (big, [T::ONE, T::ZERO])
    }
}
