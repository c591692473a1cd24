//! Which way a tear turns: the mode mixity $K_{II}/K_I$ at a tip, read over the disk of
//! [`crate::release`] with the interaction integral, and the kink of the maximum hoop
//! stress it implies.
//!
//! **Why not $J$'s direction.** $J = (J_1, J_2)$ in the crack's frame is
//! $\bigl(K_I^2 + K_{II}^2,\ -2K_I K_{II}\bigr)/Y$: its direction turns by
//! $-2K_{II}/K_I$ for a slight mixity, as the maximum hoop stress does, but by at most 45°
//! for any mixity where a real tear kinks up to 70.5°. And $J_2$ also counts the lips: on
//! a tear loaded in mixed mode the energy density differs on its two lips, and the domain
//! integral adds $\int q\thinspace(W^+ - W^-)\thinspace dx_1$ along them, which grows with
//! the mesh's resolution of the lips near the tip.
//!
//! **The interaction integral** (Yau, Wang and Corten 1980; the domain form: Moran and
//! Shih 1987). For the actual field $(\sigma, u)$ and an auxiliary one
//! $(\sigma^a, u^a)$, Williams' field of a pure mode with $K^a = 1$ at the same tip, in the
//! crack's frame ($x_1$ ahead, $x_2$ to its left), with the weights $q$ of
//! [`crate::release::cone_weights`],
//! $$I = \int_\Omega \bigl(\sigma_{ij}\thinspace u^a_{i,1} + \sigma^a_{ij}\thinspace u_{i,1} -
//!   \sigma_{ik}\thinspace\varepsilon^a_{ik}\thinspace\delta_{1j}\bigr)\thinspace q_{,j}\thinspace dA
//!   = \frac{2}{Y} K_m$$
//! for the mode $m$ of the auxiliary field (plane stress, $Y$ the 2D Young's modulus).
//! Straight lips are free of traction in both fields and have $n_1 = 0$, so they add
//! nothing: the ratio $I_{II}/I_I = K_{II}/K_I$ is read from the disk's stresses alone. On
//! the mesh $\sigma$ is each triangle's second Piola–Kirchhoff stress $S$ (the sheet barely
//! stretches: $S$ is the Cauchy stress to first order), $u_{,j} = R^T F - I$ with $R$ the
//! rotation of the disk's mean deformation gradient (the sheet near a tip is flat but may
//! be turned in space), and the auxiliary field is taken at each triangle's centroid.
//!
//! **The kink** (Erdogan and Sih 1963): the tear runs where the hoop stress ahead of the tip
//! is largest, at
//! $$\theta_c = 2 \arctan \frac{1 - \sqrt{1 + 8\rho^2}}{4\rho},\qquad \rho = K_{II}/K_I,$$
//! from the crack's line ($\theta_c = 0$ for $\rho = 0$; $\mp 70.5°$ for pure mode II).

use folio_geometry::SheetMesh;
use folio_kernels::{Real, Vec3Ops, math};

use crate::release::{TriangleLoads, area_gradient};

/// A $2 \times 2$ matrix, rows first.
type Mat2 = [[f64; 2]; 2];

/// Williams' displacement at local point `x` for $K_I = 1$ (`mode_two` false) or
/// $K_{II} = 1$, in plane stress with shear modulus `mu` and $\kappa = (3 - \nu)/(1 + \nu)$
/// (Anderson, *Fracture Mechanics*, Table 2.2).
fn williams_displacement(x: [f64; 2], mode_two: bool, mu: f64, kappa: f64) -> [f64; 2] {
    let r = math::sqrt(x[0] * x[0] + x[1] * x[1]);
    let theta = math::atan2(x[1], x[0]);
    let (s, c) = (math::sin(0.5 * theta), math::cos(0.5 * theta));
    let scale = math::sqrt(r / (2.0 * core::f64::consts::PI)) / (2.0 * mu);
    if mode_two {
        [
            scale * s * (kappa + 1.0 + 2.0 * c * c),
            -scale * c * (kappa - 1.0 - 2.0 * s * s),
        ]
    } else {
        [
            scale * c * (kappa - 1.0 + 2.0 * s * s),
            scale * s * (kappa + 1.0 - 2.0 * c * c),
        ]
    }
}

/// Williams' stress at local point `x` for a unit $K$ of the mode (same reference).
fn williams_stress(x: [f64; 2], mode_two: bool) -> Mat2 {
    let r = math::sqrt(x[0] * x[0] + x[1] * x[1]);
    let theta = math::atan2(x[1], x[0]);
    let (s, c) = (math::sin(0.5 * theta), math::cos(0.5 * theta));
    let (s3, c3) = (math::sin(1.5 * theta), math::cos(1.5 * theta));
    let k = 1.0 / math::sqrt(2.0 * core::f64::consts::PI * r);
    let (xx, yy, xy) = if mode_two {
        (-s * (2.0 + c * c3), s * c * c3, c * (1.0 - s * s3))
    } else {
        (c * (1.0 - s * s3), c * (1.0 + s * s3), c * s * c3)
    };
    [[k * xx, k * xy], [k * xy, k * yy]]
}

/// $\partial u^a_i / \partial x_j$ of Williams' displacement at `x`, by central differences
/// over a step of $10^{-6}|x|$ (the field is smooth off the crack's line, where no
/// centroid lies).
fn williams_gradient(x: [f64; 2], mode_two: bool, mu: f64, kappa: f64) -> Mat2 {
    let step = 1e-6 * math::sqrt(x[0] * x[0] + x[1] * x[1]);
    let mut g = [[0.0; 2]; 2];
    for j in 0..2 {
        let (mut a, mut b) = (x, x);
        a[j] += step;
        b[j] -= step;
        let (ua, ub) = (
            williams_displacement(a, mode_two, mu, kappa),
            williams_displacement(b, mode_two, mu, kappa),
        );
        for i in 0..2 {
            g[i][j] = (ua[i] - ub[i]) / (2.0 * step);
        }
    }
    g
}

/// $Q^T A Q$ for the frame $Q = [d, d^\perp]$ (columns): pattern components into the
/// crack's.
fn to_local(a: Mat2, d: [f64; 2]) -> Mat2 {
    let q = [[d[0], -d[1]], [d[1], d[0]]];
    let mut out = [[0.0; 2]; 2];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..2)
                .flat_map(|k| (0..2).map(move |l| (k, l)))
                .map(|(k, l)| q[k][i] * a[k][l] * q[l][j])
                .sum();
        }
    }
    out
}

/// The rotation part $R = \bar F (\bar F^T \bar F)^{-1/2}$ ($3 \times 2$, orthonormal
/// columns) of the mean deformation gradient `f`, or `None` when it is degenerate. For a
/// $2 \times 2$ SPD $C$, $\sqrt{C} = (C + \sqrt{\det C}\thinspace I)/\sqrt{\operatorname{tr} C + 2\sqrt{\det C}}$.
fn rotation<T: Real>(f: [T::Vec3; 2]) -> Option<[T::Vec3; 2]> {
    let c = [
        f[0].dot(f[0]).to_f64(),
        f[0].dot(f[1]).to_f64(),
        f[1].dot(f[1]).to_f64(),
    ];
    let det = c[0] * c[2] - c[1] * c[1];
    if !(det > 0.0 && det.is_finite()) {
        return None;
    }
    let sd = math::sqrt(det);
    let norm = math::sqrt(c[0] + c[2] + 2.0 * sd);
    // U = sqrt(C), then U^{-1} = adj(U) / det(U), det(U) = sqrt(det C).
    let u = [(c[0] + sd) / norm, c[1] / norm, (c[2] + sd) / norm];
    let inv = [u[2] / sd, -u[1] / sd, u[0] / sd];
    let t = |x: f64| T::from_f64(x);
    Some([
        f[0] * t(inv[0]) + f[1] * t(inv[1]),
        f[0] * t(inv[1]) + f[1] * t(inv[2]),
    ])
}

/// $\rho = K_{II}/K_I$ at pattern point `tip` for a crack running along the unit pattern
/// direction `d`, over the weights `q` of [`crate::release::cone_weights`] (module docs);
/// `None` when the disk holds no opening ($I_I \le 0$) or a value is not finite.
#[must_use]
pub fn mode_mixity<T: Real>(
    mesh: &SheetMesh<T>,
    loads: &TriangleLoads<'_, T>,
    tip: [f64; 2],
    d: [f64; 2],
    q: &[f64],
) -> Option<f64> {
    let (y, nu) = (loads.stretch_modulus, loads.poisson);
    let mu = y / (2.0 * (1.0 + nu));
    let kappa = (3.0 - nu) / (1.0 + nu);
    let weight = |i: u32| q.get(i as usize).copied().unwrap_or(0.0);
    let corners = |tri: &[u32; 3]| {
        tri.map(|i| {
            let p = mesh.pattern()[i as usize];
            [p[0].to_f64(), p[1].to_f64()]
        })
    };
    // The disk's mean deformation gradient, weighted by q and area.
    let mut mean = [T::Vec3::ZERO; 2];
    for (k, tri) in mesh.triangles().iter().enumerate() {
        let Some(f) = loads.deformations.get(k) else {
            continue;
        };
        let w = tri.map(weight);
        let a = mesh.pattern_area(k) * T::from_f64((w[0] + w[1] + w[2]) / 3.0);
        mean = [mean[0] + f[0] * a, mean[1] + f[1] * a];
    }
    let r = rotation::<T>(mean)?;
    let mut integral = [0.0; 2];
    for (k, tri) in mesh.triangles().iter().enumerate() {
        let (Some(f), Some(s)) = (loads.deformations.get(k), loads.stresses.get(k)) else {
            continue;
        };
        let pts = corners(tri);
        let g = area_gradient(&pts, tri.map(weight));
        if g == [0.0; 2] {
            continue;
        }
        // The actual field: u_{i,j} = (R^T F - I)_{ij} and the membrane's S.
        let h = [
            [r[0].dot(f[0]).to_f64() - 1.0, r[0].dot(f[1]).to_f64()],
            [r[1].dot(f[0]).to_f64(), r[1].dot(f[1]).to_f64() - 1.0],
        ];
        let s = s.map(|v| v.to_f64());
        let s = [[s[0], s[1]], [s[1], s[2]]];
        let (s, h) = (to_local(s, d), to_local(h, d));
        let g = [g[0] * d[0] + g[1] * d[1], -g[0] * d[1] + g[1] * d[0]];
        let c = [
            (pts[0][0] + pts[1][0] + pts[2][0]) / 3.0 - tip[0],
            (pts[0][1] + pts[1][1] + pts[2][1]) / 3.0 - tip[1],
        ];
        let x = [c[0] * d[0] + c[1] * d[1], -c[0] * d[1] + c[1] * d[0]];
        for (mode, total) in integral.iter_mut().enumerate() {
            let two = mode == 1;
            let (sa, ga) = (
                williams_stress(x, two),
                williams_gradient(x, two, mu, kappa),
            );
            let work: f64 = (0..2)
                .flat_map(|i| (0..2).map(move |k| (i, k)))
                .map(|(i, k)| s[i][k] * 0.5 * (ga[i][k] + ga[k][i]))
                .sum();
            for j in 0..2 {
                let mut term = (0..2)
                    .map(|i| s[i][j] * ga[i][0] + sa[i][j] * h[i][0])
                    .sum::<f64>();
                if j == 0 {
                    term -= work;
                }
                *total += term * g[j];
            }
        }
    }
    let rho = integral[1] / integral[0];
    (integral[0] > 0.0 && rho.is_finite()).then_some(rho)
}

/// The kink $\theta_c$ of the maximum hoop stress for $\rho = K_{II}/K_I$ (module docs),
/// radians from the crack's line toward its left.
#[must_use]
pub fn kink_angle(rho: f64) -> f64 {
    if rho == 0.0 || !rho.is_finite() {
        return 0.0;
    }
    2.0 * math::atan2((1.0 - math::sqrt(1.0 + 8.0 * rho * rho)) / (4.0 * rho), 1.0)
}
