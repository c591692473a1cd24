//! The `#[repr(C)]` report of `folio_book_step` ([`crate::step`]): how the step ended, the
//! book's phase and the step's figures.

use folio_book::{Book, BookStepReport, Phase};
use folio_kernels::Real;
use folio_solvers::StepStatus;

use crate::side::{FolioSide, side_value};

/// How the time stepper's step ended (seed `000_…` eq. 2-4, solved by Newton on the KKT
/// system). Only `CONVERGED` and `ITERATION_LIMIT` advanced the state; on the others the
/// previous state is kept (the book never holds NaN).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FolioStepStatus {
    /// The residual of seed eq. 3 is within the tolerance.
    Converged = 0,
    /// The configured Newton iterations ran (the default: one, as the seed does); the
    /// state advanced.
    IterationLimit = 1,
    /// No step length decreased the merit function; the state is unchanged.
    LineSearchFailed = 2,
    /// A factorization or solve gave a non-finite value; the state is unchanged.
    NumericalFailure = 3,
    /// The state was non-finite at the start of the step; unchanged.
    NonFiniteInput = 4,
    /// A status this version of the C API does not name; treat as not advanced.
    Other = 5,
}

/// What the book was doing during a step.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FolioPhase {
    /// No active page: only the blocks were simulated.
    AtRest = 0,
    /// A page was held by the user.
    Held = 1,
    /// The active page was released and falling or settling.
    Released = 2,
    /// A phase this version of the C API does not name.
    Other = 3,
}

/// The record of one `folio_book_step`. The page measures are of the active page after the
/// step; when there is none (`has_active_page` 0, e.g. after the step that merged it) they
/// are 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FolioStepReport {
    /// How the time stepper's step ended.
    pub status: FolioStepStatus,
    /// The phase the step ran in.
    pub phase: FolioPhase,
    /// Newton iterations (KKT systems solved).
    pub newton_iterations: u32,
    /// Line-search step halvings over the step.
    pub line_search_halvings: u32,
    /// Unknowns of the step's KKT system (the page's appear only with an active page).
    pub kkt_unknowns: u32,
    /// Constraint rows of the step's KKT system.
    pub kkt_rows: u32,
    /// Collision detect/resolve rounds that found a contact.
    pub collision_rounds: u32,
    /// 1 if there is an active page after the step (the page measures are valid), else 0.
    pub has_active_page: u32,
    /// $\max_l \lvert C_{\mathrm{DOG},l}\rvert$ over the active page's DOG constraints
    /// (dimensionless: differences of cosines).
    pub dog_residual: f64,
    /// Largest relative stretch $\lvert \ell / \ell_0 - 1\rvert$ of a page grid edge.
    pub stretch_max: f64,
    /// RMS relative stretch over the page grid edges.
    pub stretch_rms: f64,
    /// Deepest penetration of a page node into a block's clearance band (page units).
    pub penetration: f64,
    /// $\lVert C\rVert_\infty$ after the constraint projection that follows the step
    /// (0 when none ran).
    pub constraint_residual: f64,
    /// The block the active page merged into at the end of this step, or
    /// `FOLIO_SIDE_NONE`.
    pub merged: FolioSide,
    /// Pages in the left block after the step.
    pub pages_left: u32,
    /// Pages in the right block after the step.
    pub pages_right: u32,
    /// Pages held as the active page after the step (0 at rest).
    pub pages_active: u32,
}

/// `n` as a `u32`, saturating (counts of a book never come near).
fn count(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

impl FolioStepReport {
    /// The C report of `r`, a step of `book`.
    pub(crate) fn new<T: Real>(book: &Book<T>, r: &BookStepReport<T>) -> Self {
        let status = match r.solver.status {
            StepStatus::Converged => FolioStepStatus::Converged,
            StepStatus::IterationLimit => FolioStepStatus::IterationLimit,
            StepStatus::LineSearchFailed => FolioStepStatus::LineSearchFailed,
            StepStatus::NumericalFailure => FolioStepStatus::NumericalFailure,
            StepStatus::NonFiniteInput => FolioStepStatus::NonFiniteInput,
            _ => FolioStepStatus::Other,
        };
        let phase = match r.phase {
            Phase::AtRest => FolioPhase::AtRest,
            Phase::Held => FolioPhase::Held,
            Phase::Released => FolioPhase::Released,
            _ => FolioPhase::Other,
        };
        let (stretch_max, stretch_rms) = book
            .stretch()
            .map_or((0.0, 0.0), |(m, s)| (m.to_f64(), s.to_f64()));
        let counts = book.counts();
        Self {
            status,
            phase,
            newton_iterations: r.solver.iterations,
            line_search_halvings: r.solver.halvings,
            kkt_unknowns: count(r.dofs),
            kkt_rows: count(r.constraint_rows),
            collision_rounds: r.collision_rounds,
            has_active_page: u32::from(book.page().is_some()),
            dog_residual: book.dog_residual().map_or(0.0, Real::to_f64),
            stretch_max,
            stretch_rms,
            penetration: book.penetration().map_or(0.0, Real::to_f64),
            constraint_residual: r.correction.after.to_f64(),
            merged: side_value(r.merged),
            pages_left: counts.left,
            pages_right: counts.right,
            pages_active: counts.active,
        }
    }
}
