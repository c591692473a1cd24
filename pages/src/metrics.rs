//! The per-frame measures every page model is judged by, computed from its samples on a
//! render grid against the flat page:
//! - edge stretch $\varepsilon_e = \lvert \ell_e / \ell^0_e - 1\rvert$ over the grid edges,
//!   its maximum and its RMSE (seed `000_…` Sec. 5 reports both for the DOG book);
//! - the developability defect: the angle defect $2\pi - \sum \alpha$ at every interior node
//!   of the grid triangulated along the $(i, j)$–$(i{+}1, j{+}1)$ diagonals, its maximum
//!   magnitude. An isometric image of the flat page has zero defect; a developable surface
//!   sampled on a grid has a defect that falls with the spacing.
//!
//! Dimensionless (ratios and radians). A non-finite sample makes the measures NaN.

use folio_geometry::QuadGrid;
use folio_kernels::{Real, Vec3Ops, math};

use super::PageError;

/// The measures of one frame (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameMetrics<T> {
    /// $\max_e \varepsilon_e$.
    pub max_stretch: T,
    /// $\sqrt{\operatorname{mean}_e \varepsilon_e^2}$.
    pub rmse_stretch: T,
    /// $\max \lvert 2\pi - \sum\alpha\rvert$ over interior nodes (radians).
    pub max_angle_defect: T,
}

/// The measures of `samples` (one per node of `grid`) of a page of size `size` (module docs).
///
/// # Errors
/// [`PageError::SampleCount`] unless `samples.len() == grid.len()`.
pub fn frame_metrics<T: Real>(
    grid: QuadGrid,
    size: [T; 2],
    samples: &[T::Vec3],
) -> Result<FrameMetrics<T>, PageError> {
    super::check_count(grid.len(), samples.len())?;
    let mut m = FrameMetrics {
        max_stretch: T::ZERO,
        rmse_stretch: T::ZERO,
        max_angle_defect: T::ZERO,
    };
    let mut sum_sq = T::ZERO;
    let mut edges = 0usize;
    edge_stretches(grid, size, samples, |s| {
        sum_sq += s * s;
        edges += 1;
        if s > m.max_stretch || !s.is_finite() {
            m.max_stretch = s;
        }
    });
    m.rmse_stretch = math::sqrt(sum_sq / T::from_f64(edges.max(1) as f64));
    for j in 1..grid.nz - 1 {
        for i in 1..grid.nx - 1 {
            let p = samples[grid.index(i, j)];
            // The six neighbours in order around the node for the diagonal split.
            let ring = [(1, 0), (1, 1), (0, 1), (-1, 0), (-1, -1), (0, -1)].map(
                |(di, dj): (isize, isize)| {
                    samples[grid.index(i.wrapping_add_signed(di), j.wrapping_add_signed(dj))]
                },
            );
            let mut total = T::ZERO;
            for w in 0..6 {
                total += angle::<T>(ring[w] - p, ring[(w + 1) % 6] - p);
            }
            let defect = abs(T::from_f64(core::f64::consts::TAU) - total);
            if defect > m.max_angle_defect || !defect.is_finite() {
                m.max_angle_defect = defect;
            }
        }
    }
    Ok(m)
}

/// $\max_e \varepsilon_e$ alone (module docs): [`frame_metrics`]'s `max_stretch` without the
/// rest; `samples` should hold one point per node of `grid` (edges off a shorter slice are
/// skipped). NaN samples give NaN.
#[must_use]
pub fn max_stretch<T: Real>(grid: QuadGrid, size: [T; 2], samples: &[T::Vec3]) -> T {
    let mut worst = T::ZERO;
    edge_stretches(grid, size, samples, |s| {
        if s > worst || !s.is_finite() {
            worst = s;
        }
    });
    worst
}

/// Calls `f` with $\varepsilon_e$ of every grid edge (across, then along, row by row).
fn edge_stretches<T: Real>(
    grid: QuadGrid,
    size: [T; 2],
    samples: &[T::Vec3],
    mut f: impl FnMut(T),
) {
    let spacing = [
        size[0] / T::from_f64(grid.nx.saturating_sub(1).max(1) as f64),
        size[1] / T::from_f64(grid.nz.saturating_sub(1).max(1) as f64),
    ];
    let mut edge = |a: usize, b: usize, rest: T| {
        if let (Some(&pa), Some(&pb)) = (samples.get(a), samples.get(b)) {
            f(abs(math::length::<T>(pa - pb) / rest - T::ONE));
        }
    };
    for j in 0..grid.nz {
        for i in 0..grid.nx {
            let k = grid.index(i, j);
            if i + 1 < grid.nx {
                edge(k, grid.index(i + 1, j), spacing[0]);
            }
            if j + 1 < grid.nz {
                edge(k, grid.index(i, j + 1), spacing[1]);
            }
        }
    }
}

fn abs<T: Real>(x: T) -> T {
    if x < T::ZERO { -x } else { x }
}

/// The angle between `a` and `b` (radians, in $[0, \pi]$), from atan2 of the cross and dot
/// products (accurate at small and large angles).
fn angle<T: Real>(a: T::Vec3, b: T::Vec3) -> T {
    math::atan2::<T>(math::length::<T>(a.cross(b)), a.dot(b))
}
