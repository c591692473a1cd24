//! A pinhole camera that frames an axis-aligned box: it looks from a given eye point at the
//! box's centre, with the focal length and principal point chosen so that the projections of
//! the box's eight corners just fill the viewport (an off-axis perspective projection).

use super::vector::{V3, cross, dot, normalize_or, sub};

/// A perspective camera on a `width` x `height` pixel viewport.
///
/// View coordinates of a point $p$: $x_v = (p - e)\cdot r$, $y_v = (p - e)\cdot u$,
/// $z_v = (p - e)\cdot f$ (the depth) with eye $e$ and the orthonormal right, up and forward
/// vectors $r, u, f$ (right-handed: $r = f \times \hat y / \lVert\cdot\rVert$,
/// $u = r \times f$). Screen coordinates (pixels, $y$ down):
/// $s_x = c_x + \phi\, x_v / z_v$, $s_y = c_y - \phi\, y_v / z_v$ with focal length $\phi$
/// (pixels) and principal point $(c_x, c_y)$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye point (world).
    pub eye: V3,
    /// Unit right vector $r$.
    pub right: V3,
    /// Unit up vector $u$.
    pub up: V3,
    /// Unit forward vector $f$ (the viewing direction).
    pub forward: V3,
    /// Focal length $\phi$ (pixels).
    pub focal: f32,
    /// Principal point $(c_x, c_y)$ (pixels).
    pub center: [f32; 2],
    /// Near clipping depth: geometry closer than this is clipped away.
    pub near: f32,
    /// Viewport width (pixels).
    pub width: usize,
    /// Viewport height (pixels).
    pub height: usize,
}

impl Camera {
    /// A camera at `eye` looking at the centre of `bounds` (min and max corners), fitted so
    /// that the box's corners span the viewport `size` less a `margin` (a fraction of each
    /// side, in $[0, 0.45]$). Fallbacks: an eye at the centre looks along −Y; a view straight
    /// down or up takes −Z as the up reference; corners at or behind the eye are treated as
    /// lying at a small positive depth; a box of zero extent gets a tiny one.
    #[must_use]
    pub fn framing(eye: V3, bounds: [[f32; 3]; 2], size: [usize; 2], margin: f32) -> Self {
        let [lo, hi] = bounds;
        let target = [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a]));
        let forward = normalize_or(sub(target, eye), [0.0, -1.0, 0.0]);
        let reference = if forward[1].abs() > 0.999 {
            [0.0, 0.0, -1.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let right = normalize_or(cross(forward, reference), [1.0, 0.0, 0.0]);
        let up = cross(right, forward);
        let diagonal = super::vector::length(sub(hi, lo)).max(1e-6);
        let floor = 1e-4 * diagonal;
        let (mut min, mut max) = ([f32::MAX; 2], [f32::MIN; 2]);
        let mut nearest = f32::MAX;
        for k in 0..8 {
            let corner = [0, 1, 2].map(|a| if k >> a & 1 == 1 { hi[a] } else { lo[a] });
            let d = sub(corner, eye);
            let z = dot(d, forward).max(floor);
            nearest = nearest.min(z);
            let n = [dot(d, right) / z, dot(d, up) / z];
            for a in 0..2 {
                min[a] = min[a].min(n[a]);
                max[a] = max[a].max(n[a]);
            }
        }
        let (w, h) = (size[0].max(1) as f32, size[1].max(1) as f32);
        let keep = 1.0 - 2.0 * margin.clamp(0.0, 0.45);
        let extent = [0, 1].map(|a| (max[a] - min[a]).max(1e-6));
        let focal = (w * keep / extent[0]).min(h * keep / extent[1]);
        let center = [
            0.5 * w - focal * 0.5 * (min[0] + max[0]),
            0.5 * h + focal * 0.5 * (min[1] + max[1]),
        ];
        Self {
            eye,
            right,
            up,
            forward,
            focal,
            center,
            near: (0.05 * nearest).max(floor),
            width: size[0].max(1),
            height: size[1].max(1),
        }
    }

    /// View coordinates $(x_v, y_v, z_v)$ of the world point `p` (type docs).
    #[inline]
    #[must_use]
    pub fn view_of(&self, p: V3) -> V3 {
        let d = sub(p, self.eye);
        [dot(d, self.right), dot(d, self.up), dot(d, self.forward)]
    }

    /// Screen coordinates (pixels, $y$ down) of the view point `v`, $z_v > 0$ (type docs).
    #[inline]
    #[must_use]
    pub fn project(&self, v: V3) -> [f32; 2] {
        [
            self.center[0] + self.focal * v[0] / v[2],
            self.center[1] - self.focal * v[1] / v[2],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framed_box_corners_fill_the_viewport() {
        let bounds = [[-12.0, 0.0, 0.0], [12.0, 6.0, 17.0]];
        let eye = [5.0, 30.0, 40.0];
        let c = Camera::framing(eye, bounds, [320, 240], 0.05);
        let (mut min, mut max) = ([f32::MAX; 2], [f32::MIN; 2]);
        for k in 0..8 {
            let p = [0, 1, 2].map(|a| bounds[usize::from(k >> a & 1 == 1)][a]);
            let s = c.project(c.view_of(p));
            for a in 0..2 {
                min[a] = min[a].min(s[a]);
                max[a] = max[a].max(s[a]);
            }
        }
        assert!(min[0] >= 15.9 && max[0] <= 304.1, "{min:?} {max:?}");
        assert!(min[1] >= 11.9 && max[1] <= 228.1, "{min:?} {max:?}");
        // One axis is filled exactly, and the box is centred.
        let filled_x = (min[0] - 16.0).abs() < 0.1 && (max[0] - 304.0).abs() < 0.1;
        let filled_y = (min[1] - 12.0).abs() < 0.1 && (max[1] - 228.0).abs() < 0.1;
        assert!(filled_x || filled_y);
        assert!((min[0] + max[0] - 320.0).abs() < 0.1 && (min[1] + max[1] - 240.0).abs() < 0.1);
        // Right-handed: +X is on the right seen from +Z, +Y is up.
        let o = c.project(c.view_of([0.0, 0.0, 8.5]));
        assert!(c.project(c.view_of([1.0, 0.0, 8.5]))[0] > o[0]);
        assert!(c.project(c.view_of([0.0, 1.0, 8.5]))[1] < o[1]);
    }

    #[test]
    fn degenerate_framing_is_finite() {
        let c = Camera::framing([0.0; 3], [[0.0; 3]; 2], [0, 0], 0.9);
        assert!(c.focal.is_finite() && c.near > 0.0);
        assert!(
            c.right
                .iter()
                .chain(&c.up)
                .chain(&c.forward)
                .all(|v| v.is_finite())
        );
    }
}
