//! The seed's semi-implicit (symplectic) Euler step of the free particles (seed `003_…`
//! Sec. 2.1 and Sec. 3.1 steps 3-5):
//! $$F_k = \sum_{s \ni k} F_s(x^n) - \nabla_k V_{\mathrm{bend}}(x^n) + c\thinspace v_k^n -
//!   w_k\thinspace\hat y,\qquad
//!   v_k^{n+1} = v_k^n + \frac{h}{m_k} F_k,\qquad x_k^{n+1} = x_k^n + h\thinspace v_k^{n+1},$$
//! with the spring forces $F_s$ of [`folio_kernels::spring::Spring::force`], the plate
//! bending of [`super::bending`] (none when $D = 0$), the particle damping $c\thinspace v$ of
//! [`particle_damping`] and the weight $w_k = m_k g$ along −Y ($m_k$ the particle's mass,
//! [`SpringNetwork::mass_of`]). Fixed and gripped particles are not advanced (the caller
//! has placed them); their positions enter the spring forces. $h$ is one substep, the frame's step over
//! [`super::SpringSettings::substeps`]. Stable while $h\thinspace\omega_{max} < 2$ (see
//! [`super::Integrator::SemiImplicitEuler`]).

use folio_kernels::spring::particle_damping;
use folio_kernels::{Real, Vec3Ops};

use super::network::{Role, SpringNetwork};

/// Advances the free particles of `x`, `v` by one step `h` with damping coefficient
/// `damping` $= c$ (module docs), using `forces` (one per particle) as scratch. Slices of
/// unequal length are cut to the shortest.
pub fn semi_implicit_euler<T: Real>(
    x: &mut [T::Vec3],
    v: &mut [T::Vec3],
    network: &SpringNetwork<T>,
    damping: T,
    h: T,
    forces: &mut [T::Vec3],
) {
    for (k, (f, &vk)) in forces.iter_mut().zip(v.iter()).enumerate() {
        let weight = T::Vec3::new(T::ZERO, -network.weight_of(k), T::ZERO);
        *f = weight + particle_damping::<T>(vk, damping);
    }
    network.add_plate_forces(x, forces);
    for t in network.springs().terms() {
        let (a, b) = (t.nodes[0] as usize, t.nodes[1] as usize);
        let (Some(&xa), Some(&xb)) = (x.get(a), x.get(b)) else {
            continue;
        };
        let f = t.kernel.force(&[xa, xb]);
        if let Some(fa) = forces.get_mut(a) {
            *fa += f[0];
        }
        if let Some(fb) = forces.get_mut(b) {
            *fb += f[1];
        }
    }
    for (k, (((xk, vk), &f), role)) in x
        .iter_mut()
        .zip(v.iter_mut())
        .zip(forces.iter())
        .zip(network.roles())
        .enumerate()
    {
        if *role == Role::Free {
            *vk += f * (h / network.mass_of(k));
            *xk += *vk * h;
        }
    }
}
