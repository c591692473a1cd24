//! The rasterizer's vectors are glam's `f32` [`Vec3`]; this adds the one operation whose
//! edge cases Folio fixes itself.

use glam::Vec3;

/// $a / \lVert a \rVert$ (as $a \cdot (1/\lVert a \rVert)$), or `fallback` when
/// $\lVert a \rVert$ is zero or not finite. (glam's `normalize_or` tests the reciprocal
/// instead, which also falls back for lengths below $1/f_{\max}$.)
#[inline]
#[must_use]
pub fn normalize_or(a: Vec3, fallback: Vec3) -> Vec3 {
    let len = a.length();
    if len > 0.0 && len.is_finite() {
        a * (1.0 / len)
    } else {
        fallback
    }
}
