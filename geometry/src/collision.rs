//! 2D collision projection (seed `000_…` Sec. 3.4). The page blocks are constant along Z, so
//! contacts are resolved in the XY plane only: a point closer than a clearance $c$ to a
//! segment $(a, b)$, on the segment's span, is translated along the segment normal $n$ (the
//! side the point belongs on) until its signed distance is $c$:
//! $$s = \frac{(p-a)\cdot(b-a)}{\lVert b-a\rVert^2} \in [0, 1],\quad d = (p - a)\cdot n,\quad
//!   d < c \Rightarrow p \mathrel{+}= (c - d)\thinspace n.$$
//! The allowed side of every contact is known structurally (the active page lies above the
//! blocks, the blocks above the cover, the cover above the table), which is what the seed
//! reads from the initial configuration; it stays defined when a point is exactly on a
//! segment or has passed through it.

use folio_kernels::contact::ContactPlane;
use folio_kernels::{Real, Vec3Ops, math};

mod bounds;
mod corner;
pub use bounds::Bounds;
pub use corner::Corner;

/// A segment in the XY plane with the unit normal of its allowed side and a clearance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall<T: Real> {
    /// Start (Z ignored).
    pub a: T::Vec3,
    /// Direction `b - a` (Z zero).
    pub along: T::Vec3,
    /// `1 / |b - a|^2`.
    pub inverse_length_sq: T,
    /// Unit normal towards the allowed side (Z zero).
    pub normal: T::Vec3,
    /// Required distance from the segment on the allowed side (page units).
    pub clearance: T,
    /// The span continues past `b` (the last segment of a block: the seed assumes the active
    /// page lies over the block, so a page edge reaching past the fore-edge still rests on it).
    pub open_end: bool,
}

impl<T: Real> Wall<T> {
    /// The segment `a -> b` (XY) whose allowed side is the one `toward` points into (any
    /// vector with a positive component along that side's normal), with clearance `clearance`.
    /// `None` for a degenerate segment or a `toward` parallel to it.
    #[must_use]
    pub fn new(a: T::Vec3, b: T::Vec3, toward: T::Vec3, clearance: T) -> Option<Self> {
        let flat = |v: T::Vec3| T::Vec3::new(v.x(), v.y(), T::ZERO);
        let along = flat(b - a);
        let len_sq = along.dot(along);
        let usable = len_sq > T::LENGTH_FLOOR * T::LENGTH_FLOOR && len_sq.is_finite();
        if !usable {
            return None;
        }
        let len = math::sqrt(len_sq);
        let mut normal = T::Vec3::new(-along.y() / len, along.x() / len, T::ZERO);
        let side = normal.dot(flat(toward));
        if side == T::ZERO || !side.is_finite() {
            return None;
        }
        if side < T::ZERO {
            normal = -normal;
        }
        Some(Self {
            a: flat(a),
            along,
            inverse_length_sq: T::ONE / len_sq,
            normal,
            clearance,
            open_end: false,
        })
    }

    /// How far `p` lies inside the clearance band (positive) when it projects onto the
    /// segment's span; `None` when it does not or is clear.
    #[inline]
    #[must_use]
    pub fn penetration(&self, p: T::Vec3) -> Option<T> {
        let s = self.span(p);
        if !(s >= T::ZERO && (s <= T::ONE || self.open_end)) {
            return None;
        }
        let depth = self.depth(p);
        (depth > T::ZERO).then_some(depth)
    }

    /// $p - a$ in the XY plane.
    #[inline]
    #[must_use]
    fn relative(&self, p: T::Vec3) -> T::Vec3 {
        T::Vec3::new(p.x() - self.a.x(), p.y() - self.a.y(), T::ZERO)
    }

    /// The span parameter of `p`, $s = (p-a)\cdot(b-a) / \lVert b-a\rVert^2$ (0 at `a`,
    /// 1 at `b`).
    #[inline]
    #[must_use]
    fn span(&self, p: T::Vec3) -> T {
        self.relative(p).dot(self.along) * self.inverse_length_sq
    }

    /// The depth of `p` in the clearance band, $c - (p-a)\cdot n$ (negative when clear).
    #[inline]
    #[must_use]
    fn depth(&self, p: T::Vec3) -> T {
        self.clearance - self.relative(p).dot(self.normal)
    }
}

/// Something a point may not enter: it pushes the point out and, for the steps after, offers
/// the plane that holds it there (a [`ContactPlane`] spring).
pub trait Obstacle<T: Real> {
    /// Moves `p` out; returns the depth it had (`None` when it was clear).
    fn resolve(&self, p: &mut T::Vec3) -> Option<T>;
    /// The supporting plane (constant along Z) at the clearance under the point `p` just
    /// moved out ([`Obstacle::resolve`]), with spring stiffness `stiffness`.
    fn contact_plane(&self, p: T::Vec3, stiffness: T) -> ContactPlane<T>;
}

impl<T: Real> Obstacle<T> for Wall<T> {
    /// Along the normal, out of the clearance band.
    #[inline]
    fn resolve(&self, p: &mut T::Vec3) -> Option<T> {
        let depth = self.penetration(*p)?;
        *p += self.normal * depth;
        Some(depth)
    }
    fn contact_plane(&self, _p: T::Vec3, stiffness: T) -> ContactPlane<T> {
        ContactPlane {
            point: self.a,
            normal: self.normal,
            clearance: self.clearance,
            stiffness,
        }
    }
}

/// A horizontal floor $y \ge$ `level` (the table, seed Sec. 3.4 "cover and table").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floor<T> {
    /// Lowest allowed Y (page units).
    pub level: T,
}

impl<T: Real> Obstacle<T> for Floor<T> {
    /// Straight up to the floor.
    #[inline]
    fn resolve(&self, p: &mut T::Vec3) -> Option<T> {
        let depth = self.level - p.y();
        (depth > T::ZERO).then(|| {
            *p = T::Vec3::new(p.x(), self.level, p.z());
            depth
        })
    }
    fn contact_plane(&self, _p: T::Vec3, stiffness: T) -> ContactPlane<T> {
        ContactPlane {
            point: T::Vec3::new(T::ZERO, self.level, T::ZERO),
            normal: T::Vec3::new(T::ZERO, T::ONE, T::ZERO),
            clearance: T::ZERO,
            stiffness,
        }
    }
}

/// What one collision pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Contacts<T> {
    /// Point-obstacle tests made (the work of collision handling).
    pub tested: usize,
    /// Box-wall tests of the broad phase ([`Wall::misses`]), each of which may spare the
    /// point tests of a group of points.
    pub bounds_tested: usize,
    /// Points moved.
    pub resolved: usize,
    /// Largest depth resolved (page units).
    pub max_depth: T,
}

impl<T: Real> Contacts<T> {
    /// Records one test, which resolved a contact of depth `depth` if `Some`.
    #[inline]
    pub fn record(&mut self, depth: Option<T>) {
        self.tested += 1;
        if let Some(d) = depth {
            self.resolved += 1;
            if d > self.max_depth {
                self.max_depth = d;
            }
        }
    }
}
