//! The backtracking line search of [`super::Solver::step`] on the merit
//! $\psi = E + \mu\lVert C\rVert_2$ (module docs of [`super`]), with its second-order
//! correction.

use folio_kernels::Real;

use super::{Workspace, add_to};
use crate::assembly::Derivatives;
use crate::error::SolverError;
use crate::model::Model;
use crate::report::StepReport;
use crate::settings::Settings;
use crate::vector::{max_abs, norm2};

/// Outcome of one backtracking line search.
#[derive(Clone, Copy, Debug)]
struct LineSearch<T> {
    before: T,
    /// Merit at the accepted point; `None` when every halving failed.
    after: Option<T>,
    halvings: u32,
    /// A second-order correction was tried.
    second_order: bool,
}

/// The line search's acceptance test ([`super`] module docs): the merit
/// $\psi = E + \mu\lVert C\rVert_2$ at the iterate and its thresholds.
#[derive(Clone, Copy, Debug)]
struct Merit<T> {
    /// $\mu = \max(1.1\lVert\lambda^+\rVert_2, 0.05)$.
    mu: T,
    /// $\lVert C\rVert_2$ at the iterate.
    theta0: T,
    /// $\psi$ at the iterate.
    before: T,
    /// $\psi$ and $E$ at the iterate, raised by the rounding noise.
    ceiling: T,
    energy_ceiling: T,
    /// [`Settings::merit_slack`].
    slack: T,
}

impl<T: Real> Merit<T> {
    /// The test at an iterate with energy `energy`, constraint values `constraint` and new
    /// multipliers `lambda`.
    fn new(energy: T, lambda: &[T], constraint: &[T], slack: T) -> Self {
        let mu = T::from_f64(1.1) * norm2(lambda);
        let mu = if mu > T::from_f64(0.05) {
            mu
        } else {
            T::from_f64(0.05)
        };
        let theta0 = norm2(constraint);
        let before = energy + mu * theta0;
        // Changes below the rounding noise count as no increase, so that a step at
        // convergence is not refused for noise.
        let noise = |v: T| v + T::from_f64(16.0) * T::EPSILON * if v < T::ZERO { -v } else { v };
        Self {
            mu,
            theta0,
            before,
            ceiling: noise(before),
            energy_ceiling: noise(energy),
            slack,
        }
    }

    /// The merit of a trial point with energy `e` and $\lVert C\rVert_2 =$ `theta` if it is
    /// accepted: the exact-penalty test, or (with a slack) the filter test: a violation
    /// within the slack is allowed if the energy does not rise or the violation falls by a
    /// tenth.
    fn accept(&self, e: T, theta: T) -> Option<T> {
        let merit = e + self.mu * theta;
        let penalty = merit <= self.ceiling;
        let filter = self.slack > T::ZERO
            && theta <= self.slack
            && (e <= self.energy_ceiling || theta <= T::from_f64(0.9) * self.theta0);
        (merit.is_finite() && (penalty || filter)).then_some(merit)
    }
}

impl<T: Real> Workspace<T> {
    /// Runs the line search along the solved step and records it; `true` when it accepted a
    /// point (left in `trial`, its $C$ in `constraint`).
    pub(super) fn search<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        energy: T,
        report: &mut StepReport<T>,
    ) -> Result<bool, SolverError> {
        let search = self.line_search(
            model,
            s.time_step,
            energy,
            s.max_halvings,
            s.second_order_correction,
            s.merit_slack,
        )?;
        report.second_order_corrections += u32::from(search.second_order);
        report.merit_before = Some(search.before);
        report.merit_after = search.after;
        report.halvings += search.halvings;
        if search.after.is_some() {
            report.constraint_residual = Some(max_abs(&self.constraint));
            return Ok(true);
        }
        Ok(false)
    }

    /// Backtracks from $\alpha = 1$ along the solved direction until the merit
    /// $\psi = E + \mu\lVert C\rVert_2$ does not increase (module docs); the accepted point is
    /// left in `trial` and its $C$ in `constraint`. `energy` is $E$ at the iterate, whose $C$
    /// is in `constraint` on entry.
    fn line_search<M: Model<T>>(
        &mut self,
        model: &M,
        h: T,
        energy: T,
        max_halvings: u32,
        soc: bool,
        slack: T,
    ) -> Result<LineSearch<T>, SolverError> {
        let merit = Merit::new(
            energy,
            &self.solution[self.kkt.pattern.dofs..],
            &self.constraint,
            slack,
        );
        let mut alpha = T::ONE;
        let mut second_order = false;
        for halvings in 0..=max_halvings {
            self.set_trial(alpha);
            let t = self.evaluate(model, h, true, Derivatives::None)?;
            let found = |after, second_order| LineSearch {
                before: merit.before,
                after: Some(after),
                halvings,
                second_order,
            };
            if let Some(after) = merit
                .accept(t.energy, norm2(&self.constraint))
                .filter(|_| t.finite)
            {
                return Ok(found(after, second_order));
            }
            if halvings == 0 && soc && t.finite {
                self.second_order_correction();
                let t = self.evaluate(model, h, true, Derivatives::None)?;
                second_order = true;
                if let Some(after) = merit
                    .accept(t.energy, norm2(&self.constraint))
                    .filter(|_| t.finite)
                {
                    return Ok(found(after, second_order));
                }
            }
            alpha *= T::HALF;
        }
        Ok(LineSearch {
            before: merit.before,
            after: None,
            halvings: max_halvings,
            second_order,
        })
    }

    /// Second-order correction (Nocedal & Wright, Alg. 18.3): the full step is often refused
    /// only because $C$ grew to second order along it (the Maratos effect); one more solve
    /// with the same factor, $[A\ J^\top; J\ 0]\thinspace [d; \mu] = [0; -C(x + \Delta x)]$, pulls
    /// the trial (whose $C$ is in `constraint`) back towards $C = 0$.
    fn second_order_correction(&mut self) {
        let dofs = self.kkt.pattern.dofs;
        self.rhs[..dofs].iter_mut().for_each(|r| *r = T::ZERO);
        for (r, &c) in self.rhs[dofs..].iter_mut().zip(&self.constraint) {
            *r = -c;
        }
        self.kkt
            .solve_refined(&mut self.product, &self.rhs, 0, T::ZERO);
        add_to(
            &mut self.trial,
            &self.kkt.pattern.coordinate_of,
            &self.product,
            T::ONE,
        );
    }
}
