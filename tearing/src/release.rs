//! The energy a tear releases, measured over a disk of fixed size around its tip: the
//! domain form of the $J$-integral (Rice 1968; the domain form: Moran and Shih, *Eng.
//! Fract. Mech.* 27, 1987), independent of the mesh.
//!
//! **Why.** The seed's force split (Sec. 5.1, [`crate::split`]) reads the tip's load from
//! the stretching forces of the triangles that touch it. Those are nodal forces: a stress
//! times an element size, so on a finer mesh they shrink and the tears stall, and their
//! directions follow the mesh's edges. Here the load is read from the stress of every
//! triangle within a disk of radius $R$ (sheet units) around the point, with a weight
//! falling linearly from the point to the disk's rim: the energy the tear releases, a
//! quantity of the continuum, which a finer mesh only resolves better. (On a mesh coarser
//! than $R$ the disk holds the point alone, and $J$ is its own configurational force.)
//!
//! **The configurational force.** Moving the point $p$ of the pattern by $\delta p$, with
//! the material around it dragged along by a weight $q$ (1 at $p$, 0 from $R$ on) and the
//! 3D positions held, changes the membrane energy by $-J \cdot \delta p$ with
//! $$J = -\int_{\Omega} \Sigma\thinspace\nabla q\thinspace dA -
//!   \int_{\Omega} q\thinspace F^T b\thinspace dA,\qquad \Sigma = W I - F^T P,$$
//! the Eshelby energy-momentum tensor of each triangle
//! ([`folio_kernels::membrane::Membrane::eshelby`]) and $b$ whatever else acts on the
//! membrane within the disk (bending, inertia, gravity, a finger): the domain form of the
//! $J$-integral with body forces. On the mesh, with $q$ linear on each triangle from its
//! corner values $q_i = \max(0, 1 - |X_i - p|/R)$, $\Sigma_k$ constant on triangle $k$, and
//! $r_i$ the membranes' net force on vertex $i$ (at rest, minus the other forces on it),
//! $$J = -\sum_k \Sigma_k\thinspace A_k \nabla q_k - \sum_i q_i\thinspace \bar F_i^T r_i,$$
//! $\bar F_i$ the area-weighted mean deformation gradient of the triangles round $i$. The
//! first sum is $-\sum_i q_i\thinspace\partial V / \partial u_i$, the energy's derivative with
//! respect to the pattern; the second makes the derivative a material one (the vertex moves
//! with the sheet), which at rest in a sheet with nothing but membranes is zero.
//!
//! **Which boundary.** The weights follow the boundary through $p$ (the tear's lips, or the
//! border a new tear would start from) for as long as it stays within $R$; every other
//! stretch of boundary the disk reaches (the far border a tear is about to meet, another
//! tear) gets $q = 0$, which puts the domain's edge between them: the disk measures the
//! tear at $p$, not the configurational force of a border nearby ([`cone_weights`]).
//!
//! **What it gives.** At a tear tip $J$ is Rice's $J$-integral as a vector: for an opening
//! crack it points straight ahead and equals $K_I^2 / Y$, whatever $R$ (path independence).
//! At a border point of a sheet stretched along the border it points into the sheet with
//! $|J| = W R$, the energy density times the disk's radius: Griffith's $\pi \sigma^2 a / Y$
//! for a flaw of size $a \sim R$, so $R$ is the paper's flaw size, a material length.
//! Checked in `tests/tests/tear_release.rs`: on a notched sheet drawn apart, $J$ is within
//! 0.3 % of the energy the sheet releases when the notch is cut one cell longer (32 and 48
//! quads across), the same for $R$ from 0.75 to 1.25 within 0.2 %, and 1.424e-7, 1.464e-7,
//! 1.483e-7 at 32, 48 and 64 quads across.
//!
//! **Release rate and direction.** The tear runs along $t = J / |J|$, the direction in
//! which moving the tip releases the most energy, and releases
//! $$E_r = |J| / e$$
//! per unit of new crack area ($e$ the thickness): energy per area, the units of the seed's
//! eq. 6 and of the fracture energy $E_f$ (eq. 3) it is compared with. For O'Keefe's set-up
//! (two tension lines meeting at the tip, paper that barely stretches) the energy released
//! by a step $\delta$ along $t$ is $\delta\thinspace(T_a \hat a + T_b \hat b) \cdot t$, with
//! $\hat a$, $\hat b$ the unit directions from the pulling points to the tip: for equal
//! tensions $J$ is their bisector, the direction the seed's split gives (eq. 4-6). The split
//! is the same reading taken on the tip's own triangles: their nodal forces, which scale with
//! the cell size. For a slightly mixed mode, $J$'s direction is $-2K_{II}/K_I$ off the
//! crack's line, the kink of the maximum hoop stress to first order; for a strongly mixed
//! mode it turns less than a real tear would, and its component across the crack also
//! counts the lips. So at a slit (a tear's tip, a notch) the tearing step takes the
//! direction from the mode mixity read over the same disk ([`crate::mixity`]) and the
//! release rate from $J$'s component along the crack; $t = J/|J|$ serves where no crack is
//! yet (a border).
//!
//! **Needs a membrane-only in-plane response.** The paper's quadratic hinge (Bergou et al.)
//! also resists in-plane deformation that is not affine; at a tip that stiffness grows on
//! every finer mesh and $J$ with it falls (1.00e-7, 0.80e-7, 0.45e-7 at 16, 32 and 64 quads
//! across, where the membrane alone gives 1.26e-7, 1.42e-7, 1.48e-7). Use
//! `HingeBending::Folds` with this estimator.

use alloc::vec::Vec;

use folio_geometry::SheetMesh;
use folio_solvers::room::Room;

use folio_kernels::{Real, Vec3Ops, math};

/// What the physics says of each triangle of the sheet, indexed like its triangles.
#[derive(Clone, Copy, Debug)]
pub struct TriangleLoads<'a, T: Real> {
    /// $\partial V_k / \partial x$ of triangle `k`'s stretching energy at its corners
    /// (force units, 3D).
    pub gradients: &'a [[T::Vec3; 3]],
    /// Triangle `k`'s Eshelby tensor $[\Sigma_{uu}, \Sigma_{uv}, \Sigma_{vv}]$.
    pub eshelby: &'a [[T; 3]],
    /// Triangle `k`'s deformation gradient, its columns $F e_u$, $F e_v$
    /// ([`folio_kernels::membrane::Membrane::deformation_gradient`]).
    pub deformations: &'a [[T::Vec3; 2]],
    /// Triangle `k`'s second Piola–Kirchhoff stress $[S_{uu}, S_{uv}, S_{vv}]$ (force per
    /// sheet unit; [`folio_kernels::membrane::Membrane::stress`], so under the membrane's
    /// law).
    pub stresses: &'a [[T; 3]],
    /// Per vertex, `true` where the motion is prescribed (a finger's pad): its net force
    /// is a reaction, not a load, and the disk leaves it out (empty: none).
    pub prescribed: &'a [bool],
    /// The membranes' 2D Young's modulus $Y$ (force per sheet unit).
    pub stretch_modulus: f64,
    /// The membranes' Poisson's ratio $\nu$.
    pub poisson: f64,
}

/// The buffers a [`TriangleLoads`] views, filled by the physics (for the sheet:
/// `SheetModel::triangle_loads`) and kept from frame to frame.
#[derive(Clone, Debug)]
pub struct LoadBuffers<T: Real> {
    /// See [`TriangleLoads::gradients`].
    pub gradients: Vec<[T::Vec3; 3]>,
    /// See [`TriangleLoads::eshelby`].
    pub eshelby: Vec<[T; 3]>,
    /// See [`TriangleLoads::deformations`].
    pub deformations: Vec<[T::Vec3; 2]>,
    /// See [`TriangleLoads::stresses`].
    pub stresses: Vec<[T; 3]>,
    /// See [`TriangleLoads::prescribed`].
    pub prescribed: Vec<bool>,
}

impl<T: Real> LoadBuffers<T> {
    /// Room for a mesh of `triangles` triangles and `vertices` vertices.
    pub fn reserve(&mut self, triangles: usize, vertices: usize) {
        self.gradients.room_for(triangles);
        self.eshelby.room_for(triangles);
        self.deformations.room_for(triangles);
        self.stresses.room_for(triangles);
        self.prescribed.room_for(vertices);
    }
}

impl<T: Real> Default for LoadBuffers<T> {
    fn default() -> Self {
        Self {
            gradients: Vec::new(),
            eshelby: Vec::new(),
            deformations: Vec::new(),
            stresses: Vec::new(),
            prescribed: Vec::new(),
        }
    }
}

impl<T: Real> LoadBuffers<T> {
    /// The view of the buffers for membranes of 2D Young's modulus `stretch_modulus` and
    /// Poisson's ratio `poisson`.
    #[must_use]
    pub fn loads(&self, stretch_modulus: f64, poisson: f64) -> TriangleLoads<'_, T> {
        TriangleLoads {
            gradients: &self.gradients,
            eshelby: &self.eshelby,
            deformations: &self.deformations,
            stresses: &self.stresses,
            prescribed: &self.prescribed,
            stretch_modulus,
            poisson,
        }
    }
}

/// The cone's value $\max(0, 1 - |x - p| / R)$ at pattern point `x`.
fn cone(x: [f64; 2], p: [f64; 2], radius: f64) -> f64 {
    let d = [x[0] - p[0], x[1] - p[1]];
    (1.0 - math::sqrt(d[0] * d[0] + d[1] * d[1]) / radius).max(0.0)
}

/// The pattern point of vertex `v` in f64.
fn pattern_at<T: Real>(mesh: &SheetMesh<T>, v: u32) -> [f64; 2] {
    let c = mesh.pattern()[v as usize];
    [c[0].to_f64(), c[1].to_f64()]
}

/// The weights $q_i$ of every vertex for the point `v` (module docs) into `q`: the cone,
/// except on stretches of the boundary other than the one through `v`, and on the vertices
/// `prescribed` (a finger's pad, whose net force is the finger's reaction). A border or a
/// tear that merely passes within $R$ is not the tear being measured, nor is a grip; the
/// cone is cut to zero there, which puts the domain's edge between them.
pub fn cone_weights<T: Real>(
    mesh: &SheetMesh<T>,
    v: u32,
    radius: f64,
    prescribed: &[bool],
    q: &mut Vec<f64>,
) {
    let p = pattern_at(mesh, v);
    q.clear();
    q.extend((0..mesh.vertex_count() as u32).map(|i| {
        if mesh.is_boundary(i) {
            0.0
        } else {
            cone(pattern_at(mesh, i), p, radius)
        }
    }));
    q[v as usize] = 1.0;
    // On the boundary, walk it both ways from v while within the disk.
    let walks: &[bool] = if mesh.is_boundary(v) {
        &[true, false]
    } else {
        &[]
    };
    for &forward in walks {
        let mut at = v;
        while let Some((next, previous)) = mesh.boundary_neighbours(at) {
            let step = if forward { next } else { previous };
            let w = cone(pattern_at(mesh, step), p, radius);
            if w == 0.0 || q[step as usize] > 0.0 {
                break;
            }
            q[step as usize] = w;
            at = step;
        }
    }
    for (w, &fixed) in q.iter_mut().zip(prescribed) {
        if fixed {
            *w = 0.0;
        }
    }
}

/// The configurational force at vertex `v` over a disk of radius `radius` (sheet units),
/// with the weights `q` of [`cone_weights`] (module docs): force units, energy per length
/// of crack front. Triangles past the end of a short slice of `loads` count as unstressed.
#[must_use]
pub fn configurational_force<T: Real>(
    mesh: &SheetMesh<T>,
    loads: &TriangleLoads<'_, T>,
    q: &[f64],
) -> [f64; 2] {
    let mut j = [0.0; 2];
    let weight = |i: u32| q.get(i as usize).copied().unwrap_or(0.0);
    // The Eshelby part, -sum_k Sigma_k A_k grad q_k.
    for (k, tri) in mesh.triangles().iter().enumerate() {
        let Some(sigma) = loads.eshelby.get(k) else {
            continue;
        };
        let g = area_gradient(&tri.map(|i| pattern_at(mesh, i)), tri.map(weight));
        let s = sigma.map(T::to_f64);
        j[0] -= s[0] * g[0] + s[1] * g[1];
        j[1] -= s[1] * g[0] + s[2] * g[1];
    }
    // The body forces, -sum_i q_i Fbar_i^T r_i.
    for v in 0..mesh.vertex_count() as u32 {
        let qv = weight(v);
        if qv == 0.0 {
            continue;
        }
        let (mut residual, mut f, mut area) = (T::Vec3::ZERO, [T::Vec3::ZERO; 2], T::ZERO);
        for h in mesh.fan_iter(v) {
            let k = h as usize / 3;
            let (Some(g), Some(fk)) = (loads.gradients.get(k), loads.deformations.get(k)) else {
                continue;
            };
            residual += g[h as usize % 3];
            let a = mesh.pattern_area(k);
            f = [f[0] + fk[0] * a, f[1] + fk[1] * a];
            area += a;
        }
        if area > T::ZERO {
            j[0] -= qv * (f[0].dot(residual) / area).to_f64();
            j[1] -= qv * (f[1].dot(residual) / area).to_f64();
        }
    }
    j
}

/// $\int_k \nabla q\thinspace dA = A_k \nabla q_k$ over the counter-clockwise triangle
/// `corners`, $q$ linear between the corner values `q`:
/// $A \nabla N_0 = \tfrac12 (v_1 - v_2,\ u_2 - u_1)$, and cyclically.
#[must_use]
pub fn area_gradient(corners: &[[f64; 2]; 3], q: [f64; 3]) -> [f64; 2] {
    let mut g = [0.0; 2];
    for i in 0..3 {
        if q[i] == 0.0 {
            continue;
        }
        let (b, c) = (corners[(i + 1) % 3], corners[(i + 2) % 3]);
        g[0] += 0.5 * q[i] * (b[1] - c[1]);
        g[1] += 0.5 * q[i] * (c[0] - b[0]);
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// $A \nabla q$ on the unit right triangle, by hand: corner values $q_0, q_1, q_2$ give
    /// $\nabla q = (q_1 - q_0, q_2 - q_0)$ and $A = 1/2$.
    #[test]
    fn the_gradient_integral_is_the_area_times_the_interpolated_gradient() {
        let corners = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let q = [0.3, 0.9, 0.1];
        let g = area_gradient(&corners, q);
        assert!((g[0] - 0.5 * (q[1] - q[0])).abs() < 1e-15);
        assert!((g[1] - 0.5 * (q[2] - q[0])).abs() < 1e-15);
    }

    /// A uniform field in equilibrium (no nodal forces): nothing in the interior, where
    /// $\int \nabla q = 0$; at a border stretched along itself, $|J| = W R$ into the sheet
    /// (module docs), exact where the cone's kinks fall on vertices; at a corner the other
    /// border is cut out of the domain.
    #[test]
    fn a_uniform_field_gives_nothing_inside_and_w_r_at_a_border() {
        for (nx, ny) in [(12, 8), (24, 16)] {
            let mesh = SheetMesh::<f64>::rectangle(12.0, 8.0, nx, ny).unwrap();
            // Stretched along u by a uniaxial stress s: Sigma = W I - S with W = s^2/2Y.
            let (s, y) = (0.01, 1.0);
            let w = s * s / (2.0 * y);
            let sigma = vec![[w - s, 0.0, w]; mesh.triangle_count()];
            let gradients = vec![[DVec3::ZERO; 3]; mesh.triangle_count()];
            let deformations = vec![[DVec3::X, DVec3::Y]; mesh.triangle_count()];
            let loads = TriangleLoads {
                gradients: &gradients,
                eshelby: &sigma,
                deformations: &deformations,
                stresses: &[],
                prescribed: &[],
                stretch_modulus: y,
                poisson: 0.0,
            };
            let vertex = |x: f64, y: f64| {
                mesh.pattern()
                    .iter()
                    .position(|p| (p[0] - x).abs() < 1e-12 && (p[1] - y).abs() < 1e-12)
                    .unwrap() as u32
            };
            let mut q = Vec::new();
            cone_weights(&mesh, vertex(6.0, 4.0), 2.0, &[], &mut q);
            let inside = configurational_force(&mesh, &loads, &q);
            assert!(
                inside[0].abs() < 1e-15 && inside[1].abs() < 1e-15,
                "{inside:?}"
            );
            cone_weights(&mesh, vertex(5.0, 0.0), 2.0, &[], &mut q);
            let border = configurational_force(&mesh, &loads, &q);
            assert!(border[0].abs() < 1e-15, "{border:?}");
            assert!((border[1] - w * 2.0).abs() < 1e-12 * w, "{border:?}");
        }
    }

    /// The walk along the boundary from the point: round a corner within the disk, but not
    /// across the sheet to another stretch of border that the disk reaches; a held vertex
    /// is left out.
    #[test]
    fn the_weights_follow_the_point_s_own_boundary() {
        let mesh = SheetMesh::<f64>::rectangle(12.0, 2.0, 12, 2).unwrap();
        let vertex = |x: f64, y: f64| {
            mesh.pattern()
                .iter()
                .position(|p| (p[0] - x).abs() < 1e-12 && (p[1] - y).abs() < 1e-12)
                .unwrap()
        };
        let mut q = Vec::new();
        cone_weights(&mesh, vertex(5.0, 0.0) as u32, 3.0, &[], &mut q);
        assert_eq!(
            q[vertex(5.0, 2.0)],
            0.0,
            "the top border is another stretch"
        );
        assert!((q[vertex(4.0, 0.0)] - 2.0 / 3.0).abs() < 1e-12);
        assert!(
            (q[vertex(5.0, 1.0)] - 2.0 / 3.0).abs() < 1e-12,
            "interior: the cone"
        );
        cone_weights(&mesh, vertex(1.0, 0.0) as u32, 3.0, &[], &mut q);
        assert!(q[vertex(0.0, 1.0)] > 0.0, "round the corner");
        let mut prescribed = vec![false; mesh.vertex_count()];
        prescribed[vertex(2.0, 1.0)] = true;
        cone_weights(&mesh, vertex(1.0, 0.0) as u32, 3.0, &prescribed, &mut q);
        assert_eq!(q[vertex(2.0, 1.0)], 0.0, "a held vertex is out of the disk");
        assert!(q[vertex(1.0, 1.0)] > 0.0);
    }
}
