//! Polylines in the pattern plane, for the tearing tests: a tear's length and how far a
//! point is from a tear.

/// Distance between pattern points `a` and `b`.
#[must_use]
pub fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
}

/// Length of the polyline `path`.
#[must_use]
pub fn length(path: &[[f64; 2]]) -> f64 {
    path.windows(2).map(|w| distance(w[0], w[1])).sum()
}

/// Distance from `p` to the polyline `path` (to its one point if it has one; NaN if it is
/// empty or anything is NaN).
#[must_use]
pub fn distance_to_path(p: [f64; 2], path: &[[f64; 2]]) -> f64 {
    let Some(&first) = path.first() else {
        return f64::NAN;
    };
    path.windows(2)
        .map(|w| {
            let e = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            let s = if len2 > 0.0 {
                (((p[0] - w[0][0]) * e[0] + (p[1] - w[0][1]) * e[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            distance(p, [w[0][0] + s * e[0], w[0][1] + s * e[1]])
        })
        .fold(distance(p, first), crate::least)
}

/// How far `path` strays from the hyperbola through its first point with foci `a` and `b`
/// (O'Keefe's path of a tear pulled from `a` and `b`): the largest
/// $\bigl|\thinspace|pa| - |pb| - d_0\bigr|$ over its points, $d_0$ that of the first
/// (NaN for an empty path).
#[must_use]
pub fn off_hyperbola(path: &[[f64; 2]], a: [f64; 2], b: [f64; 2]) -> f64 {
    let focal = |p: [f64; 2]| distance(p, a) - distance(p, b);
    let Some(&first) = path.first() else {
        return f64::NAN;
    };
    let d0 = focal(first);
    path.iter()
        .map(|&p| (focal(p) - d0).abs())
        .fold(0.0, crate::worst)
}
