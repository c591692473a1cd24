//! The broad phase of the [`Wall`] contacts: an axis-aligned box in the XY plane around a
//! group of points, and the test that no point of a box can reach a wall, so that a group
//! is skipped without changing what the point tests would find.
//!
//! [`Wall::penetration`] finds a contact for $p$ when
//! $$s(p) = \mathrm{fl}\big((p - a)\cdot(b - a)\big)\,\lVert b-a\rVert^{-2} \in [0, 1]
//!   \ (\text{or } s \ge 0 \text{ with an open end}),\qquad
//!   \delta(p) = c - \mathrm{fl}\big((p - a)\cdot n\big) > 0$$
//! (seed `000_…` Sec. 3.4), every operation rounded. Each rounded operation is monotone
//! in its operands, so $s$ and $\delta$ are monotone in $p_x$ and in $p_y$ separately, the
//! direction set by the sign of the matching component of $b - a$ and of $n$. Over a box
//! their extremes are therefore at corners, computed with the same arithmetic: the box is
//! clear of the wall when the largest $s$ is below 0, the smallest above 1 (closed end), or
//! the largest $\delta$ is at most 0. A comparison with NaN never declares a box clear.

use super::Wall;
use folio_kernels::{Real, Vec3Ops};

/// An axis-aligned box in the XY plane (Z ignored) around a group of points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds<T> {
    /// Smallest X and Y (page units).
    pub min: [T; 2],
    /// Largest X and Y (page units).
    pub max: [T; 2],
}

impl<T: Real> Bounds<T> {
    /// The box of the point `p` alone.
    #[inline]
    #[must_use]
    pub fn at(p: T::Vec3) -> Self {
        Self {
            min: [p.x(), p.y()],
            max: [p.x(), p.y()],
        }
    }

    /// Grows the box to hold `p`. A NaN coordinate is left out: such a point never
    /// penetrates a wall.
    #[inline]
    pub fn include(&mut self, p: T::Vec3) {
        for (k, v) in [p.x(), p.y()].into_iter().enumerate() {
            if v < self.min[k] {
                self.min[k] = v;
            }
            if v > self.max[k] {
                self.max[k] = v;
            }
        }
    }

    /// Grows the box to hold `other`.
    #[inline]
    pub fn include_bounds(&mut self, other: &Self) {
        for k in 0..2 {
            if other.min[k] < self.min[k] {
                self.min[k] = other.min[k];
            }
            if other.max[k] > self.max[k] {
                self.max[k] = other.max[k];
            }
        }
    }

    /// The corner whose X is the smallest when `low[0]`, else the largest, and Y likewise.
    #[inline]
    #[must_use]
    fn corner(&self, low: [bool; 2]) -> T::Vec3 {
        let pick = |k: usize| if low[k] { self.min[k] } else { self.max[k] };
        T::Vec3::new(pick(0), pick(1), T::ZERO)
    }
}

impl<T: Real> Wall<T> {
    /// `true` when [`Wall::penetration`] is `None` for every point (any Z) of `bounds`: the
    /// largest span parameter is below 0, or the smallest above 1 without an open end, or
    /// the largest depth is at most 0, each taken at its corner of the box (module docs).
    #[inline]
    #[must_use]
    pub fn misses(&self, bounds: &Bounds<T>) -> bool {
        let (along, normal) = (self.along, self.normal);
        let s_max = self.span(bounds.corner([along.x() < T::ZERO, along.y() < T::ZERO]));
        if s_max < T::ZERO {
            return true;
        }
        if !self.open_end {
            let s_min = self.span(bounds.corner([along.x() >= T::ZERO, along.y() >= T::ZERO]));
            if s_min > T::ONE {
                return true;
            }
        }
        let depth_max = self.depth(bounds.corner([normal.x() >= T::ZERO, normal.y() >= T::ZERO]));
        depth_max <= T::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::Bounds;
    use crate::Wall;
    use folio_kernels::splitmix::SplitMix64;
    use folio_kernels::{Real, Vec3Ops};

    /// Random walls (any direction, open or closed end) and random boxes around them: a box
    /// the wall misses holds no point that penetrates it, among its corners, points on its
    /// edges and inside it; and both answers occur.
    fn a_missed_box_holds_no_contact<T: Real>() {
        let mut r = SplitMix64::new(19);
        let mut u = move |lo: f64, hi: f64| T::from_f64(r.uniform(lo, hi));
        let v = |x: T, y: T| T::Vec3::new(x, y, T::ZERO);
        let (mut missed, mut kept) = (0, 0);
        for case in 0..4000 {
            let a = v(u(-2.0, 2.0), u(-2.0, 2.0));
            let b = v(u(-2.0, 2.0), u(-2.0, 2.0));
            let toward = v(u(-1.0, 1.0), u(-1.0, 1.0));
            let Some(mut wall) = Wall::new(a, b, toward, u(0.0, 0.5)) else {
                continue;
            };
            wall.open_end = case % 2 == 0;
            let corner = v(u(-3.0, 3.0), u(-3.0, 3.0));
            // Some boxes flat or a point, some wide.
            let size = [u(0.0, 1.5), u(0.0, 1.5)].map(|s| if case % 5 == 0 { T::ZERO } else { s });
            let mut bounds = Bounds::at(corner);
            bounds.include(corner + v(size[0], size[1]));
            let misses = wall.misses(&bounds);
            if misses {
                missed += 1;
            } else {
                kept += 1;
                continue;
            }
            let steps = 12_u32;
            for i in 0..=steps {
                for j in 0..=steps {
                    let f = |k: u32| T::from_f64(f64::from(k) / f64::from(steps));
                    let p = v(
                        bounds.min[0] + (bounds.max[0] - bounds.min[0]) * f(i),
                        bounds.min[1] + (bounds.max[1] - bounds.min[1]) * f(j),
                    );
                    assert_eq!(
                        wall.penetration(p),
                        None,
                        "case {case}: {p:?} in {bounds:?}"
                    );
                }
            }
            for p in [
                bounds.min,
                bounds.max,
                [bounds.min[0], bounds.max[1]],
                [bounds.max[0], bounds.min[1]],
            ] {
                assert_eq!(wall.penetration(v(p[0], p[1])), None, "case {case}");
            }
        }
        assert!(missed > 500 && kept > 500, "{missed} missed, {kept} kept");
    }

    #[test]
    fn a_missed_box_holds_no_contact_f64() {
        a_missed_box_holds_no_contact::<f64>();
    }

    #[test]
    fn a_missed_box_holds_no_contact_f32() {
        a_missed_box_holds_no_contact::<f32>();
    }

    /// A box grows to hold each point included, and leaves out NaN.
    #[test]
    fn a_box_holds_what_it_includes() {
        let v = <f64 as Real>::Vec3::new;
        let mut b = Bounds::<f64>::at(v(1.0, 2.0, 3.0));
        b.include(v(-1.0, 5.0, 0.0));
        b.include(v(f64::NAN, 0.5, 0.0));
        assert_eq!(b.min, [-1.0, 0.5]);
        assert_eq!(b.max, [1.0, 5.0]);
    }
}
