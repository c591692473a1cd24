//! Small `f64` vector helpers for meshing, for points in the XY plane (`D = 2`) and in space
//! (`D = 3`), and the "nearest valid neighbour" fallback for degenerate directions. Every
//! square root goes through the `folio_kernels::math` shim.

use alloc::vec::Vec;

use folio_kernels::{Real, math};

/// Vectors shorter than this have no direction (the kernels' `f64` length floor, so that
/// $1/\lVert v\rVert$ stays finite).
pub(super) const LENGTH_FLOOR: f64 = <f64 as Real>::LENGTH_FLOOR;

/// $a + b$.
#[inline]
#[must_use]
pub(super) fn add<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|k| a[k] + b[k])
}

/// $a - b$.
#[inline]
#[must_use]
pub(super) fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|k| a[k] - b[k])
}

/// $s\thinspace a$.
#[inline]
#[must_use]
pub(super) fn scale<const D: usize>(a: [f64; D], s: f64) -> [f64; D] {
    a.map(|c| s * c)
}

/// $a \cdot b$.
#[inline]
#[must_use]
pub(super) fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    a.iter().zip(&b).map(|(x, y)| x * y).sum()
}

/// $\lVert a \rVert$.
#[inline]
#[must_use]
pub(super) fn norm<const D: usize>(a: [f64; D]) -> f64 {
    math::sqrt::<f64>(dot(a, a))
}

/// $\lVert b - a \rVert$.
#[inline]
#[must_use]
pub(super) fn distance<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    norm(sub(b, a))
}

/// $a \times b$.
#[inline]
#[must_use]
pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// $a / \lVert a \rVert$, or `None` if $\lVert a \rVert$ is below `floor` (or not finite).
#[inline]
#[must_use]
pub(super) fn unit_above<const D: usize>(a: [f64; D], floor: f64) -> Option<[f64; D]> {
    let len = norm(a);
    (len.is_finite() && len >= floor).then(|| scale(a, 1.0 / len))
}

/// $a / \lVert a \rVert$, or `None` for a vector shorter than [`LENGTH_FLOOR`].
#[inline]
#[must_use]
pub(super) fn unit<const D: usize>(a: [f64; D]) -> Option<[f64; D]> {
    unit_above(a, LENGTH_FLOOR)
}

/// Lifts an XY point or direction to space at height `z`.
#[inline]
#[must_use]
pub(super) fn lift(a: [f64; 2], z: f64) -> [f64; 3] {
    [a[0], a[1], z]
}

/// Length of the polyline through `points`, $\sum_k \lVert p_{k+1} - p_k \rVert$.
#[must_use]
pub(super) fn polyline_length<const D: usize>(points: &[[f64; D]]) -> f64 {
    points.windows(2).map(|w| distance(w[0], w[1])).sum()
}

/// Arc length at each point of the polyline divided by `scale_length` and clamped to
/// $[0, 1]$ (a texture coordinate along the curve).
#[must_use]
pub(super) fn arc_parameter<const D: usize>(points: &[[f64; D]], scale_length: f64) -> Vec<f64> {
    let mut s = 0.0;
    let mut previous = points.first().copied();
    points
        .iter()
        .map(|&p| {
            if let Some(q) = previous {
                s += distance(q, p);
            }
            previous = Some(p);
            (s / scale_length).clamp(0.0, 1.0)
        })
        .collect()
}

/// Replaces each missing value by the nearest valid one before it; missing values before
/// the first valid one take that first valid one; if none is valid, all take `default`.
/// This is the fallback for degenerate directions (a vertex without a normal takes its
/// predecessor's).
#[must_use]
pub(super) fn fill_gaps<T: Copy>(raw: &[Option<T>], default: T) -> Vec<T> {
    let first = raw.iter().flatten().next().copied().unwrap_or(default);
    fill_forward(raw)
        .into_iter()
        .map(|v| v.unwrap_or(first))
        .collect()
}

/// For each index, the nearest valid value at or before it (`None` before the first one).
#[must_use]
pub(super) fn fill_forward<T: Copy>(raw: &[Option<T>]) -> Vec<Option<T>> {
    let mut last = None;
    raw.iter()
        .map(|v| {
            last = v.or(last);
            last
        })
        .collect()
}

/// For each index, the nearest valid value at or after it (`None` after the last one).
#[must_use]
pub(super) fn fill_backward<T: Copy>(raw: &[Option<T>]) -> Vec<Option<T>> {
    let mut next = None;
    let mut out: Vec<Option<T>> = raw
        .iter()
        .rev()
        .map(|v| {
            next = v.or(next);
            next
        })
        .collect();
    out.reverse();
    out
}
