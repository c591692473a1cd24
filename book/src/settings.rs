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
    /// ([`crate::quadrature`]): the page's bending stiffness is $D = 2 w_{\mathrm{bend3D}}$
    /// at every grid. Default 172: the seed's 120 with its unweighted terms, which made the
    /// page 1.43 times stiffer at the 8x11 grid (so the same page as before there; at 120
    /// with the weighted terms a page grabbed at its fore-edge and dragged low towards the
    /// spine arched against the drag instead of turning, and `three-and-back` kept 51/49).
    pub bend_page: T,
    /// $w_{\mathrm{bend2D}}$, curve-Laplacian bending of the block midlines (200).
    pub bend_blocks: T,
    /// $w_{\mathrm{glue}}$, binding glue (600).
    pub glue: T,
    /// $w_{\mathrm{iso3D}}$, soft isometry of the active page (4000 at the 11x8 grid).
    pub iso_page: T,
    /// $w_{\mathrm{pos}}$, the grab pull (400).
    pub pull: T,
}

/// The range each weight is documented and validated for (field path, lowest, highest),
/// in field order; the
/// defaults lie inside. Scenes were allowed [0, 1e9]; inside the ranges below, random
/// gestures (grabs anywhere, drags beyond the book, flicks, releases) keep the page within
/// 10 % stretch for any combination of weights (`tests/tests/bounded_book.rs`, and the
/// box's 32 corners in `tests/tests/hard_cases/book.rs`). Outside them the model cannot
/// hold that bound, measured with a one-second page turn before the ranges were narrowed
/// (other weights at their defaults):
/// - `bend_page`: the DOG Laplacian (eq. 9) divides by the rest lengths, so its energy on
///   a bent page falls with the fourth power of the edges' length, and bending much
///   stiffer than the soft isometry shrinks a bent page instead of flattening it (max
///   stretch 10 % at 1000, 27 % at $10^4$, 22 % at $10^9$; at 490 with `iso_page` 3400,
///   11 % one step after the grab); with almost no bending the page kinks where it is held
///   (40 % at 10).
/// - `iso_page`: the soft isometry (eq. 13) is the only term that holds the edges'
///   lengths (the DOG constraints are angle conditions): at 0 the page shrinks freely and
///   never comes to rest (50 % stretch, no merge); at 300, 17 %; at 1000 with `bend_page`
///   300, 16 %. Far above it the one Newton step per frame locks and the page no longer
///   lifts ($10^6$).
/// - `bend_blocks`, `glue`: a block midline with little bending flaps and flings the page
///   (`bend_blocks` 1: 14000 %; 20 with `glue` 6000: 16 %); a glue far above the default
///   tips the blocks over (`glue` $10^9$: 118 %).
/// - `pull`: its force is bounded by the grip ([`BookSettings::grip_strain`]; without it
///   the page stretched 4280 % at $10^9$), but its stiffness is not: a pull of $10^8$ holds
///   the node as a pin, and one Newton step per frame then stretches the page around it
///   (15 %); with no pull at all a grab holds nothing and the page springs off the block
///   (19 % at 0 with `bend_page` 80, `bend_blocks` 400, `glue` 300, `iso_page` 8000).
pub const WEIGHT_RANGES: [(&str, f64, f64); 5] = [
    ("weights.bend_page", 30.0, 200.0),
    ("weights.bend_blocks", 100.0, 1e4),
    ("weights.glue", 100.0, 3000.0),
    ("weights.iso_page", 3000.0, 3e4),
    ("weights.pull", 50.0, 2000.0),
];

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
    /// Quads of the active page across its width (from the binding to the fore-edge).
    pub quads_across: usize,
    /// Quads of the active page along the binding. The seed's 11x8 grid is read as 11 along
    /// the binding and 8 across, which gives near-square cells on a $\sqrt 2$ page.
    pub quads_along: usize,
    /// Potential weights at the reference grid (see [`BookSettings::iso_scale`]).
    pub weights: Weights<T>,
    /// Gravitational acceleration (page units per s², along −Y).
    pub gravity: T,
    /// Linear air drag $c$ (1/s): before each step every velocity is divided by $1 + c h$
    /// (the implicit update of $\dot v = -c v$). The seed names no damping; without it a
    /// released page, whose weight is small next to its bending stiffness, swings about the
    /// binding for many seconds, because implicit Euler at $h = 1/60$ s barely damps motions
    /// of a few radians per second. Air drag is what stops a real page.
    pub air_drag: T,
    /// Mass of one page (page masses: 1).
    pub page_mass: T,
    /// Mass of each cover board's outer node (page masses).
    pub cover_mass: T,
    /// Smallest mass given to a block's midline (page masses), so that an empty block still
    /// has a positive mass matrix. A block is never lighter than the active page or stack
    /// either (see the book's mass update).
    pub min_block_mass: T,
    /// The grab's leash (page units): the pull (eq. 14) aims at most this far from the held
    /// node, towards the user's target. A finger that runs ahead of the page otherwise asks
    /// one Newton step to carry the page many cells at once, far outside its
    /// linearization; the line search then cuts the step to a sliver every frame and the
    /// page crawls further and further behind. Default 1 (two thirds of a grid cell).
    pub pull_reach: T,
    /// The grip (dimensionless): the grab's pull never pulls harder than the tension that
    /// stretches a grid edge of the page by this much; a finger that pulls harder slips
    /// (see [`crate::terms::Grip`] and [`crate::BookTerms::grip_force`]). Default 0.0075,
    /// just above the default pull's largest force, so the default grab never slips.
    /// Without it the pull's force is $2 w_{\mathrm{pos}} r$ on the leash $r$ and grows
    /// with the pull weight: drags of the page turn stretched the page by 18 % at
    /// $w_{\mathrm{pos}} = 10^4$, 33 % at $10^6$ and 4280 % at $10^9$; with a grip of
    /// 0.02, 3.5 % to 7.6 % at the same weights, and random gestures still found 12 %.
    pub grip_strain: T,
    /// The fastest turn of the held node about the binding (radians per second): the leash
    /// of one step is also at most this turn, $\omega h \rho$ at the node's distance
    /// $\rho$ from the binding along the flat page. One Newton iteration per step
    /// linearizes the soft isometry (eq. 13), and an edge turned by $\theta$ along its
    /// tangent grows by $\approx\theta^2/2$; a node held one cell from the spine and led on
    /// the plain leash turned 0.3 rad per step and stretched the page by over 10 %.
    /// Default 4 (0.067 rad per step at 60 steps per second): the default grab near the
    /// fore-edge, 10.5 units from the binding, gets a leash of 0.7, and a smoothstep half
    /// turn in 100 steps (2.8 rad/s at its fastest) still lands on the left in `f32`; at 3
    /// it fell back to the right (`capi/tests/page_turn.rs`), and at 6 random gestures within
    /// the weight ranges stretched the page by 13 %.
    pub pull_turn_rate: T,
    /// Tent height over the binding as a fraction of the grabbed node's distance from the
    /// binding (see [`crate::interaction::Tent`]).
    pub tent_height: T,
    /// A released page merges when its fastest node has been slower than this (page units
    /// per second) for `merge_frames` consecutive steps.
    pub merge_speed: T,
    /// See `merge_speed`.
    pub merge_frames: u32,
    /// A book at rest (no active page, no page in flight) falls asleep once every node of
    /// its blocks and cover has been slower than this (page units per second) for
    /// `sleep_frames` consecutive steps: its velocities are zeroed and its steps do no
    /// solver work until an input makes a page active ([`crate::Book::is_asleep`]; seed
    /// 000's "a book at rest simulates blocks only", taken to its end). A net force above
    /// $2 m v_{sleep}/h$ on a node of mass $m$ would raise its speed from below
    /// $v_{sleep}$ to above it within one step, so the test bounds the forces too: at the
    /// defaults, by 1.2 % of a node's weight. In ten steps under the threshold a node moves
    /// at most $10 v_{sleep} h$, $1.7 \cdot 10^{-4}$ page units. 0 keeps the book awake.
    /// Default $10^{-3}$: the default book falls asleep 10 steps after it is built (its
    /// `f32` nodes drift at up to $3 \cdot 10^{-4}$, its `f64` ones at $3 \cdot 10^{-11}$),
    /// and after a page merges once the blocks' slow rocking has died down.
    pub sleep_speed: T,
    /// See `sleep_speed`; at least 1. Default 10.
    pub sleep_frames: u32,
    /// After the step and the collision handling, the constraint projection
    /// ([`folio_solvers::Solver::project_constraints`]) iterates until $\lVert C\rVert_\infty$ is at
    /// most this (dimensionless for the DOG rows, page units for the others)...
    pub constraint_tolerance: T,
    /// ...or this many iterations ran (0 switches it off: the seed's plain step, which
    /// leaves DOG residuals of a few 1e-2 while the page moves fast), per projection pass.
    /// Default 5 in `f64`, 3 in `f32`. Where the page lands on a block, projection and
    /// collision alternate (up to twice `collision_rounds` passes) and the step ends on a
    /// collision push; a pass that stops short leaves more for the pushes to break.
    /// Measured in `f64` with `folio run` on the built-in scenes, the largest DOG residual
    /// with 3 → 5: page-turn 2.6e-4 → 1.2e-4, stack 7.3e-4 → 2.8e-4, bookmark-flip
    /// 1.4e-4 → 1.0e-4; peek and paperback stay below 1e-4, and every penetration stays at
    /// rounding level. In `f32` (quasi-definite KKT order) more passes did not help: on the
    /// page turn, 3, 4, 5, 6 and 8 gave DOG residuals of 3.5e-4, 5.4e-4, 4.8e-4, 4.8e-4 and
    /// 4.8e-4 (`cargo run --release -p folio-bench --example frame_work` with the field
    /// set).
    pub max_corrections: u32,
    /// Contact spring stiffness per unit of node mass ($s^{-2}$): a node pushed out of a
    /// block, the cover or the table in one step is held on that surface by a
    /// [`folio_kernels::contact::ContactPlane`] spring of stiffness $k = s\thinspace m$ in the next, so
    /// that the step carries the contact force instead of re-penetrating by $F h^2 / m$
    /// every frame (a resting node then sinks by $g / s$). 0 switches the springs off.
    /// The springs hold for one step whatever the direction, so a node that should lift off
    /// by less than the rounding noise of its coordinates ($\approx \varepsilon W$, $W$ the
    /// page width) stays: the spring's adhesion $k\thinspace \varepsilon W$ must be small next to the
    /// node's weight $m g$, i.e. $s \ll g / (\varepsilon W)$. Default $10^6$ in `f64`
    /// (adhesion $\approx 10^{-9}\thinspace m g$) and $10^5$ in `f32` ($\approx 0.015\thinspace m g$;
    /// at $10^6$ the f32 page sticks to its block and the page turn fails). It was
    /// $4 \cdot 10^4$ in `f32` while the `f32` factor was equilibrated
    /// (`folio_solvers::Settings::equilibrate`); unscaled, that soft a contact let a page
    /// pressed over the spine sink into the gutter, the inertia correction shifted the primal
    /// block by up to 66 times a page node's $m/h^2$, and the page stood still while the
    /// finger moved on: `capi/tests/page_turn.rs`'s drag of 100 steps fell back to the right
    /// (the held node stalled at $x = -0.3$). At $10^5$ the same drag over 80 to 160 steps
    /// lands left every time (the held node at $x \approx -9$ to $-10$ at the release, as in
    /// `f64`), and the recorded page turn takes 193 KKT factorizations instead of 256 with 4
    /// shifted steps instead of 25, its mean stretch 0.27 % instead of 0.32 %.
    pub contact_stiffness: T,
    /// Coulomb friction coefficient $\mu$ of the active page on the blocks (dimensionless;
    /// [`crate::friction`]): each contact cuts a page node's tangential speed by $\mu$ times
    /// the normal speed it gave. Default 0, the seed's frictionless contact (friction does
    /// not help a page settle; the module docs give the measurements).
    pub contact_friction: T,
    /// Weight multiplier of the nodes a collision pushed in this step during the projection,
    /// along the normal of the surface that pushed them (they slide along it, and the
    /// constraints may lift them off; `Book::project` in `collide.rs` gives why). At least
    /// 1; default $10^3$.
    pub contact_pin_weight: T,
    /// Collision detect/resolve rounds per step (the seed's "at most three times").
    pub collision_rounds: u32,
    /// Steps at construction to settle the blocks into their rest shape (the book stops
    /// early once a step moves no node by more than `settle_tolerance`).
    pub settle_steps: u32,
    /// Page units; see `settle_steps`. Default $10^{-9}$ in `f64` (a settled book's next
    /// step at $h$ then moves no node by more than $10^{-9}$, `tests/tests/book.rs`; the
    /// old $10^{-13}$ sits under the noise of contacts on the table, $10^{-10}$ to
    /// $10^{-9}$ a step for a book without a cover) and $10^{-6}$ in `f32`.
    pub settle_tolerance: T,
    /// The longest pseudo time step of the settling at construction, in multiples of the
    /// time step (at least 1; 1 steps the dynamics at $h$ until the blocks are still). The settling
    /// doubles its step from $h$ up to this after each step that advanced (pseudo-transient
    /// continuation, `Book::settle` in `simulation.rs`). Default 24, measured
    /// (`tests/tests/book_settle.rs`): the default book settles in 28 steps in `f64` and 24
    /// in `f32` where stepping the dynamics takes 523 and 323, 3.0e-7 and 3.0e-5 page
    /// units from the dynamics' `f64` rest. A book of two pages, whose single-page blocks
    /// fall a long way, takes 181 steps in `f64` against 2,461; in `f32` its contacts
    /// jitter under the long pseudo step, the settling hands over to the dynamics, and it
    /// takes 1,962 steps against 1,415. Of 8, 12, 16, 24 and 32, each with settling
    /// tolerances $10^{-9}$, $3 \cdot 10^{-10}$ and $10^{-10}$, only 24 kept
    /// `three-and-back`'s first turn for all three: its rests differ by under $10^{-6}$,
    /// and 5 of the 15 stalled that turn (the closing note of issue 40).
    pub settle_stretch: T,
    /// Snapshots of the active page kept for finger-bookmarking (seed Fig. 11).
    pub history_capacity: usize,
    /// Steps between snapshots (doubling whenever the history is thinned).
    pub history_interval: u32,
    /// Steps a bookmarked page takes to fly between the block and the grip.
    pub flip_frames: u32,
    /// Pages that may be in flight at once.
    pub max_flips: usize,
    /// The time stepper's settings (time step, Newton iterations, line search, ...). The
    /// book's defaults differ from the solver's in two fields: `merit_slack` 0.05 (the
    /// projection removes what the step leaves), and `refinement_tolerance`
    /// $\sqrt{\varepsilon}$: one Newton iteration per step leaves a nonlinear residual far
    /// above it, so a tighter solve buys nothing. Measured on the page turn (`cargo run
    /// --release -p folio-bench --example frame_work`) against the solver's
    /// $\varepsilon^{3/4}$: refinement steps over the turn 837 → 279 in `f64` and 270 → 0 in
    /// `f32`, with the DOG residual, the stretch and the merge unchanged within the turn's
    /// run-to-run spread.
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
            gravity: T::from_f64(9.81),
            air_drag: T::from_f64(3.0),
            page_mass: T::ONE,
            cover_mass: T::from_f64(5.0),
            min_block_mass: T::HALF,
            pull_reach: T::ONE,
            grip_strain: T::from_f64(0.0075),
            pull_turn_rate: T::from_f64(4.0),
            tent_height: T::from_f64(0.6),
            merge_speed: T::from_f64(0.5),
            merge_frames: 10,
            sleep_speed: T::from_f64(1e-3),
            sleep_frames: 10,
            constraint_tolerance: T::from_f64(1e-4),
            max_corrections: if T::EPSILON.to_f64() < 1e-10 { 5 } else { 3 },
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
/// tolerance (`constraint_tolerance`, $10^{-4}$ page units by default): in a smaller page
/// every constraint holds to within the tolerance whatever the page does, and a gesture
/// no longer moves it measurably (a page $10^{-9}$ wide cannot be touched).
pub const MIN_CELL_TOLERANCES: f64 = 100.0;

/// The most iterations of one constraint projection pass (`max_corrections`).
pub const MAX_CORRECTIONS: u32 = 50;

impl<T: Real> BookSettings<T> {
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
            ("constraint_tolerance", self.constraint_tolerance),
        ] {
            require_positive(field, v.to_f64())?;
        }
        require_at_least(
            "params.page_width",
            self.params.page_width,
            MIN_CELL_TOLERANCES * self.constraint_tolerance.to_f64() * across as f64,
            "a page too small to touch: its grid cells must be at least 100 constraint \
             tolerances wide",
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
            ("max_corrections", self.max_corrections, 0, MAX_CORRECTIONS),
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
        assert_eq!(field(with(|s| s.max_corrections = 51)), "max_corrections");
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
