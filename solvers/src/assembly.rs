//! The evaluating visitor: sums potentials, writes constraint values, and scatters
//! gradients, Hessians and Jacobians through the pattern's precomputed slots.

use folio_kernels::{Constraint, Mat3Ops, Potential, Real, Vec3Ops};

use crate::model::{ConstraintSet, PotentialSet, TermVisitor};
use crate::pattern::{Family, KktPattern, NONE};

/// What an evaluation computes beyond $V(x)$ and $C(x)$.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Derivatives {
    /// Values only (line search).
    None,
    /// $\nabla C$ only (the constraint projection).
    Jacobian,
    /// $\nabla V$ and $\nabla C$ (residual check).
    First,
    /// $\nabla V$, $\nabla C$, $\nabla^2 V$ and, if in the pattern, $\sum_l \lambda_l \nabla^2 C_l$.
    Second,
}

/// Accumulates one evaluation of a model (see [`crate::model::Model::visit_terms`]).
pub(crate) struct Assemble<'a, T: Real> {
    pub pattern: &'a KktPattern,
    pub x: &'a [T::Vec3],
    /// Multipliers for the constraint Hessian (one per row).
    pub lambda: &'a [T],
    /// KKT values: Hessian and Jacobian entries are added here.
    pub values: &'a mut [T],
    /// $\nabla V$ per dof, added to.
    pub gradient: &'a mut [T],
    /// $C(x)$ per row, overwritten.
    pub constraint: &'a mut [T],
    pub derivatives: Derivatives,
    /// $V(x)$, summed.
    pub energy: T,
    /// Index of the next family.
    pub family: usize,
    /// Set when the model's families differ from the analysed ones.
    pub mismatch: bool,
}

impl<T: Real> Assemble<'_, T> {
    /// The analysed family for the next visited one, if it matches in shape.
    fn next_family(&mut self, terms: usize, nodes: usize, rows: usize) -> Option<Family> {
        let f = self.pattern.families.get(self.family).copied();
        self.family += 1;
        match f {
            Some(f) if f.terms == terms && f.nodes == nodes && f.rows == rows => Some(f),
            _ => {
                self.mismatch = true;
                None
            }
        }
    }

    /// Adds `weight * blocks` through the Hessian slots of term `t` of `f`.
    fn scatter_hessian<const N: usize>(
        &mut self,
        f: &Family,
        t: usize,
        blocks: &[[T::Mat3; N]; N],
        weight: T,
    ) {
        let stride = 3 * N;
        let slots = &self.pattern.hessian_slots[f.hessian_offset + t * stride * stride..];
        for (a, row) in blocks.iter().enumerate() {
            for (b, block) in row.iter().enumerate() {
                for i in 0..3 {
                    for j in 0..3 {
                        let s = slots[(3 * a + i) * stride + 3 * b + j];
                        if s != NONE {
                            self.values[s as usize] += weight * block.entry(i, j);
                        }
                    }
                }
            }
        }
    }
}

/// The term's node positions.
#[inline]
fn gather<T: Real, const N: usize>(x: &[T::Vec3], nodes: &[u32; N]) -> [T::Vec3; N] {
    let mut out = [T::Vec3::ZERO; N];
    for (o, &n) in out.iter_mut().zip(nodes) {
        *o = x[n as usize];
    }
    out
}

impl<T: Real> TermVisitor<T> for Assemble<'_, T> {
    fn potentials<P: Potential<T, N>, const N: usize>(&mut self, set: &PotentialSet<T, P, N>) {
        let Some(f) = self.next_family(set.terms().len(), N, 0) else {
            return;
        };
        let w = set.weight;
        for (t, term) in set.terms().iter().enumerate() {
            let xs = gather::<T, N>(self.x, &term.nodes);
            self.energy += w * term.kernel.value(&xs);
            if matches!(self.derivatives, Derivatives::None | Derivatives::Jacobian) {
                continue;
            }
            let g = term.kernel.gradient(&xs);
            let dofs = &self.pattern.local_dofs[f.dof_offset + t * 3 * N..][..3 * N];
            for (a, ga) in g.iter().enumerate() {
                for i in 0..3 {
                    let d = dofs[3 * a + i];
                    if d != NONE {
                        self.gradient[d as usize] += w * ga.get(i);
                    }
                }
            }
            if self.derivatives == Derivatives::Second {
                let h = term.kernel.hessian(&xs);
                self.scatter_hessian::<N>(&f, t, &h, w);
            }
        }
    }

    fn constraints<C: Constraint<T, R, N>, const R: usize, const N: usize>(
        &mut self,
        set: &ConstraintSet<C, N>,
    ) {
        let Some(f) = self.next_family(set.terms().len(), N, R) else {
            return;
        };
        for (t, term) in set.terms().iter().enumerate() {
            let xs = gather::<T, N>(self.x, &term.nodes);
            let row0 = f.first_row + t * R;
            self.constraint[row0..row0 + R].copy_from_slice(&term.kernel.value(&xs));
            if self.derivatives == Derivatives::None {
                continue;
            }
            let jac = term.kernel.jacobian(&xs);
            let slots = &self.pattern.jacobian_slots[f.jacobian_offset + t * 3 * N * R..];
            for (r, row) in jac.iter().enumerate() {
                for (a, ja) in row.iter().enumerate() {
                    for i in 0..3 {
                        let s = slots[r * 3 * N + 3 * a + i];
                        if s != NONE {
                            self.values[s as usize] += ja.get(i);
                        }
                    }
                }
            }
            if self.derivatives == Derivatives::Second && f.has_hessian {
                let mut lambda = [T::ZERO; R];
                lambda.copy_from_slice(&self.lambda[row0..row0 + R]);
                let h = term.kernel.hessian(&xs, &lambda);
                self.scatter_hessian::<N>(&f, t, &h, T::ONE);
            }
        }
    }
}
