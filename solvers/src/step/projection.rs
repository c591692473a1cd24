//! Projection onto the constraints after a step ([`super::Solver::project_constraints`]).

use folio_kernels::{Real, Vec3Ops};

use super::{Solver, State, Workspace};
use crate::assembly::Derivatives;
use crate::error::SolverError;
use crate::model::Model;
use crate::normal_equations::slide;
use crate::pattern::{KktPattern, NONE};
use crate::settings::Settings;
use crate::vector::max_abs;

/// Solves a projection iteration may add to let go of contacts the constraints pull off
/// their surfaces ([`Pins`]). Measured on the firmware page turn (`embedded/README.md`):
/// with none (a node let go only from the next iteration on) `three-and-back`'s second
/// turn fell back; with one, solved again only for a node that would leave by more than
/// the tolerance, the M4F's median active step costs 26.7 M instructions (22.8 M with the
/// isotropic pins before, 31.5 M solving again for any node let go).
const RELEASE_ROUNDS: u32 = 1;

/// Step halvings a projection iteration may try before it gives up.
const PROJECTION_HALVINGS: u32 = 6;

/// What [`Solver::project_constraints`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Correction<T> {
    /// Projection iterations accepted.
    pub steps: u32,
    /// $\lVert C(x)\rVert_\infty$ before the first iteration.
    pub before: T,
    /// $\lVert C(x)\rVert_\infty$ after the last accepted one.
    pub after: T,
    /// Numeric factorizations of the normal equations (one per solve that had work to do:
    /// every solve factorizes, [`crate::normal_equations::NormalEquations::solve`]).
    pub factorizations: u32,
    /// Triangular solves with the normal equations' factor.
    pub solves: u32,
}

/// The nodes a projection holds ([`Solver::project_constraints`]): contact points that
/// must stay on the surfaces that pushed them.
#[derive(Clone, Copy, Debug)]
pub struct Pins<'a, T: Real> {
    /// One flag per node: held.
    pub nodes: &'a [bool],
    /// Per node, the unit normal of the surface a held node stays on: its weight factor then
    /// applies along the normal only, it slides freely along the surface, and the hold is
    /// one-sided: a node the constraints pull off the surface is let go. A zero
    /// normal, or an empty slice for every node, holds it in every direction, as does a
    /// node with an eliminated coordinate.
    pub normals: &'a [T::Vec3],
    /// The weight factor $w_{pin} \ge 1$ of held nodes.
    pub weight: T,
}

impl<'a, T: Real> Pins<'a, T> {
    /// The flagged nodes held in every direction with weight factor `weight`.
    #[must_use]
    pub fn isotropic(nodes: &'a [bool], weight: T) -> Self {
        Self {
            nodes,
            normals: &[],
            weight,
        }
    }

    /// Node `node`'s three dofs and unit normal when it is held along a normal only.
    fn along(&self, pattern: &KktPattern, node: usize) -> Option<([usize; 3], [T; 3])> {
        if !self.nodes[node] || self.normals.is_empty() {
            return None;
        }
        let n = *self.normals.get(node)?;
        let length = folio_kernels::math::length::<T>(n);
        if !(length > T::ZERO && length.is_finite()) {
            return None;
        }
        let d = &pattern.dof_of[3 * node..3 * node + 3];
        if d.contains(&NONE) {
            return None;
        }
        let unit = n / length;
        Some((
            [d[0] as usize, d[1] as usize, d[2] as usize],
            [unit.x(), unit.y(), unit.z()],
        ))
    }
}

impl<T: Real> Solver<T> {
    /// Pulls `state` back onto the constraints after a step and anything done to it since
    /// (collision projection): the mass-weighted closest point on $C(x) = 0$, found by
    /// Gauss-Newton iterations with the Jacobian re-evaluated at each iterate,
    /// $$\begin{bmatrix} W & J(x)^\top \cr J(x) & 0\end{bmatrix}\begin{bmatrix}\delta \cr \mu\end{bmatrix}
    ///   = \begin{bmatrix} 0 \cr -C(x)\end{bmatrix},\qquad x \mathrel{+}= \delta,\ v \mathrel{+}= \delta / h,$$
    /// with $W = M/h^2$ except on the nodes `pins` holds, whose weight is multiplied by
    /// $w_{pin}$ so that they barely move (contact points stay on the surface that pushed
    /// them): in every direction, or along their contact normal $n$ only,
    /// $W_i = (m_i/h^2)(I + (w_{pin} - 1) n n^\top)$, so that they slide along the surface
    /// ([`Pins`]). This is the fast projection of Goldenthal et al. 2007. Since $W$ is diagonal,
    /// each iteration solves the normal equations $J W^{-1} J^\top\mu = C$ instead
    /// ([`crate::normal_equations::NormalEquations`]: constraint rows only, analysed once per
    /// topology, factorized for every solve, since $J$ and $W$ change with each iteration and
    /// release round; a factor held across them served one iteration in 10 to 16 and cost
    /// more than it saved, f85c306), and allocates nothing. The one-Newton-step
    /// default leaves $C = O(\lVert\Delta x\rVert^2)$ behind, and a collision push of depth
    /// $d$ leaves $C = O(d/\ell)$ (module docs); this removes both. Iterates until
    /// $\lVert C\rVert_\infty \le$ `tolerance` or `max_iterations` iterations; each iteration
    /// halves its step (up to 6 times) until $\lVert C\rVert_\infty$ falls, and one that
    /// cannot lower it ends the projection. Does
    /// nothing (zero steps) before the first successful step of the topology. The normal
    /// equations come from [`Solver::analyse_projection`] at setup; a solver set up without
    /// it builds them (and allocates) at its first call of each topology.
    ///
    /// # Errors
    /// As [`Solver::step`] for a model that changed or a state of the wrong length;
    /// [`SolverError::StateLength`] also when `pins` has not one flag per node, or normals
    /// that are neither none nor one per node.
    pub fn project_constraints<M: Model<T>>(
        &mut self,
        model: &M,
        state: &mut State<T>,
        pins: Pins<'_, T>,
        tolerance: T,
        max_iterations: u32,
    ) -> Result<Correction<T>, SolverError> {
        let mut out = Correction {
            steps: 0,
            before: T::ZERO,
            after: T::ZERO,
            factorizations: 0,
            solves: 0,
        };
        let s = self.settings;
        let h = s.time_step;
        if self
            .work
            .as_ref()
            .is_some_and(|w| w.version == model.topology_version())
        {
            self.prepare_projection();
        }
        let Some(w) = self.work.as_mut() else {
            return Ok(out);
        };
        if w.version != model.topology_version() {
            return Err(SolverError::ModelChanged);
        }
        let nodes = w.x.len();
        let normals_fit = pins.normals.is_empty() || pins.normals.len() == nodes;
        if state.x.len() != nodes || state.v.len() != nodes || pins.nodes.len() != nodes {
            return Err(SolverError::StateLength {
                expected: nodes,
                positions: state.x.len(),
                velocities: state.v.len().min(pins.nodes.len()),
            });
        }
        if !normals_fit {
            return Err(SolverError::StateLength {
                expected: nodes,
                positions: state.x.len(),
                velocities: pins.normals.len(),
            });
        }
        if !w.factored {
            return Ok(out);
        }
        w.x.copy_from_slice(&state.x);
        w.released.iter_mut().for_each(|r| *r = false);
        let e = w.evaluate(model, h, false, Derivatives::None)?;
        let mut residual = max_abs(&w.constraint);
        if !(e.finite && residual.is_finite()) {
            return Ok(out);
        }
        out.before = residual;
        while out.steps < max_iterations && residual > tolerance {
            let Some(next) = w.project_once(model, &s, pins, tolerance, residual, &mut out)? else {
                break;
            };
            core::mem::swap(&mut w.x, &mut w.trial);
            residual = next;
            out.steps += 1;
        }
        out.after = residual;
        let inv_h = T::ONE / h;
        for ((x, v), &new) in state.x.iter_mut().zip(state.v.iter_mut()).zip(&w.x) {
            *v += (new - *x) * inv_h;
            *x = new;
        }
        Ok(out)
    }
}

impl<T: Real> Workspace<T> {
    /// One iteration of [`Solver::project_constraints`] from the iterate, whose
    /// $\lVert C\rVert_\infty$ is `residual`: evaluates $J(x)$, sets
    /// $W = M/h^2$ (times $w_{pin}$ on held nodes, [`Pins`]), solves the normal equations
    /// $J W^{-1} J^\top \mu = C$ to a linear residual of a quarter of `tolerance`
    /// ([`crate::normal_equations::NormalEquations`], factorized anew), takes
    /// $\delta = -W^{-1} J^\top\mu$, and halves the step until $\lVert C\rVert_\infty$ falls.
    /// Returns the new $\lVert C\rVert_\infty$ with the point in `trial`, or `None` when the
    /// iteration cannot lower it.
    fn project_once<M: Model<T>>(
        &mut self,
        model: &M,
        s: &Settings<T>,
        pins: Pins<'_, T>,
        tolerance: T,
        residual: T,
        out: &mut Correction<T>,
    ) -> Result<Option<T>, SolverError> {
        let h = s.time_step;
        let dofs = self.kkt.pattern.dofs;
        let e = self.evaluate(model, h, false, Derivatives::Jacobian)?;
        if !e.finite {
            return Ok(None);
        }
        let Some(normal) = self.normal.as_mut() else {
            return Ok(None);
        };
        let h2 = h * h;
        let held = T::ONE - T::ONE / pins.weight;
        // Contacts are one-sided: a node held along its normal that the constraints pull
        // off its surface (n . delta > 0) is let go for the rest of the call, and the
        // system solved again without its pin, up to RELEASE_ROUNDS times.
        for round in 0..=RELEASE_ROUNDS {
            let (pattern, released) = (&self.kkt.pattern, &self.released);
            let along = |node: usize| pins.along(pattern, node).filter(|_| !released[node]);
            for ((w, &m), &c) in normal
                .inverse_w
                .iter_mut()
                .zip(&self.mass)
                .zip(&self.kkt.pattern.coordinate_of)
            {
                let node = c as usize / 3;
                let weight = if pins.nodes[node] && !released[node] && along(node).is_none() {
                    pins.weight
                } else {
                    T::ONE
                };
                *w = h2 / (m * weight);
            }
            normal.assemble(&self.kkt.pattern, &self.kkt.values, s.projection_damping);
            // Held along a normal: W_i^{-1} = (h^2/m)(I - (1 - 1/w_pin) n n^T).
            for node in 0..pins.nodes.len() {
                if let Some((dofs, n)) = along(node) {
                    let c = held * normal.inverse_w[dofs[0]];
                    normal.pin_along(&self.kkt.values, dofs, n, c, s.projection_damping);
                }
            }
            let (delta, mu) = self.solution.split_at_mut(dofs);
            let solve = normal.solve(
                mu,
                &self.constraint,
                T::from_f64(0.25) * tolerance,
                s.refinement_steps,
                s.regularization,
                s.regularization,
            );
            out.solves += solve.solves;
            out.factorizations += u32::from(solve.factorized);
            if solve.failed || !(solve.residual.is_finite() && max_abs(mu).is_finite()) {
                return Ok(None);
            }
            normal.back_substitute(delta, mu, &self.kkt.values);
            let mut lifted = false;
            for node in 0..pins.nodes.len() {
                let Some((dofs, n)) = pins.along(&self.kkt.pattern, node) else {
                    continue;
                };
                if !self.released[node] {
                    slide(delta, dofs, n, held);
                    let off = dofs
                        .iter()
                        .zip(&n)
                        .fold(T::ZERO, |s, (&d, &n)| s + delta[d] * n);
                    if off > T::ZERO {
                        self.released[node] = true;
                        // Solved again only for a node that would leave by more than
                        // the tolerance: off / (1 - held) is its move without the pin.
                        lifted |= off > tolerance * (T::ONE - held);
                    }
                }
            }
            if !lifted || round == RELEASE_ROUNDS {
                break;
            }
        }
        // Backtrack while max|C| does not fall (on nearly flat DOG stars the remedied
        // Jacobian is not the exact one, and a full step can overshoot).
        let mut alpha = T::ONE;
        for _ in 0..PROJECTION_HALVINGS {
            self.set_trial(alpha);
            let e = self.evaluate(model, h, true, Derivatives::None)?;
            let c = max_abs(&self.constraint);
            if e.finite && c < residual {
                return Ok(Some(c));
            }
            alpha *= T::HALF;
        }
        Ok(None)
    }
}
