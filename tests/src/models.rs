//! Small models for solver tests and benches: a DOG sheet (the shape of the book's active
//! page KKT) and a hanging chain with inextensible links.

use folio_kernels::dog::{DogBoundaryStar, DogInnerStar};
use folio_kernels::dog_laplacian::{DogLaplacianBoundary, DogLaplacianInner};
use folio_kernels::gravity::Gravity;
use folio_kernels::iso2d::Iso2d;
use folio_kernels::positional::Positional;
use folio_kernels::{Real, Vec3Ops, dog_laplacian};
use folio_solvers::{ConstraintSet, Model, PotentialSet, State, TermVisitor};

use crate::{GridStar, grid_stars};

/// Gravitational acceleration of the test models (page units per second squared).
pub const G: f64 = 9.81;

/// A DOG sheet of `quads_x x quads_y` quads with spacing `spacing`: DOG constraints on every
/// inner and 3-neighbour boundary star, DOG-Laplacian bending (weight 120), gravity on every
/// node, a positional pull (weight 400) on the node at the middle of the free edge, and the
/// left column clamped (all three coordinates eliminated). Total mass 1.
#[derive(Clone, Debug)]
pub struct DogSheet<T: Real> {
    /// Vertices per row.
    pub nx: usize,
    /// Vertex rows.
    pub ny: usize,
    /// Rest positions (flat, in the XZ plane... see [`DogSheet::new`]).
    pub rest: Vec<T::Vec3>,
    mass: T,
    inner: ConstraintSet<DogInnerStar<T>, 5>,
    boundary: ConstraintSet<DogBoundaryStar<T>, 4>,
    bend_inner: PotentialSet<T, DogLaplacianInner<T>, 5>,
    bend_boundary: PotentialSet<T, DogLaplacianBoundary<T>, 3>,
    gravity: PotentialSet<T, Gravity<T>, 1>,
    /// The pull on the free edge; its target may be moved between steps.
    pub pull: PotentialSet<T, Positional<T>, 1>,
}

impl<T: Real> DogSheet<T> {
    /// The sheet lying flat in the XZ plane (X across, Z along the clamped edge, Y up),
    /// vertex `(i, j)` at `(i s, 0, j s)` with index `i + nx j`.
    ///
    /// # Panics
    /// On zero quads or a non-positive spacing (test fixture).
    #[must_use]
    pub fn new(quads_x: usize, quads_y: usize, spacing: f64) -> Self {
        let (nx, ny) = (quads_x + 1, quads_y + 1);
        let rest: Vec<T::Vec3> = (0..nx * ny)
            .map(|k| {
                let (i, j) = ((k % nx) as f64, (k / nx) as f64);
                T::Vec3::new(T::from_f64(i * spacing), T::ZERO, T::from_f64(j * spacing))
            })
            .collect();
        let s = T::from_f64(spacing);
        let mass = T::ONE / T::from_f64((nx * ny) as f64);
        let mut sheet = Self {
            nx,
            ny,
            rest,
            mass,
            inner: ConstraintSet::new(),
            boundary: ConstraintSet::new(),
            bend_inner: PotentialSet::new(T::from_f64(120.0)),
            bend_boundary: PotentialSet::new(T::from_f64(120.0)),
            gravity: PotentialSet::new(T::ONE),
            pull: PotentialSet::new(T::from_f64(400.0)),
        };
        for star in grid_stars(nx, ny) {
            match star {
                GridStar::Inner(n) => {
                    let n = n.map(|k| k as u32);
                    sheet.inner.push(DogInnerStar::new(), n);
                    let lap = dog_laplacian::inner([s; 4]).expect("positive spacing");
                    sheet.bend_inner.push(lap, n);
                }
                GridStar::Boundary(n) => {
                    let n = n.map(|k| k as u32);
                    sheet.boundary.push(DogBoundaryStar::new(), n);
                    let lap = dog_laplacian::boundary([s; 2]).expect("positive spacing");
                    sheet.bend_boundary.push(lap, [n[0], n[1], n[3]]);
                }
            }
        }
        let g = T::from_f64(G);
        for k in 0..nx * ny {
            let weight = Gravity::new(g, mass).expect("finite");
            sheet.gravity.push(weight, [k as u32]);
        }
        let grabbed = sheet.grabbed_node();
        let target = sheet.rest[grabbed];
        sheet
            .pull
            .push(Positional::new(target).expect("finite"), [grabbed as u32]);
        sheet
    }

    /// The node the pull acts on: the middle of the free (right) edge.
    #[must_use]
    pub fn grabbed_node(&self) -> usize {
        self.nx - 1 + self.nx * (self.ny / 2)
    }

    /// Moves the pull's target.
    pub fn set_target(&mut self, target: T::Vec3) {
        for p in self.pull.kernels_mut() {
            p.target = target;
        }
    }

    /// The sheet rolled onto a cylinder of radius `radius` around the Z axis line
    /// `(0, radius, z)` starting at the clamped edge: an exact DOG (rulings along Z).
    #[must_use]
    pub fn rolled(&self, radius: f64) -> State<T> {
        let x = self
            .rest
            .iter()
            .map(|p| {
                let u = p.x().to_f64();
                T::Vec3::new(
                    T::from_f64(radius * (u / radius).sin()),
                    T::from_f64(radius * (1.0 - (u / radius).cos())),
                    p.z(),
                )
            })
            .collect();
        State::at_rest(x)
    }
}

impl<T: Real> Model<T> for DogSheet<T> {
    fn topology_version(&self) -> u64 {
        0
    }
    fn node_count(&self) -> usize {
        self.nx * self.ny
    }
    fn is_fixed(&self, node: usize, _axis: usize) -> bool {
        node % self.nx == 0
    }
    fn mass(&self, _node: usize) -> T {
        self.mass
    }
    fn visit_terms<V: TermVisitor<T>>(&self, v: &mut V) {
        v.potentials(&self.bend_inner);
        v.potentials(&self.bend_boundary);
        v.potentials(&self.gravity);
        v.potentials(&self.pull);
        v.constraints(&self.inner);
        v.constraints(&self.boundary);
    }
}

/// A chain of `links` inextensible links of length `length` between two pinned end nodes
/// (all their coordinates eliminated), node masses `mass`, gravity along −Y.
#[derive(Clone, Debug)]
pub struct Chain<T: Real> {
    /// Number of links.
    pub links: usize,
    /// Link length (page units).
    pub length: f64,
    /// Node mass.
    pub mass: f64,
    links_set: ConstraintSet<Iso2d<T>, 2>,
    gravity: PotentialSet<T, Gravity<T>, 1>,
    /// Bumped to test re-analysis.
    pub version: u64,
}

impl<T: Real> Chain<T> {
    /// The chain (see type docs).
    ///
    /// # Panics
    /// On a non-positive length or a negative mass (test fixture).
    #[must_use]
    pub fn new(links: usize, length: f64, mass: f64) -> Self {
        let mut links_set = ConstraintSet::new();
        for k in 0..links {
            let c = Iso2d::new(T::from_f64(length)).expect("positive length");
            links_set.push(c, [k as u32, k as u32 + 1]);
        }
        let mut gravity = PotentialSet::new(T::ONE);
        for k in 0..=links {
            let g = Gravity::new(T::from_f64(G), T::from_f64(mass)).expect("finite");
            gravity.push(g, [k as u32]);
        }
        Self {
            links,
            length,
            mass,
            links_set,
            gravity,
            version: 0,
        }
    }

    /// Adds a second copy of every link constraint (redundant rows: a singular KKT).
    pub fn duplicate_links(&mut self) {
        let copies: Vec<_> = self.links_set.terms().to_vec();
        for t in copies {
            self.links_set.push(t.kernel, t.nodes);
        }
        self.version += 1;
    }
}

impl<T: Real> Model<T> for Chain<T> {
    fn topology_version(&self) -> u64 {
        self.version
    }
    fn node_count(&self) -> usize {
        self.links + 1
    }
    fn is_fixed(&self, node: usize, _axis: usize) -> bool {
        node == 0 || node == self.links
    }
    fn mass(&self, _node: usize) -> T {
        T::from_f64(self.mass)
    }
    fn visit_terms<V: TermVisitor<T>>(&self, v: &mut V) {
        v.potentials(&self.gravity);
        v.constraints(&self.links_set);
    }
}

/// The static equilibrium of a chain of `links` equal links of length `length` and equal
/// node masses hanging between `(0, 0)` and `(span, 0)`, computed without the solver.
///
/// Joint balance gives link tension vectors $t_k = (H, V_0 + k m g)$ with $V_0 = -(n-1) m g / 2$
/// by symmetry; $H$ is found by bisection on $\sum_k L H / \lVert t_k\rVert = $ `span`.
/// Returns the node positions in the XY plane.
#[must_use]
pub fn hanging_chain(links: usize, length: f64, mass: f64, span: f64) -> Vec<[f64; 2]> {
    let w = mass * G;
    let v0 = -((links - 1) as f64) * w / 2.0;
    let reach = |h: f64| -> f64 {
        (0..links)
            .map(|k| length * h / h.hypot(v0 + k as f64 * w))
            .sum()
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    while reach(hi) < span {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if reach(mid) < span {
            lo = mid
        } else {
            hi = mid
        }
    }
    let h = 0.5 * (lo + hi);
    let mut p = [0.0, 0.0];
    let mut out = vec![p];
    for k in 0..links {
        let t = [h, v0 + k as f64 * w];
        let norm = t[0].hypot(t[1]);
        p = [p[0] + length * t[0] / norm, p[1] + length * t[1] / norm];
        out.push(p);
    }
    out
}
