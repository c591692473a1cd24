//! The book's parameters: geometry, weights, masses, interaction and solver settings.
//! Defaults are the seed's (`000_…` Sec. 5) where it gives them.

use crate::BookParams;
use folio_kernels::Real;
use folio_kernels::setting::{
    SettingError, require, require_at_least, require_non_negative, require_positive, require_range,
};

use super::effects::Effects;
use folio_solvers::settings::Settings;

/// Weights of the potentials of seed `000_…` eq. 9-14 at the seed's 11x8 grid
/// (dimensionless multipliers of the unweighted kernels), each in its range of
/// [`WEIGHT_RANGES`].
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights<T: Real> {
    /// $w_{\mathrm{bend3D}}$, DOG-Laplacian bending of the active page, area-weighted
    /// ([`crate::quadrature`]): the page's bending stiffness is $D = 2 w_{\mathrm{bend3D}}$ at
    /// every grid. In $[30, 200]$, from [`SOFT_BEND_PAGE_MIN`] under
    /// [`IsometryHessian::Projected`]; default 172, the seed's 120 with its unweighted terms
    /// (why: `docs/settings.md`).
    pub bend_page: T,
    /// $w_{\mathrm{bend2D}}$, curve-Laplacian bending of the block midlines. In $[100, 10^4]$;
    /// default 200.
    pub bend_blocks: T,
    /// $w_{\mathrm{glue}}$, binding glue. In $[100, 3000]$; default 600.
    pub glue: T,
    /// $w_{\mathrm{iso3D}}$, soft isometry of the active page. In $[3000, 3 \cdot 10^4]$;
    /// default 4000 at the 8x11 grid (scaled with the grid, [`BookSettings::iso_scale`]).
    pub iso_page: T,
    /// $w_{\mathrm{pos}}$, the grab's pull. In $[50, 2000]$; default 400; its force is bounded
    /// by the grip (`grip_strain`).
    pub pull: T,
}

/// The range each weight is documented and validated for (field path, lowest, highest),
/// in field order; the defaults lie inside. Inside them, random gestures (grabs anywhere,
/// drags beyond the book, flicks, releases) keep the page within 10 % stretch for any
/// combination of weights (`tests/tests/bounded_book.rs`, and the box's 32 corners in
/// `tests/tests/hard_cases/book.rs`); `docs/settings.md` gives what breaks outside them.
pub const WEIGHT_RANGES: [(&str, f64, f64); 5] = [
    ("weights.bend_page", 30.0, 200.0),
    ("weights.bend_blocks", 100.0, 1e4),
    ("weights.glue", 100.0, 3000.0),
    ("weights.iso_page", 3000.0, 3e4),
    ("weights.pull", 50.0, 2000.0),
];

/// The lowest `weights.bend_page` under [`IsometryHessian::Projected`] (or a convexifying
/// solver, [`BookSettings::holds_a_soft_page`]), which holds a page
/// that soft (the exact Hessian holds its range of [`WEIGHT_RANGES`], from 30): a sag number
/// of 167 at the default page mass, bible paper on an A4 page (`tests/tests/paper_turns.rs`
/// turns a page at this bound).
pub const SOFT_BEND_PAGE_MIN: f64 = 0.25;

impl<T: Real> Weights<T> {
    /// Every weight with its path from [`BookSettings`] (`"weights.glue"`), in field order.
    #[must_use]
    pub fn named(&self) -> [(&'static str, T); 5] {
        [
            ("weights.bend_page", self.bend_page),
            ("weights.bend_blocks", self.bend_blocks),
            ("weights.glue", self.glue),
            ("weights.iso_page", self.iso_page),
            ("weights.pull", self.pull),
        ]
    }

    /// The same weights in another precision (or any other map of each weight).
    #[must_use]
    pub fn map<U: Real>(self, f: impl Fn(T) -> U) -> Weights<U> {
        Weights {
            bend_page: f(self.bend_page),
            bend_blocks: f(self.bend_blocks),
            glue: f(self.glue),
            iso_page: f(self.iso_page),
            pull: f(self.pull),
        }
    }
}

impl<T: Real> Default for Weights<T> {
    fn default() -> Self {
        Self {
            bend_page: T::from_f64(172.0),
            bend_blocks: T::from_f64(200.0),
            glue: T::from_f64(600.0),
            iso_page: T::from_f64(4000.0),
            pull: T::from_f64(400.0),
        }
    }
}

/// Which Hessian of the soft isometry $V = (\lVert d\rVert^2 - L_0^2)^2$ (seed `000_…`
/// eq. 13, [`folio_kernels::iso3d`]) the Newton step assembles.
///
/// The exact Hessian $8dd^{\mathsf T} + 4sI$, $s = \lVert d\rVert^2 - L_0^2$, is
/// indefinite on a compressed edge ($s < 0$). Against the seed's stiff page the inertia
/// $M/h^2$ outweighs that; against a page of real paper, 2.6 (card) to 229 (bible paper)
/// times softer for its weight, it does not, and the step's inertia correction then shifts
/// the primal block by up to $7 \cdot 10^5$, 450 times the page's $M/h^2$: measured on a
/// novel page (sag number 11), the held node stalled 8 page units from the finger and the
/// page fell back. Dropping the $4sI$ part where $s < 0$ keeps every term positive
/// semi-definite and the step unshifted: the same page follows the finger and turns.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "lowercase")
)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IsometryHessian {
    /// $8dd^{\mathsf T} + 4sI$ (the seed's Newton step).
    #[default]
    Exact,
    /// $8dd^{\mathsf T} + 4\max(s, 0)I$: positive semi-definite
    /// ([`folio_kernels::iso3d::Iso3d::hessian_projected`]).
    Projected,
}

impl IsometryHessian {
    /// The Hessian that holds a page of bending weight `bend_page`:
    /// [`IsometryHessian::Projected`] below the exact Hessian's range ([`WEIGHT_RANGES`],
    /// from 30), where a soft page makes the exact one indefinite, else
    /// [`IsometryHessian::Exact`]. [`crate::Paper::apply`] sets it.
    #[must_use]
    pub fn for_bend_page(bend_page: f64) -> Self {
        if bend_page < WEIGHT_RANGES[0].1 {
            Self::Projected
        } else {
            Self::Exact
        }
    }
}

/// What the active page meets near the binding (issue 42; Folio's choice against the seed's,
/// [`crate::gutter`]).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Gutter {
    /// The seed's (Sec. 3.4): each block is the clearance band around its midline, with a
    /// rounded cap at its spine edge, a quarter disk about the block's binding node that
    /// clamps a page leaving the hinge upright (`docs/accuracy.md`, "the gutter is a cusp").
    #[default]
    Seed,
    /// Each block's top page as paper lies ([`crate::gutter::top_page`], 200 segments): a
    /// heavy elastica from the hinge over its block cut square at the binding, solved when
    /// the page counts change (a grab, a merge, a flip) and kept as
    /// [`crate::gutter::TOP_PAGE_WALLS`] walls the active page stays above (clearance half
    /// the active page plus half a page). The blocks' midline walls stay; their rounded
    /// caps at the spine edge go. A grabbed page is laid on its block's top page. Needs
    /// the Cargo feature `gutter` (the firmware leaves it out: the elastica's solver is
    /// 47 KB of flash).
    TopPage,
}

/// Everything that defines a simulated book.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BookSettings<T: Real> {
    /// Page counts, page size and thickness, cover, midline resolution.
    pub params: BookParams,
    /// Quads of the active page across its width, from the binding to the fore-edge: at least
    /// 2, and at most 65536 quads in all. Default 8.
    pub quads_across: usize,
    /// Quads of the active page along the binding, at least 2. Default 11: the seed's 11x8 grid
    /// read as 11 along the binding and 8 across, near-square cells on a $\sqrt 2$ page.
    pub quads_along: usize,
    /// Potential weights at the reference grid ([`Weights`], each in its range of
    /// [`WEIGHT_RANGES`]; see [`BookSettings::iso_scale`]).
    pub weights: Weights<T>,
    /// The Hessian of the page's soft isometry (eq. 13) that the Newton step uses
    /// ([`IsometryHessian`]). Default `Exact`, the seed's; a page softer than it holds
    /// (`weights.bend_page` below 30: every book paper [`crate::Paper::apply`] gives) takes
    /// `Projected`.
    pub isometry_hessian: IsometryHessian,
    /// What the active page meets near the binding ([`Gutter`]). Default `Seed`.
    pub gutter: Gutter,
    /// Gravitational acceleration (page units per s², along −Y; finite, $\ge 0$). Default 9.81.
    pub gravity: T,
    /// Linear air drag $c$ (1/s; finite, $\ge 0$): before each step every velocity is divided
    /// by $1 + c h$, the implicit update of $\dot v = -c v$. Not in the seed, which names no
    /// damping. Default 3 (why: `docs/settings.md`).
    pub air_drag: T,
    /// Mass of one page (page masses; finite, $> 0$). Default 1.
    pub page_mass: T,
    /// Mass of each cover board's outer node (page masses; finite, $> 0$). Default 5.
    pub cover_mass: T,
    /// Smallest mass given to a block's midline (page masses; finite, $> 0$), so that an empty
    /// block still has a positive mass matrix; a block is never lighter than the active page or
    /// stack either. Default 0.5.
    pub min_block_mass: T,
    /// The grab's leash (page units; finite, $> 0$): the pull (eq. 14) aims at most this far
    /// from the held node, towards the finger, so that one Newton step is never asked to carry
    /// the page many cells at once. Default 1, two thirds of a grid cell (why:
    /// `docs/settings.md`).
    pub pull_reach: T,
    /// The grip (dimensionless; finite, $> 0$): the grab's pull never pulls harder than the
    /// tension that stretches a grid edge of the page by this much; a finger that pulls harder
    /// slips ([`crate::terms::Grip`], [`crate::BookTerms::grip_force`]). Default 0.0075, just
    /// above the default pull's largest force, so the default grab never slips (why:
    /// `docs/settings.md`).
    pub grip_strain: T,
    /// The finger's pad (page units; finite, in $[0, W/2]$ for the page width $W$): a grab
    /// holds every material point of the page within this radius of the grab point, whatever
    /// the grid ([`crate::pad`]); 0 holds one node, the seed's pull (eq. 14). Default 0. A
    /// fingertip's pad is about 7 mm, 0.57 page units on an A5 page.
    pub pad_radius: T,
    /// The fastest turn of the held node about the binding (radians per second; finite, $> 0$):
    /// the leash of one step is also at most this turn, $\omega h \rho$ at the node's distance
    /// $\rho$ from the binding along the flat page, so that one Newton iteration never turns an
    /// edge far along its tangent. Default 4 (why: `docs/settings.md`).
    pub pull_turn_rate: T,
    /// Tent height over the binding as a fraction of the grabbed node's distance from the
    /// binding, in $(0, 1]$ ([`crate::interaction::Tent`]). Default 0.6.
    pub tent_height: T,
    /// A released page merges when its fastest node has been slower than this (page units per
    /// second; finite, $> 0$) for `merge_frames` consecutive steps. Default 0.5.
    pub merge_speed: T,
    /// Consecutive slow steps before a released page merges (see `merge_speed`). Default 10.
    pub merge_frames: u32,
    /// A book at rest (no active page, no page in flight) falls asleep once every node of its
    /// blocks and cover has been slower than this (page units per second; finite, $\ge 0$) for
    /// `sleep_frames` consecutive steps: its velocities are zeroed and its steps do no solver
    /// work until an input makes a page active ([`crate::Book::is_asleep`]). 0 keeps the book
    /// awake. Default $10^{-3}$ (why: `docs/settings.md`).
    pub sleep_speed: T,
    /// Consecutive quiet steps before a book at rest falls asleep (see `sleep_speed`); at least
    /// 1. Default 10.
    pub sleep_frames: u32,
    /// The constraint projection after the step and the collision handling
    /// ([`folio_solvers::Solver::project_constraints`]) iterates until $\lVert C\rVert_\infty$
    /// is at most this (finite, $> 0$; dimensionless for the DOG rows, page units for the
    /// others) or `projection_iterations` ran. Default $10^{-4}$.
    pub projection_tolerance: T,
    /// Most iterations of one constraint projection pass, 0 to [`MAX_PROJECTION_ITERATIONS`]; 0
    /// switches the projection off (the seed's plain step, which leaves DOG residuals of a few
    /// $10^{-2}$ while the page moves fast). Where the page lands on a block, projection and
    /// collision alternate, up to twice `collision_rounds` passes. Default 5 in `f64`, 3 in
    /// `f32` (why: `docs/settings.md`).
    pub projection_iterations: u32,
    /// Contact spring stiffness per unit of node mass ($s^{-2}$; finite, $\ge 0$; 0 switches
    /// the springs off): a node pushed out of a block, the cover or the table in one step is
    /// held on that surface in the next by a [`folio_kernels::contact::ContactPlane`] spring of
    /// stiffness $k = s\thinspace m$, so that the step carries the contact force instead of
    /// re-penetrating (a resting node sinks by $g / s$); it must stay well below $g /
    /// (\varepsilon W)$, $W$ the page width, or nodes stick to their surface. Default $10^6$ in
    /// `f64`, $10^5$ in `f32` (why: `docs/settings.md`).
    pub contact_stiffness: T,
    /// Coulomb friction coefficient $\mu$ of the active page on the blocks (dimensionless;
    /// [`crate::friction`]): each contact cuts a page node's tangential speed by $\mu$ times
    /// the normal speed it gave. Default 0, the seed's frictionless contact (friction does
    /// not help a page settle; the module docs give the measurements).
    pub contact_friction: T,
    /// Weight multiplier (finite, $\ge 1$) of the nodes a collision pushed in this step during
    /// the projection, along the normal of the surface that pushed them, so that they slide
    /// along it and the constraints may lift them off (`Book::project` in `collide.rs`).
    /// Default $10^3$.
    pub contact_pin_weight: T,
    /// Collision detect/resolve rounds per step, 1 to 16 (the seed's "at most three times").
    /// Default 3.
    pub collision_rounds: u32,
    /// Most steps at construction to settle the blocks into their rest shape; the book stops
    /// early once a step moves no node by more than `settle_tolerance`. Default 20000.
    pub settle_steps: u32,
    /// The settling's stopping distance (page units; finite, $> 0$): the settling ends once a
    /// step moves no node by more than this. Default $10^{-9}$ in `f64`, $10^{-6}$ in `f32`
    /// (why: `docs/settings.md`).
    pub settle_tolerance: T,
    /// The longest pseudo time step of the settling at construction, in multiples of the time
    /// step (finite, $\ge 1$; 1 steps the dynamics at $h$ until the blocks are still): the
    /// settling doubles its step from $h$ up to this after each step that advanced
    /// (pseudo-transient continuation, `Book::settle` in `simulation.rs`). Default 24 (why:
    /// `docs/settings.md`).
    pub settle_stretch: T,
    /// Snapshots of the active page kept for finger-bookmarking (seed Fig. 11). Default 32.
    pub history_capacity: usize,
    /// Steps between snapshots (doubling whenever the history is thinned). Default 4.
    pub history_interval: u32,
    /// Steps a bookmarked page takes to fly between the block and the grip. Default 24.
    pub flip_frames: u32,
    /// Pages that may be in flight at once. Default 8.
    pub max_flips: usize,
    /// The time stepper's settings ([`Settings`]: time step, Newton iterations, line search,
    /// factorization, refinement). The book's defaults differ from the solver's in two fields:
    /// `merit_slack` 0.05 (the projection removes what the step leaves) and
    /// `refinement_tolerance` $\sqrt{\varepsilon}$ (one Newton iteration a step needs no
    /// tighter solve; why: `docs/settings.md`).
    pub solver: Settings<T>,
    /// The effects simulated (default: all; see [`Effects`]).
    pub effects: Effects,
}

impl<T: Real> Default for BookSettings<T> {
    fn default() -> Self {
        Self {
            params: BookParams::default(),
            quads_across: 8,
            quads_along: 11,
            weights: Weights::default(),
            isometry_hessian: IsometryHessian::Exact,
            gutter: Gutter::Seed,
            gravity: T::from_f64(9.81),
            air_drag: T::from_f64(3.0),
            page_mass: T::ONE,
            cover_mass: T::from_f64(5.0),
            min_block_mass: T::HALF,
            pull_reach: T::ONE,
            grip_strain: T::from_f64(0.0075),
            pad_radius: T::ZERO,
            pull_turn_rate: T::from_f64(4.0),
            tent_height: T::from_f64(0.6),
            merge_speed: T::from_f64(0.5),
            merge_frames: 10,
            sleep_speed: T::from_f64(1e-3),
            sleep_frames: 10,
            projection_tolerance: T::from_f64(1e-4),
            projection_iterations: if T::EPSILON.to_f64() < 1e-10 { 5 } else { 3 },
            contact_friction: T::ZERO,
            contact_pin_weight: T::from_f64(1e3),
            contact_stiffness: T::from_f64(if T::EPSILON.to_f64() < 1e-10 {
                1e6
            } else {
                1e5
            }),
            collision_rounds: 3,
            settle_steps: 20_000,
            settle_tolerance: T::from_f64(if T::EPSILON.to_f64() < 1e-10 {
                1e-9
            } else {
                1e-6
            }),
            settle_stretch: T::from_f64(24.0),
            history_capacity: 32,
            history_interval: 4,
            flip_frames: 24,
            max_flips: 8,
            solver: Settings {
                merit_slack: T::from_f64(0.05),
                refinement_tolerance: folio_kernels::math::sqrt(T::EPSILON),
                ..Settings::default()
            },
            effects: Effects::ALL,
        }
    }
}

/// The page grid of [`BookSettings::microcontroller`] (quads across, along): the finest with
/// about square cells that keeps the default page turn's median active step under 1.5 M
/// instructions on the Cortex-M4F in `f32` (issue 40's `page-turn-mcu`; 3 x 5 is under it
/// too, at 1.45 M with cells of 4 x 3.3, too close to the bound). Measured with the firmware
/// (`embedded/`, QEMU `-icount`; median / p99 instructions per active step, heap peak):
/// 8 x 11 (the default) 18.9 M / 43.7 M, 683 KB; 6 x 8 8.0 M / 12.7 M, 388 KB; 5 x 7
/// 4.9 M / 9.2 M, 298 KB; 4 x 6 3.0 M / 5.9 M, 225 KB; 4 x 4 2.0 M / 3.4 M, 172 KB;
/// 3 x 5 1.45 M / 3.4 M, 167 KB; 3 x 4 1.18 M / 2.7 M, 148 KB; 3 x 3 0.98 M / 1.9 M,
/// 129 KB. Every one of them turned the page onto the left block within the bounds.
/// Its cells, 4 x 4.1 page units, are about square, as the default's are.
pub const MICROCONTROLLER_GRID: [usize; 2] = [3, 4];

impl<T: Real> BookSettings<T> {
    /// The book for the smallest parts: the default book on the coarse page grid
    /// [`MICROCONTROLLER_GRID`] (the built-in scene `page-turn-mcu` runs it in `f32`), with
    /// a GMRES restart of 3 (`solver.krylov_restart`; the default 10 keeps 7 more vectors
    /// of the KKT order per solver: the firmware's heap peak 148,422 → 139,346 B): the page
    /// turn's refinement cycles in `f32` are at most 2 long (199 of 200 are 1), so the turn
    /// is the same bit for bit. What
    /// it costs in accuracy is in the accuracy atlas (`docs/atlas/page-turn/atlas.md`, the
    /// variant `dog 3x4, f32`, against the same reference as the default's).
    #[must_use]
    pub fn microcontroller() -> Self {
        let [across, along] = MICROCONTROLLER_GRID;
        let mut settings = Self {
            quads_across: across,
            quads_along: along,
            ..Self::default()
        };
        settings.solver.krylov_restart = 3;
        settings
    }
}

impl<T: Real> BookSettings<T> {
    /// Sets the Newton iterations of a step with the linear solves' refinement they need:
    /// the book's $\sqrt{\varepsilon}$ for one iteration (see `solver`), the solver's
    /// $\varepsilon^{3/4}$ for more. With $\sqrt{\varepsilon}$, Newton with the constraint
    /// Hessian on a 24 x 33 page never reached a KKT residual of $10^{-10}$ in 20 iterations.
    pub fn set_newton_iterations(&mut self, iterations: u32) {
        self.solver.newton_iterations = iterations;
        self.solver.refinement_tolerance = if iterations > 1 {
            folio_solvers::settings::Settings::<T>::default().refinement_tolerance
        } else {
            Self::default().solver.refinement_tolerance
        };
    }

    /// The page's sag number $\alpha = \rho g W^3 / D$ ([`crate::paper`]) from the book's own
    /// figures: $\rho$ the page mass over its area, $g$ the gravity, $W$ the page width and
    /// $D = 2 w_{\mathrm{bend3D}}$ ([`crate::quadrature::bending_stiffness`]). The seed's
    /// weights give 0.24; [`crate::Paper::apply`] sets a paper's.
    #[must_use]
    pub fn sag_number(&self) -> f64 {
        let p = &self.params;
        let density = self.page_mass.to_f64() / (p.page_width * p.page_height());
        let d = crate::quadrature::bending_stiffness(self.weights.bend_page.to_f64());
        density * self.gravity.to_f64() * p.page_width * p.page_width * p.page_width / d
    }

    /// The reference cell area: the seed's weights hold for an 8x11 grid on the default page.
    fn reference_cell_area(&self) -> f64 {
        let p = &self.params;
        p.page_width * p.page_height() / (8.0 * 11.0)
    }

    /// The factor applied to $w_{\mathrm{iso3D}}$ for this grid: $A_0 / A$, the reference
    /// cell area over this grid's. Per edge the iso3D energy of a uniform strain
    /// $\varepsilon$ is $4\varepsilon^2 h^4$ and there are $\sim 2A_{page}/h^2$ edges, so the
    /// sum scales with $h^2$; the factor makes the page's stretch stiffness independent of
    /// the grid. Bending has no factor, but its sum is not resolution-invariant as this doc
    /// once claimed: the DOG Laplacian divides by the rest lengths, so an inner vertex adds
    /// $h^2\kappa^2$ at any spacing, but the 3-neighbour edge rows add $4h^2\kappa^2$ on
    /// half a cell (8 times their share). On a page rolled across its rows the sum is
    /// $\kappa^2 h^2 (n_x - 2)(n_y + 6)$ against $A_{page}\kappa^2$: 1.43 times at 8x11,
    /// 1.24 at 16x22, falling only as $1/n$. The book uses the area-weighted terms and
    /// masses of [`crate::quadrature`] instead, which converge at every grid (with
    /// $D = 2 w_{\mathrm{bend3D}}$).
    #[must_use]
    pub fn iso_scale(&self) -> f64 {
        let [across, along] = self.grid_spacing();
        self.reference_cell_area() / (across * along)
    }

    /// The page grid's rest spacing `[across, along]` (page units).
    #[must_use]
    pub fn grid_spacing(&self) -> [f64; 2] {
        let p = &self.params;
        [
            p.page_width / self.quads_across as f64,
            p.page_height() / self.quads_along as f64,
        ]
    }
}

pub use folio_kernels::setting::MIN_TIME_STEP;

/// The longest time step (seconds) of a book: six frames at 60 per second. (A scene file
/// holds its steps to at most one frame, since a frame takes a whole number of steps.)
pub const MAX_TIME_STEP: f64 = 0.1;

/// A grid cell of the page must be at least this many times the book's constraint
/// tolerance (`projection_tolerance`, $10^{-4}$ page units by default): in a smaller page
/// every constraint holds to within the tolerance whatever the page does, and a gesture
/// no longer moves it measurably (a page $10^{-9}$ wide cannot be touched).
pub const MIN_CELL_TOLERANCES: f64 = 100.0;

/// The most iterations of one constraint projection pass (`projection_iterations`).
pub const MAX_PROJECTION_ITERATIONS: u32 = 50;

impl<T: Real> BookSettings<T> {
    /// The Newton step can take the convex stand-in of the page's isometry Hessian: it
    /// assembles it always ([`IsometryHessian::Projected`]) or where the exact one is
    /// indefinite (`solver.convexify`, [`folio_solvers::Convexify`]). Such a step holds a
    /// page down to [`SOFT_BEND_PAGE_MIN`]; the exact Hessian alone, from 30.
    #[must_use]
    pub fn holds_a_soft_page(&self) -> bool {
        self.isometry_hessian == IsometryHessian::Projected
            || self.solver.convexify != folio_solvers::Convexify::Never
    }

    /// Checks every field against its range (each field's docs, [`WEIGHT_RANGES`], and the
    /// layout's, the effects' and the solver's own `validate`), and that the page can be
    /// touched: a grid cell at least [`MIN_CELL_TOLERANCES`] constraint tolerances wide.
    ///
    /// # Errors
    /// The first unusable field, by its path in these settings (`params.page_width`,
    /// `weights.glue`, `solver.time_step`), its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        self.params.validate().map_err(|e| e.within("params"))?;
        self.effects.validate().map_err(|e| e.within("effects"))?;
        if self.gutter == Gutter::TopPage && !cfg!(feature = "gutter") {
            return Err(SettingError::new(
                "gutter",
                "\"seed\": the top-page gutter's Cargo feature (gutter) of folio-book is not enabled",
            ));
        }
        if self.pad_radius > T::ZERO && !cfg!(feature = "pad") {
            return Err(SettingError::new(
                "pad_radius",
                "0: the finger's pad's Cargo feature (pad) of folio-book is not enabled",
            ));
        }
        // The book's range of the step first: it is narrower than the solver's.
        let h = self.solver.time_step.to_f64();
        require(
            (MIN_TIME_STEP..=MAX_TIME_STEP).contains(&h),
            "solver.time_step",
            "in [1e-6, 0.1] seconds",
            h,
        )?;
        self.solver.validate().map_err(|e| e.within("solver"))?;
        let (across, along) = (self.quads_across, self.quads_along);
        require(across >= 2, "quads_across", "at least 2", across as f64)?;
        require(along >= 2, "quads_along", "at least 2", along as f64)?;
        require(
            across.saturating_mul(along) <= 1 << 16,
            "quads_across",
            "such that the page has at most 65536 quads (quads_across x quads_along)",
            across as f64,
        )?;
        for (field, v) in [
            ("gravity", self.gravity),
            ("air_drag", self.air_drag),
            ("contact_stiffness", self.contact_stiffness),
            ("contact_friction", self.contact_friction),
            ("sleep_speed", self.sleep_speed),
        ] {
            require_non_negative(field, v.to_f64())?;
        }
        for ((field, v), (_, lo, hi)) in self.weights.named().into_iter().zip(WEIGHT_RANGES) {
            let soft = field == "weights.bend_page" && self.holds_a_soft_page();
            let lo = if soft { SOFT_BEND_PAGE_MIN } else { lo };
            require_range(field, v.to_f64(), lo, hi)?;
        }
        for (field, v) in [
            ("page_mass", self.page_mass),
            ("cover_mass", self.cover_mass),
            ("min_block_mass", self.min_block_mass),
            ("merge_speed", self.merge_speed),
            ("pull_reach", self.pull_reach),
            ("grip_strain", self.grip_strain),
            ("pull_turn_rate", self.pull_turn_rate),
            ("settle_tolerance", self.settle_tolerance),
            ("projection_tolerance", self.projection_tolerance),
        ] {
            require_positive(field, v.to_f64())?;
        }
        require_at_least(
            "params.page_width",
            self.params.page_width,
            MIN_CELL_TOLERANCES * self.projection_tolerance.to_f64() * across as f64,
            "a page too small to touch: its grid cells must be at least 100 constraint \
             tolerances wide",
        )?;
        require_range(
            "pad_radius",
            self.pad_radius.to_f64(),
            0.0,
            0.5 * self.params.page_width,
        )?;
        require(
            self.tent_height > T::ZERO && self.tent_height <= T::ONE,
            "tent_height",
            "in (0, 1]",
            self.tent_height.to_f64(),
        )?;
        for (field, v) in [
            ("contact_pin_weight", self.contact_pin_weight),
            ("settle_stretch", self.settle_stretch),
        ] {
            require(
                v.is_finite() && v >= T::ONE,
                field,
                "finite and >= 1",
                v.to_f64(),
            )?;
        }
        let sleep = self.sleep_frames;
        require(sleep >= 1, "sleep_frames", "at least 1", f64::from(sleep))?;
        let counts = [
            (
                "projection_iterations",
                self.projection_iterations,
                0,
                MAX_PROJECTION_ITERATIONS,
            ),
            ("collision_rounds", self.collision_rounds, 1, 16),
        ];
        for (field, n, lo, hi) in counts {
            require_range(field, f64::from(n), f64::from(lo), f64::from(hi))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(settings: BookSettings<f64>) -> String {
        match settings.validate() {
            Err(e) => e.path.to_string(),
            other => panic!("expected an invalid setting, got {other:?}"),
        }
    }

    #[test]
    fn the_defaults_are_valid_in_both_precisions() {
        assert_eq!(BookSettings::<f64>::default().validate(), Ok(()));
        assert_eq!(BookSettings::<f32>::default().validate(), Ok(()));
    }

    #[test]
    fn validate_names_the_field() {
        let ok = BookSettings::<f64>::default();
        let with = |f: fn(&mut BookSettings<f64>)| {
            let mut s = ok;
            f(&mut s);
            s
        };
        assert_eq!(field(with(|s| s.quads_across = 1)), "quads_across");
        assert_eq!(field(with(|s| s.quads_along = 1)), "quads_along");
        assert_eq!(field(with(|s| s.quads_along = 70_000)), "quads_across");
        assert_eq!(field(with(|s| s.weights.glue = -1.0)), "weights.glue");
        assert_eq!(field(with(|s| s.gravity = f64::NAN)), "gravity");
        assert_eq!(field(with(|s| s.page_mass = 0.0)), "page_mass");
        assert_eq!(field(with(|s| s.tent_height = 1.5)), "tent_height");
        assert_eq!(
            field(with(|s| s.contact_pin_weight = 0.5)),
            "contact_pin_weight"
        );
        assert_eq!(field(with(|s| s.collision_rounds = 0)), "collision_rounds");
        // Zero is allowed for the non-negative fields.
        assert_eq!(with(|s| s.gravity = 0.0).validate(), Ok(()));
        assert_eq!(
            field(with(|s| s.projection_iterations = 51)),
            "projection_iterations"
        );
        assert_eq!(
            field(with(|s| s.solver.time_step = 0.2)),
            "solver.time_step"
        );
        assert_eq!(
            field(with(|s| s.solver.time_step = 0.0)),
            "solver.time_step"
        );
        assert_eq!(
            field(with(|s| s.solver.krylov_restart = 0)),
            "solver.krylov_restart"
        );
        assert_eq!(
            field(with(|s| s.params.page_width = 1e-3)),
            "params.page_width"
        );
        assert_eq!(field(with(|s| s.effects.blocks = false)), "effects.glue");
        // The layout is checked first.
        let layout = with(|s| {
            s.params.total_pages = 0;
            s.quads_across = 1;
        });
        assert_eq!(field(layout), "params.total_pages");
    }

    #[test]
    fn the_reference_grid_has_unit_iso_scale() {
        let s = BookSettings::<f64>::default();
        assert!((s.iso_scale() - 1.0).abs() < 1e-12);
        let fine = BookSettings::<f64> {
            quads_across: 16,
            quads_along: 22,
            ..s
        };
        assert!((fine.iso_scale() - 4.0).abs() < 1e-12);
        let [across, along] = s.grid_spacing();
        assert!((across * 8.0 - s.params.page_width).abs() < 1e-12);
        assert!((along * 11.0 - s.params.page_height()).abs() < 1e-12);
    }
}
