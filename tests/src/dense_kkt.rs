//! Any small symmetric quasi-definite matrix as a [`Kkt`]: a model whose pattern is the
//! matrix's nonzero structure, with the values written through [`Kkt::values_mut`].
//!
//! The solver builds KKT patterns from models only, so the structure is declared with
//! kernels that carry nothing but their stencils: primal unknown $i$ is the X coordinate of
//! node $i$ (Y and Z eliminated), a [`Spring`] on nodes $(a, b)$ couples unknowns $a$ and
//! $b$, and constraint row $r$ is a one-row [`DogBoundaryStar`] on the (up to four) unknowns
//! its column couples to, padded with a node whose coordinates are all eliminated. The
//! values the kernels would give are never evaluated: every entry is overwritten.

use folio_kernels::Real;
use folio_kernels::dog::DogBoundaryStar;
use folio_kernels::spring::Spring;
use folio_solvers::pattern::KktPattern;
use folio_solvers::{ConstraintSet, Kkt, Model, Ordering, PotentialSet, TermVisitor};

/// Most unknowns one constraint row may couple to (the stencil of [`DogBoundaryStar`]).
pub const ROW_COUPLINGS: usize = 4;

/// The structure of a dense symmetric matrix (see the module docs); node `dofs` is the
/// padding node with no free coordinate.
#[derive(Clone, Debug)]
pub struct DenseStructure<T: Real> {
    dofs: usize,
    couplings: PotentialSet<T, Spring<T>, 2>,
    rows: ConstraintSet<DogBoundaryStar<T>, 4>,
}

impl<T: Real> DenseStructure<T> {
    /// The structure of the `order x order` row-major matrix `k` whose first `dofs`
    /// unknowns are primal. The constraint block's off-diagonal entries are ignored (a KKT
    /// pattern has none); `None` when a row couples to more than [`ROW_COUPLINGS`]
    /// unknowns.
    #[must_use]
    pub fn new(dofs: usize, order: usize, k: &[f64]) -> Option<Self> {
        let spring = Spring::new(T::ZERO, T::ZERO).ok()?;
        let mut couplings = PotentialSet::new(T::ONE);
        for a in 0..dofs {
            for b in a + 1..dofs {
                if k[a * order + b] != 0.0 || k[b * order + a] != 0.0 {
                    couplings.push(spring, [a as u32, b as u32]);
                }
            }
        }
        let pad = dofs as u32;
        let mut rows = ConstraintSet::new();
        for r in dofs..order {
            let mut nodes = [pad; ROW_COUPLINGS];
            let mut count = 0;
            for a in 0..dofs {
                if k[r * order + a] != 0.0 || k[a * order + r] != 0.0 {
                    *nodes.get_mut(count)? = a as u32;
                    count += 1;
                }
            }
            rows.push(DogBoundaryStar::new(), nodes);
        }
        Some(Self {
            dofs,
            couplings,
            rows,
        })
    }
}

impl<T: Real> Model<T> for DenseStructure<T> {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.dofs + 1
    }
    fn is_fixed(&self, node: usize, axis: usize) -> bool {
        node == self.dofs || axis != 0
    }
    fn mass(&self, _node: usize) -> T {
        T::ONE
    }
    fn visit_terms<V: TermVisitor<T>>(&self, v: &mut V) {
        v.potentials(&self.couplings);
        v.constraints(&self.rows);
    }
}

/// The KKT system of the `order x order` row-major symmetric matrix `k` (first `dofs`
/// unknowns primal), analysed in `ordering`, with its upper triangle as values; `None` when
/// a constraint row couples to more than [`ROW_COUPLINGS`] unknowns.
#[must_use]
pub fn dense_kkt<T: Real>(dofs: usize, k: &[f64], ordering: Ordering) -> Option<Kkt<T>> {
    let order = (k.len() as f64).sqrt() as usize;
    assert_eq!(order * order, k.len(), "a square matrix");
    let model = DenseStructure::<T>::new(dofs, order, k)?;
    let pattern = KktPattern::build::<T, _>(&model, false).ok()?;
    debug_assert_eq!(pattern.order(), order);
    let mut kkt = Kkt::new(pattern, ordering);
    for c in 0..order {
        let p = kkt.pattern();
        let slots = p.col_ptr()[c] as usize..p.col_ptr()[c + 1] as usize;
        let rows: Vec<usize> = p.row_idx()[slots.clone()]
            .iter()
            .map(|&r| r as usize)
            .collect();
        for (slot, r) in slots.zip(rows) {
            kkt.values_mut()[slot] = T::from_f64(k[r * order + c]);
        }
    }
    Some(kkt)
}

/// $\lVert K z - b\rVert_\infty / \lVert b\rVert_\infty$ in f64 against the dense row-major
/// `k` ($n \times n$), or the residual's norm alone when $b = 0$; NaN when any entry is
/// NaN.
#[must_use]
pub fn dense_residual<T: Real>(k: &[f64], z: &[T], b: &[f64]) -> f64 {
    let n = b.len();
    let residual = crate::nan_max((0..n).map(|r| {
        let kz: f64 = (0..n).map(|c| k[r * n + c] * z[c].to_f64()).sum();
        (b[r] - kz).abs()
    }));
    let b_norm = crate::nan_max(b.iter().map(|v| v.abs()));
    if b_norm == 0.0 {
        residual
    } else {
        residual / b_norm
    }
}
