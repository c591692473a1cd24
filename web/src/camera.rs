//! The view: a perspective camera orbiting the book, the one source of both the matrix the
//! page draws with and the rays its pointer grabs with, so that a page is grabbed where it is
//! seen.
//!
//! Book frame (page units): X across the book with the spine near $x = 0$, Y up, Z along the
//! spine from the head ($z = 0$) to the foot ($z = H$), as in `folio_book` and the contact
//! sheet of `folio run`.
//!
//! The eye sits at $e = c + d\thinspace(\cos\phi \sin\theta,\ \sin\phi,\ \cos\phi \cos\theta)$ around
//! the target $c$, with yaw $\theta$ about Y (0: in front of the foot), pitch $\phi$ above
//! the table and distance $d$. Its orthonormal frame is $f = (c - e)/\lVert c - e\rVert$,
//! $r = f \times \hat y / \lVert\cdot\rVert$, $u = r \times f$. A pixel $(s_x, s_y)$ of a
//! $w \times h$ viewport (y down) has normalized device coordinates
//! $x_n = 2 s_x / w - 1$, $y_n = 1 - 2 s_y / h$ and the ray
//! $e + t\thinspace(f + x_n \tau a\thinspace r + y_n \tau\thinspace u)$, $t \ge 0$, with $\tau = \tan(\mathrm{fov}/2)$
//! and $a = w / h$: the inverse of the projection below.

use glam::DVec3;

/// Vertical field of view (radians): 40°, a normal lens.
pub const FIELD_OF_VIEW: f64 = 0.698_131_700_797_731_8;
/// Default yaw $\theta$ (radians): a little to the right of the foot, as the contact sheet's
/// eye direction $(0.25, 1, 0.8)$.
pub const YAW: f64 = 0.302_884_868_374_971_4;
/// Default pitch $\phi$ (radians) above the table, as the contact sheet's eye direction.
pub const PITCH: f64 = 0.873_220_549_145_984_9;
/// Steepest pitch: just short of straight down, where the frame's right vector is undefined.
const PITCH_MAX: f64 = 1.45;
/// Lowest pitch: just above the table.
const PITCH_MIN: f64 = 0.1;
/// Radians of orbit per pixel dragged.
const ORBIT_RATE: f64 = 0.006;

/// A camera on a viewport (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// What it looks at, $c$.
    pub target: DVec3,
    /// Distance $d$ from the target.
    pub distance: f64,
    /// Yaw $\theta$ (radians).
    pub yaw: f64,
    /// Pitch $\phi$ (radians).
    pub pitch: f64,
    /// Viewport width and height (CSS pixels, each at least 1).
    pub viewport: [f64; 2],
}

/// The eye's orthonormal frame: eye $e$, right $r$, up $u$, forward $f$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Eye position.
    pub eye: DVec3,
    /// Unit right vector.
    pub right: DVec3,
    /// Unit up vector.
    pub up: DVec3,
    /// Unit viewing direction.
    pub forward: DVec3,
}

impl Camera {
    /// A camera at the default yaw and pitch, looking at the centre of the box `bounds` (min
    /// and max corners) from the nearest distance at which the box's eight corners fall
    /// inside the viewport less a margin of 4 % of each side (bisection between a twentieth
    /// of, and, the distance $\rho / \sin(\mathrm{fov}_{min}/2)$ at which its bounding sphere
    /// of radius $\rho$ fits).
    #[must_use]
    pub fn framing(bounds: [[f64; 3]; 2], viewport: [f64; 2]) -> Self {
        let [lo, hi] = bounds.map(DVec3::from);
        let mut camera = Self {
            target: 0.5 * (lo + hi),
            distance: 1.0,
            yaw: YAW,
            pitch: PITCH,
            viewport: [1.0, 1.0],
        };
        camera.resize(viewport);
        let radius = (0.5 * (hi - lo).length()).max(1e-3);
        let half = 0.5 * FIELD_OF_VIEW;
        let aspect = camera.aspect();
        let narrow = if aspect < 1.0 {
            (half.tan() * aspect).atan()
        } else {
            half
        };
        let corners: [DVec3; 8] = core::array::from_fn(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        });
        let [w, h] = camera.viewport;
        let inside = |c: &Self| {
            corners.iter().all(|&p| {
                c.project(p).is_some_and(|s| {
                    (0.04 * w..=0.96 * w).contains(&s[0]) && (0.04 * h..=0.96 * h).contains(&s[1])
                })
            })
        };
        let (mut near, mut far) = (0.05 * radius / narrow.sin(), radius / narrow.sin());
        for _ in 0..40 {
            camera.distance = 0.5 * (near + far);
            if inside(&camera) {
                far = camera.distance;
            } else {
                near = camera.distance;
            }
        }
        camera.distance = far;
        camera
    }

    /// Sets the viewport (CSS pixels); a non-finite or non-positive side becomes 1.
    pub fn resize(&mut self, viewport: [f64; 2]) {
        self.viewport = viewport.map(|s| if s.is_finite() && s >= 1.0 { s } else { 1.0 });
    }

    /// Width over height.
    #[must_use]
    pub fn aspect(&self) -> f64 {
        self.viewport[0] / self.viewport[1]
    }

    /// Turns the view by a pointer drag of `dx`, `dy` pixels: yaw with `dx`, pitch with `dy`,
    /// the pitch kept between just above the table and just short of straight down.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        if dx.is_finite() && dy.is_finite() {
            self.yaw -= ORBIT_RATE * dx;
            self.pitch = (self.pitch + ORBIT_RATE * dy).clamp(PITCH_MIN, PITCH_MAX);
        }
    }

    /// The eye's frame (module docs).
    #[must_use]
    pub fn frame(&self) -> Frame {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let eye = self.target + self.distance * DVec3::new(cp * sy, sp, cp * cy);
        let forward = (self.target - eye).normalize();
        let right = forward.cross(DVec3::Y).normalize();
        let up = right.cross(forward);
        Frame {
            eye,
            right,
            up,
            forward,
        }
    }

    /// The ray through pixel `(x, y)` (module docs): its origin (the eye) and a unit
    /// direction; `None` for a non-finite pixel.
    #[must_use]
    pub fn ray(&self, x: f64, y: f64) -> Option<(DVec3, DVec3)> {
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let f = self.frame();
        let tau = (0.5 * FIELD_OF_VIEW).tan();
        let xn = 2.0 * x / self.viewport[0] - 1.0;
        let yn = 1.0 - 2.0 * y / self.viewport[1];
        let d = f.forward + xn * tau * self.aspect() * f.right + yn * tau * f.up;
        Some((f.eye, d.normalize()))
    }

    /// The pixel where `p` is seen, `None` behind the eye: the inverse of [`Camera::ray`].
    #[must_use]
    pub fn project(&self, p: DVec3) -> Option<[f64; 2]> {
        let f = self.frame();
        let rel = p - f.eye;
        let depth = rel.dot(f.forward);
        if depth.is_nan() || depth <= 1e-9 {
            return None;
        }
        let tau = (0.5 * FIELD_OF_VIEW).tan();
        let xn = rel.dot(f.right) / (depth * tau * self.aspect());
        let yn = rel.dot(f.up) / (depth * tau);
        Some([
            0.5 * (xn + 1.0) * self.viewport[0],
            0.5 * (1.0 - yn) * self.viewport[1],
        ])
    }

    /// The clip-space matrix $P V$ for WebGL (column-major, 16 values): the view
    /// $V = [r\ u\ {-f}]^T (x - e)$ and the OpenGL perspective with
    /// $\cot(\mathrm{fov}/2)$, aspect $a$ and near and far planes $d/100$ and $4d$.
    #[must_use]
    pub fn view_projection(&self) -> [f32; 16] {
        let f = self.frame();
        let cot = 1.0 / (0.5 * FIELD_OF_VIEW).tan();
        let (near, far) = (0.01 * self.distance, 4.0 * self.distance);
        let rows = [f.right, f.up, -f.forward];
        let t = rows.map(|r| -r.dot(f.eye));
        // View rows (as 4-vectors) scaled by the projection.
        let sx = cot / self.aspect();
        let a = (far + near) / (near - far);
        let b = 2.0 * far * near / (near - far);
        let row = |k: usize| [rows[k].x, rows[k].y, rows[k].z, t[k]];
        let (r0, r1, r2) = (row(0), row(1), row(2));
        let clip = [
            r0.map(|v| sx * v),
            r1.map(|v| cot * v),
            [a * r2[0], a * r2[1], a * r2[2], a * r2[3] + b],
            r2.map(|v| -v),
        ];
        let mut out = [0.0f32; 16];
        for (c, column) in out.chunks_exact_mut(4).enumerate() {
            for (r, value) in column.iter_mut().enumerate() {
                *value = clip[r][c] as f32;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::framing([[-12.0, 0.0, 0.0], [12.0, 1.0, 16.0]], [800.0, 500.0])
    }

    /// The matrix the page draws with maps a point to the pixel the pointer's ray goes
    /// through: clip coordinates from `view_projection`, divided by w, are the NDC of
    /// `project`, and `ray` through that pixel passes through the point.
    #[test]
    fn drawing_and_picking_agree() {
        let c = camera();
        let m = c.view_projection();
        for p in [
            DVec3::new(6.0, 0.5, 8.0),
            DVec3::new(-11.0, 0.0, 1.0),
            DVec3::new(0.0, 3.0, 15.0),
        ] {
            let clip: Vec<f64> = (0..4)
                .map(|r| {
                    (0..3).map(|k| f64::from(m[4 * k + r]) * p[k]).sum::<f64>()
                        + f64::from(m[12 + r])
                })
                .collect();
            let ndc = [clip[0] / clip[3], clip[1] / clip[3], clip[2] / clip[3]];
            let px = c.project(p).expect("in front");
            let from_ndc = [
                0.5 * (ndc[0] + 1.0) * c.viewport[0],
                0.5 * (1.0 - ndc[1]) * c.viewport[1],
            ];
            assert!((px[0] - from_ndc[0]).abs() < 1e-3 && (px[1] - from_ndc[1]).abs() < 1e-3);
            assert!(ndc[2].abs() < 1.0, "inside the depth range: {ndc:?}");
            let (o, d) = c.ray(px[0], px[1]).expect("ray");
            let t = (p - o).dot(d);
            assert!((o + t * d - p).length() < 1e-9 * t.max(1.0), "{p}");
        }
    }

    /// The framed box is seen whole: its corners land inside the viewport.
    #[test]
    fn the_framed_box_is_inside_the_viewport() {
        for viewport in [[800.0, 500.0], [400.0, 900.0]] {
            let c = Camera::framing([[-12.0, 0.0, 0.0], [12.0, 1.0, 16.0]], viewport);
            for k in 0..8 {
                let p = DVec3::new(
                    if k & 1 == 0 { -12.0 } else { 12.0 },
                    if k & 2 == 0 { 0.0 } else { 1.0 },
                    if k & 4 == 0 { 0.0 } else { 16.0 },
                );
                let s = c.project(p).expect("in front");
                assert!(
                    (0.0..=viewport[0]).contains(&s[0]) && (0.0..=viewport[1]).contains(&s[1]),
                    "{p} at {s:?} in {viewport:?}"
                );
            }
        }
    }

    /// Bad input changes nothing and builds no ray.
    #[test]
    fn bad_input_is_ignored() {
        let mut c = camera();
        let before = c;
        c.orbit(f64::NAN, 1.0);
        assert_eq!(c, before);
        assert!(c.ray(f64::INFINITY, 0.0).is_none());
        c.resize([0.0, f64::NAN]);
        assert_eq!(c.viewport, [1.0, 1.0]);
        c.orbit(0.0, 1e9);
        assert!(c.pitch <= PITCH_MAX);
    }
}
