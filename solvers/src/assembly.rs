//! The evaluating visitor: sums potentials, writes constraint values, and scatters
//! gradients, Hessians and Jacobians through the pattern's precomputed slots.

use folio_kernels::fused::mul_add;
use folio_kernels::{Constraint, Mat3Ops, Potential, Real, Vec3Ops};

use crate::index::Index;
use crate::model::{ConstraintSet, PotentialSet, TermVisitor};
use crate::pattern::{Family, KktPattern, NONE, first_free, hessian_slot, pair_index};
use crate::slots::{Slots, slot};

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
    /// As [`Derivatives::Second`] with each potential's convex stand-in for $\nabla^2 V$
    /// ([`Potential::convex_hessian`], [`crate::Convexify`]).
    SecondConvex,
}

impl Derivatives {
    /// The gradient and the primal block are assembled.
    pub(crate) fn first(self) -> bool {
        matches!(self, Self::First | Self::Second | Self::SecondConvex)
    }

    /// Second derivatives are assembled.
    pub(crate) fn second(self) -> bool {
        matches!(self, Self::Second | Self::SecondConvex)
    }
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

    /// Adds `weight * blocks` to the stored entries of term `t` of `f`'s Hessian block,
    /// placed by the family's node-pair depths ([`KktPattern::hessian_depths`]), in the
    /// map's width. Each slot receives the same terms in the same order either way: a term
    /// adds to a slot once, except for a repeated dof (full layout, row by row).
    fn scatter_hessian<const N: usize>(
        &mut self,
        f: &Family,
        t: usize,
        blocks: &[[T::Mat3; N]; N],
        weight: T,
    ) {
        let at = f.hessian_offset + t * f.hessian_pairs_per_term();
        match &self.pattern.hessian_depths {
            Slots::Narrow(map) => self.scatter_blocks(f, t, &map[at..], blocks, weight),
            Slots::Wide(map) => self.scatter_blocks(f, t, &map[at..], blocks, weight),
        }
    }

    /// [`Assemble::scatter_hessian`] with `depths`, term `t`'s part of the map. Generic
    /// in the stencil's size, so that its loops unroll: written for any size, the M4F's
    /// median active step took 0.6 % more instructions (for 8 KB less flash).
    fn scatter_blocks<I: Index, const N: usize>(
        &mut self,
        f: &Family,
        t: usize,
        depths: &[I],
        blocks: &[[T::Mat3; N]; N],
        weight: T,
    ) {
        let stride = 3 * N;
        let entry = |p: usize, q: usize| blocks[p / 3][q / 3].entry(p % 3, q % 3);
        let col_ptr = &self.pattern.col_ptr;
        let dofs = &self.pattern.local_dofs[f.dof_offset + t * stride..][..stride];
        let first: [u32; N] = core::array::from_fn(|a| first_free(&dofs[3 * a..3 * a + 3]));
        // Depth of local nodes (a, b), a != b; unread for one node.
        let depth = |a: usize, b: usize| {
            if a == b {
                NONE
            } else {
                depths[pair_index(N, a.min(b), a.max(b))].get() as u32
            }
        };
        if f.hessian_upper {
            // Pair by pair: the rows are the free dofs x of the node numbered first, the
            // columns those (y) of the other (x <= y within one node), and the stored entry
            // (x, y) is one column base past x ([`hessian_slot`]).
            for a in 0..N {
                for b in a..N {
                    if first[a] == NONE || first[b] == NONE {
                        continue;
                    }
                    let (r, c) = if first[a] <= first[b] { (a, b) } else { (b, a) };
                    let d = depth(a, b);
                    for j in 0..3 {
                        let py = 3 * c + j;
                        let y = dofs[py];
                        if y == NONE {
                            continue;
                        }
                        let base = if a == b {
                            (col_ptr[y as usize + 1] - 1).wrapping_sub(y)
                        } else {
                            col_ptr[y as usize].wrapping_add(d).wrapping_sub(first[r])
                        };
                        for i in 0..3 {
                            let px = 3 * r + i;
                            let x = dofs[px];
                            if x == NONE {
                                continue;
                            }
                            if a == b && x > y {
                                break;
                            }
                            let s = base.wrapping_add(x) as usize;
                            debug_assert_eq!(s, hessian_slot(col_ptr, x, y, first[r], first[c], d));
                            self.values[s] = mul_add(self.values[s], weight, entry(px, py));
                        }
                    }
                }
            }
        } else {
            for p in 0..stride {
                for q in 0..stride {
                    let (dp, dq) = (dofs[p], dofs[q]);
                    if dp == NONE || dq == NONE || dp > dq {
                        continue;
                    }
                    let (a, b) = (p / 3, q / 3);
                    let s = hessian_slot(col_ptr, dp, dq, first[a], first[b], depth(a, b));
                    self.values[s] = mul_add(self.values[s], weight, entry(p, q));
                }
            }
        }
    }

    /// Adds the Jacobian rows `jac` of term `t` of `f` through the Jacobian slots (row by
    /// row, node by node, axis by axis), skipping the marks of no slot. Written for any
    /// stencil ([`add_vectors`]): unrolled for each, the maps in two widths took 5.8 KB of
    /// the M4F's flash.
    fn scatter_jacobian<const R: usize, const N: usize>(
        &mut self,
        f: &Family,
        t: usize,
        jac: &[[T::Vec3; N]; R],
    ) {
        let at = f.jacobian_offset + t * 3 * N * R;
        let rows = jac.as_flattened();
        match &self.pattern.jacobian_slots {
            Slots::Narrow(map) => add_vectors(self.values, &map[at..], rows),
            Slots::Wide(map) => add_vectors(self.values, &map[at..], rows),
        }
    }
}

/// Adds the coordinates of `vectors` to `values` through `slots`, three slots per vector.
fn add_vectors<T: Real, I: Index>(values: &mut [T], slots: &[I], vectors: &[T::Vec3]) {
    for (k, v) in vectors.iter().enumerate() {
        for i in 0..3 {
            if let Some(s) = slot(slots[3 * k + i]) {
                values[s] += v.get(i);
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
            self.energy = mul_add(self.energy, w, term.kernel.value(&xs));
            if matches!(self.derivatives, Derivatives::None | Derivatives::Jacobian) {
                continue;
            }
            let g = term.kernel.gradient(&xs);
            let dofs = &self.pattern.local_dofs[f.dof_offset + t * 3 * N..][..3 * N];
            for (a, ga) in g.iter().enumerate() {
                for i in 0..3 {
                    let d = dofs[3 * a + i];
                    if d != NONE {
                        let d = d as usize;
                        self.gradient[d] = mul_add(self.gradient[d], w, ga.get(i));
                    }
                }
            }
            let h = match self.derivatives {
                Derivatives::Second => term.kernel.hessian(&xs),
                Derivatives::SecondConvex => term.kernel.convex_hessian(&xs),
                _ => continue,
            };
            self.scatter_hessian::<N>(&f, t, &h, w);
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
            self.scatter_jacobian::<R, N>(&f, t, &jac);
            if self.derivatives.second() && f.has_hessian {
                let mut lambda = [T::ZERO; R];
                lambda.copy_from_slice(&self.lambda[row0..row0 + R]);
                let h = term.kernel.hessian(&xs, &lambda);
                self.scatter_hessian::<N>(&f, t, &h, T::ONE);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;
    use folio_kernels::spring::Spring;

    use super::{Assemble, Derivatives};
    use crate::chain::Chain;
    use crate::model::Model;
    use crate::pattern::KktPattern;

    /// The KKT values of `chain` on `pattern` at a bent configuration with nonzero
    /// multipliers.
    fn assembled(chain: &Chain, pattern: &KktPattern) -> Vec<f64> {
        let x: Vec<_> = (0..chain.nodes)
            .map(|i| {
                let t = i as f64;
                <f64 as folio_kernels::Real>::Vec3::new(t, 0.3 * t * t, 0.1 * t)
            })
            .collect();
        let lambda: Vec<f64> = (0..pattern.rows()).map(|r| 0.3 + r as f64).collect();
        let mut values = vec![0.0; pattern.nnz()];
        let (mut gradient, mut constraint) = (vec![0.0; pattern.dofs()], vec![0.0; pattern.rows()]);
        let mut assemble = Assemble {
            pattern,
            x: &x,
            lambda: &lambda,
            values: &mut values,
            gradient: &mut gradient,
            constraint: &mut constraint,
            derivatives: Derivatives::Second,
            energy: 0.0,
            family: 0,
            mismatch: false,
        };
        chain.visit_terms(&mut assemble);
        assert!(!assemble.mismatch);
        values
    }

    /// The upper local triangle assembles bit for bit what the full local blocks do, and a
    /// family with a repeated node keeps the full layout.
    #[test]
    fn upper_hessian_maps_assemble_as_the_full_blocks() {
        let mut chain = Chain::new(6);
        for repeated in [false, true] {
            if repeated {
                chain.springs.push(Spring::new(1.0, 0.5).unwrap(), [3, 3]);
            }
            for hessian in [false, true] {
                let pattern = chain.pattern(hessian);
                let upper: Vec<bool> = pattern.families.iter().map(|f| f.hessian_upper).collect();
                assert_eq!(upper, [!repeated, true]);
                let mut full = pattern.clone();
                full.families
                    .iter_mut()
                    .for_each(|f| f.hessian_upper = false);
                full.fill_maps();
                let (ours, theirs) = (assembled(&chain, &pattern), assembled(&chain, &full));
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&ours),
                    bits(&theirs),
                    "repeated {repeated}, Hessian {hessian}"
                );
            }
        }
    }
}
