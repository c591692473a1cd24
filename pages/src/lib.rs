//! # folio-pages
//!
//! Page models behind one interface, driven by the same touch input and measured by the
//! same metrics, so that a scene can pick the accuracy it pays for:
//! - [`cone::ConePage`], the conical curl of seed `001_…`: a closed-form map, the cheapest;
//! - [`spring::SpringPage`], the mass-spring page of seed `003_…` (and
//!   [`spring::ReplayPage`], its key-frame playback);
//! - [`dog::DogPage`], the active page of the DOG book of seed `000_…`, the most accurate;
//! - [`xpbd::XpbdPage`], a peer from games: an inextensible particle page with isometric
//!   bending solved by XPBD in small steps.
//!
//! **The page frame.** Every model reports its page in one frame: the flat page at rest is
//! $\lbrace(u, 0, v) : u \in [0, W],\ v \in [0, H]\rbrace$, with the spine along Z through the origin,
//! X across the page (away from the spine), Y up (gravity along −Y). A page turned over the
//! spine lies near $\lbrace(-u, 0, v)\rbrace$. Page coordinates $(u, v)$ name material points: $u$
//! across from the spine, $v$ along it. Units: page units (the seed's page width is 12).
//!
//! **Input.** A grab at a page point $(u, v)$, the finger's position in the page frame once
//! per frame while held, a release ([`PageModel::grab`], [`PageModel::drag`],
//! [`PageModel::release`]); [`touch::TouchScript`] records such an input.
//!
//! **Output.** Page surface samples at the nodes of a render grid ([`PageModel::sample`];
//! grid node $(i, j)$ is the material point $u = W i/(n_x - 1)$, $v = H j/(n_z - 1)$), a
//! mesh built from them ([`mesh`]), and per-frame metrics ([`metrics::frame_metrics`]).
//!
//! Layers: `folio-kernels`, `folio-geometry` (render grid, page mesh) and `folio-solvers`
//! (the implicit step of the mass-spring page) below; the DOG page wraps `folio-book`
//! (feature `dog`). Features: `std`, `cone`, `mass-spring`, `dog`, `xpbd`.
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

#[cfg(feature = "cone")]
pub mod cone;
#[cfg(feature = "dog")]
pub mod dog;
pub mod gestures;
#[cfg(any(feature = "mass-spring", feature = "xpbd"))]
mod hold;
pub mod metrics;
#[cfg(feature = "mass-spring")]
pub mod spring;
pub mod touch;
#[cfg(feature = "xpbd")]
pub mod xpbd;

use folio_geometry::QuadGrid;
use folio_geometry::mesh::{MeshError, TriMesh, page_mesh};
use folio_kernels::{Real, SettingError, Vec3Ops};

#[cfg(feature = "dog")]
use folio_book::BookError;

pub use folio_geometry::BlockSide;
pub use gestures::{Gesture, GestureError, Gestures};
pub use metrics::{FrameMetrics, frame_metrics};
pub use touch::TouchScript;

/// Why a page model refused an input or a request.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum PageError {
    /// A setting of the page model that is NaN, infinite or out of its range (the path is
    /// the field's in the model's settings type).
    InvalidSetting(SettingError),
    /// A non-finite or out-of-range input; `what` names it.
    InvalidInput {
        /// The offending input.
        what: &'static str,
    },
    /// A sample buffer of the wrong length.
    SampleCount {
        /// Nodes of the render grid.
        expected: usize,
        /// Length of the buffer given.
        got: usize,
    },
    /// The book under the DOG page refused.
    #[cfg(feature = "dog")]
    Book(BookError),
    /// The mesher refused the samples, the grid or the thickness.
    Mesh(MeshError),
    /// The model cannot take this gesture (a grab where it has no page, a stack on a
    /// one-page model, a page still moving elsewhere).
    Gesture(GestureError),
}

/// The effects of the particle pages (the mass-spring and XPBD pages) by their scene names:
/// `gravity` (the particles' weight) and `collisions` (the table under the page). The one
/// list of the names.
pub const PARTICLE_PAGE_EFFECTS: [&str; 2] = ["gravity", "collisions"];

/// `Ok` when a page's `width` and `height` are finite, > 0 and at most the precision's
/// largest coordinate ([`Real::COORD_MAX`]).
///
/// # Errors
/// The first of `width` and `height` that is not.
pub(crate) fn require_page_size<T: Real>(width: T, height: T) -> Result<(), SettingError> {
    for (field, v) in [("width", width), ("height", height)] {
        let ok = v.is_finite() && v > T::ZERO && v <= T::COORD_MAX;
        let rule = "finite and > 0, at most the precision's largest coordinate";
        folio_kernels::setting::require(ok, field, rule, v.to_f64())?;
    }
    Ok(())
}

impl From<SettingError> for PageError {
    fn from(e: SettingError) -> Self {
        Self::InvalidSetting(e)
    }
}

#[cfg(feature = "dog")]
impl From<BookError> for PageError {
    fn from(e: BookError) -> Self {
        Self::Book(e)
    }
}

impl core::fmt::Display for PageError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::InvalidSetting(e) => write!(f, "page setting {e}"),
            Self::InvalidInput { what } => write!(f, "invalid input: {what}"),
            Self::SampleCount { expected, got } => {
                write!(
                    f,
                    "sample buffer holds {got} points, the render grid has {expected}"
                )
            }
            #[cfg(feature = "dog")]
            Self::Book(e) => write!(f, "book: {e}"),
            Self::Mesh(e) => write!(f, "mesh: {e}"),
            Self::Gesture(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for PageError {}

/// How a frame went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PageStatus {
    /// The page moved as asked (or is at rest).
    Moved,
    /// The finger asked for a shape the model cannot make; the page took the nearest one it
    /// could (the cone's touch fit).
    Unreachable,
    /// The model could not advance this frame and kept its previous state.
    Stalled,
}

/// The record of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PageStep<T> {
    /// How the frame went.
    pub status: PageStatus,
    /// Distance from the held material point to the finger after the frame (page units),
    /// while held.
    pub finger_gap: Option<T>,
}

/// A simulated or animated page (module docs). Object safe: a scene holds a
/// `Box<dyn PageModel<T>>` and switches models without touching anything else.
pub trait PageModel<T: Real> {
    /// A short name for reports (`"dog"`, `"cone"`, `"mass-spring"`, `"xpbd"`).
    fn name(&self) -> &'static str;

    /// Page width $W$ and height $H$ (page units).
    fn size(&self) -> [T; 2];

    /// Takes hold of the page at the material point `at` $= (u, v)$.
    ///
    /// # Errors
    /// [`PageError::InvalidInput`] for a non-finite point or one off the page.
    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError>;

    /// Moves the finger to `finger` (page frame). Ignored while nothing is held.
    ///
    /// # Errors
    /// [`PageError::InvalidInput`] for a non-finite point; nothing changes.
    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError>;

    /// Takes hold of `pages` pages lying on `side` at the material point `at` (the gesture
    /// of a [`Gestures`] sequence): the next page of that side, or, for a model of one page,
    /// that page again. The default is for a model of one page: one page, on the side where
    /// it lies ([`PageModel::lying_side`]), taken by [`PageModel::grab`] and then
    /// [`PageModel::taken_from`]; anything else is refused.
    ///
    /// # Errors
    /// As [`PageModel::grab`]; [`PageError::Gesture`] for a grab the model cannot take.
    fn grab_page(&mut self, side: BlockSide, pages: u32, at: [T; 2]) -> Result<(), PageError> {
        one_page(pages)?;
        if side != self.lying_side() {
            return Err(PageError::Gesture(GestureError::NoPage {
                side,
                model: self.name(),
            }));
        }
        self.grab(at)?;
        self.taken_from(side);
        Ok(())
    }

    /// The side of the spine a model of one page lies on, where [`PageModel::grab_page`]
    /// takes it. The default: the right, where every model's page starts.
    fn lying_side(&self) -> BlockSide {
        BlockSide::Right
    }

    /// Called by [`PageModel::grab_page`] after it took the one page from `side`: a model
    /// whose page may lie on the left holds it there as it lies (the particle pages mirror
    /// their grip across the spine). The default does nothing.
    fn taken_from(&mut self, _side: BlockSide) {}

    /// Lets go; the page finishes its turn (or falls back) on its own.
    fn release(&mut self);

    /// Advances one frame.
    ///
    /// # Errors
    /// Only for a model that cannot run at all (the DOG page's book refusing a step).
    fn step(&mut self) -> Result<PageStep<T>, PageError>;

    /// Writes the page surface at the nodes of `grid` into `out` (page frame).
    ///
    /// # Errors
    /// [`PageError::SampleCount`] unless `out.len() == grid.len()`.
    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError>;
}

/// `Ok` for one page, else [`GestureError::Stack`]: the cone and the mass-spring page model a
/// single page.
///
/// # Errors
/// [`PageError::Gesture`] for `pages != 1`.
pub fn one_page(pages: u32) -> Result<(), PageError> {
    if pages == 1 {
        Ok(())
    } else {
        Err(PageError::Gesture(GestureError::Stack { pages }))
    }
}

/// The side of the spine a one-page model's page lies on: left when the mean X of its
/// points `x` is negative, else right.
#[must_use]
pub fn lying_side<T: Real>(x: &[T::Vec3]) -> BlockSide {
    let n = T::from_f64(x.len().max(1) as f64);
    let mean_x = x.iter().fold(T::ZERO, |m, p| m + p.x()) / n;
    if mean_x < T::ZERO {
        BlockSide::Left
    } else {
        BlockSide::Right
    }
}

/// The material point $(u, v)$ of render-grid node `k` on a page of size `size`.
#[must_use]
pub fn material_point<T: Real>(grid: QuadGrid, size: [T; 2], k: usize) -> [T; 2] {
    let (i, j) = grid.coords(k);
    let fraction = |a: usize, n: usize| T::from_f64(a as f64 / (n - 1).max(1) as f64);
    [
        size[0] * fraction(i, grid.nx),
        size[1] * fraction(j, grid.nz),
    ]
}

/// Checks that a buffer holds `expected` points.
///
/// # Errors
/// [`PageError::SampleCount`] otherwise.
pub fn check_count(expected: usize, got: usize) -> Result<(), PageError> {
    if expected == got {
        Ok(())
    } else {
        Err(PageError::SampleCount { expected, got })
    }
}

/// Checks a grab point: finite and on the page.
///
/// # Errors
/// [`PageError::InvalidInput`] otherwise.
pub fn check_grab<T: Real>(at: [T; 2], size: [T; 2]) -> Result<(), PageError> {
    let on = |x: T, max: T| x.is_finite() && x >= T::ZERO && x <= max;
    if on(at[0], size[0]) && on(at[1], size[1]) {
        Ok(())
    } else {
        Err(PageError::InvalidInput {
            what: "grab point (must be finite and on the page)",
        })
    }
}

/// Checks a finger position: finite.
///
/// # Errors
/// [`PageError::InvalidInput`] otherwise.
pub fn check_finger<T: Real>(finger: T::Vec3) -> Result<(), PageError> {
    if folio_kernels::real::vec_is_finite::<T>(finger) {
        Ok(())
    } else {
        Err(PageError::InvalidInput {
            what: "finger position (not finite)",
        })
    }
}

/// The page `model` as a render mesh: its samples on `grid` offset by $\pm t/2$ (front and
/// back distinguished, rim closed; [`page_mesh`]), appended to `out`. `thickness` $t > 0$
/// (the cone's zero-thickness page takes the book's paper thickness).
///
/// # Errors
/// [`PageError::Mesh`] for samples, a grid or a thickness the mesher refuses (`out` is then
/// unchanged).
pub fn mesh<T: Real>(
    model: &dyn PageModel<T>,
    grid: QuadGrid,
    thickness: f64,
    out: &mut TriMesh,
) -> Result<(), PageError> {
    let mut samples = alloc::vec![T::Vec3::ZERO; grid.len()];
    model.sample(grid, &mut samples)?;
    mesh_samples::<T>(grid, &samples, model.size()[0].to_f64(), thickness, out)
}

/// The render mesh of a page already sampled on `grid` ([`PageModel::sample`] into
/// `samples`, $N$ = `grid.len()` points), for a caller that also measures the samples
/// ([`frame_metrics`]) and so samples once; as [`mesh`] otherwise. `page_width` is the
/// page's width $W$ (page units), the length each row of the offset surfaces is kept at.
///
/// # Errors
/// As [`mesh`].
pub fn mesh_samples<T: Real>(
    grid: QuadGrid,
    samples: &[T::Vec3],
    page_width: f64,
    thickness: f64,
    out: &mut TriMesh,
) -> Result<(), PageError> {
    let positions: alloc::vec::Vec<[f64; 3]> = samples
        .iter()
        .map(|p| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()])
        .collect();
    page_mesh(out, grid, &positions, thickness, page_width).map_err(PageError::Mesh)
}
