//! Provot springs of the mass-spring page (seed `003_…` Sec. 2.1, after Provot 1995):
//! stretch (grid neighbours), shear (cell diagonals) and bend (two apart) springs, each a
//! Hooke spring between particles `[x_i, x_j]` with rest length $L^0$ and stiffness $k$.
//! With $d = x_i - x_j$, $\ell = \lVert d\rVert$, $\hat d = d/\ell$:
//! $$V = \tfrac12 k (\ell - L^0)^2,\quad F_i = -\nabla_{x_i} V = -k(\ell - L^0)\thinspace\hat d,\quad F_j = -F_i,$$
//! $$\frac{\partial F_i}{\partial x_i} = -\nabla^2_{x_i x_i} V
//!   = -k\left[\left(1 - \frac{L^0}{\ell}\right)(I - \hat d\hat d^T) + \hat d\hat d^T\right].$$
//! Damping: the seed's per-particle viscous force $F = c\thinspace v$ with a signed coefficient
//! ($c = -0.7125$ in its experiment), [`particle_damping`], and the spring's axial damping
//! $F_i = -k_d\thinspace((v_i - v_j)\cdot\hat d)\thinspace\hat d$, [`Spring::damping_force`].
//! Units: $k$ in force/length, lengths in page units, $c$ and $k_d$ in force·time/length.
//!
//! Degenerate spring ($\ell$ below [`Real::LENGTH_FLOOR`]): the direction is undefined;
//! the fallback is zero force, zero damping force and Hessian $kI$.

use crate::error::{KernelError, finite};
use crate::math;
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, pair_blocks};

/// The three Provot spring families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpringKind {
    /// Between grid neighbours: rest length = spacing.
    Stretch,
    /// Across a cell diagonal: rest length = $\sqrt 2$ spacing.
    Shear,
    /// Between particles two apart along a grid line: rest length = 2 spacing.
    Bend,
}

impl SpringKind {
    /// Rest length of this kind on a square particle grid with the given spacing.
    #[must_use]
    pub fn rest_length<T: Real>(self, spacing: T) -> T {
        match self {
            Self::Stretch => spacing,
            Self::Shear => spacing * math::sqrt(T::TWO),
            Self::Bend => spacing * T::TWO,
        }
    }
}

/// A Hooke spring between two particles (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring<T> {
    /// $L^0$, page units.
    pub rest_length: T,
    /// $k$, force per length.
    pub stiffness: T,
}

/// Spring geometry: $(\hat d, \ell)$, or `None` when degenerate.
fn direction<T: Real>(x: &NodeVecs<T, 2>) -> Option<(T::Vec3, T)> {
    let d = x[0] - x[1];
    let len = math::length::<T>(d);
    if len < T::LENGTH_FLOOR {
        None
    } else {
        Some((d / len, len))
    }
}

impl<T: Real> Spring<T> {
    /// From the rest length ($\ge 0$) and stiffness ($\ge 0$), both finite.
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] or [`KernelError::OutOfRange`] for negative values.
    pub fn new(rest_length: T, stiffness: T) -> Result<Self, KernelError> {
        let l = finite(rest_length, "rest_length")?;
        let k = finite(stiffness, "stiffness")?;
        if l < T::ZERO {
            return Err(KernelError::OutOfRange {
                name: "rest_length",
            });
        }
        if k < T::ZERO {
            return Err(KernelError::OutOfRange { name: "stiffness" });
        }
        Ok(Self {
            rest_length: l,
            stiffness: k,
        })
    }

    /// Spring forces `[F_i, F_j]` $= -\nabla V$.
    #[must_use]
    pub fn force(&self, x: &NodeVecs<T, 2>) -> NodeVecs<T, 2> {
        self.gradient(x).map(|g| -g)
    }

    /// Force Jacobian $\partial F / \partial x = -\nabla^2 V$.
    #[must_use]
    pub fn force_jacobian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        let h = self.hessian(x)[0][0];
        pair_blocks::<T>(-h)
    }

    /// Axial damping forces `[F_i, F_j]`, $F_i = -k_d((v_i - v_j)\cdot\hat d)\hat d$, for
    /// velocities `v` and damping coefficient `k_d` ($\ge 0$ damps).
    #[must_use]
    pub fn damping_force(&self, x: &NodeVecs<T, 2>, v: &NodeVecs<T, 2>, k_d: T) -> NodeVecs<T, 2> {
        match direction::<T>(x) {
            None => [T::Vec3::ZERO; 2],
            Some((dh, _)) => {
                let f = dh * (-k_d * (v[0] - v[1]).dot(dh));
                [f, -f]
            }
        }
    }

    /// Jacobian of [`Spring::damping_force`] with respect to the velocities:
    /// $\partial F_i/\partial v_i = -k_d\thinspace\hat d\hat d^T$ (zero when degenerate).
    #[must_use]
    pub fn damping_jacobian(&self, x: &NodeVecs<T, 2>, k_d: T) -> Blocks<T, 2> {
        let h = match direction::<T>(x) {
            None => T::Mat3::ZERO,
            Some((dh, _)) => T::Mat3::outer(dh, dh) * -k_d,
        };
        pair_blocks::<T>(h)
    }
}

/// The seed's per-particle damping force $F = c\thinspace v$ (seed `003_…` Sec. 3.1; $c = -0.7125$
/// there, a negative coefficient opposing the motion).
#[inline]
#[must_use]
pub fn particle_damping<T: Real>(velocity: T::Vec3, c: T) -> T::Vec3 {
    velocity * c
}

impl<T: Real> Potential<T, 2> for Spring<T> {
    fn value(&self, x: &NodeVecs<T, 2>) -> T {
        let s = math::length::<T>(x[0] - x[1]) - self.rest_length;
        T::HALF * self.stiffness * s * s
    }
    fn gradient(&self, x: &NodeVecs<T, 2>) -> NodeVecs<T, 2> {
        match direction::<T>(x) {
            None => [T::Vec3::ZERO; 2],
            Some((dh, len)) => {
                let g = dh * (self.stiffness * (len - self.rest_length));
                [g, -g]
            }
        }
    }
    fn hessian(&self, x: &NodeVecs<T, 2>) -> Blocks<T, 2> {
        let k = self.stiffness;
        let h = match direction::<T>(x) {
            None => T::Mat3::IDENTITY * k,
            Some((dh, len)) => {
                let dd = T::Mat3::outer(dh, dh);
                ((T::Mat3::IDENTITY - dd) * (T::ONE - self.rest_length / len) + dd) * k
            }
        };
        pair_blocks::<T>(h)
    }
}
