//! A contact held implicitly: one node kept at clearance $c$ on the allowed side of a plane
//! through $a$ with unit normal $n$ (seed `000_…` Sec. 3.4 resolves contacts by projecting
//! after the step; a contact found in one step is this spring in the next, so that the
//! step itself carries the contact force and the projection afterwards has almost nothing
//! left to move):
//! $$g = c - n\cdot(x - a),\quad V = \tfrac12 k g^2,\quad \nabla V = -k g\thinspace n,\quad
//!   \nabla^2 V = k\thinspace n n^\top.$$
//! Two-sided for the one step it is on: a node that moves away leaves the contact set at
//! the next detection. It is one more term of the potential $V$ of seed `000_…` eq. 9.
//! Units: $k$ in force per length, $V$ in energy.

use crate::error::KernelError;
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential};

/// Quadratic spring of one node towards the plane at clearance `clearance` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPlane<T: Real> {
    /// $a$, a point of the plane (page units).
    pub point: T::Vec3,
    /// $n$, unit normal towards the allowed side.
    pub normal: T::Vec3,
    /// $c$, the required distance from the plane (page units).
    pub clearance: T,
    /// $k$, the spring's stiffness (force per page unit).
    pub stiffness: T,
}

impl<T: Real> ContactPlane<T> {
    /// From a point, a normal (normalized here), the clearance and the stiffness.
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] for a non-finite input;
    /// [`KernelError::OutOfRange`] for a normal too short to normalize or a negative
    /// stiffness.
    pub fn new(
        point: T::Vec3,
        normal: T::Vec3,
        clearance: T,
        stiffness: T,
    ) -> Result<Self, KernelError> {
        if !crate::real::vec_is_finite::<T>(point) {
            return Err(KernelError::NonFiniteParameter { name: "point" });
        }
        if !clearance.is_finite() {
            return Err(KernelError::NonFiniteParameter { name: "clearance" });
        }
        if !stiffness.is_finite() {
            return Err(KernelError::NonFiniteParameter { name: "stiffness" });
        }
        if stiffness < T::ZERO {
            return Err(KernelError::OutOfRange { name: "stiffness" });
        }
        if !crate::real::vec_is_finite::<T>(normal) {
            return Err(KernelError::NonFiniteParameter { name: "normal" });
        }
        let length = crate::math::length::<T>(normal);
        if !(length.is_finite() && length > T::LENGTH_FLOOR) {
            return Err(KernelError::OutOfRange { name: "normal" });
        }
        Ok(Self {
            point,
            normal: normal / length,
            clearance,
            stiffness,
        })
    }

    /// $g$: how far the node is inside the clearance band (negative when clear).
    #[must_use]
    pub fn gap(&self, x: T::Vec3) -> T {
        self.clearance - self.normal.dot(x - self.point)
    }
}

impl<T: Real> Potential<T, 1> for ContactPlane<T> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, 1>) -> T {
        let g = self.gap(x[0]);
        T::HALF * self.stiffness * g * g
    }
    fn gradient(&self, x: &NodeVecs<T, 1>) -> NodeVecs<T, 1> {
        [self.normal * -(self.stiffness * self.gap(x[0]))]
    }
    fn hessian(&self, _x: &NodeVecs<T, 1>) -> Blocks<T, 1> {
        [[T::Mat3::outer(self.normal, self.normal) * self.stiffness]]
    }
}
