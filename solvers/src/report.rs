//! What a time step reports.

/// How a step ended. Only `Converged` and `IterationLimit` change the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum StepStatus {
    /// The eq. 3 residual is within [`crate::Settings::tolerance`].
    Converged,
    /// The configured Newton iterations ran (the paper's default: one); the residual is above
    /// the tolerance or was not evaluated. The state was advanced.
    IterationLimit,
    /// No step length up to [`crate::Settings::max_halvings`] halvings decreased the merit
    /// function; the state is unchanged.
    LineSearchFailed,
    /// A factorization or solve produced a non-finite value; the state is unchanged.
    NumericalFailure,
    /// The state or the model's terms are non-finite at the start of the step; the state is
    /// unchanged.
    NonFiniteInput,
}

impl StepStatus {
    /// `true` when the step advanced the state.
    #[must_use]
    pub fn advanced(self) -> bool {
        matches!(self, Self::Converged | Self::IterationLimit)
    }
}

/// The record of one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepReport<T> {
    /// How the step ended.
    pub status: StepStatus,
    /// KKT systems solved.
    pub iterations: u32,
    /// Numeric factorizations of the KKT matrix (inertia-correction and damping retries
    /// included).
    pub factorizations: u32,
    /// The eq. 3 residual at the final iterate (see [`crate::Settings::tolerance`]), when it
    /// was evaluated.
    pub residual: Option<T>,
    /// $\lVert C(x)\rVert_\infty$ at the final iterate, when it was evaluated.
    pub constraint_residual: Option<T>,
    /// Worst relative residual $\lVert Kz - b\rVert_\infty / \lVert b\rVert_\infty$ of the
    /// step's KKT solves after refinement (0 when none ran).
    pub linear_residual: T,
    /// Merit $\psi = E + \mu\lVert C\rVert_2$ before the last line search, if one ran.
    pub merit_before: Option<T>,
    /// Merit at the accepted point of the last line search, if one ran and succeeded.
    pub merit_after: Option<T>,
    /// Step halvings over all line searches of the step.
    pub halvings: u32,
    /// Damped re-solves after failed line searches (see
    /// [`crate::Settings::damping_retries`]) in the last iteration.
    pub damping_retries: u32,
    /// Line searches that tried a second-order correction (see
    /// [`crate::Settings::second_order_correction`]).
    pub second_order_corrections: u32,
    /// Pivots replaced by the sign-aware regularization, summed over the step's
    /// factorizations. Nonzero with the default ordering means a (numerically) singular KKT:
    /// redundant or conflicting constraints.
    pub regularized_pivots: usize,
    /// Largest shift $\beta$ added to the primal block to make it positive definite
    /// ([`crate::Kkt::factorize_with_inertia_correction`]); 0 when the Hessian was.
    pub hessian_shift: T,
    /// Iterative-refinement steps over all solves.
    pub refinement_steps: u32,
    /// The symbolic analysis was (re)built in this step (topology change or first step).
    pub analysed: bool,
}

impl<T: folio_kernels::Real> StepReport<T> {
    /// A report of a step that has done nothing yet: status `status`, every count zero and
    /// every measure unevaluated. A model with no unknowns reports
    /// `StepReport::new(StepStatus::Converged, false)` without calling the solver.
    #[must_use]
    pub fn new(status: StepStatus, analysed: bool) -> Self {
        Self {
            status,
            iterations: 0,
            factorizations: 0,
            residual: None,
            constraint_residual: None,
            linear_residual: T::ZERO,
            merit_before: None,
            merit_after: None,
            halvings: 0,
            damping_retries: 0,
            second_order_corrections: 0,
            regularized_pivots: 0,
            hessian_shift: T::ZERO,
            refinement_steps: 0,
            analysed,
        }
    }
}
