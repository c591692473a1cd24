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
//! ([`Gravity`] with weight $w = m g$, the setting `particle_weight`).
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
use folio_kernels::{Real, Vec3Ops, math};

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
    springs: PotentialSet<T, Spring<T>, 2>,
    kinds: Vec<SpringKind>,
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
                SpringKind::Bend => settings.bend_stiffness,
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
        let mut gravity = PotentialSet::new(T::ONE);
        let mut damping = PotentialSet::new(-settings.damping / (T::TWO * settings.substep()));
        for (k, &p) in rest.iter().enumerate() {
            gravity.push(
                Gravity {
                    weight: settings.particle_weight,
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
            springs,
            kinds,
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

    /// Mass of every particle.
    #[must_use]
    pub fn particle_mass(&self) -> T {
        self.mass
    }

    /// Gravity force on every particle ($m g$, along −Y).
    #[must_use]
    pub fn particle_weight(&self) -> T {
        self.gravity
            .terms()
            .first()
            .map_or(T::ZERO, |t| t.kernel.weight)
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

    fn mass(&self, _node: usize) -> T {
        self.mass
    }

    fn visit_terms<V: TermVisitor<T>>(&self, visitor: &mut V) {
        visitor.potentials(&self.springs);
        visitor.potentials(&self.gravity);
        visitor.potentials(&self.damping);
    }
}

/// Zero vectors for `n` particles (setup helper).
pub(crate) fn zeros<T: Real>(n: usize) -> Vec<T::Vec3> {
    vec![T::Vec3::ZERO; n]
}
