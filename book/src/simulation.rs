//! The simulated book (seed `000_…` Sec. 3-4): a book at rest steps only its page blocks;
//! a grab turns the top page of a block (or a stack of them) into the active page, which
//! follows the drag through the tent, falls under gravity when released, and merges into
//! the block it comes to rest on.
//!
//! The book's methods live by concern: grab and drag in `grab.rs`, collisions and the
//! constraint projection in `collide.rs`, release and merge in `merge.rs`, finger-bookmarking
//! in `flip.rs`; this file holds the book itself, its construction, the step and the read
//! accessors.

use crate::BookLayout;
use alloc::vec::Vec;
use folio_geometry::{BlockSide, Contacts, QuadGrid};
use folio_kernels::{Real, SettingError, Vec3Ops, math};

use super::bookmark::{Flip, History};
use super::broad_phase::PageBroadPhase;
use super::effects::TermCensus;
use super::error::BookError;
use super::interaction::{Ray, Tent};
use super::model::{ActiveView, BookTerms, NodeMap, RestView};
use super::script::Action;
use super::settings::BookSettings;
use folio_solvers::model::Model;
use folio_solvers::report::{StepReport, StepStatus};
use folio_solvers::step::{Correction, Solver, State};

pub use crate::outcome::{BookmarkOutcome, DragOutcome, GrabOutcome, InputOutcome};

/// Unknowns and constraint rows of `solver`'s analysed KKT pattern.
fn pattern_size<T: Real>(solver: &Solver<T>) -> (usize, usize) {
    solver
        .kkt()
        .map_or((0, 0), |k| (k.pattern().dofs(), k.pattern().rows()))
}

/// Every node's initial position: the layout's midlines and cover ends in the XY plane; the
/// page nodes at the origin until the page is placed.
fn initial_positions<T: Real>(layout: &BookLayout, n: NodeMap) -> Vec<T::Vec3> {
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
    x
}

/// The page grid's edges with their rest lengths (`spacing = [across, along]`).
fn rest_edges<T: Real>(grid: QuadGrid, spacing: [f64; 2]) -> Vec<([usize; 2], T)> {
    grid.edges()
        .into_iter()
        .map(|[a, b]| {
            let along = grid.coords(a).1 != grid.coords(b).1;
            ([a, b], T::from_f64(spacing[usize::from(along)]))
        })
        .collect()
}

/// Steps without a new smallest move after which the settling's continuation hands over
/// to the dynamics ([`Book::new`]). Measured: an `f32` book of two pages, whose contacts
/// jitter by 4e-5 page units a step at $8h$, never settled from rest.
const STALLED_SETTLE_STEPS: u32 = 16;

/// The settling's stop ([`Book::new`]): the last step moved no node by more than
/// `tolerance`, and the distance still to go is within it too. The iteration converges
/// linearly, each move $r$ = `moved` / `previous` times the last, so what is left is the
/// geometric tail $m\,r/(1 - r)$; a step that moved no less than the one before ($r \ge 1$)
/// has reached the rounding floor, where the moves no longer shrink. A crawl ($r$ near 1:
/// a pseudo step held short by the inertia correction) must move far less than
/// `tolerance` before it stops: stopped at `moved` = `tolerance`, an `f32` book of two
/// pages settled 1.8e-3 page units from rest (8× its dynamic settling).
fn settled<T: Real>(moved: T, previous: T, tolerance: T) -> bool {
    if moved > tolerance {
        return false;
    }
    if moved >= previous {
        return true;
    }
    let r = moved / previous;
    moved * r <= tolerance * (T::ONE - r)
}

/// The settling's next pseudo time step ([`Book::new`]) after a step at `h`: doubled, up
/// to `longest`, after a clean step (advanced with one factorization); halved, down to
/// the scene's `base`, after one that did not advance or needed the inertia correction.
fn next_pseudo_step<T: Real>(h: T, clean: bool, base: T, longest: T) -> T {
    if clean {
        if h + h < longest { h + h } else { longest }
    } else if h * T::HALF > base {
        h * T::HALF
    } else {
        base
    }
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
    pub(crate) fn block_mut(&mut self, side: BlockSide) -> &mut u32 {
        match side {
            BlockSide::Left => &mut self.left,
            BlockSide::Right => &mut self.right,
        }
    }
}

/// What the book is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
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
pub(crate) struct Hold<T: Real> {
    /// The held node (global index).
    pub(crate) node: usize,
    /// Where the user wants the node (the pull's target is this on a leash, see
    /// [`BookSettings::pull_reach`]).
    pub(crate) target: T::Vec3,
    /// A point of the drag plane (the held node at the grab).
    pub(crate) plane_point: T::Vec3,
    /// The drag plane's unit normal (the camera's forward direction at the grab).
    pub(crate) plane_normal: T::Vec3,
    /// The tent over the binding the drag target is projected onto.
    pub(crate) tent: Tent<T>,
}

/// The active page (or stack).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ActivePage<T: Real> {
    /// The block it was taken from.
    pub(crate) from: BlockSide,
    /// The user's hold, `None` once released.
    pub(crate) hold: Option<Hold<T>>,
    /// Consecutive steps, since the release, with every node slower than `merge_speed`.
    pub(crate) slow_frames: u32,
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
    /// The book was asleep: the step did no solver work ([`Book::is_asleep`]).
    pub asleep: bool,
}

/// The simulated book (module docs).
#[derive(Clone, Debug)]
pub struct Book<T: Real> {
    pub(crate) settings: BookSettings<T>,
    pub(crate) layout: BookLayout,
    pub(crate) terms: BookTerms<T>,
    pub(crate) rest_solver: Solver<T>,
    pub(crate) active_solver: Solver<T>,
    pub(crate) state: State<T>,
    pub(crate) counts: PageCounts,
    pub(crate) active: Option<ActivePage<T>>,
    /// Grid edges with their rest lengths.
    pub(crate) edges: Vec<([usize; 2], T)>,
    pub(crate) settle_steps: u32,
    pub(crate) history: History<T>,
    pub(crate) flips: Vec<Flip<T>>,
    /// Nodes a collision pushed in the current step (pinned by the projection).
    pub(crate) pushed: Vec<bool>,
    /// Per node, the normal of the surface that pushed it in the current step (zero when
    /// two surfaces of different normals pushed it): the projection holds it along this
    /// normal and lets it slide along the surface.
    pub(crate) pushed_normal: Vec<T::Vec3>,
    /// The broad phase of the active page's collisions.
    pub(crate) broad: PageBroadPhase<T>,
    /// The terms of the rest view and of the active view.
    pub(crate) census: [TermCensus; 2],
    /// Consecutive steps at rest with every block and cover node slower than
    /// [`BookSettings::sleep_speed`]; the book sleeps from `sleep_frames` on.
    pub(crate) quiet_frames: u32,
    /// Each block's top page as walls, left then right ([`crate::Gutter::TopPage`],
    /// `gutter/walls.rs`); empty under the seed's gutter.
    pub(crate) top_pages: [Vec<T::Vec3>; 2],
    /// The page counts the top pages were settled for.
    pub(crate) top_page_counts: Option<PageCounts>,
    /// Top pages that did not settle ([`Book::top_page_failures`]).
    pub(crate) top_page_failures: u32,
    /// The finger's pad while one holds the page ([`BookSettings::pad_radius`]).
    pub(crate) pad: crate::pad::HeldPad<T>,
}

impl<T: Real> BookStepReport<T> {
    /// The report of a step the book slept through: nothing solved, nothing moved.
    fn asleep() -> Self {
        Self {
            solver: StepReport::new(StepStatus::Converged, false),
            phase: Phase::AtRest,
            dofs: 0,
            constraint_rows: 0,
            contacts: Contacts::default(),
            collision_rounds: 0,
            correction: Correction::default(),
            census: TermCensus::default(),
            snapshot: false,
            merged: None,
            asleep: true,
        }
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
        let grid = QuadGrid::new(settings.quads_across, settings.quads_along)
            .ok_or(SettingError::new("quads_across", "at least 1"))?;
        let terms = BookTerms::new(&layout, &settings, grid)?;
        let n = terms.nodes;
        let p = &layout.params;
        let x = initial_positions::<T>(&layout, n);
        let edges = rest_edges(grid, settings.grid_spacing());
        let counts = PageCounts {
            left: p.left_pages,
            right: p.total_pages - p.left_pages,
            active: 0,
        };
        let pushed = alloc::vec![false; n.total()];
        let pushed_normal = alloc::vec![T::Vec3::ZERO; n.total()];
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
            pushed_normal,
            broad: PageBroadPhase::new(n),
            census: [TermCensus::default(); 2],
            quiet_frames: 0,
            top_pages: [Vec::new(), Vec::new()],
            top_page_counts: None,
            top_page_failures: 0,
            pad: crate::pad::HeldPad::none(),
        };
        book.place_page(BlockSide::Right, 1);
        book.update_masses();
        book.analyse()?;
        book.settle()?;
        Ok(book)
    }

    /// Analyses the views the book steps (the rest view only when the blocks are simulated)
    /// and counts their terms. Both solvers project after their steps (`collide.rs`), so
    /// both analyse the projection's normal equations too.
    fn analyse(&mut self) -> Result<(), BookError> {
        if self.settings.effects.blocks {
            self.rest_solver
                .analyse_projection(&RestView(&self.terms))?;
            RestView(&self.terms).visit_terms(&mut self.census[0]);
        }
        self.active_solver
            .analyse_projection(&ActiveView(&self.terms))?;
        ActiveView(&self.terms).visit_terms(&mut self.census[1]);
        Ok(())
    }

    /// Settles the blocks into their rest shape by pseudo-transient continuation (Kelley
    /// and Keyes 1998, "Convergence analysis of pseudo-transient continuation"): implicit
    /// steps from rest, $v = 0$, so that each is the proximal step
    /// $x_{k+1} = \arg\min_x E(x) + \tfrac{1}{2h_k^2}\lVert x - x_k\rVert_M^2$ on the
    /// potential energy, under the constraints and contacts, with the pseudo time step
    /// $h_k$ from [`next_pseudo_step`]. As $h_k$ grows the step tends to Newton's on the
    /// equilibrium $\nabla E = 0$, so the blocks reach the rest that stepping at $h$
    /// reaches, in far fewer steps (no inertia to ring down).
    ///
    /// At the first clean step (advanced, one factorization) that is [`settled`], the
    /// dynamics at $h$ take over, and the settling stops at their first step that moves no
    /// node by more than `settle_tolerance` (or after `settle_steps`). They take over too
    /// once the largest move has been under $\sqrt{\text{settle\_tolerance}}$ and has not
    /// fallen to a new low for [`STALLED_SETTLE_STEPS`] steps (the bound keeps a long fall,
    /// whose moves grow before they shrink, in the continuation). With `settle_stretch` 1
    /// the blocks step their dynamics at $h$ throughout (velocities kept).
    fn settle(&mut self) -> Result<(), BookError> {
        let base = self.settings.solver;
        let mut h = base.time_step;
        let longest = base.time_step * self.settings.settle_stretch;
        let mut before = self.state.x.clone();
        let mut from_rest = longest > base.time_step;
        let (mut previous, mut best, mut since_best) = (T::ZERO, T::ZERO, 0);
        let mut result = Ok(());
        for k in 0..self.settings.settle_steps {
            if from_rest {
                self.state.v.iter_mut().for_each(|v| *v = T::Vec3::ZERO);
            }
            self.settings.solver.time_step = h;
            if let Err(e) = self.rest_solver.set_settings(self.settings.solver) {
                result = Err(e.into());
                break;
            }
            let report = match self.advance() {
                Ok(r) => r,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            };
            let moved = self
                .state
                .x
                .iter()
                .zip(&before)
                .map(|(a, b)| math::length::<T>(*a - *b))
                .fold(T::ZERO, |m, d| if d > m { d } else { m });
            before.copy_from_slice(&self.state.x);
            self.settle_steps = k + 1;
            let advanced = report.solver.status.advanced();
            // A step that needed the inertia correction (a second factorization) took a
            // shifted, shortened step: the pseudo step is past what the Hessian carries,
            // and its small move says nothing about rest.
            let clean = advanced && report.solver.factorizations <= 1;
            let tolerance = self.settings.settle_tolerance;
            if !from_rest {
                if advanced && moved <= tolerance {
                    break;
                }
                continue;
            }
            let settled_now = clean && settled(moved, previous, tolerance);
            previous = moved;
            (best, since_best) = if k == 0 || moved < best {
                (moved, 0)
            } else {
                (best, since_best + 1)
            };
            let stalled = since_best >= STALLED_SETTLE_STEPS && best * best <= tolerance;
            if settled_now || stalled {
                // The dynamics at h finish from here: rest is checked at the scene's step,
                // and a stalled continuation (contacts jittering at a floor the pseudo step
                // amplifies) gets there too.
                from_rest = false;
                h = base.time_step;
                continue;
            }
            h = next_pseudo_step(h, clean, base.time_step, longest);
        }
        self.settings.solver = base;
        self.rest_solver.set_settings(base)?;
        self.state.v.iter_mut().for_each(|v| *v = T::Vec3::ZERO);
        result
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

    /// The page's width $W$ and height $H = W a$ (page units, $a$ the aspect ratio): the
    /// material points $(u, v) \in [0, W] \times [0, H]$ of [`Book::grab_at`].
    #[inline]
    #[must_use]
    pub fn page_size(&self) -> [f64; 2] {
        let p = &self.layout.params;
        [p.page_width, p.page_height()]
    }

    /// The page grid's rest spacing `[across, along]` (page units).
    #[must_use]
    pub fn grid_spacing(&self) -> [f64; 2] {
        self.settings.grid_spacing()
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
    pub(crate) fn update_masses(&mut self) {
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

    /// Advances the book by one time step: the implicit-Euler step of the blocks (and the
    /// active page, if any), collision handling, and the merge of a page come to rest. A
    /// book asleep ([`Book::is_asleep`]) does none of it: the step returns at once with a
    /// report that says so.
    ///
    /// # Errors
    /// Only setup errors of the solver (they cannot occur after a successful [`Book::new`]).
    pub fn step(&mut self) -> Result<BookStepReport<T>, BookError> {
        if self.is_asleep() {
            return Ok(BookStepReport::asleep());
        }
        let report = self.advance()?;
        self.doze(report.phase, report.dofs);
        Ok(report)
    }

    /// [`Book::step`] awake: the step itself, whether or not the book would sleep (the
    /// settling at construction has a test of its own).
    fn advance(&mut self) -> Result<BookStepReport<T>, BookError> {
        let phase = self.phase();
        self.leash_pull();
        let drag = T::ONE / (T::ONE + self.settings.air_drag * self.settings.solver.time_step);
        for v in &mut self.state.v {
            *v *= drag;
        }
        let (report, dofs, constraint_rows, census) = self.solve()?;
        let mut contacts = Contacts::default();
        let mut correction = Correction::default();
        let rounds = if report.status.advanced() && dofs > 0 {
            self.collide_and_project(&mut contacts, &mut correction)?
        } else {
            0
        };
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
            asleep: false,
        })
    }

    /// The book is asleep ([`BookSettings::sleep_speed`]): at rest, with no page in
    /// flight, and its blocks and cover slower than `sleep_speed` for the last
    /// `sleep_frames` steps. Its steps do no solver work until an input makes a page active
    /// (a grab, or a bookmark that sends a page flying), which wakes it.
    #[must_use]
    pub fn is_asleep(&self) -> bool {
        self.quiet_frames >= self.settings.sleep_frames
            && self.active.is_none()
            && self.flips.is_empty()
    }

    /// Counts the step just taken in `phase` (a view of `dofs` unknowns) towards sleep:
    /// quiet when the book was at rest, nothing is in flight, and every node of the view
    /// (blocks and cover, `..page_offset`) is slower than `sleep_speed`. On the step that
    /// makes the book fall asleep, their velocities are zeroed, so that it wakes from rest.
    fn doze(&mut self, phase: Phase, dofs: usize) {
        let s = &self.settings;
        let po = self.terms.nodes.page_offset();
        let at_rest = phase == Phase::AtRest && self.active.is_none() && self.flips.is_empty();
        let quiet = at_rest
            && dofs > 0
            && s.sleep_speed > T::ZERO
            && self.state.v[..po]
                .iter()
                .all(|v| math::length::<T>(*v) < s.sleep_speed);
        self.quiet_frames = if quiet {
            self.quiet_frames.saturating_add(1)
        } else {
            0
        };
        if self.is_asleep() {
            self.state.v[..po]
                .iter_mut()
                .for_each(|v| *v = T::Vec3::ZERO);
        }
    }

    /// The implicit step of the view the book is in (the blocks with the active page, the
    /// blocks alone, or nothing when the blocks are fixed and no page is active): the
    /// stepper's report, the unknowns and constraint rows of its KKT system, and the terms
    /// of the view.
    fn solve(&mut self) -> Result<(StepReport<T>, usize, usize, TermCensus), BookError> {
        Ok(if self.active.is_some() {
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
        })
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
}
