//! Grabbing and dragging (seed `000_…` Sec. 3.3 and Fig. 7): camera rays, the drag plane and
//! the tent function that turns a drag point into a reachable positional target.

use folio_kernels::{Real, Vec3Ops, math};

/// A camera ray in world coordinates (page units): `origin + t * direction`, `t >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<T: Real> {
    /// Camera position.
    pub origin: T::Vec3,
    /// Direction (any positive length).
    pub direction: T::Vec3,
}

impl<T: Real> Ray<T> {
    /// `true` when every coordinate is finite and the direction is not zero.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let finite = |v: T::Vec3| v.x().is_finite() && v.y().is_finite() && v.z().is_finite();
        finite(self.origin)
            && finite(self.direction)
            && self.direction.dot(self.direction) > T::LENGTH_FLOOR
    }

    /// Squared distance from `p` to the ray.
    #[must_use]
    pub fn distance_sq(&self, p: T::Vec3) -> T {
        let d = self.direction;
        let rel = p - self.origin;
        let mut t = rel.dot(d) / d.dot(d);
        if t < T::ZERO {
            t = T::ZERO;
        }
        let off = rel - d * t;
        off.dot(off)
    }

    /// Where the ray meets the plane through `point` with normal `normal`, if it does
    /// (in front of the camera, not parallel).
    #[must_use]
    pub fn hit_plane(&self, point: T::Vec3, normal: T::Vec3) -> Option<T::Vec3> {
        let denom = self.direction.dot(normal);
        let scale = math::sqrt(self.direction.dot(self.direction) * normal.dot(normal));
        let crossing = math::abs(denom) > scale * T::from_f64(1e-6);
        if !crossing {
            return None;
        }
        let t = (point - self.origin).dot(normal) / denom;
        (t >= T::ZERO && t.is_finite()).then(|| self.origin + self.direction * t)
    }
}

/// The tent over the book (seed Fig. 7; its shape is left to the implementer). A drag point
/// $\tilde p$ is first moved over the book, $x \in [x_b - r, x_b + r]$ and $z \in [0, H]$,
/// then given the height of the tent
/// $$y(x) = y_{base} + \eta\thinspace r \left(1 - \frac{\lvert x - x_b\rvert}{r}\right),$$
/// with $x_b$ the binding's centre, $r$ the grabbed node's distance from the binding along
/// the flat page, $y_{base}$ the top of the thicker block and $\eta$ the tent height ratio
/// (0.6 by default). At $x = x_b \pm r$ the target is where the node lies on a flat block;
/// over the binding it is $\eta r$ up, which a page reaches by bending, so a horizontal
/// swipe draws the arc of a hand turning a page and every target stays reachable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tent<T> {
    /// $x_b$.
    pub center: T,
    /// $r$.
    pub reach: T,
    /// $y_{base}$.
    pub base: T,
    /// $\eta$.
    pub height: T,
    /// $H$, the page height.
    pub page_height: T,
}

impl<T: Real> Tent<T> {
    /// The target for drag point `p` (type docs).
    #[must_use]
    pub fn project(&self, p: T::Vec3) -> T::Vec3 {
        let clamp = |v: T, lo: T, hi: T| folio_kernels::real::clamp_keep_nan(v, lo, hi);
        let x = clamp(p.x(), self.center - self.reach, self.center + self.reach);
        let z = clamp(p.z(), T::ZERO, self.page_height);
        let u = if self.reach > T::ZERO {
            T::ONE - math::abs(x - self.center) / self.reach
        } else {
            T::ZERO
        };
        T::Vec3::new(x, self.base + self.height * self.reach * u, z)
    }
}
