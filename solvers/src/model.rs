//! What the solver needs from a model: its nodes, masses, eliminated coordinates and term
//! families, visited in one fixed order.
//!
//! A model owns its terms as [`PotentialSet`]s and [`ConstraintSet`]s (one set per kernel
//! type) and hands them to a [`TermVisitor`] in [`Model::visit_terms`]. The solver visits
//! once to declare the stencils (building the sparsity pattern and scatter maps) and then
//! on every evaluation; the order and sizes of the families must stay the same until the
//! model bumps [`Model::topology_version`].

use crate::room::Room;
use alloc::vec::Vec;
use folio_kernels::{Constraint, Potential, Real};

/// A physical system the implicit-Euler step can advance (seed `000_…` eq. 1-3).
///
/// Units follow the kernels: lengths in page units, masses in page masses, time in seconds.
pub trait Model<T: Real> {
    /// Changes whenever the terms' stencils, the node count or the eliminated coordinates
    /// change; the solver re-runs its symbolic analysis when it does, and only then.
    fn topology_version(&self) -> u64;

    /// Number of nodes (3 coordinates each).
    fn node_count(&self) -> usize;

    /// `true` when coordinate `axis` (0 = X, 1 = Y, 2 = Z) of `node` is fixed by the model
    /// and eliminated from the unknowns (seed `000_…` Sec. 3.1: Z of midline and cover
    /// nodes, Z of the bound column). Read at analysis only.
    fn is_fixed(&self, node: usize, axis: usize) -> bool;

    /// Mass of `node` (page masses; positive and finite for nodes with a free coordinate).
    fn mass(&self, node: usize) -> T;

    /// Hands every term family to `visitor`, always in the same order.
    fn visit_terms<V: TermVisitor<T>>(&self, visitor: &mut V);
}

/// Receives a model's term families (see [`Model::visit_terms`]).
pub trait TermVisitor<T: Real> {
    /// A family of potentials with `N` nodes each, summed with the family's weight.
    fn potentials<P: Potential<T, N>, const N: usize>(&mut self, set: &PotentialSet<T, P, N>);

    /// A family of constraints with `R` rows on `N` nodes each.
    fn constraints<C: Constraint<T, R, N>, const R: usize, const N: usize>(
        &mut self,
        set: &ConstraintSet<C, N>,
    );
}

/// One kernel instance and the global node indices of its local nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Term<K, const N: usize> {
    /// The kernel with its parameters.
    pub kernel: K,
    /// Global node index of each local node, in the kernel's documented order.
    pub nodes: [u32; N],
}

/// A term whose kernel may change and whose nodes may not ([`PotentialSet::terms_mut`]).
#[derive(Debug)]
pub struct TermMut<'a, K, const N: usize> {
    /// The kernel with its parameters.
    pub kernel: &'a mut K,
    /// Global node index of each local node.
    pub nodes: &'a [u32; N],
}

/// Potentials of one kernel type: $V = w \sum_t V_t(x_{\text{nodes}(t)})$.
#[derive(Clone, Debug, PartialEq)]
pub struct PotentialSet<T, P, const N: usize> {
    /// The family weight $w$ (seed `000_…` eq. 9), multiplying value, gradient and Hessian.
    pub weight: T,
    terms: Vec<Term<P, N>>,
}

impl<T, P, const N: usize> PotentialSet<T, P, N> {
    /// An empty family with weight `weight`.
    #[must_use]
    pub fn new(weight: T) -> Self {
        Self {
            weight,
            terms: Vec::new(),
        }
    }

    /// Adds a term on `nodes`. Node indices are checked when the solver analyses the model.
    pub fn push(&mut self, kernel: P, nodes: [u32; N]) {
        self.terms.push(Term { kernel, nodes });
    }

    /// Removes every term and sets the weight, keeping the capacity (a model rebuilt in
    /// place allocates nothing while its terms fit).
    pub fn reset(&mut self, weight: T) {
        self.weight = weight;
        self.terms.clear();
    }

    /// Makes room for `terms` terms in all.
    pub fn reserve(&mut self, terms: usize) {
        self.terms.room_for(terms);
    }

    /// The terms.
    #[must_use]
    pub fn terms(&self) -> &[Term<P, N>] {
        &self.terms
    }

    /// The kernel of term `t`, if there is one (values change, the pattern does not).
    pub fn kernel_mut(&mut self, t: usize) -> Option<&mut P> {
        self.terms.get_mut(t).map(|t| &mut t.kernel)
    }

    /// The terms with their kernels mutable and their nodes read-only (a kernel's parameters
    /// may follow its nodes' positions; the stencils may not change).
    pub fn terms_mut(&mut self) -> impl Iterator<Item = TermMut<'_, P, N>> {
        self.terms.iter_mut().map(|t| TermMut {
            kernel: &mut t.kernel,
            nodes: &t.nodes,
        })
    }

    /// The kernels, mutable (parameters such as a positional target may change every step;
    /// the stencils may not).
    pub fn kernels_mut(&mut self) -> impl Iterator<Item = &mut P> {
        self.terms.iter_mut().map(|t| &mut t.kernel)
    }
}

/// Constraints of one kernel type, `R` consecutive rows per term.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintSet<C, const N: usize> {
    terms: Vec<Term<C, N>>,
}

impl<C, const N: usize> Default for ConstraintSet<C, N> {
    fn default() -> Self {
        Self { terms: Vec::new() }
    }
}

impl<C, const N: usize> ConstraintSet<C, N> {
    /// An empty family.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a term on `nodes`. Node indices are checked when the solver analyses the model.
    pub fn push(&mut self, kernel: C, nodes: [u32; N]) {
        self.terms.push(Term { kernel, nodes });
    }

    /// The terms.
    #[must_use]
    pub fn terms(&self) -> &[Term<C, N>] {
        &self.terms
    }

    /// The kernels, mutable (parameters such as the binding's `q` may change every step).
    pub fn kernels_mut(&mut self) -> impl Iterator<Item = &mut C> {
        self.terms.iter_mut().map(|t| &mut t.kernel)
    }
}
