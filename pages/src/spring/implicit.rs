//! The implicit-Euler alternative to the seed's integrator: [`folio_solvers::Solver`] (seed `000_…`
//! eq. 2-4) on the [`SpringNetwork`] model,
//! $$\min_x \frac{1}{2h^2}(x - \bar x)^\top M (x - \bar x) + \sum_s V_s(x) + w\sum_k y_k -
//!   \frac{c}{2h}\lVert x - x^n\rVert^2,\qquad \bar x = x^n + h v^n,$$
//! over the free particles (fixed and gripped ones are eliminated and keep the positions
//! written into the state before the step), one Newton iteration with line search, then
//! $v = (x - x^n)/h$, $h$ one substep ([`super::SpringSettings::substep`]; the page takes
//! [`super::SpringSettings::substeps`] of them per frame, one solve each). The last term is
//! the particle damping $c\thinspace v^{n+1}$ taken implicitly ([`super::network`] module docs).
//!
//! The symbolic analysis depends on which particles are free: it is redone when the roles
//! change (at a grab or a release, which call [`ImplicitStepper::analyse`], so that the frame
//! steps themselves do not allocate).

use folio_kernels::Real;

use super::network::SpringNetwork;
use folio_solvers::settings::Settings;
use folio_solvers::step::{Solver, State};

/// The solver of the implicit integrator (module docs).
#[derive(Clone, Debug)]
pub struct ImplicitStepper<T: Real> {
    solver: Solver<T>,
}

impl<T: Real> ImplicitStepper<T> {
    /// A stepper with time step `h` (finite, $> 0$) and the solver's other defaults; `None`
    /// for a bad `h`.
    #[must_use]
    pub fn new(h: T) -> Option<Self> {
        let settings = Settings {
            time_step: h,
            ..Settings::default()
        };
        Solver::new(settings).ok().map(|solver| Self { solver })
    }

    /// Runs the symbolic analysis for the current roles of `network` (allocates when they
    /// changed). Returns `false` if the solver refused the model.
    pub fn analyse(&mut self, network: &SpringNetwork<T>) -> bool {
        self.solver.analyse(network).is_ok()
    }

    /// One implicit step of `state` (module docs), its damping pulls aimed at the current
    /// positions. Returns `true` when the state advanced; otherwise the state may hold the
    /// caller's kinematic placements but nothing else changed.
    pub fn step(&mut self, network: &mut SpringNetwork<T>, state: &mut State<T>) -> bool {
        network.set_damping_targets(&state.x);
        match self.solver.step(&*network, state) {
            Ok(report) => report.status.advanced(),
            Err(_) => false,
        }
    }
}
