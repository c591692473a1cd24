//! The mechanical energy of the particle system (seed `003_…` Sec. 2.1):
//! $$E = \underbrace{\tfrac12 m\sum_k \lVert v_k\rVert^2}\_{\text{kinetic}} +
//!   \underbrace{\sum_s \tfrac12 k_s(\lVert x_a - x_b\rVert - L^0_s)^2}\_{\text{springs}} +
//!   V_{\mathrm{bend}} + \underbrace{\sum_k w_k y_k}\_{\text{gravity}},$$
//! with the particle masses $m_k$ and weights $w_k$ of [`SpringNetwork::mass_of`] and
//! [`SpringNetwork::weight_of`] and the plate bending $V_{\mathrm{bend}}$ of
//! [`super::bending`] (0 when $D = 0$; counted in `spring`),
//! gravity measured from the plane $y = 0$ of the flat page. With damping $c < 0$ and no
//! input the exact dynamics lose energy at the rate $\dot E = c\sum_k\lVert v_k\rVert^2$.
//! Units: mass·length²/s².

use folio_kernels::{Real, Vec3Ops};

use super::network::SpringNetwork;

/// The three parts of $E$ (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpringEnergy<T> {
    /// $\tfrac12 \sum_k m_k \lVert v_k\rVert^2$.
    pub kinetic: T,
    /// $\sum_s \tfrac12 k_s(\ell_s - L^0_s)^2 + V_{\mathrm{bend}}$.
    pub spring: T,
    /// $\sum_k w_k y_k$.
    pub gravity: T,
}

impl<T: Real> SpringEnergy<T> {
    /// The energy of positions `x` and velocities `v` of `network`'s particles.
    #[must_use]
    pub fn of(network: &SpringNetwork<T>, x: &[T::Vec3], v: &[T::Vec3]) -> Self {
        let mut kinetic = T::ZERO;
        let mut gravity = T::ZERO;
        for (k, vk) in v.iter().enumerate() {
            kinetic += network.mass_of(k) * vk.dot(*vk);
        }
        for (k, xk) in x.iter().enumerate() {
            gravity += network.weight_of(k) * xk.y();
        }
        Self {
            kinetic: T::HALF * kinetic,
            spring: network.spring_energy(x) + network.plate_energy(x),
            gravity,
        }
    }

    /// $E$, the sum of the parts.
    #[must_use]
    pub fn total(&self) -> T {
        self.kinetic + self.spring + self.gravity
    }
}
