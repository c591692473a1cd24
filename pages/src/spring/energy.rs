//! The mechanical energy of the particle system (seed `003_…` Sec. 2.1):
//! $$E = \underbrace{\tfrac12 m\sum_k \lVert v_k\rVert^2}\_{\text{kinetic}} +
//!   \underbrace{\sum_s \tfrac12 k_s(\lVert x_a - x_b\rVert - L^0_s)^2}\_{\text{springs}} +
//!   \underbrace{w\sum_k y_k}\_{\text{gravity}},$$
//! gravity measured from the plane $y = 0$ of the flat page. With damping $c < 0$ and no
//! input the exact dynamics lose energy at the rate $\dot E = c\sum_k\lVert v_k\rVert^2$.
//! Units: mass·length²/s².

use folio_kernels::{Real, Vec3Ops};

use super::network::SpringNetwork;

/// The three parts of $E$ (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpringEnergy<T> {
    /// $\tfrac12 m \sum_k \lVert v_k\rVert^2$.
    pub kinetic: T,
    /// $\sum_s \tfrac12 k_s(\ell_s - L^0_s)^2$.
    pub spring: T,
    /// $w \sum_k y_k$.
    pub gravity: T,
}

impl<T: Real> SpringEnergy<T> {
    /// The energy of positions `x` and velocities `v` of `network`'s particles.
    #[must_use]
    pub fn of(network: &SpringNetwork<T>, x: &[T::Vec3], v: &[T::Vec3]) -> Self {
        let mut kinetic = T::ZERO;
        let mut height = T::ZERO;
        for vk in v {
            kinetic += vk.dot(*vk);
        }
        for xk in x {
            height += xk.y();
        }
        Self {
            kinetic: T::HALF * network.particle_mass() * kinetic,
            spring: network.spring_energy(x),
            gravity: network.particle_weight() * height,
        }
    }

    /// $E$, the sum of the parts.
    #[must_use]
    pub fn total(&self) -> T {
        self.kinetic + self.spring + self.gravity
    }
}
