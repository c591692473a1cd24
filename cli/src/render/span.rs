//! The columns of one pixel row a triangle covers, found without testing every column of
//! its bounding box: a long thin triangle (a block's side face, a page's rim) spans a
//! large box but covers few of its pixels, and the rasterizer ([`super::raster`]) would spend
//! most of its time rejecting the rest one by one.
//!
//! The test is the rasterizer's own: pixel centre $p$ lies inside edge $i$ when its
//! barycentric coordinate $\lambda_i = E_i(p) / E$ is not negative, with the edge
//! function $E_i(p) = (b_x - a_x)(p_y - a_y) - (b_y - a_y)(p_x - a_x)$. Along a row $p_y$ is
//! fixed, and each floating-point step of $E_i(p) / E$ (a subtraction, a product with a
//! constant, a subtraction from a constant, a division by a constant) is correctly rounded,
//! hence monotone in $p_x$; so the computed $\lambda_i$ is monotone in the column (signed
//! zeros compare equal, as the test treats them). The columns inside edge $i$ are therefore
//! a prefix or a suffix of the row, found by bisection, and the covered columns are the
//! intersection of three such intervals. The rasterizer still tests every column of the
//! span, so it draws exactly what testing the whole box draws, in the same order.
//! Monotonicity needs finite arithmetic: screen coordinates or an area too large for the
//! products to stay finite give the whole row.

/// Largest magnitude of a screen coordinate and of twice the area for which no step of an
/// edge function or its division by the area can overflow ($2^{40}$: products of
/// differences stay below $2^{82}$, quotients by an area of at least $10^{-12}$ below
/// $2^{122}$).
const FINITE: f32 = 1_099_511_627_776.0;

/// Edge function: twice the signed area of $(a, b, p)$ in screen coordinates.
#[inline]
#[must_use]
pub fn edge(a: [f32; 2], b: [f32; 2], p: [f32; 2]) -> f32 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// The barycentric coordinates $\lambda_i = E_i(p) / E$ of the pixel centre `p` in the
/// triangle `screen` of twice the signed area `area`.
#[inline]
#[must_use]
pub fn barycentric(screen: &[[f32; 2]; 3], area: f32, p: [f32; 2]) -> [f32; 3] {
    [
        edge(screen[1], screen[2], p) / area,
        edge(screen[2], screen[0], p) / area,
        edge(screen[0], screen[1], p) / area,
    ]
}

/// The columns `first..=last` of `x0..=x1` in the row whose pixel centres have $p_y$ = `y`
/// that can be inside the triangle `screen` of twice the signed area `area` (module docs):
/// every column outside them has a negative [`barycentric`] coordinate; `None` when every
/// column has one (or `x0 > x1`).
#[must_use]
pub fn row_span(
    screen: &[[f32; 2]; 3],
    area: f32,
    y: f32,
    x0: usize,
    x1: usize,
) -> Option<(usize, usize)> {
    if x0 > x1 {
        return None;
    }
    let bounded = |v: f32| v.abs() <= FINITE;
    if !(screen.iter().flatten().all(|&v| bounded(v)) && bounded(area) && bounded(y)) {
        return Some((x0, x1));
    }
    let (mut first, mut last) = (x0, x1);
    for (a, b) in [(1, 2), (2, 0), (0, 1)] {
        let outside = |x: usize| edge(screen[a], screen[b], [x as f32 + 0.5, y]) / area < 0.0;
        match (outside(first), outside(last)) {
            (false, false) => {}
            (true, true) => return None,
            // A prefix is inside: the last column inside is in first..last.
            (false, true) => last = partition(first, last, &|x| !outside(x)) - 1,
            // A suffix is inside: the first column inside is in first+1..=last.
            (true, false) => first = partition(first, last, &outside),
        }
    }
    Some((first, last))
}

/// The first column of `lo..=hi` where `holds` fails, for `holds` true at `lo`, false at
/// `hi`, and true on a prefix (bisection).
fn partition(mut lo: usize, mut hi: usize, holds: &impl Fn(usize) -> bool) -> usize {
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if holds(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small linear congruential generator (deterministic test triangles).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self, scale: f32) -> f32 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            scale * ((self.0 >> 40) as f32 / (1u64 << 24) as f32) - 0.25 * scale
        }
    }

    /// The span holds exactly the columns that pass the rasterizer's test, for slivers,
    /// large triangles, both windings and triangles partly outside the row.
    #[test]
    fn span_is_exactly_the_covered_columns() {
        let mut rng = Lcg(7);
        let mut covered = 0;
        for k in 0..2000 {
            let scale = if k % 2 == 0 { 80.0 } else { 8.0 };
            let mut screen = [[0.0; 2]; 3];
            for c in &mut screen {
                *c = [rng.next(scale), rng.next(scale)];
            }
            if k % 3 == 0 {
                // A sliver: the third corner close to the first edge.
                let t = 0.37;
                screen[2] = [
                    screen[0][0] + t * (screen[1][0] - screen[0][0]) + 0.3,
                    screen[0][1] + t * (screen[1][1] - screen[0][1]),
                ];
            }
            let area = edge(screen[0], screen[1], screen[2]);
            if area.abs() <= 1e-12 {
                continue;
            }
            for y in 0..60 {
                let py = y as f32 + 0.5;
                let (x0, x1) = (3, 57);
                let brute: Vec<usize> = (x0..=x1)
                    .filter(|&x| {
                        let l = barycentric(&screen, area, [x as f32 + 0.5, py]);
                        !l.iter().any(|&v| v < 0.0)
                    })
                    .collect();
                covered += brute.len();
                let span = row_span(&screen, area, py, x0, x1);
                let listed: Vec<usize> = span.map_or(Vec::new(), |(a, b)| (a..=b).collect());
                assert_eq!(listed, brute, "triangle {screen:?}, row {y}");
            }
        }
        assert!(covered > 10_000, "{covered}");
    }

    /// Coordinates too large to keep the arithmetic finite give the whole row.
    #[test]
    fn huge_coordinates_give_the_whole_row() {
        let screen = [[0.0, 0.0], [1e30, 1.0], [0.0, 2.0]];
        let area = edge(screen[0], screen[1], screen[2]);
        assert_eq!(row_span(&screen, area, 0.5, 2, 9), Some((2, 9)));
    }
}
