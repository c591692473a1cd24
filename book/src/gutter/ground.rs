//! What a heavy strip ([`super::Elastica`]) lies on: a signed distance with its outward
//! normal, and the sharp corners a strip's segments are tested against.

use folio_kernels::math;

/// A point in the XY plane.
pub type Point2 = [f64; 2];

/// What the strip lies on: a signed distance, positive where the strip may be.
pub trait Ground {
    /// The signed distance $\varphi(p)$ from the ground's surface (positive outside) and its
    /// gradient, the unit normal that points out of the ground.
    fn signed_distance(&self, p: Point2) -> (f64, Point2);

    /// Calls `f(d, n)` for each face of the ground that `p` is inside (signed distance
    /// $d < 0$ from it, outward normal $n$), or once with [`Ground::signed_distance`] when
    /// it is inside none. A point in a concave crease is inside two faces: a strip's node
    /// resting there is held by both, where the signed distance alone gives the nearer one
    /// and its normal jumps as the node moves. By default the signed distance alone.
    fn for_each_face(&self, p: Point2, f: &mut dyn FnMut(f64, Point2)) {
        let (d, n) = self.signed_distance(p);
        f(d, n);
    }

    /// Calls `f(q, n)` for each sharp convex corner $q$ of the ground, with $n$ its outward
    /// direction: a strip's nodes may straddle a sharp corner, so its segments are tested
    /// against each corner as well ([`super::Elastica::settle`]). None by default.
    fn for_each_corner(&self, f: &mut dyn FnMut(Point2, Point2)) {
        let _ = f;
    }
}

/// No ground: a strip that hangs free.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Air;

impl Ground for Air {
    fn signed_distance(&self, _p: Point2) -> (f64, Point2) {
        (f64::INFINITY, [0.0, 1.0])
    }
}

/// Everything below a level: a table or a cover board under a block ([`Both`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Level {
    /// The surface's height (page units).
    pub y: f64,
}

impl Ground for Level {
    fn signed_distance(&self, p: Point2) -> (f64, Point2) {
        (p[1] - self.y, [0.0, 1.0])
    }
}

/// Two grounds together: a point is inside when it is inside either. A block with the
/// table or cover under it: a strip's nodes, a segment apart, can pass through a band
/// thinner than a segment (a block of a few pages) but not through what it lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Both<A, B>(pub A, pub B);

impl<A: Ground, B: Ground> Ground for Both<A, B> {
    fn signed_distance(&self, p: Point2) -> (f64, Point2) {
        let (a, b) = (self.0.signed_distance(p), self.1.signed_distance(p));
        if b.0 < a.0 { b } else { a }
    }

    fn for_each_face(&self, p: Point2, f: &mut dyn FnMut(f64, Point2)) {
        let (a, b) = (self.0.signed_distance(p), self.1.signed_distance(p));
        match (a.0 < 0.0, b.0 < 0.0) {
            (false, false) => f(
                if b.0 < a.0 { b.0 } else { a.0 },
                if b.0 < a.0 { b.1 } else { a.1 },
            ),
            (true, false) => self.0.for_each_face(p, f),
            (false, true) => self.1.for_each_face(p, f),
            (true, true) => {
                self.0.for_each_face(p, f);
                self.1.for_each_face(p, f);
            }
        }
    }

    fn for_each_corner(&self, f: &mut dyn FnMut(Point2, Point2)) {
        self.0.for_each_corner(f);
        self.1.for_each_corner(f);
    }
}

/// The band of width `clearance` around a polyline: the points closer to it than the
/// clearance are inside. A block of pages around its midline, with the rounded convex
/// corners of the seed's clearance band ([`folio_geometry::Corner`]) and a rounded far end;
/// its start (the block's spine edge) rounded too, or cut square when `open_start`.
///
/// A block's top page lies on the block cut square: the pages under it end at the binding
/// as it does. On the rounded spine edge of the seed's band instead, a strip rooted at the
/// hinge (where the two blocks' rounded edges touch, their tangent vertical) cannot lean
/// towards its block at all, and rests clamped upright: a card stands (chord angle
/// 85.3°, 87.6°, 88.8°, 89.4° at 200 to 1600 segments, tending to 90° at first order), a
/// novel page arches over in the air (Folio's measurements, 2026-12-07).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band<'a> {
    /// The polyline's vertices, at least two.
    pub line: &'a [Point2],
    /// The band's half width (page units).
    pub clearance: f64,
    /// The band's start is cut square across the first segment (a block's body without
    /// its rounded spine edge).
    pub open_start: bool,
}

impl Band<'_> {
    /// The signed distance from piece `i` of the band (segment `i` with its rounded ends,
    /// or cut square at the start, [`Band::square_start`]) and its outward normal; `None`
    /// for a degenerate first segment cut square.
    fn piece(&self, i: usize, p: Point2) -> Option<(f64, Point2)> {
        let (a, b) = (self.line[i], self.line[i + 1]);
        if i == 0 && self.open_start {
            return self.square_start(a, b, p);
        }
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let r = [p[0] - a[0] - t * d[0], p[1] - a[1] - t * d[1]];
        let dist = math::sqrt(r[0] * r[0] + r[1] * r[1]);
        // On the polyline itself the direction is the segment's left normal.
        let normal = if dist > 0.0 {
            [r[0] / dist, r[1] / dist]
        } else {
            let len = math::sqrt(len2).max(f64::MIN_POSITIVE);
            [-d[1] / len, d[0] / len]
        };
        Some((dist - self.clearance, normal))
    }

    /// The signed distance from the first segment's piece cut square at its start
    /// (`a` to `b`): along $u$ and across $v$ in the segment's frame, behind the cut
    /// ($u < 0$) the distance to the cut's face, inside the nearer of the face and the
    /// side, past the end the rounded end.
    fn square_start(&self, a: Point2, b: Point2, p: Point2) -> Option<(f64, Point2)> {
        let c = self.clearance;
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = math::sqrt(d[0] * d[0] + d[1] * d[1]);
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let e = [d[0] / len, d[1] / len];
        let across = [-e[1], e[0]];
        let r = [p[0] - a[0], p[1] - a[1]];
        let (u, v) = (
            r[0] * e[0] + r[1] * e[1],
            r[0] * across[0] + r[1] * across[1],
        );
        let side = if v < 0.0 { -1.0 } else { 1.0 };
        let combine = |fu: f64, fv: f64| [fu * e[0] + fv * across[0], fu * e[1] + fv * across[1]];
        Some(if u > len {
            let q = [p[0] - b[0], p[1] - b[1]];
            let dist = math::sqrt(q[0] * q[0] + q[1] * q[1]);
            if dist > 0.0 {
                (dist - c, [q[0] / dist, q[1] / dist])
            } else {
                (-c, across)
            }
        } else if u < 0.0 {
            let over = v.abs() - c;
            if over <= 0.0 {
                (-u, [-e[0], -e[1]])
            } else {
                let dist = math::sqrt(u * u + over * over);
                (dist, combine(u / dist, side * over / dist))
            }
        } else if v.abs() - c >= -u {
            (v.abs() - c, combine(0.0, side))
        } else {
            (-u, [-e[0], -e[1]])
        })
    }
}

impl Ground for Band<'_> {
    fn for_each_corner(&self, f: &mut dyn FnMut(Point2, Point2)) {
        if !self.open_start || self.line.len() < 2 {
            return;
        }
        let (a, b) = (self.line[0], self.line[1]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = math::sqrt(d[0] * d[0] + d[1] * d[1]);
        if len.is_nan() || len <= 0.0 {
            return;
        }
        let (e, c) = ([d[0] / len, d[1] / len], self.clearance);
        for side in [1.0, -1.0] {
            let across = [-side * e[1], side * e[0]];
            let q = [a[0] + c * across[0], a[1] + c * across[1]];
            let out = [across[0] - e[0], across[1] - e[1]];
            let norm = math::sqrt(out[0] * out[0] + out[1] * out[1]);
            f(q, [out[0] / norm, out[1] / norm]);
        }
    }

    fn signed_distance(&self, p: Point2) -> (f64, Point2) {
        let mut best = (f64::INFINITY, [0.0, 1.0]);
        for i in 0..self.line.len().saturating_sub(1) {
            if let Some(piece) = self.piece(i, p) {
                if piece.0 < best.0 {
                    best = piece;
                }
            }
        }
        best
    }

    fn for_each_face(&self, p: Point2, f: &mut dyn FnMut(f64, Point2)) {
        let mut inside = false;
        for i in 0..self.line.len().saturating_sub(1) {
            if let Some((d, n)) = self.piece(i, p).filter(|piece| piece.0 < 0.0) {
                inside = true;
                f(d, n);
            }
        }
        if !inside {
            let (d, n) = self.signed_distance(p);
            f(d, n);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Band, Both, Ground, Level};
    use alloc::vec::Vec;

    /// The band of half width 1 around the segment (0, 0)-(10, 0).
    fn slab(open_start: bool) -> Band<'static> {
        const LINE: [[f64; 2]; 2] = [[0.0, 0.0], [10.0, 0.0]];
        Band {
            line: &LINE,
            clearance: 1.0,
            open_start,
        }
    }

    fn close(a: (f64, [f64; 2]), b: (f64, [f64; 2])) -> bool {
        (a.0 - b.0).abs() < 1e-12
            && (a.1[0] - b.1[0]).abs() < 1e-12
            && (a.1[1] - b.1[1]).abs() < 1e-12
    }

    #[test]
    fn a_band_measures_from_its_sides_its_rounded_start_or_its_square_cut() {
        for open in [false, true] {
            let b = slab(open);
            assert!(close(b.signed_distance([5.0, 3.0]), (2.0, [0.0, 1.0])));
            assert!(close(b.signed_distance([5.0, -0.5]), (-0.5, [0.0, -1.0])));
            assert!(close(b.signed_distance([13.0, 4.0]), (4.0, [0.6, 0.8])));
        }
        // Behind the start: the rounded start measures from its centre, the cut from its face.
        assert!(close(
            slab(false).signed_distance([-3.0, 0.0]),
            (2.0, [-1.0, 0.0])
        ));
        assert!(close(
            slab(true).signed_distance([-3.0, 0.5]),
            (3.0, [-1.0, 0.0])
        ));
        assert!(close(
            slab(true).signed_distance([-3.0, 5.0]),
            (5.0, [-0.6, 0.8])
        ));
        // Inside near the cut, the face is nearer than the side.
        assert!(close(
            slab(true).signed_distance([0.25, 0.1]),
            (-0.25, [-1.0, 0.0])
        ));
        // Only the cut has sharp corners.
        let mut corners = Vec::new();
        slab(true).for_each_corner(&mut |q, n| corners.push((q, n)));
        assert_eq!(corners.len(), 2);
        assert!(corners.iter().any(|(q, _)| *q == [0.0, 1.0]));
        slab(false).for_each_corner(&mut |_, _| panic!("no sharp corner"));
    }

    #[test]
    fn a_point_in_a_crease_or_in_two_grounds_has_a_face_in_each() {
        // The band around (0, 0)-(10, 0) on the level y = -0.5: a point inside both.
        let both = Both(slab(false), Level { y: -0.5 });
        let mut faces = Vec::new();
        both.for_each_face([5.0, -0.75], &mut |d, n| faces.push((d, n)));
        assert_eq!(faces.len(), 2, "{faces:?}");
        assert!(
            faces
                .iter()
                .any(|&(d, n)| (d + 0.25).abs() < 1e-12 && n == [0.0, 1.0])
        );
        assert!(
            faces
                .iter()
                .any(|&(d, n)| (d + 0.25).abs() < 1e-12 && n == [0.0, -1.0])
        );
        // Outside both: the nearer one only.
        let mut faces = Vec::new();
        both.for_each_face([5.0, 3.0], &mut |d, n| faces.push((d, n)));
        assert_eq!(faces, [(2.0, [0.0, 1.0])]);
        // In the crease of a band that turns up: inside both pieces, each with its normal.
        const V: [[f64; 2]; 3] = [[-10.0, 0.0], [0.0, 0.0], [10.0, 10.0]];
        let crease = Band {
            line: &V,
            clearance: 1.0,
            open_start: false,
        };
        let mut faces = Vec::new();
        crease.for_each_face([0.0, 0.9], &mut |d, n| faces.push((d, n)));
        assert_eq!(faces.len(), 2, "{faces:?}");
    }
}
