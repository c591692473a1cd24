//! A small model for the unit tests: a chain of nodes with springs between neighbours and
//! a length constraint across every other pair, and the hand-filled values of its KKT
//! matrix.

use alloc::vec::Vec;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::spring::Spring;

use crate::model::{ConstraintSet, Model, PotentialSet, TermVisitor};
use crate::pattern::KktPattern;

/// `nodes` nodes; springs on `[i, i + 1]`, constraints on `[i, i + 2]` for even `i`; the Z
/// coordinate of node 0 is eliminated.
pub(crate) struct Chain {
    pub nodes: usize,
    pub springs: PotentialSet<f64, Spring<f64>, 2>,
    pub lengths: ConstraintSet<Iso2d<f64>, 2>,
}

impl Chain {
    /// The chain of `nodes` nodes (at least 3).
    pub fn new(nodes: usize) -> Self {
        let mut springs = PotentialSet::new(1.0);
        for i in 0..nodes - 1 {
            springs.push(Spring::new(1.0, 1.0).unwrap(), [i as u32, i as u32 + 1]);
        }
        let mut lengths = ConstraintSet::new();
        for i in (0..nodes - 2).step_by(2) {
            lengths.push(Iso2d::new(2.0).unwrap(), [i as u32, i as u32 + 2]);
        }
        Self {
            nodes,
            springs,
            lengths,
        }
    }

    /// Its KKT pattern.
    pub fn pattern(&self, with_constraint_hessian: bool) -> KktPattern {
        KktPattern::build(self, with_constraint_hessian).unwrap()
    }
}

impl Model<f64> for Chain {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.nodes
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        node == 0 && axis == 2
    }
    fn mass(&self, _node: usize) -> f64 {
        1.0
    }
    fn visit_terms<V: TermVisitor<f64>>(&self, visitor: &mut V) {
        visitor.potentials(&self.springs);
        visitor.constraints(&self.lengths);
    }
}

/// Every stored upper entry of `pattern` as `(row, column, slot)`, column by column.
pub(crate) fn entries(pattern: &KktPattern) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..pattern.order()).flat_map(move |c| {
        (pattern.col_ptr[c] as usize..pattern.col_ptr[c + 1] as usize)
            .map(move |s| (pattern.row_idx[s] as usize, c, s))
    })
}

/// Upper-triangle values of a quasi-definite KKT matrix on `pattern`: a diagonally dominant
/// primal block (diagonal 10, off-diagonals in $[0.1, 0.7]$), Jacobian entries in
/// $[0.1, 0.7]$ and a zero constraint block.
pub(crate) fn kkt_values(pattern: &KktPattern) -> Vec<f64> {
    entries(pattern)
        .map(|(r, c, s)| match (r == c, c < pattern.dofs) {
            (true, true) => 10.0,
            (true, false) => 0.0,
            (false, _) => 0.1 * (1 + s % 7) as f64,
        })
        .collect()
}

/// The full symmetric matrix of upper-triangle `values` on `pattern`, dense, row-major.
pub(crate) fn dense(pattern: &KktPattern, values: &[f64]) -> Vec<Vec<f64>> {
    let n = pattern.order();
    let mut m = alloc::vec![alloc::vec![0.0; n]; n];
    for (r, c, s) in entries(pattern) {
        m[r][c] = values[s];
        m[c][r] = values[s];
    }
    m
}
