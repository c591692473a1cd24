//! The rounded convex corner between two consecutive [`Wall`]s of a polyline. Each wall's
//! band holds only the points that project onto its span, so where the polyline turns away
//! from the allowed side the two bands leave a wedge between them: at the vertex $v$, the
//! points beyond the end of the wall before (direction $t_0$) and before the start of the
//! wall after (direction $t_1$). The clearance band of the polyline (the points closer than
//! $c$ to it) holds the part of that wedge within $c$ of $v$; a point there is moved out
//! radially:
//! $$r = p - v,\quad r\cdot t_0 > 0,\quad r\cdot t_1 < 0,\quad d = c - \lVert r\rVert > 0
//!   \Rightarrow p \mathrel{+}= d\thinspace \hat r$$
//! (XY only, as every contact of seed `000_…` Sec. 3.4). The start of a polyline has the
//! same gap (points before the first wall's span, [`Corner::start`]): there the wall's
//! normal $n$ takes the place of $t_0$, a quarter disk between $n$ and $-t_1$. For the
//! blocks of a book that is the rounded spine edge of each block: the binding point of the
//! active page lies at distance $c$ from both blocks' binding nodes, where their two caps
//! touch.
//!
//! Without the corners a page node came to rest in such a gap (inside the band, seen by no
//! wall), slipped into a wall's span in the next step, was pushed out by the full depth (a
//! normal velocity of depth over the time step), flew off and fell back, every other frame:
//! books of 100 pages 0.01 thick or 400 pages 0.0075 thick never settled (the figures are in
//! `folio_book::friction`'s docs).

use folio_kernels::contact::ContactPlane;
use folio_kernels::{Real, Vec3Ops, math};

use super::{Bounds, Obstacle, Wall};

/// The rounded corner at the vertex shared by two consecutive walls (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner<T: Real> {
    /// The shared vertex $v$ (Z zero).
    pub vertex: T::Vec3,
    /// Unit direction $t_0$ of the wall that ends at the vertex (Z zero).
    pub before: T::Vec3,
    /// Unit direction $t_1$ of the wall that starts there (Z zero).
    pub after: T::Vec3,
    /// The walls' clearance $c$ (page units).
    pub clearance: T,
}

/// `v` scaled to unit length, `None` when too short or not finite.
fn unit<T: Real>(v: T::Vec3) -> Option<T::Vec3> {
    let len = math::length::<T>(v);
    (len.is_finite() && len > T::LENGTH_FLOOR).then(|| v / len)
}

impl<T: Real> Corner<T> {
    /// The corner where `before` ends and `after` starts (at `after.a`), with `after`'s
    /// clearance; `None` unless the polyline turns away from the allowed side there
    /// (`before`'s normal has a negative component along `after`): at a concave vertex the
    /// two bands overlap and leave no wedge.
    #[must_use]
    pub fn new(before: &Wall<T>, after: &Wall<T>) -> Option<Self> {
        let t0 = unit::<T>(before.along)?;
        let t1 = unit::<T>(after.along)?;
        (before.normal.dot(t1) < T::ZERO).then_some(Self {
            vertex: after.a,
            before: t0,
            after: t1,
            clearance: after.clearance,
        })
    }

    /// The rounded start of the polyline whose first wall is `first` (at `first.a`): the
    /// quarter disk of radius $c$ between the wall's normal and its backward direction
    /// (module docs). `None` for a degenerate wall.
    #[must_use]
    pub fn start(first: &Wall<T>) -> Option<Self> {
        Some(Self {
            vertex: first.a,
            before: first.normal,
            after: unit::<T>(first.along)?,
            clearance: first.clearance,
        })
    }

    /// $p - v$ in the XY plane.
    #[inline]
    fn relative(&self, p: T::Vec3) -> T::Vec3 {
        T::Vec3::new(p.x() - self.vertex.x(), p.y() - self.vertex.y(), T::ZERO)
    }

    /// How far `p` lies inside the corner's band (positive) when it is in the wedge; `None`
    /// when it is not or is clear.
    #[inline]
    #[must_use]
    pub fn penetration(&self, p: T::Vec3) -> Option<T> {
        let r = self.relative(p);
        if !(r.dot(self.before) > T::ZERO && r.dot(self.after) < T::ZERO) {
            return None;
        }
        let depth = self.clearance - math::length::<T>(r);
        (depth > T::ZERO).then_some(depth)
    }

    /// The outward unit normal at `p`: $\hat r$, or the wedge's bisector
    /// $(t_0 - t_1)/\lVert t_0 - t_1\rVert$ for a point at the vertex.
    #[inline]
    #[must_use]
    pub fn normal_at(&self, p: T::Vec3) -> T::Vec3 {
        unit::<T>(self.relative(p))
            .or_else(|| unit::<T>(self.before - self.after))
            .unwrap_or(T::Vec3::new(T::ZERO, T::ONE, T::ZERO))
    }

    /// `true` when [`Corner::penetration`] is `None` for every point of `bounds`: the box's
    /// nearest point to the vertex is farther than $c$ (by a relative margin of $2^{-10}$
    /// that covers rounding).
    #[inline]
    #[must_use]
    pub fn misses(&self, bounds: &Bounds<T>) -> bool {
        let clamp = |v: T, lo: T, hi: T| {
            if v < lo {
                lo
            } else if v > hi {
                hi
            } else {
                v
            }
        };
        let (x, y) = (self.vertex.x(), self.vertex.y());
        let dx = clamp(x, bounds.min[0], bounds.max[0]) - x;
        let dy = clamp(y, bounds.min[1], bounds.max[1]) - y;
        let reach = self.clearance * (T::ONE + T::from_f64(1.0 / 1024.0));
        dx * dx + dy * dy > reach * reach
    }
}

impl<T: Real> Obstacle<T> for Corner<T> {
    /// Radially out of the corner's band.
    #[inline]
    fn resolve(&self, p: &mut T::Vec3) -> Option<T> {
        let depth = self.penetration(*p)?;
        *p += self.normal_at(*p) * depth;
        Some(depth)
    }
    /// The tangent plane of the rounded corner under `p`.
    fn contact_plane(&self, p: T::Vec3, stiffness: T) -> ContactPlane<T> {
        ContactPlane {
            point: self.vertex,
            normal: self.normal_at(p),
            clearance: self.clearance,
            stiffness,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Corner;
    use crate::{Bounds, Obstacle, Wall};
    use folio_kernels::splitmix::SplitMix64;
    use folio_kernels::{Real, Vec3Ops, math};

    fn v<T: Real>(x: f64, y: f64) -> T::Vec3 {
        T::Vec3::new(T::from_f64(x), T::from_f64(y), T::ZERO)
    }

    /// A polyline (0,0) -> (1,0) -> (2,-1), allowed side up, clearance 0.5: a convex turn.
    fn kink<T: Real>() -> (Wall<T>, Wall<T>) {
        let up = v::<T>(0.0, 1.0);
        let c = T::from_f64(0.5);
        let before = Wall::new(v::<T>(0.0, 0.0), v::<T>(1.0, 0.0), up, c).unwrap();
        let after = Wall::new(v::<T>(1.0, 0.0), v::<T>(2.0, -1.0), up, c).unwrap();
        (before, after)
    }

    /// A point in the wedge that neither wall sees is pushed radially onto the rounded
    /// band, and its contact plane is the tangent there.
    fn the_wedge_is_covered<T: Real>() {
        let (before, after) = kink::<T>();
        let corner = Corner::new(&before, &after).expect("a convex turn");
        // Straight up-right of the vertex, 0.3 away: beyond `before`, before `after`.
        let mut p = v::<T>(1.0 + 0.3 * 0.5, 0.3 * 0.866);
        assert_eq!((before.penetration(p), after.penetration(p)), (None, None));
        let depth = corner.resolve(&mut p).expect("inside the corner's band");
        let tol = T::from_f64(1e-5);
        assert!(math::abs(depth - T::from_f64(0.2)) < tol);
        let r = p - v::<T>(1.0, 0.0);
        assert!(math::abs(r.dot(r) - T::from_f64(0.25)) < tol);
        assert!(corner.penetration(p).is_none_or(|d| d < tol));
        let plane = corner.contact_plane(p, T::ONE);
        assert!(math::abs(plane.gap(p)) < tol);
        // Outside the wedge (above the first wall's span) the corner leaves the point alone.
        assert_eq!(corner.penetration(v::<T>(0.9, 0.2)), None);
        // A concave turn has no corner.
        assert_eq!(Corner::new(&after, &before), None);
        // The start cap: before the first wall's span, on its allowed side.
        let cap = Corner::start(&before).unwrap();
        let mut q = v::<T>(-0.2, 0.2);
        assert_eq!(before.penetration(q), None);
        let depth = cap.resolve(&mut q).expect("inside the cap");
        assert!(math::abs(depth - T::from_f64(0.5 - 0.08_f64.sqrt())) < tol);
        assert!(math::abs(q.dot(q) - T::from_f64(0.25)) < tol);
        // Below the wall's line (the material side) the cap does not reach.
        assert_eq!(cap.penetration(v::<T>(-0.2, -0.2)), None);
    }

    #[test]
    fn the_wedge_is_covered_f64() {
        the_wedge_is_covered::<f64>();
    }

    #[test]
    fn the_wedge_is_covered_f32() {
        the_wedge_is_covered::<f32>();
    }

    /// Random boxes: a box the corner misses holds no point that penetrates it.
    #[test]
    fn a_missed_box_holds_no_contact() {
        let (before, after) = kink::<f64>();
        let corner = Corner::new(&before, &after).unwrap();
        let mut r = SplitMix64::new(23);
        let (mut missed, mut kept) = (0, 0);
        for _ in 0..4000 {
            let p = v::<f64>(r.uniform(0.0, 2.0), r.uniform(-1.0, 1.0));
            let mut b = Bounds::at(p);
            b.include(p + v::<f64>(r.uniform(0.0, 0.6), r.uniform(0.0, 0.6)));
            if !corner.misses(&b) {
                kept += 1;
                continue;
            }
            missed += 1;
            for i in 0..=10 {
                for j in 0..=10 {
                    let (fi, fj) = (f64::from(i) / 10.0, f64::from(j) / 10.0);
                    let q = v::<f64>(
                        b.min[0] + (b.max[0] - b.min[0]) * fi,
                        b.min[1] + (b.max[1] - b.min[1]) * fj,
                    );
                    assert_eq!(corner.penetration(q), None, "{q:?} in {b:?}");
                }
            }
        }
        assert!(missed > 500 && kept > 500, "{missed} missed, {kept} kept");
    }
}
