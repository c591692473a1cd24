//! The particle grid and its Provot springs (seed `003_…` Sec. 2.1, Fig. 2), as a
//! [`Model`] the implicit solver can step.
//!
//! Particle $(i, j)$, index $k = i + n_x j$ ([`QuadGrid`]), rests at
//! $\bar x_k = (u_i, 0, v_j)$ with $u_i = W\thinspace i/(n_x - 1)$, $v_j = H\thinspace j/(n_z - 1)$ (the page
//! frame of [`crate`]). Springs ([`Spring`], $V = \tfrac12 k(\lVert x_a - x_b\rVert - L^0)^2$):
//! - stretch between $(i, j)$–$(i{+}1, j)$ and $(i, j)$–$(i, j{+}1)$,
//! - shear across both diagonals of every cell,
//! - bend between $(i, j)$–$(i{+}2, j)$ and $(i, j)$–$(i, j{+}2)$,
//!
//! each with the rest length of its pair, $L^0 = \lVert \bar x_a - \bar x_b\rVert$, which on a
//! square grid is [`SpringKind::rest_length`] of the spacing. Gravity $V = w\thinspace y$ per particle
//! ([`Gravity`] with weight $w = m g$, the setting `particle_weight`, times the particle's
//! area share with [`SpringSettings::area_masses`], [`super::bending::mass_share`]; so is
//! its mass). With [`SpringSettings::bending_stiffness`] $D > 0$, the plate bending term of
//! [`super::bending`]: [`SquaredStencil`]s of the second differences along the grid lines
//! and of the cells' twists, family weight $D/2$.
//!
//! **Implicit damping.** The seed's particle damping $F = c\thinspace v$ is not a potential, but over an
//! implicit-Euler step of $h$ (the substep, [`SpringSettings::substep`]) with
//! $v^{n+1} = (x - x^n)/h$ it is the force of
//! $V_c = -\frac{c}{2h}\lVert x - x^n\rVert^2$, $-\nabla V_c = \frac{c}{h}(x - x^n) = c\thinspace v^{n+1}$:
//! a [`Positional`] pull towards $x^n$ with family weight $-c/(2h) \ge 0$, re-targeted every
//! frame ([`SpringNetwork::set_damping_targets`]).
//!
//! **Roles.** A particle is free, fixed (the spine column with `fixed_spine`) or gripped (moved
//! by the finger). Fixed and gripped particles are eliminated from the implicit solve
//! ([`Model::is_fixed`] on all three axes); a change of roles bumps the topology version.

use alloc::vec;
use alloc::vec::Vec;
use folio_geometry::QuadGrid;
use folio_kernels::gravity::Gravity;
use folio_kernels::positional::Positional;
use folio_kernels::spring::{Spring, SpringKind};
use folio_kernels::stencil::SquaredStencil;
use folio_kernels::{Real, Vec3Ops, math};

use super::bending::{PlateStencil, SpineClamp, mass_share, plate_stencils, spine_clamps};
use super::settings::SpringSettings;
use folio_solvers::model::{Model, PotentialSet, TermVisitor};

/// What moves a particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Advanced by the integrator.
    Free,
    /// Held at rest (the spine column).
    Fixed,
    /// Moved kinematically by the finger.
    Gripped,
}

/// The particles' rest positions, roles and terms (module docs).
#[derive(Clone, Debug)]
pub struct SpringNetwork<T: Real> {
    grid: QuadGrid,
    rest: Vec<T::Vec3>,
    roles: Vec<Role>,
    mass: T,
    /// Each particle's mass over `mass` ([`super::bending::mass_share`]).
    shares: Vec<T>,
    springs: PotentialSet<T, Spring<T>, 2>,
    kinds: Vec<SpringKind>,
    plate_second: PotentialSet<T, SquaredStencil<T, 3>, 3>,
    plate_twist: PotentialSet<T, SquaredStencil<T, 4>, 4>,
    plate_clamp: PotentialSet<T, SpineClamp<T>, 1>,
    gravity: PotentialSet<T, Gravity<T>, 1>,
    damping: PotentialSet<T, Positional<T>, 1>,
    version: u64,
}

/// The rest position of particle `(i, j)`: $(W i/(n_x-1), 0, H j/(n_z-1))$, computed exactly
/// as [`crate::material_point`] computes a render node, so that a render node on a
/// particle has the particle's material coordinates bit for bit.
#[must_use]
pub fn rest_position<T: Real>(grid: QuadGrid, size: [T; 2], i: usize, j: usize) -> T::Vec3 {
    let p = crate::material_point(grid, size, grid.index(i, j));
    T::Vec3::new(p[0], T::ZERO, p[1])
}

impl<T: Real> SpringNetwork<T> {
    /// The network of validated `settings` (module docs): every particle at rest, the spine
    /// column fixed if asked, no particle gripped.
    #[must_use]
    pub fn new(settings: &SpringSettings<T>) -> Self {
        let (nx, nz) = (settings.particles_across, settings.particles_along);
        let grid = QuadGrid { nx, nz };
        let size = [settings.width, settings.height];
        let rest: Vec<T::Vec3> = (0..grid.len())
            .map(|k| {
                let (i, j) = grid.coords(k);
                rest_position::<T>(grid, size, i, j)
            })
            .collect();
        let roles = (0..grid.len())
            .map(|k| {
                if settings.fixed_spine && k % nx == 0 {
                    Role::Fixed
                } else {
                    Role::Free
                }
            })
            .collect();
        let mut springs = PotentialSet::new(T::ONE);
        let mut kinds = Vec::new();
        let mut add = |a: usize, b: usize, kind: SpringKind| {
            let k = match kind {
                SpringKind::Stretch => settings.stretch_stiffness,
                SpringKind::Shear => settings.shear_stiffness,
                SpringKind::Bend => settings.bend_spring_stiffness,
            };
            let spring = Spring {
                rest_length: math::length::<T>(rest[a] - rest[b]),
                stiffness: k,
            };
            springs.push(spring, [a as u32, b as u32]);
            kinds.push(kind);
        };
        for j in 0..nz {
            for i in 0..nx {
                let k = grid.index(i, j);
                if i + 1 < nx {
                    add(k, grid.index(i + 1, j), SpringKind::Stretch);
                }
                if j + 1 < nz {
                    add(k, grid.index(i, j + 1), SpringKind::Stretch);
                }
                if i + 1 < nx && j + 1 < nz {
                    add(k, grid.index(i + 1, j + 1), SpringKind::Shear);
                    add(
                        grid.index(i + 1, j),
                        grid.index(i, j + 1),
                        SpringKind::Shear,
                    );
                }
                if i + 2 < nx {
                    add(k, grid.index(i + 2, j), SpringKind::Bend);
                }
                if j + 2 < nz {
                    add(k, grid.index(i, j + 2), SpringKind::Bend);
                }
            }
        }
        // The one place where D becomes solver weights (module docs of `super::bending`):
        // family weight D/2, stencil weights the differences' coefficients times the square
        // root of their area weight.
        let d = settings.bending_stiffness;
        let mut plate_second = PotentialSet::new(d * T::HALF);
        let mut plate_twist = PotentialSet::new(d * T::HALF);
        if d > T::ZERO {
            let spacing = settings.spacing().map(|h| h.to_f64());
            plate_stencils(grid, spacing, |stencil| match stencil {
                PlateStencil::Second {
                    nodes,
                    coefficients,
                    area,
                } => push_stencil(&mut plate_second, nodes, coefficients, area),
                PlateStencil::Twist {
                    nodes,
                    coefficients,
                    area,
                } => push_stencil(&mut plate_twist, nodes, coefficients, area),
            });
        }
        let mut plate_clamp = PotentialSet::new(d * T::HALF);
        if d > T::ZERO {
            spine_clamps(&settings.flat_page(), |spine, k, w| {
                plate_clamp.push(
                    SpineClamp {
                        spine: rest[spine],
                        weight: T::from_f64(w),
                    },
                    [k as u32],
                );
            });
        }
        let shares: Vec<T> = (0..grid.len())
            .map(|k| T::from_f64(mass_share(grid, k, settings.area_masses)))
            .collect();
        let mut gravity = PotentialSet::new(T::ONE);
        let mut damping = PotentialSet::new(-settings.damping / (T::TWO * settings.substep()));
        for (k, (&p, &share)) in rest.iter().zip(&shares).enumerate() {
            gravity.push(
                Gravity {
                    weight: settings.particle_weight * share,
                },
                [k as u32],
            );
            damping.push(Positional { target: p }, [k as u32]);
        }
        Self {
            grid,
            rest,
            roles,
            mass: settings.particle_mass,
            shares,
            springs,
            kinds,
            plate_second,
            plate_twist,
            plate_clamp,
            gravity,
            damping,
            version: 0,
        }
    }

    /// The particle grid.
    #[must_use]
    pub fn grid(&self) -> QuadGrid {
        self.grid
    }

    /// Rest positions, one per particle.
    #[must_use]
    pub fn rest(&self) -> &[T::Vec3] {
        &self.rest
    }

    /// Roles, one per particle.
    #[must_use]
    pub fn roles(&self) -> &[Role] {
        &self.roles
    }

    /// The springs with their particle pairs.
    #[must_use]
    pub fn springs(&self) -> &PotentialSet<T, Spring<T>, 2> {
        &self.springs
    }

    /// The family of each spring, in the order of [`SpringNetwork::springs`].
    #[must_use]
    pub fn kinds(&self) -> &[SpringKind] {
        &self.kinds
    }

    /// Mass of an inner particle, the setting `particle_mass` (of every particle without
    /// [`SpringSettings::area_masses`]).
    #[must_use]
    pub fn particle_mass(&self) -> T {
        self.mass
    }

    /// Mass of particle `k` (0 out of range): `particle_mass` times its area share.
    #[must_use]
    pub fn mass_of(&self, k: usize) -> T {
        self.shares.get(k).map_or(T::ZERO, |&s| s * self.mass)
    }

    /// Gravity force on particle `k` ($m_k g$, along −Y; 0 out of range).
    #[must_use]
    pub fn weight_of(&self, k: usize) -> T {
        self.gravity
            .terms()
            .get(k)
            .map_or(T::ZERO, |t| t.kernel.weight)
    }

    /// Gravity force on an inner particle ($m g$, along −Y): the setting `particle_weight`.
    #[must_use]
    pub fn particle_weight(&self) -> T {
        let share = self.shares.first().copied().unwrap_or(T::ONE);
        if share > T::ZERO {
            self.weight_of(0) / share
        } else {
            T::ZERO
        }
    }

    /// The plate bending term's second differences ([`super::bending`]); empty when
    /// $D = 0$.
    #[must_use]
    pub fn plate_second(&self) -> &PotentialSet<T, SquaredStencil<T, 3>, 3> {
        &self.plate_second
    }

    /// The plate bending term's cell twists ([`super::bending`]); empty when $D = 0$.
    #[must_use]
    pub fn plate_twist(&self) -> &PotentialSet<T, SquaredStencil<T, 4>, 4> {
        &self.plate_twist
    }

    /// The clamp's terms ([`super::bending::SpineClamp`]); empty unless the spine is
    /// clamped and $D > 0$.
    #[must_use]
    pub fn plate_clamp(&self) -> &PotentialSet<T, SpineClamp<T>, 1> {
        &self.plate_clamp
    }

    /// The plate bending energy $V_{\mathrm{bend}}$ (with the clamp's terms) at `x`
    /// ([`super::bending`]).
    #[must_use]
    pub fn plate_energy(&self, x: &[T::Vec3]) -> T {
        fn family<T: Real, const N: usize>(
            set: &PotentialSet<T, SquaredStencil<T, N>, N>,
            x: &[T::Vec3],
        ) -> T {
            use folio_kernels::Potential;
            let mut e = T::ZERO;
            for t in set.terms() {
                let mut p = [T::Vec3::ZERO; N];
                for (pa, &n) in p.iter_mut().zip(&t.nodes) {
                    *pa = x.get(n as usize).copied().unwrap_or(T::Vec3::ZERO);
                }
                e += t.kernel.value(&p);
            }
            e * set.weight
        }
        use folio_kernels::Potential;
        let mut clamp = T::ZERO;
        for t in self.plate_clamp.terms() {
            if let Some(&p) = x.get(t.nodes[0] as usize) {
                clamp += t.kernel.value(&[p]);
            }
        }
        family(&self.plate_second, x)
            + family(&self.plate_twist, x)
            + clamp * self.plate_clamp.weight
    }

    /// Adds the plate bending forces $-\nabla V_{\mathrm{bend}}$ at `x` to `forces` (one per
    /// particle; no allocation).
    pub fn add_plate_forces(&self, x: &[T::Vec3], forces: &mut [T::Vec3]) {
        fn family<T: Real, const N: usize>(
            set: &PotentialSet<T, SquaredStencil<T, N>, N>,
            x: &[T::Vec3],
            forces: &mut [T::Vec3],
        ) {
            use folio_kernels::Potential;
            for t in set.terms() {
                let mut p = [T::Vec3::ZERO; N];
                for (pa, &n) in p.iter_mut().zip(&t.nodes) {
                    *pa = x.get(n as usize).copied().unwrap_or(T::Vec3::ZERO);
                }
                let g = t.kernel.gradient(&p);
                for (&n, ga) in t.nodes.iter().zip(g) {
                    if let Some(f) = forces.get_mut(n as usize) {
                        *f -= ga * set.weight;
                    }
                }
            }
        }
        family(&self.plate_second, x, forces);
        family(&self.plate_twist, x, forces);
        use folio_kernels::Potential;
        for t in self.plate_clamp.terms() {
            let k = t.nodes[0] as usize;
            if let (Some(&p), Some(f)) = (x.get(k), forces.get_mut(k)) {
                *f -= t.kernel.gradient(&[p])[0] * self.plate_clamp.weight;
            }
        }
    }

    /// Sets the role of particle `k` (ignored out of range), bumping the topology version
    /// when it changes.
    pub fn set_role(&mut self, k: usize, role: Role) {
        if let Some(r) = self.roles.get_mut(k) {
            if *r != role {
                *r = role;
                self.version += 1;
            }
        }
    }

    /// Points the implicit damping pulls ([`Positional`], module docs) at the positions `x`
    /// of the start of the frame.
    pub fn set_damping_targets(&mut self, x: &[T::Vec3]) {
        for (p, &target) in self.damping.kernels_mut().zip(x) {
            p.target = target;
        }
    }

    /// $\sum_s V_s$: the springs' potential energy at positions `x`.
    #[must_use]
    pub fn spring_energy(&self, x: &[T::Vec3]) -> T {
        use folio_kernels::Potential;
        let mut e = T::ZERO;
        for t in self.springs.terms() {
            if let (Some(&a), Some(&b)) = (x.get(t.nodes[0] as usize), x.get(t.nodes[1] as usize)) {
                e += t.kernel.value(&[a, b]);
            }
        }
        e
    }
}

impl<T: Real> Model<T> for SpringNetwork<T> {
    fn topology_version(&self) -> u64 {
        self.version
    }

    fn node_count(&self) -> usize {
        self.rest.len()
    }

    fn is_fixed(&self, node: usize, _axis: usize) -> bool {
        self.roles.get(node).is_none_or(|r| *r != Role::Free)
    }

    fn mass(&self, node: usize) -> T {
        self.mass_of(node)
    }

    fn visit_terms<V: TermVisitor<T>>(&self, visitor: &mut V) {
        visitor.potentials(&self.springs);
        if !self.plate_second.terms().is_empty() {
            visitor.potentials(&self.plate_second);
        }
        if !self.plate_twist.terms().is_empty() {
            visitor.potentials(&self.plate_twist);
        }
        if !self.plate_clamp.terms().is_empty() {
            visitor.potentials(&self.plate_clamp);
        }
        visitor.potentials(&self.gravity);
        visitor.potentials(&self.damping);
    }
}

/// Adds the plate stencil $a\lVert\sum_k c_k x_k\rVert^2$ on `nodes` to `set` as a
/// [`SquaredStencil`] of weights $c_k\sqrt a$ (setup helper; module docs of
/// [`super::bending`]).
fn push_stencil<T: Real, const N: usize>(
    set: &mut PotentialSet<T, SquaredStencil<T, N>, N>,
    nodes: [usize; N],
    coefficients: [f64; N],
    area: f64,
) {
    let root = math::sqrt::<f64>(area);
    set.push(
        SquaredStencil {
            weights: coefficients.map(|c| T::from_f64(c * root)),
        },
        nodes.map(|n| n as u32),
    );
}

/// Zero vectors for `n` particles (setup helper).
pub(crate) fn zeros<T: Real>(n: usize) -> Vec<T::Vec3> {
    vec![T::Vec3::ZERO; n]
}
