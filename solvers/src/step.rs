//! The implicit-Euler SQP step (seed `000_…` eq. 2-4, DESIGN.md "Time step" and "Line
//! search").
//!
//! With $\bar x = x^{(k-1)} + h v^{(k-1)}$ the step solves
//! $\min_x E(x) = \tfrac{1}{2h^2}(x-\bar x)^\top M (x-\bar x) + V(x)$ s.t. $C(x) = 0$ by Newton
//! on its KKT conditions, starting from $x^{(k-1)}$ and $\lambda = 0$:
//! $$\begin{bmatrix} M/h^2 + \nabla^2 V\ (+\textstyle\sum_l\lambda_l\nabla^2 C_l) & \nabla C^\top \cr \nabla C & 0\end{bmatrix}
//! \begin{bmatrix}\Delta x \cr \lambda^+\end{bmatrix} = -\begin{bmatrix} M/h^2(x-\bar x) + \nabla V \cr C(x)\end{bmatrix},$$
//! optionally backtracking on $\psi = E + \mu\lVert C\rVert_2$, $\mu = \max(1.1\lVert\lambda^+\rVert_2, 0.05)$,
//! at most `max_halvings` times, then $v = (x - x^{(k-1)})/h$.
//!
//! The penalty uses $\lVert\lambda^+\rVert_2$, not the $\max|\lambda^+|$ that DESIGN.md quotes
//! from RHS19: the Newton direction is a descent direction of the $\ell_2$ merit when
//! $\mu \ge \lVert\lambda^+\rVert_2$ (the dual norm of $\ell_2$), because
//! $D\psi \le -\Delta x^\top B\thinspace \Delta x + \lambda^{+\top} C - \mu\lVert C\rVert_2$. With many
//! active constraints $\max|\lambda|$ is several times too small and the search fails (seen on
//! the hanging chain). A trial whose merit exceeds $\psi$ by at most $16\varepsilon|\psi|$
//! (rounding noise at convergence) is accepted.

use alloc::vec;
use alloc::vec::Vec;
use folio_kernels::{Real, Vec3Ops};

use crate::assembly::{Assemble, Derivatives};
use crate::error::SolverError;
use crate::kkt::Kkt;
use crate::ldlt::FactorOutcome;
use crate::model::Model;
use crate::normal_equations::NormalEquations;
use crate::ordering::Ordering;
use crate::pattern::KktPattern;
use crate::report::{StepReport, StepStatus};
use crate::room::{Room, refill, scaled};
use crate::settings::{Convexify, Parallelism, Settings};
use crate::vector::max_abs;

mod line_search;
mod projection;

pub use projection::{Correction, Pins};

/// Node positions and velocities (page units, page units per second).
#[derive(Clone, Debug, PartialEq)]
pub struct State<T: Real> {
    /// Positions, one per node.
    pub x: Vec<T::Vec3>,
    /// Velocities, one per node.
    pub v: Vec<T::Vec3>,
}

impl<T: Real> State<T> {
    /// Positions `x` at rest.
    #[must_use]
    pub fn at_rest(x: Vec<T::Vec3>) -> Self {
        let v = vec![T::Vec3::ZERO; x.len()];
        Self { x, v }
    }
}

/// Everything sized by one topology: the KKT system and the step's vectors, allocated
/// together by [`Solver::analyse`].
#[derive(Clone, Debug)]
struct Workspace<T: Real> {
    version: u64,
    ordering: Ordering,
    /// [`Settings::equilibrate`] as the KKT was set up.
    equilibrate: bool,
    /// [`Settings::parallelism`] as the KKT was set up.
    parallelism: Parallelism,
    /// [`Settings::krylov_restart`] as the KKT was set up.
    krylov_restart: u32,
    kkt: Kkt<T>,
    /// Right-hand side, then product scratch, then solution: `dofs + rows` each.
    rhs: Vec<T>,
    product: Vec<T>,
    solution: Vec<T>,
    /// $\nabla V$ per dof.
    gradient: Vec<T>,
    /// $C(x)$ per row.
    constraint: Vec<T>,
    /// Current multipliers.
    lambda: Vec<T>,
    /// `lambda` holds the multipliers of the last committed step of this topology
    /// ([`Settings::warm_multipliers`]).
    lambda_committed: bool,
    /// Mass per dof.
    mass: Vec<T>,
    /// $x^{(k-1)}$ and $\bar x$ per dof.
    x_prev: Vec<T>,
    x_bar: Vec<T>,
    /// Current iterate and line-search trial, per node.
    x: Vec<T::Vec3>,
    trial: Vec<T::Vec3>,
    /// The numeric factor holds a successful factorization of this topology.
    factored: bool,
    /// The factor holds the current KKT values, factored unshifted with the inertia of a
    /// minimum ([`Workspace::factor_if_definite`]): the next solve needs no factorization.
    definite_factor: Option<FactorOutcome>,
    /// The projection's normal equations $J W^{-1} J^\top$, analysed with the KKT for a
    /// solver that projects ([`Solver::analyse_projection`]), absent otherwise.
    normal: Option<NormalEquations<T>>,
    /// Per node, a contact the projection let go of in this call: the node was held along
    /// a normal and the constraints pulled it off its surface ([`projection::Pins`]).
    released: Vec<bool>,
    /// The pattern's node-pair keys while it is rebuilt ([`KktPattern::rebuild`]).
    entries: Vec<u64>,
    /// How many keys the last rebuild held before they merged (0 before the first).
    keys: usize,
    /// [`Solver::reserve`] made room: keep the analysis's scratch between analyses.
    kept: bool,
}

impl<T: Real> Workspace<T> {
    /// The workspace of one topology (`version`, `nodes` nodes) with KKT pattern `pattern`,
    /// analysed with `s`'s ordering, parallelism and equilibration, with the normal equations when the
    /// solver `projects`. Generic in the value type only: one copy serves every model.
    fn new(
        pattern: KktPattern,
        s: &Settings<T>,
        version: u64,
        nodes: usize,
        projects: bool,
    ) -> Self {
        let mut kkt = Kkt::with_krylov_restart(
            pattern,
            s.ordering,
            s.parallelism,
            s.krylov_restart as usize,
        );
        kkt.set_equilibration(s.equilibrate);
        let mut work = Self {
            version,
            ordering: s.ordering,
            equilibrate: s.equilibrate,
            parallelism: s.parallelism,
            krylov_restart: s.krylov_restart,
            kkt,
            rhs: Vec::new(),
            product: Vec::new(),
            solution: Vec::new(),
            gradient: Vec::new(),
            constraint: Vec::new(),
            lambda: Vec::new(),
            lambda_committed: false,
            mass: Vec::new(),
            x_prev: Vec::new(),
            x_bar: Vec::new(),
            x: Vec::new(),
            trial: Vec::new(),
            factored: false,
            definite_factor: None,
            normal: None,
            released: Vec::new(),
            entries: Vec::new(),
            keys: 0,
            kept: false,
        };
        work.size_vectors(nodes, projects);
        work
    }

    /// The workspace of `model`'s topology in this one's buffers, as [`Workspace::new`]
    /// makes it: no allocation when they hold it ([`Solver::reserve`]), on one thread and
    /// without the normal equations (which are built anew).
    ///
    /// # Errors
    /// As [`KktPattern::build`]; the workspace must not be used then.
    fn reanalyse<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        projects: bool,
    ) -> Result<(), SolverError> {
        self.keys = self
            .kkt
            .pattern
            .rebuild(model, s.constraint_hessian, &mut self.entries)?;
        if !self.kept {
            // Not reserved: keep no scratch, as a first analysis does.
            self.entries = Vec::new();
            self.kkt.pattern.shrink_to_fit();
        }
        if self.equilibrate != s.equilibrate {
            self.kkt.set_equilibration(s.equilibrate);
        }
        if self.krylov_restart != s.krylov_restart {
            self.kkt.set_krylov_restart(s.krylov_restart as usize);
        }
        self.kkt.reanalyse(s.ordering, s.parallelism);
        self.version = model.topology_version();
        self.ordering = s.ordering;
        self.equilibrate = s.equilibrate;
        self.parallelism = s.parallelism;
        self.krylov_restart = s.krylov_restart;
        self.size_vectors(model.node_count(), projects);
        Ok(())
    }

    /// Zeroed step vectors for the KKT system's pattern and `nodes` nodes, and the normal
    /// equations when the solver `projects`.
    fn size_vectors(&mut self, nodes: usize, projects: bool) {
        let pattern = &self.kkt.pattern;
        let (dofs, rows) = (pattern.dofs, pattern.rows);
        let n = dofs + rows;
        self.normal = projects.then(|| NormalEquations::new(pattern));
        for v in [&mut self.rhs, &mut self.product, &mut self.solution] {
            refill(v, n, T::ZERO);
        }
        for v in [
            &mut self.gradient,
            &mut self.mass,
            &mut self.x_prev,
            &mut self.x_bar,
        ] {
            refill(v, dofs, T::ZERO);
        }
        refill(&mut self.constraint, rows, T::ZERO);
        refill(&mut self.lambda, rows, T::ZERO);
        self.lambda_committed = false;
        refill(&mut self.x, nodes, T::Vec3::ZERO);
        refill(&mut self.trial, nodes, T::Vec3::ZERO);
        refill(&mut self.released, nodes, false);
        self.factored = false;
    }

    /// Room for a topology `scale` times this one's size (module docs of
    /// [`Solver::reserve`]).
    fn reserve_scaled(&mut self, scale: f64) {
        self.kept = true;
        let k = &self.kkt;
        let (n, nnz, nnz_l) = (k.pattern.order(), k.pattern.nnz(), k.symbolic().nnz_l());
        let grown = |len: usize| scaled(len, scale);
        self.kkt
            .reserve(grown(n), grown(nnz), scaled(nnz_l, FILL_GROWTH * scale));
        self.kkt.pattern.reserve_scaled(scale);
        self.entries.room_for(grown(self.keys));
        for v in [
            &mut self.rhs,
            &mut self.product,
            &mut self.solution,
            &mut self.gradient,
            &mut self.constraint,
            &mut self.lambda,
            &mut self.mass,
            &mut self.x_prev,
            &mut self.x_bar,
        ] {
            v.room_for(grown(v.len()));
        }
        self.x.room_for(grown(self.x.len()));
        self.trial.room_for(grown(self.trial.len()));
        self.released.room_for(grown(self.released.len()));
    }
}

/// How much faster than the system's order [`Solver::reserve`] lets the factor's fill grow:
/// the fill of a mesh's matrix under a minimum-degree order grows like $n \log n$ in 2D, a
/// little faster than $n$.
const FILL_GROWTH: f64 = 2.0;

/// The time stepper: settings, and the symbolic analysis and buffers of the last topology it
/// saw.
///
/// Owns its [`Settings`] and, once a model is analysed, one workspace for that topology: the
/// [`Kkt`] system (pattern, symbolic analysis, factor and values) and the step's vectors
/// (`dofs + rows` entries for the KKT right-hand side, product and solution, one per dof,
/// row or node for the rest). The workspace is allocated at setup: the first step,
/// [`Solver::analyse`] or [`Solver::linearize`], or a step after a change of topology
/// version, ordering, constraint-Hessian switch or equilibration. Every other step
/// allocates nothing. A later analysis refills the workspace's buffers, and after
/// [`Solver::reserve`] made room for the model's growth it allocates nothing either (on one
/// thread, for the AMD orders, without projection). A solver whose caller projects ([`Solver::project_constraints`])
/// also holds the projection's normal equations, from [`Solver::analyse_projection`] on;
/// one that never projects does not build them. Once built, every later analysis builds
/// them too.
#[derive(Clone, Debug)]
pub struct Solver<T: Real> {
    settings: Settings<T>,
    work: Option<Workspace<T>>,
}

/// Values of one model evaluation.
#[derive(Clone, Copy, Debug)]
struct Evaluation<T> {
    /// $E = $ inertia $+ V$.
    energy: T,
    finite: bool,
}

impl<T: Real> Solver<T> {
    /// A solver with validated `settings`.
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`] for a bad field.
    pub fn new(settings: Settings<T>) -> Result<Self, SolverError> {
        settings.validate()?;
        Ok(Self {
            settings,
            work: None,
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &Settings<T> {
        &self.settings
    }

    /// Replaces the settings (a change of ordering or of the constraint-Hessian switch
    /// re-runs the analysis at the next step).
    ///
    /// # Errors
    /// [`SolverError::InvalidSetting`]; the old settings are kept.
    pub fn set_settings(&mut self, settings: Settings<T>) -> Result<(), SolverError> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }

    /// The current KKT system (pattern, values, symbolic analysis, factor), once analysed.
    #[must_use]
    pub fn kkt(&self) -> Option<&Kkt<T>> {
        self.work.as_ref().map(|w| &w.kkt)
    }

    /// The right-hand side of the last assembled KKT system (`dofs + rows` entries).
    #[must_use]
    pub fn rhs(&self) -> Option<&[T]> {
        self.work.as_ref().map(|w| w.rhs.as_slice())
    }

    /// Makes room, at setup, for a model of the same kind as the analysed one with up to
    /// `nodes` nodes (a mesh that will grow, such as a tearing sheet's): every buffer of the
    /// workspace grows in proportion to the node count, and the factor's fill twice as fast.
    /// A later analysis of a model within that room, on one thread and in the same index
    /// width, allocates nothing (faer's AMD included: its stack is kept). Returns `false`
    /// (and does nothing) before the first analysis.
    pub fn reserve(&mut self, nodes: usize) -> bool {
        let Some(w) = &mut self.work else {
            return false;
        };
        let now = w.x.len().max(1);
        w.reserve_scaled(nodes as f64 / now as f64);
        true
    }

    /// Runs the symbolic analysis for `model` unless the current one is still valid; returns
    /// whether it ran.
    ///
    /// # Errors
    /// [`SolverError::NodeOutOfRange`] or [`SolverError::TooLarge`] from the pattern.
    pub fn analyse<M: Model<T>>(&mut self, model: &M) -> Result<bool, SolverError> {
        let s = &self.settings;
        if let Some(w) = &self.work {
            if w.version == model.topology_version()
                && w.ordering == s.ordering
                && w.kkt.pattern.with_constraint_hessian == s.constraint_hessian
                && w.equilibrate == s.equilibrate
                && w.parallelism == s.parallelism
                && w.krylov_restart == s.krylov_restart
            {
                return Ok(false);
            }
        }
        // A solver that projected keeps projecting: its new workspace gets normal equations.
        // A workspace is analysed again in its own buffers; on error it is dropped.
        let mut work = self.work.take();
        let projects = work.as_ref().is_some_and(|w| w.normal.is_some());
        match &mut work {
            Some(w) => w.reanalyse(model, s, projects)?,
            None => {
                // A first analysis keeps no scratch (a heap peak matters on a
                // microcontroller): [`Solver::reserve`] makes room for the next ones.
                let mut pattern = KktPattern::default();
                let keys = pattern.rebuild(model, s.constraint_hessian, &mut Vec::new())?;
                pattern.shrink_to_fit();
                let (version, nodes) = (model.topology_version(), model.node_count());
                let mut w = Workspace::new(pattern, s, version, nodes, projects);
                w.keys = keys;
                work = Some(w);
            }
        }
        self.work = work;
        Ok(true)
    }

    /// Setup for a solver that projects: runs [`Solver::analyse`] for `model` and builds the
    /// normal equations of [`Solver::project_constraints`]
    /// ([`crate::normal_equations::NormalEquations`]) with it, now and at every later
    /// analysis; returns whether anything was built. Without this call, the first
    /// projection of each topology builds them (and allocates); a solver that never
    /// projects never does.
    ///
    /// # Errors
    /// As [`Solver::analyse`].
    pub fn analyse_projection<M: Model<T>>(&mut self, model: &M) -> Result<bool, SolverError> {
        let analysed = self.analyse(model)?;
        Ok(self.prepare_projection() || analysed)
    }

    /// Builds the normal equations for the current workspace if it lacks them (from now on
    /// every analysis builds them); returns whether it did.
    fn prepare_projection(&mut self) -> bool {
        match &mut self.work {
            Some(w) if w.normal.is_none() => {
                w.normal = Some(NormalEquations::new(&w.kkt.pattern));
                true
            }
            _ => false,
        }
    }

    /// Assembles the first Newton system of a step from `state` (as [`Solver::step`] would)
    /// without solving it: afterwards [`Solver::kkt`] and [`Solver::rhs`] hold $K$ and $b$.
    /// Returns `false` when the state or the model's terms are non-finite.
    ///
    /// # Errors
    /// As [`Solver::step`].
    pub fn linearize<M: Model<T>>(
        &mut self,
        model: &M,
        state: &State<T>,
    ) -> Result<bool, SolverError> {
        self.analyse(model)?;
        let s = self.settings;
        let h = s.time_step;
        let Some(w) = self.work.as_mut() else {
            return Ok(false);
        };
        if !w.begin(model, state, &s)? {
            return Ok(false);
        }
        let e = w.evaluate(model, h, false, Derivatives::Second)?;
        w.fill_rhs(h);
        Ok(e.finite)
    }

    /// Advances `state` by one implicit-Euler step of `model` (module docs). On any status
    /// but `Converged` / `IterationLimit` the state is left exactly as it was.
    ///
    /// # Errors
    /// Setup errors only: [`SolverError::NodeOutOfRange`], [`SolverError::TooLarge`],
    /// [`SolverError::StateLength`], [`SolverError::NonPositiveMass`],
    /// [`SolverError::ModelChanged`].
    pub fn step<M: Model<T>>(
        &mut self,
        model: &M,
        state: &mut State<T>,
    ) -> Result<StepReport<T>, SolverError> {
        let analysed = self.analyse(model)?;
        let s = self.settings;
        let h = s.time_step;
        let mut report = StepReport::new(StepStatus::NonFiniteInput, analysed);
        let Some(w) = self.work.as_mut() else {
            return Ok(report);
        };
        if !w.begin(model, state, &s)? {
            return Ok(report);
        }
        // Until this step commits, its multipliers are no start for the next.
        w.lambda_committed = false;
        let mut converged = false;
        for iteration in 0..s.newton_iterations {
            match w.newton_iteration(model, &s, iteration, &mut report)? {
                Iteration::Converged => {
                    converged = true;
                    break;
                }
                Iteration::Advanced => {}
                Iteration::Failed => return Ok(report),
            }
        }
        if !converged && s.check_final_residual {
            let Some(final_converged) = w.final_residual(model, &s, &mut report)? else {
                return Ok(report);
            };
            converged = final_converged;
        }
        report.status = if converged {
            StepStatus::Converged
        } else {
            StepStatus::IterationLimit
        };
        w.commit(state, h);
        Ok(report)
    }
}

/// How one Newton iteration of [`Solver::step`] ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Iteration {
    /// The residual at the iterate was within the tolerance; nothing was solved.
    Converged,
    /// A step was solved and accepted: the iterate and the multipliers moved.
    Advanced,
    /// The step failed; the report's status says how, and the state must stay as it was.
    Failed,
}

impl<T: Real> Workspace<T> {
    /// One Newton iteration of [`Solver::step`]: evaluates the model at the iterate, checks
    /// the eq. 3 residual, solves for a step (with damped retries), and accepts it.
    fn newton_iteration<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        iteration: u32,
        report: &mut StepReport<T>,
    ) -> Result<Iteration, SolverError> {
        let h = s.time_step;
        let second = if s.convexify == Convexify::Always {
            Derivatives::SecondConvex
        } else {
            Derivatives::Second
        };
        let e = self.evaluate(model, h, false, second)?;
        if !e.finite {
            report.status = if iteration == 0 {
                StepStatus::NonFiniteInput
            } else {
                StepStatus::NumericalFailure
            };
            return Ok(Iteration::Failed);
        }
        self.fill_rhs(h);
        let residual = self.residual(h);
        report.residual = Some(residual);
        report.constraint_residual = Some(max_abs(&self.constraint));
        if residual <= s.tolerance {
            return Ok(Iteration::Converged);
        }
        if s.convexify == Convexify::WhenIndefinite && !self.factor_if_definite(s, report) {
            // The same point: the gradient, the constraints and so the right-hand side
            // come out as they were; only the primal block takes the convex stand-ins.
            let convex = self.evaluate(model, h, false, Derivatives::SecondConvex)?;
            if !convex.finite {
                report.status = StepStatus::NumericalFailure;
                return Ok(Iteration::Failed);
            }
        }
        if let Some(failed) = self.solve_with_damping(model, s, e.energy, report)? {
            report.status = failed;
            return Ok(Iteration::Failed);
        }
        self.accept();
        report.residual = None;
        Ok(Iteration::Advanced)
    }

    /// Factors, solves and (with [`Settings::line_search`]) searches along the step until a
    /// trial point is accepted into `trial`; `None` then. A factorization that fails, or a
    /// direction the line search refuses, is retried with the inertia scaled up,
    /// $M/h^2 \to (1 + \gamma) M/h^2$ with $\gamma = 1, 10, 100, \dots$ (a proximal
    /// damping: shorter, better conditioned steps), up to `damping_retries` times; after
    /// the last, the status of the failure is returned.
    fn solve_with_damping<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        energy: T,
        report: &mut StepReport<T>,
    ) -> Result<Option<StepStatus>, SolverError> {
        let mut gamma = T::ZERO;
        let mut retry = 0;
        loop {
            let failed = if self.factor_and_solve(s, report) {
                if !s.line_search {
                    self.set_trial(T::ONE);
                    report.constraint_residual = None;
                    return Ok(None);
                }
                if self.search(model, s, energy, report)? {
                    return Ok(None);
                }
                StepStatus::LineSearchFailed
            } else {
                StepStatus::NumericalFailure
            };
            if retry == s.damping_retries {
                return Ok(Some(failed));
            }
            retry += 1;
            report.damping_retries = retry;
            gamma = self.damp(gamma, s.time_step);
        }
    }

    /// Factorizes the assembled KKT system (with inertia correction) and solves it with
    /// refinement into `solution`; `true` when the factorization succeeded and the solution
    /// is finite.
    fn factor_and_solve(&mut self, s: &Settings<T>, report: &mut StepReport<T>) -> bool {
        let before = self.kkt.factorizations();
        let (outcome, shift) = match self.definite_factor.take() {
            Some(outcome) => (outcome, T::ZERO),
            None => self
                .kkt
                .factorize_with_inertia_correction(s.pivot_epsilon, s.regularization),
        };
        report.factorizations += (self.kkt.factorizations() - before) as u32;
        if shift > report.hessian_shift {
            report.hessian_shift = shift;
        }
        self.factored = matches!(outcome, FactorOutcome::Factored { .. });
        let FactorOutcome::Factored { regularized, .. } = outcome else {
            return false;
        };
        report.regularized_pivots += regularized;
        let refinement = self.kkt.solve_refined(
            &mut self.solution,
            &self.rhs,
            s.refinement_steps,
            s.refinement_tolerance,
        );
        report.iterations += 1;
        report.refinement_steps += refinement.steps;
        let solved =
            refinement.relative_residual.is_finite() && max_abs(&self.solution).is_finite();
        if solved && refinement.relative_residual > report.linear_residual {
            report.linear_residual = refinement.relative_residual;
        }
        solved
    }

    /// [`Convexify::WhenIndefinite`]'s test: factors the assembled (exact) system once,
    /// unshifted. `true` when it has the inertia of a minimum; its factor then serves the
    /// iteration's first solve ([`Workspace::factor_and_solve`]).
    fn factor_if_definite(&mut self, s: &Settings<T>, report: &mut StepReport<T>) -> bool {
        let before = self.kkt.factorizations();
        let outcome = self.kkt.factorize(s.pivot_epsilon, s.regularization);
        report.factorizations += (self.kkt.factorizations() - before) as u32;
        let definite = outcome.primal_definite();
        self.definite_factor = definite.then_some(outcome);
        definite
    }

    /// Makes the accepted trial point the iterate and takes its multipliers $\lambda^+$.
    fn accept(&mut self) {
        core::mem::swap(&mut self.x, &mut self.trial);
        let (_, lambda) = self.solution.split_at(self.kkt.pattern.dofs);
        self.lambda.copy_from_slice(lambda);
    }

    /// The optional residual check after the last Newton iteration: evaluates the first
    /// derivatives at the final iterate and records its residual. `None` (status set) when
    /// the evaluation is non-finite, else whether the residual is within the tolerance.
    fn final_residual<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        report: &mut StepReport<T>,
    ) -> Result<Option<bool>, SolverError> {
        let h = s.time_step;
        let e = self.evaluate(model, h, false, Derivatives::First)?;
        if !e.finite {
            report.status = StepStatus::NumericalFailure;
            return Ok(None);
        }
        self.fill_rhs(h);
        let residual = self.residual(h);
        report.residual = Some(residual);
        report.constraint_residual = Some(max_abs(&self.constraint));
        Ok(Some(residual <= s.tolerance))
    }
}

/// `x[node] += alpha * v[d]` along the axis of every free coordinate `d`.
fn add_to<T: Real>(x: &mut [T::Vec3], coordinate_of: &[u32], v: &[T], alpha: T) {
    for (d, &c) in coordinate_of.iter().enumerate() {
        let (node, axis) = (c as usize / 3, c as usize % 3);
        x[node] += T::Vec3::AXES[axis] * (alpha * v[d]);
    }
}

impl<T: Real> Workspace<T> {
    /// Loads $x^{(k-1)}$, $\bar x$ and the masses, and starts the iterate at $x^{(k-1)}$
    /// (or $\bar x$, [`Settings::predictor`]) and the multipliers at 0 (or the last
    /// committed step's, [`Settings::warm_multipliers`]); `Ok(false)` for a non-finite
    /// state.
    fn begin<M: Model<T>>(
        &mut self,
        model: &M,
        state: &State<T>,
        s: &Settings<T>,
    ) -> Result<bool, SolverError> {
        let h = s.time_step;
        let nodes = self.x.len();
        if state.x.len() != nodes || state.v.len() != nodes {
            return Err(SolverError::StateLength {
                expected: nodes,
                positions: state.x.len(),
                velocities: state.v.len(),
            });
        }
        let finite = |v: &T::Vec3| v.x().is_finite() && v.y().is_finite() && v.z().is_finite();
        if !(state.x.iter().all(finite) && state.v.iter().all(finite)) {
            return Ok(false);
        }
        for (d, &c) in self.kkt.pattern.coordinate_of.iter().enumerate() {
            let (node, axis) = (c as usize / 3, c as usize % 3);
            let m = model.mass(node);
            if !(m.is_finite() && m > T::ZERO) {
                return Err(SolverError::NonPositiveMass { node });
            }
            self.mass[d] = m;
            self.x_prev[d] = state.x[node].get(axis);
            self.x_bar[d] = self.x_prev[d] + h * state.v[node].get(axis);
        }
        self.x.copy_from_slice(&state.x);
        if s.predictor {
            for (d, &c) in self.kkt.pattern.coordinate_of.iter().enumerate() {
                let (node, axis) = (c as usize / 3, c as usize % 3);
                self.x[node] += T::Vec3::AXES[axis] * (self.x_bar[d] - self.x_prev[d]);
            }
        }
        let warm = s.warm_multipliers
            && self.lambda_committed
            && self.lambda.iter().all(|l| l.is_finite());
        if !warm {
            self.lambda.iter_mut().for_each(|l| *l = T::ZERO);
        }
        Ok(true)
    }

    /// Evaluates the model at the iterate (or the trial point): $E$, $C$ and the requested
    /// derivatives into the KKT values (mass diagonal included) and the gradient.
    fn evaluate<M: Model<T>>(
        &mut self,
        model: &M,
        h: T,
        trial: bool,
        derivatives: Derivatives,
    ) -> Result<Evaluation<T>, SolverError> {
        let pattern = &self.kkt.pattern;
        let x = if trial { &self.trial } else { &self.x };
        // The Jacobian lives in the constraint columns (rows above them are primal, and the
        // constraint block is zero), so a Jacobian-only evaluation clears just those; the
        // primal block and the gradient are left as they were (nothing reads them until
        // the next full evaluation).
        let jacobian_start = pattern.col_ptr[pattern.dofs] as usize;
        match derivatives {
            Derivatives::None => {}
            Derivatives::Jacobian => self.kkt.values[jacobian_start..]
                .iter_mut()
                .for_each(|v| *v = T::ZERO),
            Derivatives::First | Derivatives::Second | Derivatives::SecondConvex => {
                self.kkt.values.iter_mut().for_each(|v| *v = T::ZERO);
                self.gradient.iter_mut().for_each(|v| *v = T::ZERO);
            }
        }
        let mut visitor = Assemble {
            pattern,
            x,
            lambda: &self.lambda,
            values: &mut self.kkt.values,
            gradient: &mut self.gradient,
            constraint: &mut self.constraint,
            derivatives,
            energy: T::ZERO,
            family: 0,
            mismatch: false,
        };
        model.visit_terms(&mut visitor);
        if visitor.mismatch || visitor.family != pattern.families.len() {
            return Err(SolverError::ModelChanged);
        }
        let potential = visitor.energy;
        let inv_h2 = T::ONE / (h * h);
        let mut inertia = T::ZERO;
        for (d, &c) in pattern.coordinate_of.iter().enumerate() {
            let dx = x[c as usize / 3].get(c as usize % 3) - self.x_bar[d];
            inertia += self.mass[d] * dx * dx;
            if derivatives.first() {
                self.kkt.values[pattern.diagonal_slot(d)] += self.mass[d] * inv_h2;
            }
        }
        let energy = T::HALF * inv_h2 * inertia + potential;
        let mut finite = energy.is_finite() && max_abs(&self.constraint).is_finite();
        match derivatives {
            Derivatives::None => {}
            Derivatives::Jacobian => {
                finite = finite && max_abs(&self.kkt.values[jacobian_start..]).is_finite();
            }
            Derivatives::First | Derivatives::Second | Derivatives::SecondConvex => {
                finite = finite && max_abs(&self.gradient).is_finite();
                finite = finite && max_abs(&self.kkt.values).is_finite();
            }
        }
        Ok(Evaluation { energy, finite })
    }

    /// $b = -[M/h^2(x - \bar x) + \nabla V;\ C]$ from the last evaluation.
    fn fill_rhs(&mut self, h: T) {
        let inv_h2 = T::ONE / (h * h);
        let dofs = self.kkt.pattern.dofs;
        for (d, &c) in self.kkt.pattern.coordinate_of.iter().enumerate() {
            let x = self.x[c as usize / 3].get(c as usize % 3);
            self.rhs[d] = -(self.mass[d] * inv_h2 * (x - self.x_bar[d]) + self.gradient[d]);
        }
        for (r, &c) in self.rhs[dofs..].iter_mut().zip(&self.constraint) {
            *r = -c;
        }
    }

    /// The eq. 3 residual $\max(\lVert h^2 M^{-1}(\nabla E + \nabla C^\top \lambda)\rVert_\infty,
    /// \lVert C\rVert_\infty)$ from the last evaluation and `fill_rhs`.
    fn residual(&mut self, h: T) -> T {
        let dofs = self.kkt.pattern.dofs;
        self.solution[..dofs].iter_mut().for_each(|v| *v = T::ZERO);
        self.solution[dofs..].copy_from_slice(&self.lambda);
        self.kkt.multiply(&mut self.product, &self.solution);
        let mut worst = max_abs(&self.constraint);
        for d in 0..dofs {
            // rhs = -grad E, product = J^T lambda.
            let r = h * h / self.mass[d] * (self.product[d] - self.rhs[d]);
            let r = if r < T::ZERO { -r } else { r };
            if r > worst || !r.is_finite() {
                worst = r;
            }
        }
        worst
    }

    /// Raises the inertia damping from `gamma` to the next of $1, 10, 100, \dots$: the
    /// evaluation at the iterate is still in the KKT values (the factor is separate), so only
    /// the primal diagonal changes, by $(\gamma' - \gamma) M/h^2$. Returns $\gamma'$.
    fn damp(&mut self, gamma: T, h: T) -> T {
        let next = if gamma == T::ZERO {
            T::ONE
        } else {
            gamma * T::from_f64(10.0)
        };
        let inv_h2 = T::ONE / (h * h);
        for d in 0..self.kkt.pattern.dofs {
            let slot = self.kkt.pattern.diagonal_slot(d);
            self.kkt.values[slot] += (next - gamma) * self.mass[d] * inv_h2;
        }
        next
    }

    /// `trial = x + alpha * dx` on the free coordinates.
    fn set_trial(&mut self, alpha: T) {
        self.trial.copy_from_slice(&self.x);
        add_to(
            &mut self.trial,
            &self.kkt.pattern.coordinate_of,
            &self.solution,
            alpha,
        );
    }

    /// Writes the iterate and $v = (x - x^{(k-1)})/h$ into `state`.
    fn commit(&mut self, state: &mut State<T>, h: T) {
        self.lambda_committed = true;
        let inv_h = T::ONE / h;
        for ((x, v), &new) in state.x.iter_mut().zip(state.v.iter_mut()).zip(&self.x) {
            *v = (new - *x) * inv_h;
            *x = new;
        }
    }
}
