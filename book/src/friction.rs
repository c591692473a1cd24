//! Coulomb friction in the contact planes of the active page, off by default. Seed `000_…`
//! Sec. 3.4 leaves friction out ("negligible compared to the bending force"). Earlier notes
//! blamed its absence for released pages that never settled; the cause was elsewhere: a
//! page node at rest in the gap that two block walls leave at a convex kink of a thick block,
//! or before the start of its first wall, rocked in and out of a wall's span every other
//! frame ([`folio_geometry::Corner`] closes those gaps). Measured with
//! `cargo run --release -p folio-tests --example settle_probe -- sweep MU` (the shared page
//! turn on books of 3 to 1000 pages, 0.001 to 0.05 thick, 30 books): before the corners, 4
//! books never merged (100 x 0.01, 400 x 0.0075, 400 x 0.01, 1000 x 0.001); with them all
//! 30 merge, on average 102 frames after the release (at most 166) without friction, and
//! 112 (at most 414) with $\mu = 0.3$: friction holds a page in the bent shape it lands in,
//! so it does not help a page settle, and the default stays the seed's frictionless contact.
//!
//! **The law** (Bridson, Fedkiw and Anderson, *Robust treatment of collisions, contact and
//! friction for cloth animation*, SIGGRAPH 2002: the friction they apply with their
//! inelastic repulsion impulses): a contact that changes a node's normal velocity by
//! $\Delta v_N \ge 0$ changes its tangential velocity $v_T$ (the part of $v$ in the contact
//! plane, the obstacle taken at rest) to
//! $$v_T' = \max\Bigl(0,\ 1 - \mu\thinspace\frac{\Delta v_N}{\lVert v_T\rVert}\Bigr)\thinspace v_T,$$
//! kinetic friction $\mu\thinspace\Delta v_N$ per unit mass, and static friction when that
//! exceeds $\lVert v_T\rVert$. Two impulses act on a page node in one frame:
//! - a collision push of depth $d$ out of a block: $\Delta v_N = d/h$;
//! - the contact spring that held the node during the step (stiffness $k = s\thinspace m$,
//!   [`crate::BookSettings::contact_stiffness`]), pressed by the gap $g > 0$ it ends the step
//!   with: force $k g$ over the step, $\Delta v_N = h s g$ (per unit mass, so the node's
//!   mass drops out). A node resting on a block ends a step with $g \approx g_\perp / s$,
//!   $g_\perp$ the normal part of gravity, and gets $\Delta v_N = h g_\perp$: the weight's
//!   impulse, as Coulomb's law asks.
//!
//! Velocities are in page units per second, $h$ in seconds, $\mu$ dimensionless
//! ([`crate::BookSettings::contact_friction`]; 0 switches friction off).

use folio_kernels::{Real, Vec3Ops, math};

use super::simulation::Book;

/// Velocity `v` after Coulomb friction with coefficient `mu` at a contact of unit `normal`
/// that changed the normal velocity by `impulse` $= \Delta v_N$ (module docs):
/// $v_N + \max(0, 1 - \mu \Delta v_N / \lVert v_T\rVert)\thinspace v_T$. Unchanged for a
/// non-positive or non-finite `impulse` or `mu`, and for no tangential motion.
#[inline]
#[must_use]
pub fn coulomb<T: Real>(v: T::Vec3, normal: T::Vec3, impulse: T, mu: T) -> T::Vec3 {
    let cut = mu * impulse;
    if !(cut.is_finite() && cut > T::ZERO) {
        return v;
    }
    let vn = normal * v.dot(normal);
    let vt = v - vn;
    let speed = math::length::<T>(vt);
    if speed <= T::ZERO || !speed.is_finite() {
        return v;
    }
    let keep = T::ONE - cut / speed;
    if keep > T::ZERO { vn + vt * keep } else { vn }
}

impl<T: Real> Book<T> {
    /// Friction of a contact that changed page node `node`'s normal velocity by `impulse`
    /// against a plane of unit normal `normal` (module docs); block and cover nodes slide
    /// freely, as before.
    pub(crate) fn rub(&mut self, node: usize, normal: T::Vec3, impulse: T) {
        if node < self.terms.nodes.page_offset() {
            return;
        }
        let mu = self.settings.contact_friction;
        self.state.v[node] = coulomb::<T>(self.state.v[node], normal, impulse, mu);
    }

    /// Friction of the contact springs of the step just taken, before they are cleared
    /// (module docs): each page node held by a spring whose gap $g$ ends the step positive
    /// gets $\Delta v_N = h s g$.
    pub(crate) fn spring_friction(&mut self) {
        let s = self.settings;
        if s.contact_friction <= T::ZERO {
            return;
        }
        let h = s.solver.time_step;
        let n = self.terms.nodes;
        for node in n.page_offset()..n.total() {
            let Some(plane) = self.terms.page_contact(node) else {
                continue;
            };
            let gap = plane.gap(self.state.x[node]);
            if gap > T::ZERO {
                self.rub(node, plane.normal, h * s.contact_stiffness * gap);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::coulomb;

    type V = <f64 as folio_kernels::Real>::Vec3;

    #[test]
    fn friction_cuts_the_tangential_speed_and_stops_a_slow_node() {
        let up = V::new(0.0, 1.0, 0.0);
        let v = V::new(2.0, -1.0, 0.5);
        // Kinetic: |v_T| = sqrt(4.25), cut by mu dv_N = 0.5; the normal part is kept.
        let out = coulomb::<f64>(v, up, 1.0, 0.5);
        let vt = (2.0_f64 * 2.0 + 0.25).sqrt();
        let keep = 1.0 - 0.5 / vt;
        assert!((out - V::new(2.0 * keep, -1.0, 0.5 * keep)).length() < 1e-12);
        // Static: the cut exceeds the tangential speed.
        assert!((coulomb::<f64>(v, up, 10.0, 0.5) - V::new(0.0, -1.0, 0.0)).length() < 1e-12);
        // No friction, no impulse, a NaN impulse: unchanged.
        for (impulse, mu) in [(1.0, 0.0), (0.0, 0.5), (f64::NAN, 0.5), (-1.0, 0.5)] {
            assert_eq!(coulomb::<f64>(v, up, impulse, mu), v);
        }
    }
}
