//! Triangle rasterization: near-plane clipping, projection, optional back-face culling,
//! edge functions at pixel centres and perspective-correct interpolation.

use glam::Vec3;

use super::camera::Camera;
use super::span::{barycentric, edge, row_span};

/// Attributes interpolated across a triangle: world position (3), normal (3), UV (2).
pub const ATTRIBUTES: usize = 8;

/// A triangle corner: its view-space position ([`Camera::view_of`]) and its attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// View coordinates $(x_v, y_v, z_v)$.
    pub view: Vec3,
    /// Attributes to interpolate.
    pub attributes: [f32; ATTRIBUTES],
}

/// One covered pixel centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// Pixel column.
    pub x: usize,
    /// Pixel row (down).
    pub y: usize,
    /// Inverse depth $1/z_v$ (larger is nearer).
    pub inverse_depth: f32,
    /// Perspective-correct attributes.
    pub attributes: [f32; ATTRIBUTES],
}

/// Linear interpolation of two corners at parameter `t`.
fn lerp(a: &Corner, b: &Corner, t: f32) -> Corner {
    let mut c = *a;
    c.view = a.view + t * (b.view - a.view);
    for k in 0..ATTRIBUTES {
        c.attributes[k] = a.attributes[k] + t * (b.attributes[k] - a.attributes[k]);
    }
    c
}

/// The polygon (at most 4 corners) left of `triangle` on the near side $z_v \ge$ `near`
/// (Sutherland–Hodgman against one plane), in the triangle's winding.
fn clip_near(triangle: &[Corner; 3], near: f32) -> ([Corner; 4], usize) {
    let mut out = [triangle[0]; 4];
    let mut n = 0;
    for k in 0..3 {
        let (a, b) = (&triangle[k], &triangle[(k + 1) % 3]);
        let (a_in, b_in) = (a.view[2] >= near, b.view[2] >= near);
        if a_in && n < 4 {
            out[n] = *a;
            n += 1;
        }
        if a_in != b_in && n < 4 {
            let t = (near - a.view[2]) / (b.view[2] - a.view[2]);
            out[n] = lerp(a, b, t);
            n += 1;
        }
    }
    (out, n)
}

/// Calls `fragment` for every pixel centre of `camera`'s viewport covered by `triangle`.
///
/// The triangle is clipped at the near plane; each piece is projected
/// ([`Camera::project`]), and a pixel centre $p$ is covered when its barycentric
/// coordinates $\lambda_i = E_i(p) / E$ (edge functions over twice the signed area) are all
/// $\ge 0$; each row tests only the columns of its [`row_span`], which holds every covered
/// one. Attributes $a$ are interpolated perspective-correctly,
/// $a(p) = \sum_i \lambda_i a_i / z_i \thinspace/\thinspace \sum_i \lambda_i / z_i$.
///
/// With `cull`, triangles that are clockwise seen from the eye (back faces of a mesh whose
/// triangles are counter-clockwise seen from the side their normals point to) are skipped.
/// Corners with a non-finite coordinate skip the triangle, as do zero-area triangles.
pub fn rasterize(
    camera: &Camera,
    triangle: &[Corner; 3],
    cull: bool,
    mut fragment: impl FnMut(Fragment),
) {
    let all_finite = triangle
        .iter()
        .all(|c| c.view.is_finite() && c.attributes.iter().all(|v| v.is_finite()));
    if !all_finite {
        return;
    }
    let (polygon, n) = clip_near(triangle, camera.near);
    for k in 1..n.saturating_sub(1) {
        let piece = [polygon[0], polygon[k], polygon[k + 1]];
        rasterize_clipped(camera, &piece, cull, &mut fragment);
    }
}

/// [`rasterize`] of a triangle in front of the near plane.
fn rasterize_clipped(
    camera: &Camera,
    triangle: &[Corner; 3],
    cull: bool,
    fragment: &mut impl FnMut(Fragment),
) {
    let screen = triangle.each_ref().map(|c| camera.project(c.view));
    let inverse = triangle.each_ref().map(|c| 1.0 / c.view[2]);
    let area = edge(screen[0], screen[1], screen[2]);
    // Screen y points down: a counter-clockwise (front-facing) triangle has area < 0.
    if area.is_nan() || area.abs() <= 1e-12 || (cull && area > 0.0) {
        return;
    }
    let (width, height) = (camera.width as f32, camera.height as f32);
    let min_x = screen.iter().map(|s| s[0]).fold(f32::MAX, f32::min);
    let max_x = screen.iter().map(|s| s[0]).fold(f32::MIN, f32::max);
    let min_y = screen.iter().map(|s| s[1]).fold(f32::MAX, f32::min);
    let max_y = screen.iter().map(|s| s[1]).fold(f32::MIN, f32::max);
    if max_x < 0.0 || max_y < 0.0 || min_x >= width || min_y >= height {
        return;
    }
    // Pixel centres x + 0.5 in [min, max]; the casts saturate.
    let x0 = (min_x - 0.5).ceil().max(0.0) as usize;
    let x1 = ((max_x - 0.5).floor().min(width - 1.0)).max(-1.0) as isize;
    let y0 = (min_y - 0.5).ceil().max(0.0) as usize;
    let y1 = ((max_y - 0.5).floor().min(height - 1.0)).max(-1.0) as isize;
    let (Ok(x1), Ok(y1)) = (usize::try_from(x1), usize::try_from(y1)) else {
        return;
    };
    let weighted: [[f32; ATTRIBUTES]; 3] =
        [0, 1, 2].map(|i| triangle[i].attributes.map(|v| v * inverse[i]));
    for y in y0..=y1 {
        let py = y as f32 + 0.5;
        let Some((first, last)) = row_span(&screen, area, py, x0, x1) else {
            continue;
        };
        for x in first..=last {
            let p = [x as f32 + 0.5, py];
            let l = barycentric(&screen, area, p);
            if l.iter().any(|&v| v < 0.0) {
                continue;
            }
            let inverse_depth = l[0] * inverse[0] + l[1] * inverse[1] + l[2] * inverse[2];
            if inverse_depth.is_nan() || inverse_depth <= 0.0 {
                continue;
            }
            let mut attributes = [0.0; ATTRIBUTES];
            for (k, a) in attributes.iter_mut().enumerate() {
                *a = (l[0] * weighted[0][k] + l[1] * weighted[1][k] + l[2] * weighted[2][k])
                    / inverse_depth;
            }
            fragment(Fragment {
                x,
                y,
                inverse_depth,
                attributes,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::framing(
            Vec3::new(0.0, 10.0, 0.0),
            [[-1.0, 0.0, -1.0], [1.0, 0.0, 1.0]],
            [64, 64],
            0.0,
        )
    }

    fn corner(camera: &Camera, p: [f32; 3]) -> Corner {
        let mut attributes = [0.0; ATTRIBUTES];
        attributes[..3].copy_from_slice(&p);
        Corner {
            view: camera.view_of(p.into()),
            attributes,
        }
    }

    /// A square seen from straight above fills the viewport; its back is culled; the
    /// interpolated world position matches the pixel.
    #[test]
    fn square_fills_viewport_and_culls_back() {
        let c = camera();
        let p = [
            [-1.0, 0.0, -1.0],
            [-1.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 0.0, -1.0],
        ];
        // Counter-clockwise seen from +Y (the camera's side): (b - a) x (c - a) points +Y.
        let tris = [[p[0], p[1], p[2]], [p[0], p[2], p[3]]];
        let mut hits = vec![0u32; 64 * 64];
        for t in &tris {
            rasterize(&c, &t.map(|q| corner(&c, q)), true, |f| {
                hits[f.y * 64 + f.x] += 1;
                assert!((f.inverse_depth - 0.1).abs() < 1e-5);
                assert!(f.attributes[1].abs() < 1e-5);
            });
        }
        let covered = hits.iter().filter(|&&h| h > 0).count();
        assert!(covered >= 64 * 64 - 64, "{covered}");
        let mut back = 0;
        for t in &tris {
            let reversed = [t[0], t[2], t[1]];
            rasterize(&c, &reversed.map(|q| corner(&c, q)), true, |_| back += 1);
        }
        assert_eq!(back, 0, "back faces are culled");
    }

    #[test]
    fn degenerate_and_nan_triangles_draw_nothing() {
        let c = camera();
        let mut n = 0;
        let flat = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.5], [1.0, 0.0, 1.0]];
        rasterize(&c, &flat.map(|q| corner(&c, q)), false, |_| n += 1);
        let nan = [[f32::NAN, 0.0, 0.0], [0.5, 0.0, 0.5], [1.0, 0.0, -1.0]];
        rasterize(&c, &nan.map(|q| corner(&c, q)), false, |_| n += 1);
        let behind = [[0.0, 20.0, 0.0], [0.5, 20.0, 0.5], [1.0, 20.0, -1.0]];
        rasterize(&c, &behind.map(|q| corner(&c, q)), false, |_| n += 1);
        assert_eq!(n, 0);
    }

    /// A triangle crossing the near plane is clipped, not dropped or inverted.
    #[test]
    fn near_clipping_keeps_the_visible_part() {
        let c = camera();
        // Apex behind the eye (depth -10); the part with 0 < y < 6.7 is in view.
        let t = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 20.0, -3.0]];
        let mut n = 0;
        rasterize(&c, &t.map(|q| corner(&c, q)), false, |f| {
            assert!(f.inverse_depth > 0.0);
            n += 1;
        });
        assert!(n > 0);
    }
}
