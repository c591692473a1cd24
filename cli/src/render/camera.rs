//! A pinhole camera that frames an axis-aligned box: it looks from a given eye point at the
//! box's centre, with the focal length and principal point chosen so that the projections of
//! the box's eight corners just fill the viewport (an off-axis perspective projection).

use glam::Vec3;

use super::vector::normalize_or;

/// A perspective camera on a `width` x `height` pixel viewport.
///
/// View coordinates of a point $p$: $x_v = (p - e)\cdot r$, $y_v = (p - e)\cdot u$,
/// $z_v = (p - e)\cdot f$ (the depth) with eye $e$ and the orthonormal right, up and forward
/// vectors $r, u, f$ (right-handed: $r = f \times \hat y / \lVert\cdot\rVert$,
/// $u = r \times f$). Screen coordinates (pixels, $y$ down):
/// $s_x = c_x + \phi\thinspace x_v / z_v$, $s_y = c_y - \phi\thinspace y_v / z_v$ with focal length $\phi$
/// (pixels) and principal point $(c_x, c_y)$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye point (world).
    pub eye: Vec3,
    /// Unit right vector $r$.
    pub right: Vec3,
    /// Unit up vector $u$.
    pub up: Vec3,
    /// Unit forward vector $f$ (the viewing direction).
    pub forward: Vec3,
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
    pub fn framing(eye: Vec3, bounds: [[f32; 3]; 2], size: [usize; 2], margin: f32) -> Self {
        let [lo, hi] = bounds.map(Vec3::from);
        let target = 0.5 * (lo + hi);
        let forward = normalize_or(target - eye, Vec3::NEG_Y);
        let reference = if forward.y.abs() > 0.999 {
            Vec3::NEG_Z
        } else {
            Vec3::Y
        };
        let right = normalize_or(forward.cross(reference), Vec3::X);
        let up = right.cross(forward);
        let diagonal = (hi - lo).length().max(1e-6);
        let floor = 1e-4 * diagonal;
        let (mut min, mut max) = ([f32::MAX; 2], [f32::MIN; 2]);
        let mut nearest = f32::MAX;
        for k in 0..8 {
            let corner = Vec3::from([0, 1, 2].map(|a| if k >> a & 1 == 1 { hi[a] } else { lo[a] }));
            let d = corner - eye;
            let z = d.dot(forward).max(floor);
            nearest = nearest.min(z);
            let n = [d.dot(right) / z, d.dot(up) / z];
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
    pub fn view_of(&self, p: Vec3) -> Vec3 {
        let d = p - self.eye;
        Vec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// Screen coordinates (pixels, $y$ down) of the view point `v`, $z_v > 0$ (type docs).
    #[inline]
    #[must_use]
    pub fn project(&self, v: Vec3) -> [f32; 2] {
        [
            self.center[0] + self.focal * v.x / v.z,
            self.center[1] - self.focal * v.y / v.z,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framed_box_corners_fill_the_viewport() {
        let bounds = [[-12.0, 0.0, 0.0], [12.0, 6.0, 17.0]];
        let eye = Vec3::new(5.0, 30.0, 40.0);
        let c = Camera::framing(eye, bounds, [320, 240], 0.05);
        let (mut min, mut max) = ([f32::MAX; 2], [f32::MIN; 2]);
        for k in 0..8 {
            let p = [0, 1, 2].map(|a| bounds[usize::from(k >> a & 1 == 1)][a]);
            let s = c.project(c.view_of(p.into()));
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
        let o = c.project(c.view_of(Vec3::new(0.0, 0.0, 8.5)));
        assert!(c.project(c.view_of(Vec3::new(1.0, 0.0, 8.5)))[0] > o[0]);
        assert!(c.project(c.view_of(Vec3::new(0.0, 1.0, 8.5)))[1] < o[1]);
    }

    #[test]
    fn degenerate_framing_is_finite() {
        let c = Camera::framing(Vec3::ZERO, [[0.0; 3]; 2], [0, 0], 0.9);
        assert!(c.focal.is_finite() && c.near > 0.0);
        assert!(c.right.is_finite() && c.up.is_finite() && c.forward.is_finite());
    }
}
