//! The force split at a potential tearing point (seed `002_…` Sec. 5.1, eq. 4-5, Fig. 6)
//! and the energy release rate and direction it gives (Sec. 5.2, eq. 6).
//!
//! **Loads.** Each triangle $k$ of the fan of $p$ pulls $p$ with the in-plane stretching
//! force $\ell_k = -\partial V_k / \partial x_p$ (newtons, 3D). At a free vertex these pulls
//! sum to (almost) zero: the material around the tip holds it. The seed's two "imaginary
//! pulling points" load the tip through the pulls that point out of the material, backward
//! along the tear; the pulls that point forward are the reaction of the intact paper ahead,
//! which the tear releases rather than loads. A pull counts when $\ell_k \cdot b > 0$, $b$
//! the current bisector (pointing out of the material), and when it is a pull at all,
//! $\ell_k \cdot (c_k - x_p) > 0$ with $c_k$ the triangle's centroid: a compressed triangle
//! pushes its corners, and pushing does not tear paper. This choice is the seed's open
//! point (it writes the clusters as "approximately equivalent opposite forces" without
//! saying what becomes of the reaction); with it, two fingers pulling the lips give exactly
//! O'Keefe's bisector (the hyperbola of seed Fig. 2).
//!
//! **Clusters** (eq. 4). With $n$ the surface normal at $p$ and $m = b \times n$:
//! $$F_{\text{left}} = \sum_{\ell_k \cdot m > 0} \ell_k,\qquad
//!   F_{\text{right}} = \sum_{\ell_k \cdot m < 0} \ell_k,$$
//! over the counted pulls. $b^0$ bisects the boundary tangents at $p$ (pointing out of the
//! sheet: the outward normal on a straight border, back along the slit at a tear tip); then
//! $b^{i+1} = \widehat{F_{\text{left}}} + \widehat{F_{\text{right}}}$ normalized, until
//! $\lVert b^{i+1} - b^i \rVert < \varepsilon$ or [`MAX_ITERATIONS`] iterations.
//!
//! **Pattern** (eq. 5). Each pull maps into the pattern through its triangle's deformation
//! gradient $F_k$ (3x2, pattern to 3D): $\tilde\ell_k = F_k^\top \ell_k$ (exact for the
//! isometric deformations of paper); $\tilde F_{\text{left}}$, $\tilde F_{\text{right}}$ are
//! the sums over the clusters.
//!
//! **Release rate and direction** (eq. 6). With $\theta \in [0, \pi]$ the angle between
//! $\tilde F_{\text{left}}$ and $\tilde F_{\text{right}}$ and $e$ the thickness,
//! $$E_r = \frac{(\lVert \tilde F_{\text{left}} \rVert + \lVert \tilde F_{\text{right}}
//!   \rVert) \cos(\theta / 2)}{e},$$
//! and the tear runs along $t = -(\hat{\tilde F}\_{\text{left}} + \hat{\tilde
//! F}\_{\text{right}})$ normalized: the bisector, pointing away from the pulling points (the
//! seed's "bisector of the two forces" with the forces taken as the tip's reaction). An empty
//! cluster (nothing pulls on one side) releases nothing: $E_r = 0$.

use folio_kernels::{Real, Vec3Ops, math};

/// Most iterations of the bisector (seed Sec. 5.1: "usually no more than 10").
pub const MAX_ITERATIONS: usize = 10;

/// One pull on the tearing point: the 3D force, the direction of its triangle, and the
/// triangle's deformation-gradient columns (to map it into the pattern).
#[derive(Clone, Copy, Debug)]
pub struct Pull<T: Real> {
    /// $\ell_k = -\partial V_k / \partial x_p$ (force units).
    pub force: T::Vec3,
    /// From the point to its triangle's centroid (3D): a force with a positive component
    /// along it pulls (tension); one against it pushes (compression) and is not a load.
    pub toward: T::Vec3,
    /// The columns $F_k e_u$, $F_k e_v$ of the triangle's deformation gradient.
    pub gradient: [T::Vec3; 2],
}

/// The result of the split at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Split<T> {
    /// $\tilde F_{\text{left}}$ in the pattern.
    pub left: [T; 2],
    /// $\tilde F_{\text{right}}$ in the pattern.
    pub right: [T; 2],
    /// $\theta$, radians in $[0, \pi]$.
    pub angle: T,
    /// $E_r$ (eq. 6), force per length (force units / sheet unit).
    pub release_rate: T,
    /// Unit tear direction $t$ in the pattern (zero when $E_r = 0$).
    pub direction: [T; 2],
    /// Bisector iterations taken.
    pub iterations: usize,
}

/// The split of `pulls` at a point with unit surface normal `normal` and initial 3D bisector
/// `b0` (module docs), for sheet thickness `thickness` and bisector tolerance `epsilon`.
#[must_use]
pub fn split_forces<T: Real>(
    pulls: &[Pull<T>],
    normal: T::Vec3,
    b0: T::Vec3,
    thickness: T,
    epsilon: T,
) -> Split<T> {
    let mut b = unit::<T>(b0);
    let mut iterations = 0;
    let (mut left, mut right) = clusters(pulls, normal, b);
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let next = unit::<T>(unit::<T>(left) + unit::<T>(right));
        if next == T::Vec3::ZERO {
            break;
        }
        let change = math::length::<T>(next - b);
        b = next;
        (left, right) = clusters(pulls, normal, b);
        if change < epsilon {
            break;
        }
    }
    let (mut pl, mut pr) = ([T::ZERO; 2], [T::ZERO; 2]);
    let m = b.cross(normal);
    for pull in pulls {
        if !loads(pull, b) {
            continue;
        }
        let mapped = [
            pull.gradient[0].dot(pull.force),
            pull.gradient[1].dot(pull.force),
        ];
        let side = pull.force.dot(m);
        let target = if side > T::ZERO {
            &mut pl
        } else if side < T::ZERO {
            &mut pr
        } else {
            continue;
        };
        target[0] += mapped[0];
        target[1] += mapped[1];
    }
    let (nl, nr) = (norm2(pl), norm2(pr));
    if !(nl > T::ZERO && nr > T::ZERO && thickness > T::ZERO) {
        return Split {
            left: pl,
            right: pr,
            angle: T::ZERO,
            release_rate: T::ZERO,
            direction: [T::ZERO; 2],
            iterations,
        };
    }
    let (ul, ur) = ([pl[0] / nl, pl[1] / nl], [pr[0] / nr, pr[1] / nr]);
    let cross = ul[0] * ur[1] - ul[1] * ur[0];
    let dot = ul[0] * ur[0] + ul[1] * ur[1];
    let angle = math::abs(math::atan2(cross, dot));
    let sum = [ul[0] + ur[0], ul[1] + ur[1]];
    let ns = norm2(sum);
    let direction = if ns > T::ZERO {
        [-sum[0] / ns, -sum[1] / ns]
    } else {
        [T::ZERO; 2]
    };
    let release_rate = if ns > T::ZERO {
        (nl + nr) * math::cos(angle * T::HALF) / thickness
    } else {
        T::ZERO
    };
    Split {
        left: pl,
        right: pr,
        angle,
        release_rate,
        direction,
        iterations,
    }
}

/// $F_{\text{left}}$, $F_{\text{right}}$ in 3D for bisector `b` (eq. 4).
fn clusters<T: Real>(pulls: &[Pull<T>], normal: T::Vec3, b: T::Vec3) -> (T::Vec3, T::Vec3) {
    let m = b.cross(normal);
    let (mut left, mut right) = (T::Vec3::ZERO, T::Vec3::ZERO);
    for pull in pulls {
        if !loads(pull, b) {
            continue;
        }
        let side = pull.force.dot(m);
        if side > T::ZERO {
            left += pull.force;
        } else if side < T::ZERO {
            right += pull.force;
        }
    }
    (left, right)
}

/// `true` when `pull` loads the point for bisector `b` (module docs).
fn loads<T: Real>(pull: &Pull<T>, b: T::Vec3) -> bool {
    pull.force.dot(b) > T::ZERO && pull.force.dot(pull.toward) > T::ZERO
}

/// `v` normalized, or zero.
pub(crate) fn unit<T: Real>(v: T::Vec3) -> T::Vec3 {
    let len = math::length::<T>(v);
    if len > T::ZERO {
        v * (T::ONE / len)
    } else {
        T::Vec3::ZERO
    }
}

/// Euclidean length of a pattern vector.
fn norm2<T: Real>(v: [T; 2]) -> T {
    math::sqrt(v[0] * v[0] + v[1] * v[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn flat(force: DVec3) -> Pull<f64> {
        Pull {
            force,
            toward: force,
            gradient: [DVec3::X, DVec3::Y],
        }
    }

    /// O'Keefe's set-up: a slit along −u ending at the origin, the lips pulled toward two
    /// fingers behind it, the intact paper ahead holding the tip. The direction is the
    /// bisector of the directions away from the fingers, whatever the pulls' magnitudes, and
    /// $E_r = (|F_l| + |F_r|)\cos(\theta/2)/e$.
    #[test]
    fn two_fingers_give_the_bisector_away_from_them() {
        let a = DVec3::new(-1.0, 0.5, 0.0);
        let b = DVec3::new(-3.0, -0.8, 0.0);
        let (ta, tb) = (2.0, 0.7);
        let pa = a.normalize() * ta;
        let pb = b.normalize() * tb;
        let reaction = -(pa + pb);
        let pulls = [
            flat(pa),
            flat(pb),
            flat(reaction * 0.6),
            flat(reaction * 0.4),
        ];
        let s = split_forces(&pulls, DVec3::Z, DVec3::new(-1.0, 0.0, 0.0), 0.01, 1e-12);
        let expected = -(a.normalize() + b.normalize()).normalize();
        assert!((s.direction[0] - expected.x).abs() < 1e-12, "{s:?}");
        assert!((s.direction[1] - expected.y).abs() < 1e-12, "{s:?}");
        let theta = a.angle_between(b);
        assert!((s.angle - theta).abs() < 1e-12);
        let rate = (ta + tb) * (theta / 2.0).cos() / 0.01;
        assert!(
            (s.release_rate - rate).abs() < 1e-9 * rate,
            "{} vs {rate}",
            s.release_rate
        );
        assert!(s.iterations <= MAX_ITERATIONS);
    }

    #[test]
    fn one_sided_or_no_pull_releases_nothing() {
        let pulls = [
            flat(DVec3::new(-1.0, 0.3, 0.0)),
            flat(DVec3::new(1.0, 0.0, 0.0)),
        ];
        let s = split_forces(&pulls, DVec3::Z, DVec3::new(-1.0, 0.0, 0.0), 0.01, 1e-9);
        assert_eq!(s.release_rate, 0.0);
        let s = split_forces(&[], DVec3::Z, DVec3::new(-1.0, 0.0, 0.0), 0.01, 1e-9);
        assert_eq!(s.release_rate, 0.0);
        assert_eq!(s.direction, [0.0, 0.0]);
        let zero = [flat(DVec3::ZERO), flat(DVec3::ZERO)];
        let s = split_forces(&zero, DVec3::Z, DVec3::ZERO, 0.01, 1e-9);
        assert_eq!(s.release_rate, 0.0);
    }

    /// A stretched triangle's pull maps through $F^\top$: stretching the pattern by 2 along u
    /// doubles the u component.
    #[test]
    fn pulls_map_into_the_pattern_by_the_transposed_gradient() {
        let stretch = |f: DVec3| Pull {
            force: f,
            toward: f,
            gradient: [DVec3::X * 2.0, DVec3::Y],
        };
        let pulls = [
            stretch(DVec3::new(-1.0, 1.0, 0.0)),
            stretch(DVec3::new(-1.0, -1.0, 0.0)),
        ];
        let s = split_forces(&pulls, DVec3::Z, DVec3::new(-1.0, 0.0, 0.0), 1.0, 1e-12);
        assert_eq!(s.left, [-2.0, 1.0]);
        assert_eq!(s.right, [-2.0, -1.0]);
        assert!((s.direction[0] - 1.0_f64).abs() < 1e-12 && s.direction[1].abs() < 1e-12_f64);
    }
}
