//! The simulation behind the page: the DOG book of seed `000_…`, or one of the cheaper page
//! models (the cone of seed `001_…`, the mass-spring page of seed `003_…`) behind
//! [`PageModel`], driven by the same rays. Not a second simulation: every step, grab and
//! mesh is the library's own.

use folio_book::{Book, BookmarkOutcome, GrabOutcome, PageCounts, Phase, Ray};
use folio_geometry::QuadGrid;
use folio_geometry::mesh::TriMesh;
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::spring::SpringPage;
use folio_pages::{PageModel, PageStatus, material_point};
use folio_scene::clock::steps_per_frame;
use folio_scene::scene::{ModelKind, Scene};
use folio_scene::settings::{book_settings, spring_settings};
use glam::DVec3;

use crate::error::WebError;

/// Render grid of a page model's page (quads across and along), as `folio run`'s.
const PAGE_QUADS: (usize, usize) = (24, 34);
/// Thickness of a page model's page when meshed (page units): the book's paper.
const PAGE_THICKNESS: f64 = 0.0075;

/// What a grab did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Grab {
    /// A page is held.
    Held,
    /// The ray passes by the book.
    Missed,
    /// The block hit holds fewer pages than asked for.
    NotEnoughPages,
}

/// How one frame went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameOutcome {
    /// Steps taken.
    pub steps: u32,
    /// Steps that failed: refused, or not advanced (the state was kept).
    pub failed: u32,
}

/// A held page model: the drag plane through the grabbed point, facing the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PageHold {
    point: DVec3,
    normal: DVec3,
}

/// A one-page model with its render grid and hold.
pub struct OnePage {
    model: Box<dyn PageModel<f64>>,
    grid: QuadGrid,
    samples: Vec<DVec3>,
    hold: Option<PageHold>,
}

/// The simulation of a scene.
pub enum Model {
    /// The DOG book.
    Book(Box<Book<f64>>),
    /// A one-page model.
    Page(Box<OnePage>),
}

impl Model {
    /// The model a scene names, in `f64` (the browser runs every scene in double
    /// precision). The sheet's tearing and the XPBD page are not in the browser build.
    ///
    /// # Errors
    /// [`WebError`] for a model the browser build has not, or settings the model refuses.
    pub fn from_scene(scene: &Scene) -> Result<Self, WebError> {
        let refused = |e: &dyn core::fmt::Display| WebError::new(format!("the model refused: {e}"));
        let page = |model: Box<dyn PageModel<f64>>| {
            let grid = QuadGrid::new(PAGE_QUADS.0, PAGE_QUADS.1)
                .ok_or_else(|| WebError::new("no render grid"))?;
            Ok::<_, WebError>(Self::Page(Box::new(OnePage {
                model,
                grid,
                samples: vec![DVec3::ZERO; grid.len()],
                hold: None,
            })))
        };
        match *scene.model.get_ref() {
            ModelKind::Dog => Ok(Self::Book(Box::new(
                Book::new(book_settings(scene).map_err(|e| refused(&e))?)
                    .map_err(|e| refused(&e))?,
            ))),
            ModelKind::Cone => page(Box::new(
                ConePage::new(ConeSettings::default()).map_err(|e| refused(&e))?,
            )),
            ModelKind::MassSpring => page(Box::new(
                SpringPage::new(spring_settings(scene, false).map_err(|e| refused(&e))?)
                    .map_err(|e| refused(&e))?,
            )),
            other => Err(WebError::new(format!(
                "the {} model is not in the browser build: it runs the DOG book (\"dog\"), \
                 the cone (\"cone\") and the mass-spring page (\"mass-spring\")",
                other.name()
            ))),
        }
    }

    /// A short name (`"dog"`, `"cone"`, `"mass-spring"`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Book(_) => "dog",
            Self::Page(p) => p.model.name(),
        }
    }

    /// Grabs `pages` pages where the ray from `origin` along `direction` meets them;
    /// `forward` is the camera's viewing direction (the drag plane's normal).
    ///
    /// The book picks its block by the ray ([`Book::grab`]). A page model is taken at the
    /// render-grid sample nearest the ray, if the ray passes within one grid cell of it.
    ///
    /// # Errors
    /// [`WebError`] for a non-finite ray (the model is unchanged).
    pub fn grab(
        &mut self,
        origin: DVec3,
        direction: DVec3,
        forward: DVec3,
        pages: u32,
    ) -> Result<Grab, WebError> {
        match self {
            Self::Book(book) => {
                let ray = Ray { origin, direction };
                Ok(
                    match book.grab(&ray, forward, pages).map_err(WebError::book)? {
                        GrabOutcome::Grabbed { .. } => Grab::Held,
                        GrabOutcome::Missed => Grab::Missed,
                        GrabOutcome::NotEnoughPages => Grab::NotEnoughPages,
                        _ => Grab::Missed,
                    },
                )
            }
            Self::Page(p) => p.grab(origin, direction, forward),
        }
    }

    /// Moves the held point to where the ray meets its drag plane.
    ///
    /// # Errors
    /// [`WebError`] for a non-finite ray (the target is unchanged).
    pub fn drag(&mut self, origin: DVec3, direction: DVec3) -> Result<(), WebError> {
        match self {
            Self::Book(book) => {
                let ray = Ray { origin, direction };
                book.drag(&ray).map(|_| ()).map_err(WebError::book)
            }
            Self::Page(p) => p.drag(origin, direction),
        }
    }

    /// Lets go; `true` if something was held.
    pub fn release(&mut self) -> bool {
        match self {
            Self::Book(book) => book.release(),
            Self::Page(p) => {
                let held = p.hold.take().is_some();
                if held {
                    p.model.release();
                }
                held
            }
        }
    }

    /// Finger-bookmarking (seed `000_…` Sec. 4.1): one more page into the grip (`add`) or
    /// one back out; only the book has it.
    pub fn bookmark(&mut self, add: bool) -> &'static str {
        let Self::Book(book) = self else {
            return "only the book bookmarks";
        };
        match book.bookmark(add) {
            BookmarkOutcome::Started => "started",
            BookmarkOutcome::NotHeld => "nothing is held",
            BookmarkOutcome::NoPage => "no page to flip",
            BookmarkOutcome::Busy => "pages already in flight",
            BookmarkOutcome::Disabled => "bookmarking is off (effects)",
            _ => "refused",
        }
    }

    /// Advances one frame of [`folio_scene::clock::FRAME_SECONDS`]: the book takes
    /// $\mathrm{round}(\Delta t_{frame} / h) \ge 1$ steps, a page model its one frame.
    pub fn advance(&mut self) -> FrameOutcome {
        match self {
            Self::Book(book) => {
                let steps = steps_per_frame(book.settings().solver.time_step);
                let mut failed = 0;
                for _ in 0..steps {
                    match book.step() {
                        Ok(r) if r.solver.status.advanced() => {}
                        _ => failed += 1,
                    }
                }
                FrameOutcome { steps, failed }
            }
            Self::Page(p) => {
                let failed = match p.model.step() {
                    Ok(s) if s.status != PageStatus::Stalled => 0,
                    _ => 1,
                };
                FrameOutcome { steps: 1, failed }
            }
        }
    }

    /// The render mesh into `out` (cleared first): the book's blocks, cover and active
    /// page, or the page model's page.
    ///
    /// # Errors
    /// [`WebError`] when the state cannot be meshed (a non-finite node).
    pub fn mesh(&mut self, out: &mut TriMesh) -> Result<(), WebError> {
        out.clear();
        match self {
            Self::Book(book) => book
                .mesh(out)
                .map_err(|e| WebError::new(format!("cannot mesh the book: {e}"))),
            Self::Page(p) => {
                let fail =
                    |e: folio_pages::PageError| WebError::new(format!("cannot mesh the page: {e}"));
                p.model.sample(p.grid, &mut p.samples).map_err(fail)?;
                let width = p.model.size()[0];
                folio_pages::mesh_samples::<f64>(p.grid, &p.samples, width, PAGE_THICKNESS, out)
                    .map_err(fail)
            }
        }
    }

    /// Pages left, right and held (the book only).
    #[must_use]
    pub fn counts(&self) -> Option<PageCounts> {
        match self {
            Self::Book(book) => Some(book.counts()),
            Self::Page(_) => None,
        }
    }

    /// The book's phase: `"at-rest"`, `"held"` or `"released"`; a page model's `"held"` or
    /// `"free"`.
    #[must_use]
    pub fn phase(&self) -> &'static str {
        match self {
            Self::Book(book) => match book.phase() {
                Phase::AtRest => "at-rest",
                Phase::Held => "held",
                Phase::Released => "released",
                _ => "other",
            },
            Self::Page(p) if p.hold.is_some() => "held",
            Self::Page(_) => "free",
        }
    }

    /// The active page's largest relative edge stretch $\lvert \ell/\ell_0 - 1\rvert$ (seed
    /// `000_…` Sec. 5), over the book's page grid or the page model's render grid (the
    /// samples of the last [`Model::mesh`], which samples once for both); `None` with no
    /// active page.
    #[must_use]
    pub fn stretch(&self) -> Option<f64> {
        match self {
            Self::Book(book) => book.stretch().map(|(max, _)| max),
            Self::Page(p) => folio_pages::frame_metrics(p.grid, p.model.size(), &p.samples)
                .ok()
                .map(|m| m.max_stretch),
        }
    }

    /// The held point (book frame), if one is held.
    #[must_use]
    pub fn held_position(&self) -> Option<DVec3> {
        match self {
            Self::Book(book) => book.page()?.get(book.held_node()?).copied(),
            Self::Page(p) => p.hold.map(|h| h.point),
        }
    }

    /// Page width and height (page units).
    #[must_use]
    pub fn page_size(&self) -> [f64; 2] {
        match self {
            Self::Book(book) => book.page_size(),
            Self::Page(p) => p.model.size(),
        }
    }
}

impl OnePage {
    fn grab(&mut self, origin: DVec3, direction: DVec3, forward: DVec3) -> Result<Grab, WebError> {
        let finite = |v: DVec3| v.is_finite();
        if !(finite(origin) && finite(direction) && finite(forward)) || direction == DVec3::ZERO {
            return Err(WebError::new("a grab ray must be finite and not zero"));
        }
        self.model
            .sample(self.grid, &mut self.samples)
            .map_err(|e| WebError::new(format!("cannot sample the page: {e}")))?;
        let ray = Ray::<f64> { origin, direction };
        let size = self.model.size();
        let cell = (size[0] / self.grid.nx as f64).max(size[1] / self.grid.nz as f64);
        let nearest = self
            .samples
            .iter()
            .enumerate()
            .map(|(k, &p)| (ray.distance_sq(p), k))
            .filter(|(d, _)| *d <= cell * cell)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let Some((_, k)) = nearest else {
            return Ok(Grab::Missed);
        };
        let at = material_point(self.grid, size, k);
        self.model
            .grab(at)
            .map_err(|e| WebError::new(format!("the page refused the grab: {e}")))?;
        self.hold = Some(PageHold {
            point: self.samples[k],
            normal: forward.normalize(),
        });
        Ok(Grab::Held)
    }

    fn drag(&mut self, origin: DVec3, direction: DVec3) -> Result<(), WebError> {
        let Some(hold) = self.hold.as_mut() else {
            return Ok(());
        };
        let ray = Ray::<f64> { origin, direction };
        if !ray.is_valid() {
            return Err(WebError::new("a drag ray must be finite and not zero"));
        }
        let Some(hit) = ray.hit_plane(hold.point, hold.normal) else {
            return Ok(());
        };
        self.model
            .drag(hit)
            .map_err(|e| WebError::new(format!("the page refused the drag: {e}")))?;
        hold.point = hit;
        Ok(())
    }
}

/// `true` when every coordinate of every vertex of `mesh` is finite.
#[must_use]
pub fn mesh_is_finite(mesh: &TriMesh) -> bool {
    mesh.positions
        .iter()
        .chain(&mesh.normals)
        .all(|p| p.iter().all(|c| c.is_finite()))
}
