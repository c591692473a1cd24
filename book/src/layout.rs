//! The book's layout from its parameters (seed `000_…` Sec. 3.1, Fig. 2 and 4): page counts,
//! page size and thickness, the binding edge, the two page-block midlines and the hard cover.
//!
//! Cross-section in the XY plane (Z runs along the binding, the page spans $z \in [0, H]$):
//! the binding edge joins $b_1 = (-w/2, y_0)$ and $b_2 = (w/2, y_0)$ with $w$ the thickness of
//! all pages together and $y_0$ the cover thickness (0 without cover), so the spine rests on
//! the table $y = 0$. Each block's midline (the bottom of the block, the side facing the cover)
//! starts at its binding node ($b_1$ left, $b_2$ right) and runs outward; its pages are stacked
//! on the material side, which faces the middle of the book. The cover boards are straight
//! segments from $b_1$ and $b_2$, one page width plus the overhang long. The initial midlines
//! lie flat on the cover; the book settles them into their rest shape (glue, bending, gravity).

use alloc::vec::Vec;
use folio_kernels::math;
use folio_kernels::setting::{SettingError, require, require_at_least};

pub use folio_geometry::BlockSide;

/// A point in the XY plane.
pub type Point2 = [f64; 2];

/// The parameters of a book. Defaults: seed `000_…` Sec. 5.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BookParams {
    /// Pages in the book (leaves: one sheet is one page here), at least 1.
    pub total_pages: u32,
    /// Pages in the left block (the rest are in the right block), at most `total_pages`.
    pub left_pages: u32,
    /// Page width (page units; 12 in the seed).
    pub page_width: f64,
    /// Page height over page width (the seed scales the height by the book's aspect ratio;
    /// Folio's default is ISO 216's $\sqrt 2$).
    pub aspect_ratio: f64,
    /// Thickness of one page (page units; 0.0075 in the seed).
    pub page_thickness: f64,
    /// Hard cover present.
    pub cover: bool,
    /// Thickness of a cover board (page units); ignored without cover.
    pub cover_thickness: f64,
    /// How far the cover reaches past the pages at the fore-edge, head and tail (page units).
    pub cover_overhang: f64,
    /// Nodes of each block's midline, binding node included (the seed's 15).
    pub midline_nodes: usize,
}

impl Default for BookParams {
    fn default() -> Self {
        Self {
            total_pages: 100,
            left_pages: 50,
            page_width: 12.0,
            aspect_ratio: core::f64::consts::SQRT_2,
            page_thickness: 0.0075,
            cover: true,
            cover_thickness: 0.06,
            cover_overhang: 0.25,
            midline_nodes: 15,
        }
    }
}

/// The largest page width, page height, book thickness or cover size (page units): $10^4$
/// times the seed's page width. Beyond it the squared distances of collision tests and
/// grabs leave the `f32` range (and, near $10^{150}$, the `f64` one), so a grab could no
/// longer tell nodes apart.
pub const MAX_EXTENT: f64 = 1.2e5;

/// The most pages a book may have: more only make every frame slower.
pub const MAX_PAGES: u32 = 100_000;

/// The thinnest paper relative to the page width: $10^{-6} W$, about eight `f32` roundings
/// of a coordinate on the page ($\varepsilon_{32} W \approx 1.2 \cdot 10^{-7} W$); thinner
/// paper (a subnormal thickness) is below what the page's coordinates resolve.
pub const MIN_THICKNESS_RATIO: f64 = 1e-6;

impl BookParams {
    /// Page height (page units).
    #[must_use]
    pub fn page_height(&self) -> f64 {
        self.page_width * self.aspect_ratio
    }

    /// Checks every field (type docs).
    ///
    /// # Errors
    /// The first unusable field, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let pages = |n: u32| f64::from(n);
        require(
            (1..=MAX_PAGES).contains(&self.total_pages),
            "total_pages",
            "from 1 to 100000",
            pages(self.total_pages),
        )?;
        require(
            self.left_pages <= self.total_pages,
            "left_pages",
            "at most total_pages",
            pages(self.left_pages),
        )?;
        for (field, v) in [
            ("page_width", self.page_width),
            ("aspect_ratio", self.aspect_ratio),
            ("page_thickness", self.page_thickness),
        ] {
            require(v.is_finite() && v > 0.0, field, "finite and > 0", v)?;
        }
        for (field, v) in [
            ("cover_thickness", self.cover_thickness),
            ("cover_overhang", self.cover_overhang),
        ] {
            require(v.is_finite() && v >= 0.0, field, "finite and >= 0", v)?;
        }
        let extents = [
            ("page_width", self.page_width, "at most 1.2e5 page units"),
            (
                "aspect_ratio",
                self.page_height(),
                "such that the page's height (aspect_ratio x page_width) is at most 1.2e5 \
                 page units",
            ),
            (
                "page_thickness",
                self.page_thickness * f64::from(self.total_pages),
                "such that the book's thickness (total_pages x page_thickness) is at most \
                 1.2e5 page units",
            ),
            (
                "cover_thickness",
                self.cover_thickness,
                "at most 1.2e5 page units",
            ),
            (
                "cover_overhang",
                self.cover_overhang,
                "at most 1.2e5 page units",
            ),
        ];
        for (field, v, requirement) in extents {
            require(v <= MAX_EXTENT, field, requirement, v)?;
        }
        require_at_least(
            "page_thickness",
            self.page_thickness,
            MIN_THICKNESS_RATIO * self.page_width,
            "1e-6 of the page width: thinner paper is below what the page's coordinates \
             resolve",
        )?;
        require(
            self.midline_nodes >= 3,
            "midline_nodes",
            "at least 3",
            self.midline_nodes as f64,
        )
    }
}

/// The book's cross-section at rest (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct BookLayout {
    /// The parameters it was built from.
    pub params: BookParams,
    /// Binding nodes $b_1$ (left) and $b_2$ (right).
    pub binding: [Point2; 2],
    /// The left block's midline from $b_1$ outward.
    pub left: Vec<Point2>,
    /// The right block's midline from $b_2$ outward.
    pub right: Vec<Point2>,
    /// Outer ends of the left and right cover boards (`None` without cover).
    pub cover_ends: Option<[Point2; 2]>,
}

impl BookLayout {
    /// The layout of `params` (module docs).
    ///
    /// # Errors
    /// As [`BookParams::validate`].
    pub fn new(params: BookParams) -> Result<Self, SettingError> {
        params.validate()?;
        let half = 0.5 * f64::from(params.total_pages) * params.page_thickness;
        let y0 = if params.cover {
            params.cover_thickness
        } else {
            0.0
        };
        let binding = [[-half, y0], [half, y0]];
        let segments = (params.midline_nodes - 1) as f64;
        let flat = |b: Point2, dir: f64| -> Vec<Point2> {
            (0..params.midline_nodes)
                .map(|k| [b[0] + dir * params.page_width * k as f64 / segments, b[1]])
                .collect()
        };
        let reach = params.page_width + params.cover_overhang;
        let cover_ends = params
            .cover
            .then_some([[-half - reach, y0], [half + reach, y0]]);
        Ok(Self {
            params,
            binding,
            left: flat(binding[0], -1.0),
            right: flat(binding[1], 1.0),
            cover_ends,
        })
    }

    /// The midline of the block on `side`.
    #[must_use]
    pub fn midline(&self, side: BlockSide) -> &[Point2] {
        match side {
            BlockSide::Left => &self.left,
            BlockSide::Right => &self.right,
        }
    }

    /// Pages in the block on `side`.
    #[must_use]
    pub fn pages(&self, side: BlockSide) -> u32 {
        match side {
            BlockSide::Left => self.params.left_pages,
            BlockSide::Right => self.params.total_pages - self.params.left_pages,
        }
    }

    /// The binding parameter $q$ of an active stack of `active` pages taken from between
    /// the blocks when `left` pages remain on the left (seed `000_…` Sec. 3.2, after eq. 7):
    /// $q = (n_{left} + n_{active}/2) / n_{total}$.
    #[must_use]
    pub fn binding_parameter(&self, left: u32, active: u32) -> f64 {
        (f64::from(left) + 0.5 * f64::from(active)) / f64::from(self.params.total_pages)
    }
}

/// Unit normal on a block's material side of the direction `t` (seed Sec. 3.1 layout):
/// the left block's pages lie right of its outward direction of travel, the right block's
/// left of it. Returns `[0, 0]` for a zero direction.
#[must_use]
pub fn material_normal(side: BlockSide, t: Point2) -> Point2 {
    let len = math::sqrt::<f64>(t[0] * t[0] + t[1] * t[1]);
    if len <= 0.0 || !len.is_finite() {
        return [0.0, 0.0];
    }
    let (x, y) = (t[0] / len, t[1] / len);
    match side {
        BlockSide::Left => [y, -x],
        BlockSide::Right => [-y, x],
    }
}

/// The curve at distance `distance` from `midline` on the material side of `side`: each node
/// moved along the normalized mean of its adjacent segment normals (a node whose segments
/// are degenerate keeps its neighbour's normal, or none).
#[must_use]
pub fn offset_curve(midline: &[Point2], side: BlockSide, distance: f64) -> Vec<Point2> {
    let n = midline.len();
    let segment_normal = |k: usize| {
        let (a, b) = (midline[k], midline[k + 1]);
        material_normal(side, [b[0] - a[0], b[1] - a[1]])
    };
    (0..n)
        .map(|k| {
            let before = if k > 0 {
                segment_normal(k - 1)
            } else {
                [0.0; 2]
            };
            let after = if k + 1 < n {
                segment_normal(k)
            } else {
                [0.0; 2]
            };
            let sum = [before[0] + after[0], before[1] + after[1]];
            let len = math::sqrt::<f64>(sum[0] * sum[0] + sum[1] * sum[1]);
            let normal = if len > 1e-12 {
                [sum[0] / len, sum[1] / len]
            } else {
                [0.0, 0.0]
            };
            [
                midline[k][0] + distance * normal[0],
                midline[k][1] + distance * normal[1],
            ]
        })
        .collect()
}

/// The block's rounded spine edge as a polyline, for laying a page around it: from `from`
/// (the page's binding point) to `to` (the block's top over its binding node, `center` + $c$
/// times its normal), about `center`, in chords of at most `step` (page units, positive).
/// The direction turns the shorter way from $d_0 = (\text{from} - \text{center})/r_0$ to
/// $d_1 = (\text{to} - \text{center})/r_1$ in $2^k$ equal rotations and the radius goes
/// linearly from $r_0$ to $r_1$ with it, so for $r_0 = r_1 = c$ it is the quarter circle of
/// the collision's start cap ([`folio_geometry::Corner::start`]), where the binding point
/// lies. Square roots only (`atan2`, `sin` and `cos` added 10.9 KB to the Cortex-M4F
/// firmware): the rotation by the whole turn, $(\cos\varphi, \sin\varphi) = (d_0\cdot d_1,\ d_0\times d_1)$,
/// is halved $k \le 12$ times by $\cos\frac\varphi2 = \sqrt{(1 + \cos\varphi)/2}$,
/// $\sin\frac\varphi2 = \sin\varphi / (2\cos\frac\varphi2)$ (a half turn goes
/// counter-clockwise) until a piece's chord $r_{max}\sqrt{2(1 - \cos\varphi)}$ is at most
/// `step`. Both ends included; just the two ends when either radius is zero or not finite.
#[must_use]
pub fn spine_arc(from: Point2, center: Point2, to: Point2, step: f64) -> Vec<Point2> {
    let (r0, r1) = (distance(center, from), distance(center, to));
    let usable = r0 > 0.0 && r1 > 0.0 && r0.is_finite() && r1.is_finite() && step > 0.0;
    if !usable {
        return alloc::vec![from, to];
    }
    let d0 = [(from[0] - center[0]) / r0, (from[1] - center[1]) / r0];
    let d1 = [(to[0] - center[0]) / r1, (to[1] - center[1]) / r1];
    let (mut cos, mut sin) = (d0[0] * d1[0] + d0[1] * d1[1], d0[0] * d1[1] - d0[1] * d1[0]);
    let r_max = r0.max(r1);
    let mut pieces = 1usize;
    while pieces < 4096 && r_max * math::sqrt::<f64>((2.0 * (1.0 - cos)).max(0.0)) > step {
        let half_cos = math::sqrt::<f64>((0.5 * (1.0 + cos)).max(0.0));
        let half_sin = if half_cos > 1e-8 {
            0.5 * sin / half_cos
        } else if sin < 0.0 {
            -1.0
        } else {
            1.0
        };
        let norm = math::sqrt::<f64>(half_cos * half_cos + half_sin * half_sin);
        (cos, sin) = (half_cos / norm, half_sin / norm);
        pieces *= 2;
    }
    let mut arc = Vec::with_capacity(pieces + 1);
    arc.push(from);
    let mut d = d0;
    for k in 1..pieces {
        d = [cos * d[0] - sin * d[1], sin * d[0] + cos * d[1]];
        let r = r0 + (r1 - r0) * (k as f64 / pieces as f64);
        arc.push([center[0] + r * d[0], center[1] + r * d[1]]);
    }
    arc.push(to);
    arc
}

/// `count` points along `curve`, each at straight distance `spacing` from the one before
/// (the first is the curve's first node; past the curve's end the walk runs on straight
/// along the last segment): a page grid column per point has its edges at rest length
/// across, however tightly the curve bends, where points at equal arc lengths would put
/// the chords of a bend closer than `spacing` (a quarter circle of radius $r$ walked in
/// steps of $r\pi/2$: chords of $r\sqrt 2$, 10 % short). On the segment from $a$ to $b$
/// the next point is $a + t(b - a)$ with the exit root of
/// $\lVert a + t(b - a) - p\rVert = $ `spacing` ($p$ the point before). A curve with fewer than
/// two distinct nodes, or a spacing that is not positive and finite, yields copies of its
/// first node (nothing when it is empty).
#[must_use]
pub fn walk_chords(curve: &[Point2], spacing: f64, count: usize) -> Vec<Point2> {
    walk(curve, spacing, count, Step::Chord)
}

/// Points at arc lengths `s_k = k * spacing`, `k = 0..count`, along `curve`, continuing
/// straight along the last segment past the curve's end. A curve with fewer than two
/// distinct nodes, or a spacing that is not positive and finite, yields copies of its first
/// node (nothing when it is empty).
#[must_use]
pub fn resample(curve: &[Point2], spacing: f64, count: usize) -> Vec<Point2> {
    walk(curve, spacing, count, Step::ArcLength)
}

/// How [`walk`] measures `spacing`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Step {
    /// Along the curve ([`resample`]).
    ArcLength,
    /// Straight from the point before ([`walk_chords`]).
    Chord,
}

/// The walk of [`resample`] and [`walk_chords`]: point $k$ on the segment from $a$ to $b$
/// at $a + t(b - a)$, with $t = (s_k - s_a)/\lVert b - a\rVert$ ($s_a$ the arc length at $a$)
/// by arc length, or the exit root of $\lVert a + t(b - a) - p\rVert$ = `spacing` ($p$
/// the point before) by chord; the last segment runs on past its end.
fn walk(curve: &[Point2], spacing: f64, count: usize, step: Step) -> Vec<Point2> {
    let mut out = Vec::with_capacity(count);
    let Some(&first) = curve.first() else {
        return out;
    };
    let usable = spacing > 0.0 && spacing.is_finite();
    let mut point = first;
    // The walk is on the segment from `curve[next - 1]` (arc length `start`) to `curve[next]`.
    let (mut next, mut start) = (1, 0.0);
    for k in 0..count {
        let s = spacing * k as f64;
        while k > 0 && usable && next < curve.len() {
            let (a, b) = (curve[next - 1], curve[next]);
            let last = next + 1 == curve.len();
            let d = [b[0] - a[0], b[1] - a[1]];
            let len = distance(a, b);
            if len > 0.0 {
                let t = match step {
                    Step::ArcLength => (s - start) / len,
                    Step::Chord => {
                        // The walk's place on the segment lies within `spacing` of `point`,
                        // so the exit root is at or past it.
                        let e = [a[0] - point[0], a[1] - point[1]];
                        let half_b = e[0] * d[0] + e[1] * d[1];
                        let c = e[0] * e[0] + e[1] * e[1] - spacing * spacing;
                        let a2 = len * len;
                        (-half_b + math::sqrt::<f64>((half_b * half_b - a2 * c).max(0.0))) / a2
                    }
                };
                if t <= 1.0 || last {
                    point = [a[0] + t * d[0], a[1] + t * d[1]];
                    break;
                }
            }
            start += len;
            next += 1;
        }
        out.push(point);
    }
    out
}

/// Euclidean distance of two points.
#[inline]
#[must_use]
pub fn distance(a: Point2, b: Point2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    math::sqrt::<f64>(dx * dx + dy * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
    }

    #[test]
    fn binding_parameter_is_the_middle_of_the_active_stack() {
        let layout = BookLayout::new(BookParams::default()).unwrap();
        let total = layout.params.total_pages;
        // q = (n_left + n_active / 2) / n_total.
        assert_eq!(layout.binding_parameter(0, 0), 0.0);
        assert_eq!(layout.binding_parameter(total, 0), 1.0);
        assert_eq!(layout.binding_parameter(50, 0), 0.5);
        assert_eq!(layout.binding_parameter(0, total), 0.5);
        assert!(close(layout.binding_parameter(49, 1), 0.495));
        // Taking pages from the right moves q towards the right, never past 1.
        for left in 0..=total {
            let q = layout.binding_parameter(left, total - left);
            assert!((0.0..=1.0).contains(&q), "q = {q} for {left} left");
        }
    }

    #[test]
    fn midlines_start_at_the_binding_nodes_and_lie_flat() {
        for cover in [true, false] {
            let params = BookParams {
                cover,
                ..BookParams::default()
            };
            let layout = BookLayout::new(params).unwrap();
            let [b1, b2] = layout.binding;
            assert_eq!(layout.left[0], b1);
            assert_eq!(layout.right[0], b2);
            assert_eq!(layout.midline(BlockSide::Left)[0], b1);
            assert_eq!(layout.midline(BlockSide::Right)[0], b2);
            // The binding spans the thickness of all pages, at the cover's thickness.
            let width = f64::from(params.total_pages) * params.page_thickness;
            assert!(close(b2[0] - b1[0], width));
            let y0 = if cover { params.cover_thickness } else { 0.0 };
            assert_eq!([b1[1], b2[1]], [y0, y0]);
            for (line, dir) in [(&layout.left, -1.0), (&layout.right, 1.0)] {
                assert_eq!(line.len(), params.midline_nodes);
                let end = line[line.len() - 1];
                assert!(close(dir * (end[0] - line[0][0]), params.page_width));
                assert!(line.iter().all(|p| p[1] == y0));
            }
            assert_eq!(layout.cover_ends.is_some(), cover);
            assert_eq!(
                layout.pages(BlockSide::Left) + layout.pages(BlockSide::Right),
                params.total_pages
            );
        }
    }

    #[test]
    fn material_normals_face_the_pages() {
        // Both blocks lying flat have their pages on top.
        assert_eq!(material_normal(BlockSide::Left, [-2.0, 0.0]), [0.0, 1.0]);
        assert_eq!(material_normal(BlockSide::Right, [2.0, 0.0]), [0.0, 1.0]);
        assert_eq!(material_normal(BlockSide::Left, [0.0, 0.0]), [0.0, 0.0]);
        assert_eq!(
            material_normal(BlockSide::Right, [f64::NAN, 1.0]),
            [0.0, 0.0]
        );
    }

    #[test]
    fn offset_curve_keeps_its_distance() {
        // A bent curve: straight, then rising at 45 degrees, then flat again.
        let midline = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [3.0, 1.0], [4.0, 1.0]];
        for side in [BlockSide::Left, BlockSide::Right] {
            let distance = 0.25;
            let offset = offset_curve(&midline, side, distance);
            assert_eq!(offset.len(), midline.len());
            for (a, b) in midline.iter().zip(&offset) {
                assert!(close(super::distance(*a, *b), distance), "{a:?} -> {b:?}");
            }
            // Ends move along their one segment's normal.
            let t = [midline[1][0] - midline[0][0], midline[1][1] - midline[0][1]];
            let n = material_normal(side, t);
            assert!(close(offset[0][0], distance * n[0]));
            assert!(close(offset[0][1], distance * n[1]));
        }
        // Degenerate segments keep the nodes where they are.
        let still = offset_curve(&[[1.0, 1.0], [1.0, 1.0]], BlockSide::Left, 1.0);
        assert_eq!(still, [[1.0, 1.0], [1.0, 1.0]]);
        assert!(offset_curve(&[], BlockSide::Right, 1.0).is_empty());
    }

    #[test]
    fn spine_arc_is_the_quarter_circle_of_the_start_cap() {
        let (c, center) = (7.5, [7.5, 0.06]);
        let arc = spine_arc([0.0, 0.06], center, [7.5, 7.56], 0.1);
        assert_eq!(arc.first(), Some(&[0.0, 0.06]));
        assert_eq!(arc.last(), Some(&[7.5, 7.56]));
        let mut length = 0.0;
        for w in arc.windows(2) {
            assert!(close(distance(center, w[1]), c), "{:?}", w[1]);
            // The turn from -X up to +Y, through the upper left quadrant.
            assert!(
                w[1][0] <= 7.5 + 1e-12 && w[1][1] >= 0.06 - 1e-12,
                "{:?}",
                w[1]
            );
            assert!(distance(w[0], w[1]) <= 0.1);
            length += distance(w[0], w[1]);
        }
        let quarter = 0.5 * core::f64::consts::PI * c;
        assert!(
            (length - quarter).abs() < 1e-3 * quarter,
            "{length} vs {quarter}"
        );
        // Mirrored for the left block: the shorter way is clockwise.
        let left = spine_arc([0.0, 0.06], [-7.5, 0.06], [-7.5, 7.56], 0.1);
        assert!(left.iter().all(|p| p[0] <= 0.0 && p[1] >= 0.06 - 1e-12));
        // Degenerate: a zero radius gives the straight line.
        assert_eq!(spine_arc(center, center, [7.5, 7.56], 0.1).len(), 2);
        assert_eq!(
            spine_arc([0.0, 0.0], center, [7.5, 7.56], f64::NAN).len(),
            2
        );
    }

    #[test]
    fn both_walks_step_along_and_run_on_past_the_end() {
        let curve = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        // Nodes at whole steps: the same by arc length and by chord, straight on past the
        // end.
        let expected = [
            [0.0, 0.0],
            [0.5, 0.0],
            [1.0, 0.0],
            [1.0, 0.5],
            [1.0, 1.0],
            [1.0, 1.5],
        ];
        for walk in [resample, walk_chords] {
            let points = walk(&curve, 0.5, 6);
            assert_eq!(points.len(), expected.len());
            for (p, e) in points.iter().zip(expected) {
                assert!(close(p[0], e[0]) && close(p[1], e[1]), "{p:?} != {e:?}");
            }
            assert!(walk(&[], 1.0, 3).is_empty());
            assert_eq!(walk(&[[2.0, 3.0]], 1.0, 2), [[2.0, 3.0], [2.0, 3.0]]);
            assert_eq!(walk(&curve, f64::NAN, 2), [[0.0, 0.0], [0.0, 0.0]]);
        }
    }

    #[test]
    fn walk_chords_keeps_every_chord_across_corners_and_bends() {
        let curve = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        // Across a corner: from (0.8, 0) the next point at 0.8 lies on the second segment,
        // at (1, sqrt(0.8^2 - 0.2^2)), not at arc length 1.6, (1, 0.6).
        let points = walk_chords(&curve, 0.8, 3);
        assert!(
            close(points[1][0], 0.8) && close(points[1][1], 0.0),
            "{points:?}"
        );
        assert!(close(points[2][0], 1.0), "{points:?}");
        assert!(close(distance(points[1], points[2]), 0.8), "{points:?}");
        // On a tight quarter circle every chord is the spacing (equal arc lengths were short).
        let arc = spine_arc([0.0, 0.0], [1.0, 0.0], [1.0, 1.0], 1e-3);
        let points = walk_chords(&arc, 0.5, 5);
        for w in points.windows(2) {
            assert!(close(distance(w[0], w[1]), 0.5), "{points:?}");
        }
    }

    #[test]
    fn validate_names_the_first_bad_field() {
        let ok = BookParams::default();
        assert_eq!(ok.validate(), Ok(()));
        let bad = |f: fn(&mut BookParams)| {
            let mut p = ok;
            f(&mut p);
            let e = p.validate().unwrap_err();
            (e.path.to_string(), e.value)
        };
        let at = |field: &str, v: f64| (field.to_string(), Some(v));
        assert_eq!(bad(|p| p.total_pages = 0), at("total_pages", 0.0));
        assert_eq!(
            bad(|p| p.total_pages = 100_001),
            at("total_pages", 100_001.0)
        );
        assert_eq!(bad(|p| p.left_pages = 101), at("left_pages", 101.0));
        let nan = bad(|p| p.page_width = f64::NAN);
        assert_eq!(nan.0, "page_width");
        assert_eq!(bad(|p| p.cover_overhang = -1.0), at("cover_overhang", -1.0));
        assert_eq!(
            bad(|p| p.page_width = 2.0 * MAX_EXTENT),
            at("page_width", 2.0 * MAX_EXTENT)
        );
        assert_eq!(bad(|p| p.aspect_ratio = 2e4).0, "aspect_ratio");
        assert_eq!(
            bad(|p| p.page_thickness = 4e-320),
            at("page_thickness", 4e-320)
        );
        assert_eq!(bad(|p| p.midline_nodes = 2), at("midline_nodes", 2.0));
        // Zero is allowed where documented.
        let mut flat = ok;
        flat.cover_thickness = 0.0;
        assert_eq!(flat.validate(), Ok(()));
    }
}
