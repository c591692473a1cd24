//! The few `f32` 3-vector operations the rasterizer needs, on plain arrays.

/// A 3-vector.
pub type V3 = [f32; 3];

/// $a + b$.
#[inline]
#[must_use]
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// $a - b$.
#[inline]
#[must_use]
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// $s\,a$.
#[inline]
#[must_use]
pub fn scale(a: V3, s: f32) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// $a \cdot b$.
#[inline]
#[must_use]
pub fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// $a \times b$.
#[inline]
#[must_use]
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// $\lVert a \rVert$.
#[inline]
#[must_use]
pub fn length(a: V3) -> f32 {
    dot(a, a).sqrt()
}

/// $a / \lVert a \rVert$, or `fallback` for a zero or non-finite `a`.
#[inline]
#[must_use]
pub fn normalize_or(a: V3, fallback: V3) -> V3 {
    let len = length(a);
    if len > 0.0 && len.is_finite() {
        scale(a, 1.0 / len)
    } else {
        fallback
    }
}

/// Every component finite.
#[inline]
#[must_use]
pub fn finite(a: V3) -> bool {
    a.iter().all(|c| c.is_finite())
}
