//! The simulated book (seed `000_…` Sec. 3-4): a book at rest steps only its page blocks;
//! a grab turns the top page of a block (or a stack of them) into the active page, which
//! follows the drag through the tent, falls under gravity when released, and merges into
//! the block it comes to rest on.

use crate::BookLayout;
use crate::layout::{offset_curve, resample};
use alloc::vec::Vec;
use folio_geometry::{BlockSide, Contacts, Floor, Obstacle, QuadGrid, Wall};
use folio_kernels::{Real, Vec3Ops, math};

use super::bookmark::{Flip, History};
use super::effects::TermCensus;
use super::error::BookError;
use super::interaction::{Ray, Tent};
use super::model::{ActiveView, BookTerms, NodeMap, RestView};
use super::script::Action;
use super::settings::BookSettings;
use folio_solvers::model::Model;
use folio_solvers::report::{StepReport, StepStatus};
use folio_solvers::step::{Correction, Solver, State};

/// The node of `nodes` with the smallest `distance` (NaN counts as farthest); `None` only
/// for no nodes. Always one of `nodes`, whatever the distances: a grab never holds a node
/// that is not a page node.
fn nearest(nodes: &[usize], distance: impl Fn(usize) -> f64) -> Option<usize> {
    nodes
        .iter()
        .map(|&node| (distance(node), node))
        .min_by(|a, b| match (a.0.is_nan(), b.0.is_nan()) {
            (false, false) => a.0.total_cmp(&b.0),
            (a_nan, _) => a_nan.cmp(&b.0.is_nan()),
        })
        .map(|(_, node)| node)
}

/// Unknowns and constraint rows of `solver`'s analysed KKT pattern.
fn pattern_size<T: Real>(solver: &Solver<T>) -> (usize, usize) {
    solver
        .kkt()
        .map_or((0, 0), |k| (k.pattern().dofs(), k.pattern().rows()))
}

/// Pages in each part of the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PageCounts {
    /// In the left block.
    pub left: u32,
    /// In the right block.
    pub right: u32,
    /// Held as the active page (0 at rest).
    pub active: u32,
}

impl PageCounts {
    /// Pages in the block on `side`.
    #[must_use]
    pub fn block(&self, side: BlockSide) -> u32 {
        match side {
            BlockSide::Left => self.left,
            BlockSide::Right => self.right,
        }
    }
    fn block_mut(&mut self, side: BlockSide) -> &mut u32 {
        match side {
            BlockSide::Left => &mut self.left,
            BlockSide::Right => &mut self.right,
        }
    }
}

/// What the book is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// No active page: only the blocks are simulated.
    AtRest,
    /// The active page is held by the user.
    Held,
    /// The active page was released and is settling.
    Released,
}

/// The user's hold on the active page.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Hold<T: Real> {
    node: usize,
    /// Where the user wants the node (the pull's target is this on a leash, see
    /// [`BookSettings::pull_reach`]).
    target: T::Vec3,
    plane_point: T::Vec3,
    plane_normal: T::Vec3,
    tent: Tent<T>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct ActivePage<T: Real> {
    from: BlockSide,
    hold: Option<Hold<T>>,
    slow_frames: u32,
}

/// How a grab ended. Only `Grabbed` changes the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GrabOutcome {
    /// The page node `node` (index into the page grid) is held; the page came from `side`.
    Grabbed {
        /// The block the active page came from.
        side: BlockSide,
        /// Grid index of the held node.
        node: usize,
    },
    /// The ray does not hit the book.
    Missed,
    /// The block hit holds fewer pages than asked for.
    NotEnoughPages,
}

/// How a drag ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DragOutcome {
    /// The target moved.
    Moved,
    /// Nothing is held.
    NotHeld,
    /// The ray does not meet the drag plane (parallel or behind the camera); target kept.
    Missed,
}

/// The record of one book step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BookStepReport<T> {
    /// The time stepper's report.
    pub solver: StepReport<T>,
    /// The phase the step ran in.
    pub phase: Phase,
    /// Unknowns of the step's KKT system (the page's appear only with an active page).
    pub dofs: usize,
    /// Constraint rows of the step's KKT system.
    pub constraint_rows: usize,
    /// Collision handling (seed Sec. 3.4) over all rounds.
    pub contacts: Contacts<T>,
    /// Detect/resolve rounds that found a contact.
    pub collision_rounds: u32,
    /// The constraint corrections after collision handling.
    pub correction: Correction<T>,
    /// The terms and rows of the step's view (what the effects that are on contribute; see
    /// [`crate::Effects`]). Zero when nothing was solved.
    pub census: TermCensus,
    /// A history snapshot was taken (finger-bookmarking).
    pub snapshot: bool,
    /// The block the active page merged into at the end of this step.
    pub merged: Option<BlockSide>,
}

/// The simulated book (module docs).
#[derive(Clone, Debug)]
pub struct Book<T: Real> {
    settings: BookSettings<T>,
    layout: BookLayout,
    terms: BookTerms<T>,
    rest_solver: Solver<T>,
    active_solver: Solver<T>,
    state: State<T>,
    counts: PageCounts,
    active: Option<ActivePage<T>>,
    /// Grid edges with their rest lengths.
    edges: Vec<([usize; 2], T)>,
    settle_steps: u32,
    history: History<T>,
    flips: Vec<Flip<T>>,
    /// Nodes a collision pushed in the current step (pinned by the projection).
    pushed: Vec<bool>,
    /// The terms of the rest view and of the active view.
    census: [TermCensus; 2],
}

/// How a finger-bookmarking request ended. Only `Started` changes the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BookmarkOutcome {
    /// A page started its flight.
    Started,
    /// Nothing is held.
    NotHeld,
    /// No page left to add (the block is empty) or to remove (one page held).
    NoPage,
    /// `max_flips` pages are already in flight.
    Busy,
    /// Finger-bookmarking is not among the book's effects.
    Disabled,
}

/// What an input did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputOutcome {
    /// A grab.
    Grab(GrabOutcome),
    /// A drag.
    Drag(DragOutcome),
    /// A release; `true` if something was held.
    Release(bool),
    /// A finger-bookmarking request.
    Bookmark(BookmarkOutcome),
}

fn vec_finite<T: Real>(v: T::Vec3) -> bool {
    v.x().is_finite() && v.y().is_finite() && v.z().is_finite()
}

fn check(ok: bool, field: &'static str, requirement: &'static str) -> Result<(), BookError> {
    if ok {
        Ok(())
    } else {
        Err(BookError::InvalidSetting { field, requirement })
    }
}

impl<T: Real> BookSettings<T> {
    /// Checks every field.
    ///
    /// # Errors
    /// The first unusable field.
    pub fn validate(&self) -> Result<(), BookError> {
        self.params.validate()?;
        self.effects.validate()?;
        self.solver.validate()?;
        let positive = |v: T| v.is_finite() && v > T::ZERO;
        let non_negative = |v: T| v.is_finite() && v >= T::ZERO;
        check(self.quads_across >= 2, "quads_across", "at least 2")?;
        check(self.quads_along >= 2, "quads_along", "at least 2")?;
        check(
            self.quads_across * self.quads_along <= 1 << 16,
            "quads_across",
            "at most 65536 quads in all",
        )?;
        let w = &self.weights;
        for (field, v) in [
            ("weights.bend_page", w.bend_page),
            ("weights.bend_blocks", w.bend_blocks),
            ("weights.glue", w.glue),
            ("weights.iso_page", w.iso_page),
            ("weights.pull", w.pull),
            ("gravity", self.gravity),
            ("air_drag", self.air_drag),
            ("contact_stiffness", self.contact_stiffness),
        ] {
            check(non_negative(v), field, "finite and >= 0")?;
        }
        for (field, v) in [
            ("page_mass", self.page_mass),
            ("cover_mass", self.cover_mass),
            ("min_block_mass", self.min_block_mass),
            ("merge_speed", self.merge_speed),
            ("pull_reach", self.pull_reach),
            ("settle_tolerance", self.settle_tolerance),
            ("constraint_tolerance", self.constraint_tolerance),
        ] {
            check(positive(v), field, "finite and > 0")?;
        }
        check(
            positive(self.tent_height) && self.tent_height <= T::ONE,
            "tent_height",
            "in (0, 1]",
        )?;
        check(
            self.contact_pin_weight.is_finite() && self.contact_pin_weight >= T::ONE,
            "contact_pin_weight",
            "finite and >= 1",
        )?;
        check(
            (1..=16).contains(&self.collision_rounds),
            "collision_rounds",
            "between 1 and 16",
        )
    }
}

impl<T: Real> Book<T> {
    /// A book at rest: the blocks settled into their rest shape.
    ///
    /// # Errors
    /// [`BookError`] for unusable settings.
    pub fn new(settings: BookSettings<T>) -> Result<Self, BookError> {
        settings.validate()?;
        let layout = BookLayout::new(settings.params)?;
        let grid = QuadGrid::new(settings.quads_across, settings.quads_along).ok_or(
            BookError::InvalidSetting {
                field: "quads_across",
                requirement: "at least 1",
            },
        )?;
        let terms = BookTerms::new(&layout, &settings, grid)?;
        let n = terms.nodes;
        let p = &layout.params;
        let mut x = alloc::vec![T::Vec3::ZERO; n.total()];
        let at = |q: [f64; 2]| T::Vec3::new(T::from_f64(q[0]), T::from_f64(q[1]), T::ZERO);
        for k in 0..n.midline {
            x[n.block(false, k)] = at(layout.left[k]);
            x[n.block(true, k)] = at(layout.right[k]);
        }
        if let Some(ends) = layout.cover_ends {
            x[n.cover_end(false)] = at(ends[0]);
            x[n.cover_end(true)] = at(ends[1]);
        }
        let spacing = settings.grid_spacing();
        let edges = grid
            .edges()
            .into_iter()
            .map(|[a, b]| {
                let along = grid.coords(a).1 != grid.coords(b).1;
                ([a, b], T::from_f64(spacing[usize::from(along)]))
            })
            .collect();
        let counts = PageCounts {
            left: p.left_pages,
            right: p.total_pages - p.left_pages,
            active: 0,
        };
        let pushed = alloc::vec![false; n.total()];
        let mut book = Self {
            rest_solver: Solver::new(settings.solver)?,
            active_solver: Solver::new(settings.solver)?,
            settings,
            layout,
            terms,
            state: State::at_rest(x),
            counts,
            active: None,
            edges,
            settle_steps: 0,
            // Without bookmarking the history holds pages of no nodes: it never copies.
            history: History::new(
                if settings.effects.bookmarks() {
                    grid.len()
                } else {
                    0
                },
                settings.history_capacity,
                settings.history_interval,
            ),
            flips: Vec::with_capacity(settings.max_flips),
            pushed,
            census: [TermCensus::default(); 2],
        };
        book.place_page(BlockSide::Right, 1);
        book.update_masses();
        if settings.effects.blocks {
            book.rest_solver.analyse(&RestView(&book.terms))?;
            RestView(&book.terms).visit_terms(&mut book.census[0]);
        }
        book.active_solver.analyse(&ActiveView(&book.terms))?;
        ActiveView(&book.terms).visit_terms(&mut book.census[1]);
        book.settle()?;
        Ok(book)
    }

    /// Steps the blocks until no node moves more than `settle_tolerance` in a step.
    fn settle(&mut self) -> Result<(), BookError> {
        let mut before = self.state.x.clone();
        for k in 0..self.settings.settle_steps {
            self.step()?;
            let moved = self
                .state
                .x
                .iter()
                .zip(&before)
                .map(|(a, b)| math::length::<T>(*a - *b))
                .fold(T::ZERO, |m, d| if d > m { d } else { m });
            before.copy_from_slice(&self.state.x);
            self.settle_steps = k + 1;
            if moved <= self.settings.settle_tolerance {
                break;
            }
        }
        for v in &mut self.state.v {
            *v = T::Vec3::ZERO;
        }
        Ok(())
    }

    /// Steps taken at construction to settle the blocks.
    #[must_use]
    pub fn settle_steps(&self) -> u32 {
        self.settle_steps
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &BookSettings<T> {
        &self.settings
    }

    /// The layout the book was built from (its initial, unsettled cross-section).
    #[must_use]
    pub fn layout(&self) -> &BookLayout {
        &self.layout
    }

    /// Node numbering.
    #[must_use]
    pub fn nodes(&self) -> NodeMap {
        self.terms.nodes
    }

    /// The terms (for inspection).
    #[must_use]
    pub fn terms(&self) -> &BookTerms<T> {
        &self.terms
    }

    /// Positions and velocities of every node (page nodes are meaningful only with an
    /// active page).
    #[must_use]
    pub fn state(&self) -> &State<T> {
        &self.state
    }

    /// Page counts.
    #[must_use]
    pub fn counts(&self) -> PageCounts {
        self.counts
    }

    /// What the book is doing.
    #[must_use]
    pub fn phase(&self) -> Phase {
        match &self.active {
            None => Phase::AtRest,
            Some(a) if a.hold.is_some() => Phase::Held,
            Some(_) => Phase::Released,
        }
    }

    /// The active page's node positions (grid order), if there is one.
    #[must_use]
    pub fn page(&self) -> Option<&[T::Vec3]> {
        self.active
            .as_ref()
            .map(|_| &self.state.x[self.terms.nodes.page_offset()..])
    }

    /// The midline of the block on `side`, from its binding node outward.
    #[must_use]
    pub fn midline(&self, side: BlockSide) -> &[T::Vec3] {
        let n = self.terms.nodes;
        let start = n.block(side == BlockSide::Right, 0);
        &self.state.x[start..start + n.midline]
    }

    /// Thickness of the block on `side` (page units).
    #[must_use]
    pub fn block_thickness(&self, side: BlockSide) -> T {
        T::from_f64(f64::from(self.counts.block(side)) * self.layout.params.page_thickness)
    }

    /// Thickness of the active page (stack) (page units).
    #[must_use]
    pub fn active_thickness(&self) -> T {
        T::from_f64(f64::from(self.counts.active) * self.layout.params.page_thickness)
    }

    /// Sets the masses of blocks, cover and page from the page counts, the page stack's
    /// stiffness ([`BookTerms::set_stack`]) and the binding parameter $q$.
    ///
    /// A block is never lighter than `min_block_mass` nor than the active page (or stack):
    /// the stack hangs from the binding the blocks share, and a block much lighter than it
    /// is tossed about by it. Grabbing 45 of 80 pages from the right block, with the left
    /// one empty, bound a 45-page stack to a block of 0.5 page masses; the collisions
    /// pushed that block's midline back every step, the projection that restores the
    /// binding and the contacts undid the drag, and the stack fell back onto the right
    /// block. With the floor it turns and lands on the left.
    fn update_masses(&mut self) {
        let s = &self.settings;
        let page = T::from_f64(f64::from(self.counts.active.max(1))) * s.page_mass;
        let floor = if page > s.min_block_mass {
            page
        } else {
            s.min_block_mass
        };
        let block = |pages: u32| {
            let m = T::from_f64(f64::from(pages)) * s.page_mass;
            if m > floor { m } else { floor }
        };
        let (left, right, cover) = (
            block(self.counts.left),
            block(self.counts.right),
            s.cover_mass,
        );
        self.terms.set_masses(left, right, cover, page);
        self.terms
            .set_stack(T::from_f64(f64::from(self.counts.active.max(1))));
        let q = self
            .layout
            .binding_parameter(self.counts.left, self.counts.active);
        self.terms.set_binding_parameter(T::from_f64(q));
    }

    /// The top surface of the block on `side` offset by `extra`, as an XY curve from the
    /// binding outward.
    fn block_surface(&self, side: BlockSide, extra: T) -> Vec<[f64; 2]> {
        let midline: Vec<[f64; 2]> = self
            .midline(side)
            .iter()
            .map(|p| [p.x().to_f64(), p.y().to_f64()])
            .collect();
        offset_curve(
            &midline,
            side,
            (self.block_thickness(side) + extra).to_f64(),
        )
    }

    /// Lays the page grid on the block on `side` as it is now, `k` pages thick: each grid
    /// column on the curve half the stack above the block's top, the bound column at the
    /// binding parameter, rows at equal steps along Z. The shape is a generalized cylinder
    /// with rulings along Z, an exact DOG.
    fn place_page(&mut self, side: BlockSide, k: u32) {
        self.terms.clear_contacts();
        let n = self.terms.nodes;
        let p = self.layout.params;
        let half = T::from_f64(0.5 * f64::from(k) * p.page_thickness);
        let mut curve = self.block_surface(side, half);
        let q = self.layout.binding_parameter(self.counts.left, k);
        let (b1, b2) = (
            self.state.x[n.block(false, 0)],
            self.state.x[n.block(true, 0)],
        );
        let bound = b1 * T::from_f64(1.0 - q) + b2 * T::from_f64(q);
        curve[0] = [bound.x().to_f64(), bound.y().to_f64()];
        let hx = p.page_width / self.settings.quads_across as f64;
        let hz = p.page_height() / self.settings.quads_along as f64;
        let columns = resample(&curve, hx, n.grid.nx);
        for j in 0..n.grid.nz {
            for (i, c) in columns.iter().enumerate() {
                let node = n.page(i, j);
                self.state.x[node] = T::Vec3::new(
                    T::from_f64(c[0]),
                    T::from_f64(c[1]),
                    T::from_f64(hz * j as f64),
                );
                self.state.v[node] = T::Vec3::ZERO;
            }
        }
    }

    /// Grabs the book where `ray` first hits a block's top surface (seed Sec. 3.3, 4.1): the
    /// top `pages` pages of that block become the active page, and the page node one ring
    /// in from the border closest to the ray is held. With an active page already present,
    /// its closest ring node is held instead. `forward` is the camera's forward direction:
    /// the drag plane passes through the held node with that normal.
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite or zero ray or direction, or zero pages;
    /// the book is unchanged.
    pub fn grab(
        &mut self,
        ray: &Ray<T>,
        forward: T::Vec3,
        pages: u32,
    ) -> Result<GrabOutcome, BookError> {
        if !ray.is_valid() {
            return Err(BookError::InvalidInput { what: "grab ray" });
        }
        let forward_ok = vec_finite::<T>(forward) && forward.dot(forward) > T::LENGTH_FLOOR;
        if !forward_ok {
            return Err(BookError::InvalidInput {
                what: "camera forward direction",
            });
        }
        let pick = if self.active.is_none() {
            self.hit_block(ray)
        } else {
            None
        };
        let side = match self.grab_side(pages, pick)? {
            Ok(side) => side,
            Err(outcome) => return Ok(outcome),
        };
        let nearest = nearest(self.terms.pull_nodes(), |node| {
            ray.distance_sq(self.state.x[node]).to_f64()
        });
        Ok(nearest.map_or(GrabOutcome::Missed, |node| {
            self.hold_node(side, node, forward)
        }))
    }

    /// Grabs `pages` pages from the block on `side` (a stack when more than one) by the
    /// grab-ring node nearest the material point `at` $= (u, v)$ (page units: $u$ across from
    /// the spine, $v$ along it), as if seen from above. For callers that place the finger
    /// themselves ([`Book::drag_to`]), such as the page models.
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite point or zero pages.
    pub fn grab_at(
        &mut self,
        side: BlockSide,
        at: [f64; 2],
        pages: u32,
    ) -> Result<GrabOutcome, BookError> {
        if !(at[0].is_finite() && at[1].is_finite()) {
            return Err(BookError::InvalidInput { what: "grab point" });
        }
        let side = match self.grab_side(pages, Some(side))? {
            Ok(side) => side,
            Err(outcome) => return Ok(outcome),
        };
        let n = self.terms.nodes;
        let spacing = self.grid_spacing();
        let nearest = nearest(self.terms.pull_nodes(), |node| {
            let (i, j) = n.grid.coords(node - n.page_offset());
            let du = i as f64 * spacing[0] - at[0];
            let dv = j as f64 * spacing[1] - at[1];
            du * du + dv * dv
        });
        let down = T::Vec3::new(T::ZERO, -T::ONE, T::ZERO);
        Ok(nearest.map_or(GrabOutcome::Missed, |node| self.hold_node(side, node, down)))
    }

    /// The block a grab holds: the active page's, or else `pick` after `pages` pages of it
    /// became the active page. `Ok(Err(outcome))` when nothing was grabbed.
    fn grab_side(
        &mut self,
        pages: u32,
        pick: Option<BlockSide>,
    ) -> Result<Result<BlockSide, GrabOutcome>, BookError> {
        if pages == 0 {
            return Err(BookError::InvalidInput {
                what: "pages to grab (zero)",
            });
        }
        if let Some(a) = self.active {
            return Ok(Ok(a.from));
        }
        let Some(side) = pick else {
            return Ok(Err(GrabOutcome::Missed));
        };
        if !self.take_pages(side, pages) {
            return Ok(Err(GrabOutcome::NotEnoughPages));
        }
        Ok(Ok(side))
    }

    /// The page grid's rest spacing `[across, along]` (page units).
    #[must_use]
    pub fn grid_spacing(&self) -> [f64; 2] {
        self.settings.grid_spacing()
    }

    /// Makes the top `pages` pages of the block on `side` the active page, laid on the block;
    /// `false` (nothing changes) when the block holds fewer.
    fn take_pages(&mut self, side: BlockSide, pages: u32) -> bool {
        if self.counts.block(side) < pages {
            return false;
        }
        *self.counts.block_mut(side) -= pages;
        self.counts.active = pages;
        self.place_page(side, pages);
        self.update_masses();
        let po = self.terms.nodes.page_offset();
        self.history.restart(&self.state.x[po..]);
        self.active = Some(ActivePage {
            from: side,
            hold: None,
            slow_frames: 0,
        });
        true
    }

    /// Holds page node `node` (global index) where it is, with the drag plane facing
    /// `forward` (unit or not; checked by the callers) and the tent over the binding.
    fn hold_node(&mut self, side: BlockSide, node: usize, forward: T::Vec3) -> GrabOutcome {
        let n = self.terms.nodes;
        let held = self.state.x[node];
        let (i, _) = n.grid.coords(node - n.page_offset());
        let p = self.layout.params;
        let thicker = if self.counts.left > self.counts.right {
            BlockSide::Left
        } else {
            BlockSide::Right
        };
        let b = self.state.x[n.block(false, 0)] + self.state.x[n.block(true, 0)];
        let tent = Tent {
            center: b.x() * T::HALF,
            reach: T::from_f64(p.page_width * i as f64 / self.settings.quads_across as f64),
            base: b.y() * T::HALF
                + self.block_thickness(thicker)
                + self.active_thickness() * T::HALF,
            height: self.settings.tent_height,
            page_height: T::from_f64(p.page_height()),
        };
        let normal = forward / math::length::<T>(forward);
        let hold = Hold {
            node,
            target: held,
            plane_point: held,
            plane_normal: normal,
            tent,
        };
        self.terms.set_pull(Some((node, held)));
        if let Some(a) = self.active.as_mut() {
            a.hold = Some(hold);
            a.slow_frames = 0;
        }
        GrabOutcome::Grabbed {
            side,
            node: node - n.page_offset(),
        }
    }

    /// The block whose top surface `ray` hits first, if any.
    fn hit_block(&self, ray: &Ray<T>) -> Option<BlockSide> {
        let height = T::from_f64(self.layout.params.page_height());
        let mut best: Option<(T, BlockSide)> = None;
        for side in [BlockSide::Left, BlockSide::Right] {
            let top = self.block_surface(side, T::ZERO);
            for w in top.windows(2) {
                let a = T::Vec3::new(T::from_f64(w[0][0]), T::from_f64(w[0][1]), T::ZERO);
                let b = T::Vec3::new(T::from_f64(w[1][0]), T::from_f64(w[1][1]), T::ZERO);
                let d = b - a;
                let normal = T::Vec3::new(-d.y(), d.x(), T::ZERO);
                let Some(hit) = ray.hit_plane(a, normal) else {
                    continue;
                };
                let s = (hit - a).dot(d) / d.dot(d);
                let inside = s >= T::ZERO && s <= T::ONE && hit.z() >= T::ZERO && hit.z() <= height;
                if !inside {
                    continue;
                }
                let dist = math::length::<T>(hit - ray.origin);
                if best.is_none_or(|(t, _)| dist < t) {
                    best = Some((dist, side));
                }
            }
        }
        best.map(|(_, side)| side)
    }

    /// Moves the held node's target to where `ray` meets the drag plane, projected onto the
    /// tent (seed Sec. 3.3, Fig. 7).
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite or zero ray; the target is unchanged.
    pub fn drag(&mut self, ray: &Ray<T>) -> Result<DragOutcome, BookError> {
        if !ray.is_valid() {
            return Err(BookError::InvalidInput { what: "drag ray" });
        }
        let Some(hold) = self.active.and_then(|a| a.hold) else {
            return Ok(DragOutcome::NotHeld);
        };
        let Some(hit) = ray.hit_plane(hold.plane_point, hold.plane_normal) else {
            return Ok(DragOutcome::Missed);
        };
        let target = hold.tent.project(hit);
        if !vec_finite::<T>(target) {
            return Err(BookError::InvalidInput {
                what: "drag target",
            });
        }
        self.set_target(target);
        Ok(DragOutcome::Moved)
    }

    /// Moves the held node's target to `target` itself, without the drag plane or the tent:
    /// for callers that own the finger's path (the page models).
    ///
    /// # Errors
    /// [`BookError::InvalidInput`] for a non-finite target; the target is unchanged.
    pub fn drag_to(&mut self, target: T::Vec3) -> Result<DragOutcome, BookError> {
        if !vec_finite::<T>(target) {
            return Err(BookError::InvalidInput {
                what: "drag target",
            });
        }
        if self.active.and_then(|a| a.hold).is_none() {
            return Ok(DragOutcome::NotHeld);
        }
        self.set_target(target);
        Ok(DragOutcome::Moved)
    }

    /// Stores the user's target of the held node (applied on the leash at the next step).
    fn set_target(&mut self, target: T::Vec3) {
        if let Some(hold) = self.active.as_mut().and_then(|a| a.hold.as_mut()) {
            hold.target = target;
        }
    }

    /// Sets the pull of the held node to its target on the leash of length
    /// [`BookSettings::pull_reach`]: $p = x_i + (t - x_i)\min(1, r / \lVert t - x_i\rVert)$.
    fn leash_pull(&mut self) {
        let Some(hold) = self.active.and_then(|a| a.hold) else {
            return;
        };
        let x = self.state.x[hold.node];
        let d = hold.target - x;
        let len = math::length::<T>(d);
        let reach = self.settings.pull_reach;
        let p = if len > reach {
            x + d * (reach / len)
        } else {
            hold.target
        };
        self.terms.set_pull(Some((hold.node, p)));
    }

    /// The held node (index into the page grid), if one is held.
    #[must_use]
    pub fn held_node(&self) -> Option<usize> {
        let hold = self.active.and_then(|a| a.hold)?;
        Some(hold.node - self.terms.nodes.page_offset())
    }

    /// The held node's current target (where the user wants it), if a node is held.
    #[must_use]
    pub fn target(&self) -> Option<T::Vec3> {
        Some(self.active.and_then(|a| a.hold)?.target)
    }

    /// Lets go of the active page; returns whether something was held.
    pub fn release(&mut self) -> bool {
        self.terms.set_pull(None);
        match self.active.as_mut() {
            Some(a) if a.hold.is_some() => {
                a.hold = None;
                a.slow_frames = 0;
                true
            }
            _ => false,
        }
    }

    /// Advances the book by one time step: the implicit-Euler step of the blocks (and the
    /// active page, if any), collision handling, and the merge of a page come to rest.
    ///
    /// # Errors
    /// Only setup errors of the solver (they cannot occur after a successful [`Book::new`]).
    pub fn step(&mut self) -> Result<BookStepReport<T>, BookError> {
        let phase = self.phase();
        self.leash_pull();
        let drag = T::ONE / (T::ONE + self.settings.air_drag * self.settings.solver.time_step);
        for v in &mut self.state.v {
            *v *= drag;
        }
        let (report, dofs, constraint_rows, census) = if self.active.is_some() {
            let r = self
                .active_solver
                .step(&ActiveView(&self.terms), &mut self.state)?;
            let (d, c) = pattern_size(&self.active_solver);
            (r, d, c, self.census[1])
        } else if self.settings.effects.blocks {
            let r = self
                .rest_solver
                .step(&RestView(&self.terms), &mut self.state)?;
            let (d, c) = pattern_size(&self.rest_solver);
            (r, d, c, self.census[0])
        } else {
            // Fixed blocks and no page: nothing to simulate.
            (
                StepReport::new(StepStatus::Converged, false),
                0,
                0,
                TermCensus::default(),
            )
        };
        let mut contacts = Contacts::default();
        let mut rounds = 0;
        let mut correction = Correction::default();
        if report.status.advanced() && dofs > 0 {
            self.pushed.iter_mut().for_each(|p| *p = false);
            self.terms.clear_contacts();
            rounds = self.collide(&mut contacts, self.settings.collision_rounds);
            // Projection and collision alternate: a node the projection moves into a block
            // is pushed out and pinned in the next projection, up to twice
            // `collision_rounds` passes, so the step ends with both the constraints and the
            // contacts met (a landing page needs more passes than a resting one).
            for pass in 0..2 * self.settings.collision_rounds {
                let c = self.project()?;
                if pass == 0 {
                    correction.before = c.before;
                }
                correction.steps += c.steps;
                correction.after = c.after;
                if c.steps == 0 {
                    break;
                }
                let found = self.collide(&mut contacts, 1);
                rounds += found;
                if found == 0 {
                    break;
                }
            }
        }
        let po = self.terms.nodes.page_offset();
        let snapshot = phase == Phase::Held
            && self.settings.effects.bookmarks()
            && self.history.tick(&self.state.x[po..]);
        if self.settings.effects.bookmarks() {
            self.advance_flips();
        }
        let merged = self.merge_if_settled();
        Ok(BookStepReport {
            solver: report,
            phase,
            dofs,
            constraint_rows,
            contacts,
            collision_rounds: rounds,
            correction,
            census,
            snapshot,
            merged,
        })
    }

    /// One [`Solver::project_constraints`] of the current view, the nodes pushed in this
    /// step pinned.
    fn project(&mut self) -> Result<Correction<T>, BookError> {
        let s = &self.settings;
        let (pin, tol, max) = (
            s.contact_pin_weight,
            s.constraint_tolerance,
            s.max_corrections,
        );
        let c = if self.active.is_some() {
            self.active_solver.project_constraints(
                &ActiveView(&self.terms),
                &mut self.state,
                &self.pushed,
                pin,
                tol,
                max,
            )?
        } else {
            self.rest_solver.project_constraints(
                &RestView(&self.terms),
                &mut self.state,
                &self.pushed,
                pin,
                tol,
                max,
            )?
        };
        Ok(c)
    }

    /// Up to `max_rounds` detect/resolve rounds, stopping at the first that finds nothing;
    /// returns the rounds that found contacts.
    fn collide(&mut self, total: &mut Contacts<T>, max_rounds: u32) -> u32 {
        if !self.settings.effects.collides() {
            return 0;
        }
        let mut rounds = 0;
        for _ in 0..max_rounds {
            let c = self.resolve_contacts();
            total.tested += c.tested;
            if c.resolved == 0 {
                break;
            }
            rounds += 1;
            total.resolved += c.resolved;
            if c.max_depth > total.max_depth {
                total.max_depth = c.max_depth;
            }
        }
        rounds
    }

    /// Pushes `node` out of `obstacle`, adding the displacement over the time step to its
    /// velocity (an inelastic contact); the node is pinned in this step's projection and
    /// held on the obstacle's plane by a contact spring in the next step.
    fn push_node(&mut self, node: usize, obstacle: &impl Obstacle<T>) -> Option<T> {
        let before = self.state.x[node];
        let depth = obstacle.resolve(&mut self.state.x[node])?;
        self.pushed[node] = true;
        let k = self.settings.contact_stiffness * self.terms.mass(node);
        self.terms.set_contact(node, obstacle.contact_plane(k));
        let h = self.settings.solver.time_step;
        self.state.v[node] += (self.state.x[node] - before) / h;
        Some(depth)
    }

    /// The wall of segment `k` of the block on `side`, on the block's material side, with
    /// clearance `clearance`.
    fn block_wall(&self, side: BlockSide, k: usize, clearance: T) -> Option<Wall<T>> {
        let line = self.midline(side);
        let (a, b) = (line[k], line[k + 1]);
        let d = b - a;
        let toward = match side {
            BlockSide::Left => T::Vec3::new(d.y(), -d.x(), T::ZERO),
            BlockSide::Right => T::Vec3::new(-d.y(), d.x(), T::ZERO),
        };
        let mut wall = Wall::new(a, b, toward, clearance)?;
        wall.open_end = k + 2 == line.len();
        Some(wall)
    }

    /// The blocks' part of [`Book::resolve_contacts`]: cover and binding on the table,
    /// blocks on the cover (or the table).
    fn resolve_block_contacts(&mut self, c: &mut Contacts<T>) {
        let n = self.terms.nodes;
        let up = T::Vec3::new(T::ZERO, T::ONE, T::ZERO);
        let y0 = T::from_f64(if n.cover {
            self.layout.params.cover_thickness
        } else {
            0.0
        });
        let table = Floor { level: y0 };
        let lifted: [usize; 4] = if n.cover {
            [
                n.block(false, 0),
                n.block(true, 0),
                n.cover_end(false),
                n.cover_end(true),
            ]
        } else {
            [
                n.block(false, 0),
                n.block(true, 0),
                n.block(false, 0),
                n.block(true, 0),
            ]
        };
        for node in lifted {
            c.record(self.push_node(node, &table));
        }
        for side in [BlockSide::Left, BlockSide::Right] {
            let right = side == BlockSide::Right;
            let board = n.cover.then(|| {
                let a = self.state.x[n.block(right, 0)];
                Wall::new(a, self.state.x[n.cover_end(right)], up, T::ZERO)
            });
            for k in 1..n.midline {
                let node = n.block(right, k);
                let depth = match board {
                    Some(Some(wall)) => self.push_node(node, &wall),
                    Some(None) => None,
                    None => self.push_node(node, &table),
                };
                c.record(depth);
            }
        }
    }

    /// One detect/resolve round (seed Sec. 3.4): cover and binding on the table, blocks on
    /// the cover (or the table) when the blocks are simulated, the active page on the
    /// blocks.
    fn resolve_contacts(&mut self) -> Contacts<T> {
        let n = self.terms.nodes;
        let mut c = Contacts::default();
        if self.settings.effects.blocks {
            self.resolve_block_contacts(&mut c);
        }
        if self.active.is_some() {
            let half = self.active_thickness() * T::HALF;
            for side in [BlockSide::Left, BlockSide::Right] {
                let clearance = self.block_thickness(side) + half;
                for k in 0..n.midline - 1 {
                    let Some(wall) = self.block_wall(side, k, clearance) else {
                        continue;
                    };
                    for node in n.page_offset()..n.total() {
                        if n.is_bound(node) {
                            continue;
                        }
                        c.record(self.push_node(node, &wall));
                    }
                }
            }
        }
        c
    }

    /// Merges a released page whose nodes have all been slower than `merge_speed` for
    /// `merge_frames` steps into the block under its fore-edge (seed Sec. 4.1).
    fn merge_if_settled(&mut self) -> Option<BlockSide> {
        let n = self.terms.nodes;
        let active = self.active.as_mut()?;
        if active.hold.is_some() {
            return None;
        }
        let speed = self.state.v[n.page_offset()..]
            .iter()
            .map(|v| math::length::<T>(*v))
            .fold(T::ZERO, |m, s| if s > m { s } else { m });
        if speed < self.settings.merge_speed {
            active.slow_frames += 1;
        } else {
            active.slow_frames = 0;
        }
        if active.slow_frames < self.settings.merge_frames {
            return None;
        }
        let center =
            (self.state.x[n.block(false, 0)].x() + self.state.x[n.block(true, 0)].x()) * T::HALF;
        let mut edge = T::ZERO;
        for j in 0..n.grid.nz {
            edge += self.state.x[n.page(n.grid.nx - 1, j)].x();
        }
        let side = if edge < center * T::from_f64(n.grid.nz as f64) {
            BlockSide::Left
        } else {
            BlockSide::Right
        };
        *self.counts.block_mut(side) += self.counts.active;
        self.counts.active = 0;
        self.active = None;
        self.update_masses();
        Some(side)
    }

    /// Moves every flying page one step along its flight; drops the ones that arrived.
    fn advance_flips(&mut self) {
        for f in &mut self.flips {
            f.position += f.rate;
        }
        self.flips
            .retain(|f| f.position > T::ZERO && f.position < T::ONE);
    }

    /// Finger-bookmarking (seed Sec. 4.1): one more page of the block the active page came
    /// from flips into the grip (`add`) or one held page flips back (`!add`). Counts, masses
    /// and $q$ change at once; the flying page is drawn from [`Book::flip_page`].
    pub fn bookmark(&mut self, add: bool) -> BookmarkOutcome {
        if !self.settings.effects.bookmarks() {
            return BookmarkOutcome::Disabled;
        }
        let Some(a) = self.active.filter(|a| a.hold.is_some()) else {
            return BookmarkOutcome::NotHeld;
        };
        if self.flips.len() >= self.settings.max_flips {
            return BookmarkOutcome::Busy;
        }
        let rate = T::ONE / T::from_f64(f64::from(self.settings.flip_frames.max(1)));
        let flip = if add {
            if self.counts.block(a.from) == 0 {
                return BookmarkOutcome::NoPage;
            }
            *self.counts.block_mut(a.from) -= 1;
            self.counts.active += 1;
            Flip {
                position: T::ZERO,
                rate,
            }
        } else {
            if self.counts.active <= 1 {
                return BookmarkOutcome::NoPage;
            }
            *self.counts.block_mut(a.from) += 1;
            self.counts.active -= 1;
            Flip {
                position: T::ONE,
                rate: -rate,
            }
        };
        self.flips.push(flip);
        self.update_masses();
        BookmarkOutcome::Started
    }

    /// Pages in flight between the block and the grip.
    #[must_use]
    pub fn flips(&self) -> &[Flip<T>] {
        &self.flips
    }

    /// The geometry of flying page `k` (grid order) into `out`, interpolated along the
    /// history of the active page (seed Fig. 11). Writes nothing for a bad `k` or size.
    pub fn flip_page(&self, k: usize, out: &mut [T::Vec3]) {
        let (Some(f), Some(page)) = (self.flips.get(k), self.page()) else {
            return;
        };
        self.history.interpolate(out, page, f.position);
    }

    /// The history of active-page geometries (seed Fig. 11).
    #[must_use]
    pub fn history(&self) -> &History<T> {
        &self.history
    }

    /// Applies a recorded input (see [`super::script`]); the ray starts at `camera`.
    ///
    /// # Errors
    /// As [`Book::grab`] and [`Book::drag`] for invalid rays.
    pub fn apply(
        &mut self,
        camera: [f64; 3],
        forward: [f64; 3],
        action: Action,
    ) -> Result<InputOutcome, BookError> {
        let v = |a: [f64; 3]| T::Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]));
        let ray = |d: [f64; 3]| Ray {
            origin: v(camera),
            direction: v(d),
        };
        Ok(match action {
            Action::Grab { direction, pages } => {
                InputOutcome::Grab(self.grab(&ray(direction), v(forward), pages)?)
            }
            Action::Drag { direction } => InputOutcome::Drag(self.drag(&ray(direction))?),
            Action::Release => InputOutcome::Release(self.release()),
            Action::BookmarkAdd => InputOutcome::Bookmark(self.bookmark(true)),
            Action::BookmarkRemove => InputOutcome::Bookmark(self.bookmark(false)),
        })
    }

    /// Maximum and RMS relative stretch $\lvert \ell/\ell_0 - 1\rvert$ over the active page's
    /// grid edges (seed Sec. 5: 11 % and 1.8 % on average over a page turn).
    #[must_use]
    pub fn stretch(&self) -> Option<(T, T)> {
        let page = self.page()?;
        let mut max = T::ZERO;
        let mut sum = T::ZERO;
        for &([a, b], rest) in &self.edges {
            let s = math::abs(math::length::<T>(page[a] - page[b]) / rest - T::ONE);
            if s > max || !s.is_finite() {
                max = s;
            }
            sum += s * s;
        }
        let rms = math::sqrt(sum / T::from_f64(self.edges.len() as f64));
        Some((max, rms))
    }

    /// $\max \lvert C_{\mathrm{DOG}}\rvert$ of the active page.
    #[must_use]
    pub fn dog_residual(&self) -> Option<T> {
        self.page()?;
        Some(self.terms.dog_residual(&self.state.x))
    }

    /// Deepest penetration of an active-page node (bound column excepted) into a block's
    /// clearance band: block thickness plus half the active thickness (seed Sec. 3.4).
    #[must_use]
    pub fn penetration(&self) -> Option<T> {
        self.page()?;
        let n = self.terms.nodes;
        let half = self.active_thickness() * T::HALF;
        let mut worst = T::ZERO;
        for side in [BlockSide::Left, BlockSide::Right] {
            let clearance = self.block_thickness(side) + half;
            for k in 0..n.midline - 1 {
                let Some(wall) = self.block_wall(side, k, clearance) else {
                    continue;
                };
                for node in n.page_offset()..n.total() {
                    if n.is_bound(node) {
                        continue;
                    }
                    if let Some(d) = wall.penetration(self.state.x[node]) {
                        if d > worst {
                            worst = d;
                        }
                    }
                }
            }
        }
        Some(worst)
    }
}
