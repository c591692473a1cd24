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
    /// Pages in the book (leaves: one sheet is one page here), at least 1. Scene files
    /// also accept the older key `pages`.
    #[cfg_attr(feature = "serde", serde(alias = "pages"))]
    pub total_pages: u32,
    /// Pages in the left block (the rest are in the right block), at most `total_pages`.
    pub left_pages: u32,
    /// Page width (page units; 12 in the seed).
    pub page_width: f64,
    /// Page height over page width (the seed scales the height by the book's aspect ratio;
    /// Folio's default is ISO 216's $\sqrt 2$).
    pub aspect_ratio: f64,
    /// Thickness of one page (page units; 0.0075 in the seed). Scene files also accept the
    /// older key `thickness`.
    #[cfg_attr(feature = "serde", serde(alias = "thickness"))]
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

/// A book parameter that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LayoutError {
    /// `total_pages` is zero.
    NoPages,
    /// `left_pages` exceeds `total_pages`.
    LeftPagesExceedTotal {
        /// The left count given.
        left: u32,
        /// The total given.
        total: u32,
    },
    /// A length or ratio is not finite and positive (zero allowed where documented).
    NonPositive {
        /// The offending field.
        field: &'static str,
    },
    /// Fewer than three midline nodes per block.
    TooFewMidlineNodes {
        /// The count given.
        found: usize,
    },
    /// A length, or the book's whole thickness, exceeds [`MAX_EXTENT`].
    TooLarge {
        /// The offending field.
        field: &'static str,
    },
}

/// The largest page width, page height, book thickness or cover size (page units): $10^4$
/// times the seed's page width. Beyond it the squared distances of collision tests and
/// grabs leave the `f32` range (and, near $10^{150}$, the `f64` one), so a grab could no
/// longer tell nodes apart.
pub const MAX_EXTENT: f64 = 1.2e5;

impl core::fmt::Display for LayoutError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoPages => write!(f, "a book needs at least one page"),
            Self::LeftPagesExceedTotal { left, total } => {
                write!(f, "left_pages ({left}) exceeds total_pages ({total})")
            }
            Self::NonPositive { field } => write!(f, "{field} must be finite and positive"),
            Self::TooFewMidlineNodes { found } => {
                write!(f, "midline_nodes is {found}; at least 3 are needed")
            }
            Self::TooLarge { field } => write!(f, "{field} exceeds {MAX_EXTENT} page units"),
        }
    }
}

#[cfg(feature = "std")]
impl core::error::Error for LayoutError {}

impl BookParams {
    /// Page height (page units).
    #[must_use]
    pub fn page_height(&self) -> f64 {
        self.page_width * self.aspect_ratio
    }

    /// Checks every field (type docs).
    ///
    /// # Errors
    /// The first unusable field as a [`LayoutError`].
    pub fn validate(&self) -> Result<(), LayoutError> {
        if self.total_pages == 0 {
            return Err(LayoutError::NoPages);
        }
        if self.left_pages > self.total_pages {
            return Err(LayoutError::LeftPagesExceedTotal {
                left: self.left_pages,
                total: self.total_pages,
            });
        }
        let positive = [
            ("page_width", self.page_width),
            ("aspect_ratio", self.aspect_ratio),
            ("page_thickness", self.page_thickness),
        ];
        let non_negative = [
            ("cover_thickness", self.cover_thickness),
            ("cover_overhang", self.cover_overhang),
        ];
        for (field, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(LayoutError::NonPositive { field });
            }
        }
        for (field, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(LayoutError::NonPositive { field });
            }
        }
        let extents = [
            ("page_width", self.page_width),
            ("page_height", self.page_height()),
            (
                "page_thickness",
                self.page_thickness * f64::from(self.total_pages),
            ),
            ("cover_thickness", self.cover_thickness),
            ("cover_overhang", self.cover_overhang),
        ];
        for (field, v) in extents {
            if v > MAX_EXTENT {
                return Err(LayoutError::TooLarge { field });
            }
        }
        if self.midline_nodes < 3 {
            return Err(LayoutError::TooFewMidlineNodes {
                found: self.midline_nodes,
            });
        }
        Ok(())
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
    pub fn new(params: BookParams) -> Result<Self, LayoutError> {
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

/// Points at arc lengths `s_k = k * spacing`, `k = 0..count`, along `curve`, continuing
/// straight along the last segment past the curve's end. A curve with fewer than two
/// distinct nodes yields copies of its first node (or nothing when it is empty).
#[must_use]
pub fn resample(curve: &[Point2], spacing: f64, count: usize) -> Vec<Point2> {
    let mut out = Vec::with_capacity(count);
    let Some(&first) = curve.first() else {
        return out;
    };
    let mut segment = 0;
    let mut start = 0.0; // arc length at curve[segment]
    for k in 0..count {
        let s = spacing * k as f64;
        let mut point = first;
        while segment + 1 < curve.len() {
            let (a, b) = (curve[segment], curve[segment + 1]);
            let len = distance(a, b);
            let last = segment + 2 == curve.len();
            if s <= start + len || last {
                let u = if len > 0.0 { (s - start) / len } else { 0.0 };
                point = [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])];
                break;
            }
            start += len;
            segment += 1;
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
    fn resample_walks_the_arc_length_and_runs_on_past_the_end() {
        let curve = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        let points = resample(&curve, 0.5, 6);
        let expected = [
            [0.0, 0.0],
            [0.5, 0.0],
            [1.0, 0.0],
            [1.0, 0.5],
            [1.0, 1.0],
            [1.0, 1.5],
        ];
        assert_eq!(points.len(), expected.len());
        for (p, e) in points.iter().zip(expected) {
            assert!(close(p[0], e[0]) && close(p[1], e[1]), "{p:?} != {e:?}");
        }
        assert!(resample(&[], 1.0, 3).is_empty());
        assert_eq!(resample(&[[2.0, 3.0]], 1.0, 2), [[2.0, 3.0], [2.0, 3.0]]);
    }

    #[test]
    fn validate_names_the_first_bad_field() {
        let ok = BookParams::default();
        assert_eq!(ok.validate(), Ok(()));
        let bad = |f: fn(&mut BookParams)| {
            let mut p = ok;
            f(&mut p);
            p.validate().unwrap_err()
        };
        assert_eq!(bad(|p| p.total_pages = 0), LayoutError::NoPages);
        assert_eq!(
            bad(|p| p.left_pages = 101),
            LayoutError::LeftPagesExceedTotal {
                left: 101,
                total: 100
            }
        );
        assert_eq!(
            bad(|p| p.page_width = f64::NAN),
            LayoutError::NonPositive {
                field: "page_width"
            }
        );
        assert_eq!(
            bad(|p| p.cover_overhang = -1.0),
            LayoutError::NonPositive {
                field: "cover_overhang"
            }
        );
        assert_eq!(
            bad(|p| p.page_width = 2.0 * MAX_EXTENT),
            LayoutError::TooLarge {
                field: "page_width"
            }
        );
        assert_eq!(
            bad(|p| p.midline_nodes = 2),
            LayoutError::TooFewMidlineNodes { found: 2 }
        );
        // Zero is allowed where documented.
        let mut flat = ok;
        flat.cover_thickness = 0.0;
        assert_eq!(flat.validate(), Ok(()));
    }
}
