//! Settings of the implicit-Euler SQP step (DESIGN.md "Time step" and "Line search").

use folio_kernels::Real;

use folio_kernels::setting::{SettingError, require_non_negative, require_positive, require_range};

use crate::ordering::Ordering;

/// The most Newton iterations a step may take: enough to converge a step of the references
/// the accuracy atlas computes (`newton_tolerance` $10^{-10}$ within 20).
pub const MAX_NEWTON_ITERATIONS: u32 = 20;

/// Step settings: a plain struct; [`Settings::validate`] checks it (the solver does too).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings<T: Real> {
    /// Time step $h$ in seconds; finite, $> 0$. Default $1/60$.
    pub time_step: T,
    /// Newton iterations per step, from 1 to [`MAX_NEWTON_ITERATIONS`]. Default 1 (seed
    /// `000_…` eq. 4).
    pub newton_iterations: u32,
    /// Include $\sum_l \lambda_l \nabla^2 C_l$ in the KKT matrix. Default off (the paper
    /// omits it). Changing it changes the pattern and re-runs the symbolic analysis.
    pub constraint_hessian: bool,
    /// The step has converged when the residual of seed `000_…` eq. 3,
    /// $\max(\lVert x - \bar x + h^2 M^{-1}(\nabla V + \nabla C^\top\lambda)\rVert_\infty,
    /// \lVert C\rVert_\infty)$, is at most this (page units, and the constraints' own units).
    /// Finite, $\ge 0$. Default $\sqrt{\varepsilon}$ of the precision.
    pub tolerance: T,
    /// Start Newton at the predictor $\bar x = x^{(k-1)} + h v^{(k-1)}$ (the free
    /// coordinates) instead of at $x^{(k-1)}$: the point the inertia term pulls to, where
    /// a page in free flight is already at its step's end. Default off (seed `000_…`
    /// eq. 4 starts at $x^{(k-1)}$).
    pub predictor: bool,
    /// Start Newton's multipliers at the last committed step's $\lambda$ instead of 0
    /// while the topology stays (a first step, a new topology, or a step after one that
    /// failed in its iterations start at 0).
    /// With [`Settings::constraint_hessian`] the first iteration's matrix then holds
    /// $\sum_l \lambda_l \nabla^2 C_l$ too, and a step whose start already meets eq. 3
    /// takes no iteration. Default off.
    pub warm_multipliers: bool,
    /// Backtrack on the merit $\psi = E + \mu \lVert C\rVert_2$ (RHS19). Default on.
    pub line_search: bool,
    /// Most step halvings in the line search, at most 60. Default 20.
    pub max_halvings: u32,
    /// When the line search fails, the iteration is solved again with the inertia block
    /// scaled by $1 + \gamma$, $\gamma = 1, 10, 100, \dots$ (a proximal damping that
    /// shortens the step and improves the conditioning), at most this many times, at most 10.
    /// Default 4.
    pub damping_retries: u32,
    /// When the full step is refused, try it once more with a second-order correction
    /// (one more solve with the same factor that pulls the trial back onto the linearized
    /// constraints) before halving. Without it the merit function refuses good steps of a
    /// fast-moving constrained page (the Maratos effect) and the page crawls. Default on.
    pub second_order_correction: bool,
    /// Violation the line search lets a step leave behind. With $s = 0$ (the default) a
    /// trial point is accepted by the exact-penalty merit $\psi = E + \mu\lVert C\rVert_2$
    /// ($\mu = 1.1\lVert\lambda\rVert_2$) alone. With $s > 0$ it is also accepted when
    /// $\lVert C\rVert_2 \le s$ and either $E$ does not rise or $\lVert C\rVert_2$ falls by a
    /// tenth (a filter test). A caller that projects onto the constraints after every step
    /// (the book) sets $s > 0$: large constraint forces make $\mu$ so large that the
    /// penalty test cuts every step of a fast page to a sliver, while the projection removes
    /// the violation anyway. Finite, $\ge 0$.
    pub merit_slack: T,
    /// Elimination order of the symbolic analysis. Default: [`Ordering::Amd`] in `f64`,
    /// [`Ordering::AmdQuasiDefinite`] in `f32` (see [`Ordering`] for the measurements).
    pub ordering: Ordering,
    /// Factorize the Ruiz-equilibrated KKT matrix ([`crate::Kkt::set_equilibration`]). Default
    /// off (why: `docs/settings.md`).
    pub equilibrate: bool,
    /// A pivot with $s_k d_k \le$ `pivot_epsilon` $\cdot$ scale is regularized (scale: the
    /// largest primal diagonal). Finite, $\ge 0$. Default $1000\thinspace\varepsilon$.
    pub pivot_epsilon: T,
    /// A regularized pivot becomes $s_k \cdot$ `regularization` $\cdot$ scale. Finite,
    /// $> 0$. Default $\sqrt{\varepsilon}$.
    pub regularization: T,
    /// Most iterative-refinement steps per solve, at most 100. Default 10 (refinement stops
    /// earlier at `refinement_tolerance` or when the residual stops falling).
    pub refinement_steps: u32,
    /// Restart length $m$ of the refinement's GMRES under [`Ordering::AmdQuasiDefinite`]
    /// ([`crate::gmres`]), 1 to 50: the Krylov basis holds $m + 1$ vectors of the KKT order,
    /// the largest buffer a solver owns after its factor; a solve whose cycles need more
    /// iterations restarts from the better iterate. Unused in other orderings. Default 10 (why:
    /// `docs/settings.md`).
    pub krylov_restart: u32,
    /// Refinement stops at this relative residual $\lVert Kz - b\rVert_\infty/\lVert
    /// b\rVert_\infty$ (finite, $\ge 0$). Default $\varepsilon^{3/4}$ ($1.8 \cdot 10^{-12}$ in
    /// `f64`, $6.4 \cdot 10^{-6}$ in `f32`), which keeps Newton's quadratic convergence over
    /// several iterations; the book, one iteration a step, sets $\sqrt{\varepsilon}$.
    pub refinement_tolerance: T,
    /// Damping $\rho$ of the constraint projection's normal equations, $J W^{-1} J^\top +
    /// \rho\thinspace\mathrm{diag}(J W^{-1} J^\top)$
    /// ([`crate::normal_equations::NormalEquations::assemble`]; finite, $\ge 0$). Default 0 in
    /// `f64`, $\varepsilon^{3/4} = 6.4 \cdot 10^{-6}$ in `f32` (why: `docs/settings.md`).
    pub projection_damping: T,
    /// Evaluate the eq. 3 residual after the last iteration (one gradient and Jacobian
    /// evaluation, no factorization) so the status can say `Converged`. Default on.
    pub check_final_residual: bool,
    /// Threads of the KKT factorization ([`Parallelism`]). Default [`Parallelism::Auto`]:
    /// one thread below [`Parallelism::AUTO_MIN_ORDER`] unknowns (the book's pages), two
    /// above, with `std`.
    pub parallelism: Parallelism,
    /// Which Hessian of each potential the Newton step assembles ([`Convexify`]). Default
    /// [`Convexify::Never`]: the exact one, the seed's.
    pub convexify: Convexify,
}

/// Which Hessian of each potential the Newton step assembles: the exact
/// $\nabla^2 V$ or its positive semi-definite stand-in
/// ([`folio_kernels::term::Potential::convex_hessian`]).
///
/// Newton's iteration converges quadratically only with the exact Hessian, and only where
/// the KKT matrix has the inertia of a minimum (as many positive pivots as free
/// coordinates). Far from one, a soft page's exact Hessian is indefinite and the inertia
/// correction ([`crate::Kkt::factorize_with_inertia_correction`]) shifts the whole primal
/// block, which stalls the step; the convex stand-in never needs that shift, but Newton
/// with it converges at best linearly and may cycle between two iterates (Folio's
/// measurement: a novel page held by its pad kept a residual of 1e-6 to 1e-3 over 20
/// iterations a step at 16 x 22, `docs/accuracy.md`, R1).
/// [`Convexify::WhenIndefinite`] takes each where it works.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Convexify {
    /// The exact Hessian of every potential.
    #[default]
    Never,
    /// The convex stand-in of every potential.
    Always,
    /// The exact Hessian while the KKT matrix factors with the inertia of a minimum; in
    /// an iteration where it does not, the convex stand-in (and the inertia correction
    /// after it, should the constraint Hessian still make it indefinite). One extra
    /// factorization and assembly in such an iteration; none elsewhere.
    WhenIndefinite,
}

/// Threads of the KKT factorization. Two threads need the `std` feature; without it every
/// choice is one thread.
///
/// On two threads the symbolic analysis orders the KKT by a one-level nested dissection
/// ([`crate::nested_dissection`], each half ordered by [`Settings::ordering`]), and the two
/// halves of the factor are computed concurrently, then the separator
/// ([`crate::ldlt::Ldlt::set_threads`]). That order and the split factor's summation
/// differ from the one-thread factor, so results differ in the last bits; the split factor
/// itself is bit for bit the same on one thread and on two. Each two-thread factorization
/// spawns a scoped thread, which allocates its stack and handle: a step on two threads
/// allocates once per factorization (one thread allocates nothing).
///
/// [`Parallelism::Auto`] takes two threads from [`Parallelism::AUTO_MIN_ORDER`] unknowns:
/// below it the split order's extra fill and the thread's start cost more than the second
/// core saves (measured with `cargo run --release -p folio-bench --example kkt_threads`, see
/// `bench/README.md`). The book's 11x8 page (677 unknowns) stays on one thread.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Parallelism {
    /// One thread, in the order of [`Settings::ordering`].
    One,
    /// Two threads, in the split order (with `std`; one thread without).
    Two,
    /// Two threads from [`Parallelism::AUTO_MIN_ORDER`] unknowns on, one below.
    #[default]
    Auto,
}

impl Parallelism {
    /// KKT order from which [`Parallelism::Auto`] takes two threads.
    pub const AUTO_MIN_ORDER: usize = 1500;

    /// Threads for a KKT of `order` unknowns: 1 or 2 (always 1 without `std`).
    #[inline]
    #[must_use]
    pub fn threads(self, order: usize) -> usize {
        let two = match self {
            Self::One => false,
            Self::Two => true,
            Self::Auto => order >= Self::AUTO_MIN_ORDER,
        };
        if two && cfg!(feature = "std") { 2 } else { 1 }
    }
}

impl<T: Real> Default for Settings<T> {
    fn default() -> Self {
        let sqrt_eps = folio_kernels::math::sqrt(T::EPSILON);
        Self {
            time_step: T::from_f64(1.0 / 60.0),
            newton_iterations: 1,
            constraint_hessian: false,
            tolerance: sqrt_eps,
            predictor: false,
            warm_multipliers: false,
            line_search: true,
            max_halvings: 20,
            damping_retries: 4,
            second_order_correction: true,
            merit_slack: T::ZERO,
            ordering: if T::EPSILON.to_f64() < 1e-10 {
                Ordering::Amd
            } else {
                Ordering::AmdQuasiDefinite
            },
            equilibrate: false,
            pivot_epsilon: T::from_f64(1000.0) * T::EPSILON,
            regularization: sqrt_eps,
            refinement_steps: 10,
            krylov_restart: crate::ordering::QUASI_DEFINITE_RESTART as u32,
            refinement_tolerance: sqrt_eps * folio_kernels::math::sqrt(sqrt_eps),
            projection_damping: if T::EPSILON.to_f64() < 1e-10 {
                T::ZERO
            } else {
                sqrt_eps * folio_kernels::math::sqrt(sqrt_eps)
            },
            check_final_residual: true,
            parallelism: Parallelism::Auto,
            convexify: Convexify::Never,
        }
    }
}

impl<T: Real> Settings<T> {
    /// Checks every field against its documented range (the field docs state each).
    ///
    /// # Errors
    /// The first bad field, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let real = |v: T| v.to_f64();
        for (field, v) in [
            ("time_step", self.time_step),
            ("regularization", self.regularization),
        ] {
            require_positive(field, real(v))?;
        }
        for (field, v) in [
            ("tolerance", self.tolerance),
            ("merit_slack", self.merit_slack),
            ("pivot_epsilon", self.pivot_epsilon),
            ("refinement_tolerance", self.refinement_tolerance),
            ("projection_damping", self.projection_damping),
        ] {
            require_non_negative(field, real(v))?;
        }
        let counts = [
            (
                "newton_iterations",
                self.newton_iterations,
                1,
                MAX_NEWTON_ITERATIONS,
            ),
            ("max_halvings", self.max_halvings, 0, 60),
            ("damping_retries", self.damping_retries, 0, 10),
            ("refinement_steps", self.refinement_steps, 0, 100),
            ("krylov_restart", self.krylov_restart, 1, 50),
        ];
        for (field, n, lo, hi) in counts {
            require_range(field, f64::from(n), f64::from(lo), f64::from(hi))?;
        }
        Ok(())
    }
}
