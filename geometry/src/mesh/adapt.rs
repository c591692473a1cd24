//! Segment length adaptation (seed `000_…` Sec. 3.5, Fig. 9): the end vertex of an edge chain
//! is moved along the chain's last segment so that the chain has a prescribed length. It hides
//! the active page's stretch (a row of the page keeps the page width) and shears the fore-edge
//! of a page block (its top curve keeps the length of its bottom curve).

use super::vector::{add, distance, polyline_length, scale, sub, unit};

/// The end segment keeps at least this fraction of its unadapted length, so that a chain
/// whose other segments already exceed the target does not fold back over itself (its
/// length then stays above the target).
pub const MIN_END_FRACTION: f64 = 0.01;

/// Adapts the length of the chain $c_0, \dots, c_{n-1}$ to `target` (seed `000_…` Sec. 3.5,
/// "Segment length adaptation") by translating $c_{n-1}$ along the last segment:
/// $$L_< = \sum_{k=0}^{n-3} \lVert c_{k+1} - c_k \rVert, \quad
///   u = \frac{c_{n-1} - c_{n-2}}{\lVert c_{n-1} - c_{n-2} \rVert}, \quad
///   c_{n-1} \leftarrow c_{n-2} + \max\negthinspace\big(L - L_<,\thickspace f \lVert c_{n-1} - c_{n-2} \rVert\big)\thinspace u$$
/// with $L$ = `target` and $f$ = [`MIN_END_FRACTION`], so the chain's length becomes exactly
/// $L$ whenever $L - L_<$ is at least $f$ times the last segment.
///
/// Fallbacks: a zero-length last segment moves along the nearest earlier segment's
/// direction; a chain with fewer than two points, without any segment of nonzero length, or
/// with a `target` that is negative or not finite is left unchanged. `D` is 2 (XY curves)
/// or 3 (page rows).
pub fn adapt_length<const D: usize>(chain: &mut [[f64; D]], target: f64) {
    if !(target.is_finite() && target >= 0.0) {
        return;
    }
    let Some((last, head)) = chain.split_last_mut() else {
        return;
    };
    let Some(&previous) = head.last() else {
        return;
    };
    let Some(direction) = end_direction(head, *last) else {
        return;
    };
    let end_length = distance(previous, *last);
    let remaining = target - polyline_length(head);
    let length = remaining.max(MIN_END_FRACTION * end_length);
    *last = add(previous, scale(direction, length));
}

/// The unit direction of the chain's last segment `head.last() -> last`, or of the nearest
/// earlier segment of nonzero length.
fn end_direction<const D: usize>(head: &[[f64; D]], last: [f64; D]) -> Option<[f64; D]> {
    let (&previous, earlier) = head.split_last()?;
    unit(sub(last, previous)).or_else(|| {
        earlier
            .iter()
            .rev()
            .zip(head.iter().rev())
            .find_map(|(&a, &b)| unit(sub(b, a)))
    })
}
