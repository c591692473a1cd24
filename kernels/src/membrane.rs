//! In-plane stretching of one triangle of a tearing sheet: the Saint Venant–Kirchhoff
//! membrane energy behind the stretching forces of the FEM layer (seed `002_…` Sec. 5.1,
//! "the in-plane stretching forces … related to the deformation of the triangles").
//!
//! Nodes `[x0, x1, x2]` (3D positions) with rest coordinates `[u0, u1, u2]` in the flat 2D
//! pattern, counter-clockwise. With $B = D_m^{-1}$:
//! $$D_m = [u_1 - u_0,\ u_2 - u_0] \in \mathbb{R}^{2\times 2},\qquad
//!   F = [x_1 - x_0,\ x_2 - x_0]\thinspace D_m^{-1} = [f_0\ f_1] \in \mathbb{R}^{3\times 2},$$
//! $$E = \tfrac12\left(F^T F - I\right),\qquad
//!   V = A_0\left(\mu \lVert E\rVert_F^2 + \tfrac{\lambda}{2}(\operatorname{tr} E)^2\right),$$
//! $A_0 = \tfrac12 \det D_m$ the rest area, and the plane-stress Lamé parameters of the 2D
//! Young's modulus $Y$ (force per length: Young's modulus times thickness) and Poisson's
//! ratio $\nu$: $\mu = Y / (2(1+\nu))$, $\lambda = Y\nu / (1-\nu^2)$. (Then a uniaxial
//! strain $E = \operatorname{diag}(\epsilon, -\nu\epsilon)$ has stress
//! $S = \operatorname{diag}(Y\epsilon, 0)$.)
//!
//! Derivatives. The columns of $F$ are linear in the nodes, $f_j = \sum_i w_{ij} x_i$ with
//! $w_{0j} = -(B_{0j} + B_{1j})$, $w_{1j} = B_{0j}$, $w_{2j} = B_{1j}$. With the second
//! Piola–Kirchhoff stress $S = 2\mu E + \lambda \operatorname{tr}(E)\thinspace I$ ($2\times 2$) and
//! $P = F S = [p_0\ p_1]$:
//! $$\nabla_{x_i} V = A_0 \sum_j w_{ij}\thinspace p_j,\qquad
//!   \nabla^2_{x_a x_b} V = A_0 \sum_{j,k} w_{aj} w_{bk}\thinspace C_{jk},$$
//! $$C_{jk} = \frac{\partial p_j}{\partial f_k}
//!   = S_{jk} I_3 + \mu\thinspace f_k f_j^T + \lambda\thinspace f_j f_k^T +
//!   \mu\thinspace \delta_{jk}\left(f_0 f_0^T + f_1 f_1^T\right).$$
//! The part without $S_{jk} I_3$ (material stiffness) is positive semi-definite: its quadratic
//! form in a variation $\delta F$ is $2\mu\lVert \delta E\rVert_F^2 + \lambda (\operatorname{tr}
//! \delta E)^2$ with $\delta E = \operatorname{sym}(F^T \delta F)$. The geometric stiffness
//! $S \otimes I_3$ is indefinite when a principal stress is negative (compression);
//! [`Membrane::hessian_projected`] replaces $S$ there by its positive part
//! $S^+ = \sum_k \max(\sigma_k, 0)\thinspace v_k v_k^T$ and so is positive semi-definite, and equal to
//! the exact Hessian whenever $S \succeq 0$.
//!
//! Tension field (wrinkling). Paper a tenth of a millimetre thick buckles under a
//! compressive stress orders of magnitude below its tensile stiffness, into wrinkles far
//! finer than a sheet's triangles. [`MembraneLaw::TensionField`] replaces $W$ by its
//! relaxation (Pipkin 1986, "The relaxed energy density for isotropic elastic membranes",
//! *IMA J. Appl. Math.* 36; Steigmann 1990, *Proc. R. Soc. Lond. A* 429): with the principal
//! Green strains $e_1 \ge e_2$ of $E$, $E n = e_1 n$, and $Y = 4\mu(\mu+\lambda)/(2\mu+\lambda)$,
//! $\nu = \lambda/(2\mu+\lambda)$ recovered from the Lamé parameters,
//! $$W = \begin{cases}
//!   \mu\lVert E\rVert_F^2 + \tfrac{\lambda}{2}(\operatorname{tr}E)^2 & \text{taut: } e_2 \ge -\nu e_1,\ e_1 > 0\\
//!   \tfrac{Y}{2} e_1^2,\quad S = Y e_1\thinspace n n^T & \text{wrinkled: } e_2 < -\nu e_1,\ e_1 > 0\\
//!   0,\quad S = 0 & \text{slack: } e_1 \le 0.
//! \end{cases}$$
//! The wrinkled state is the taut energy minimised over the lateral strain (a uniaxial
//! tension $Y e_1$ along $n$): $W$ and $S$ are continuous across the three states, and $S$
//! is never compressive. In the wrinkled state, with $N = n n^T$, $m \perp n$ and
//! $M = n m^T + m n^T$ (so $\delta e_1 = N : \delta E$ and
//! $\delta n = \frac{M : \delta E}{2(e_1 - e_2)}\thinspace m$),
//! $$\delta S = Y (N : \delta E)\thinspace N + \frac{Y e_1}{2(e_1 - e_2)} (M : \delta E)\thinspace M,$$
//! two rank-one terms $\alpha (A : \delta E) A$. Since $A : \delta E = \sum_{jk} A_{jk}\thinspace
//! f_j \cdot \delta f_k$, each adds $\alpha\thinspace g_j g_k^T$ to $C_{jk}$, with
//! $g_k = \sum_j A_{jk} f_j$. There $e_1 - e_2 > (1+\nu) e_1 > 0$, so nothing divides by
//! zero, and $N = (E - e_2 I)/(e_1 - e_2)$ needs no eigenvector. Both coefficients and $S$
//! are non-negative: the tension-field Hessian is positive semi-definite in every state.
//! $W$ is $C^1$, not $C^2$: the Hessian jumps where the state changes.
//!
//! Units: pattern coordinates and positions in page units, $Y$ in force per length,
//! $V$ in force·length, gradients in force, Hessians in force per length.
//!
//! Degenerate input: the constructor refuses degenerate, clockwise and sliver rest triangles
//! ([`KernelError::NonPositiveRestArea`]), so evaluation never divides. Value, gradient and
//! Hessian are polynomials (degree 4, 3, 2) in the positions: any finite configuration,
//! including coincident or collinear nodes and inverted triangles, gives finite output unless
//! the polynomial itself overflows (the guard bounds $\lVert D_m^{-1}\rVert_F <
//! \sqrt{2}/(\sqrt{\varepsilon}\thinspace\ell_{\max})$; for page-unit triangles and coordinates up to
//! [`Real::COORD_MAX`] nothing overflows). An inverted triangle is not detected: the Green
//! strain does not see orientation, so a reflected triangle has the energy of its mirror image.
//! NaN input propagates to NaN output.

use crate::error::{KernelError, finite, rest_triangle_area2};
use crate::math;
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, zero_blocks};

/// How the membrane answers compression (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MembraneLaw {
    /// Saint Venant–Kirchhoff: compression is resisted like tension.
    #[default]
    StVenantKirchhoff,
    /// The relaxed (tension-field) energy: a compressed direction wrinkles and carries no
    /// stress; an element compressed every way is slack.
    TensionField,
}

/// Saint Venant–Kirchhoff stretching energy of one sheet triangle, or its tension-field
/// relaxation (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Membrane<T> {
    /// $B = D_m^{-1}$, row-major (`dm_inv[row][col]`), per page unit.
    pub dm_inv: [[T; 2]; 2],
    /// $A_0$, the rest area in the pattern, page units².
    pub rest_area: T,
    /// $\mu = Y/(2(1+\nu))$, force per length.
    pub mu: T,
    /// $\lambda = Y\nu/(1-\nu^2)$, force per length.
    pub lambda: T,
    /// Whether compression is resisted ([`MembraneLaw::StVenantKirchhoff`], what
    /// [`Membrane::new`] makes) or wrinkles ([`MembraneLaw::TensionField`]).
    pub law: MembraneLaw,
}

/// The state of a tension-field element (module docs), with what its tangent needs.
#[derive(Clone, Copy, Debug)]
enum Regime<T> {
    /// Both principal stresses non-negative: the Saint Venant–Kirchhoff response.
    Taut,
    /// One direction wrinkles: $S = Y e_1 N$, tangent $Y\thinspace N\otimes N + \beta\thinspace M \otimes M$.
    Wrinkled {
        /// $e_1$, the larger principal strain.
        stretch: T,
        /// $N = n n^T$.
        n: Sym2<T>,
        /// $M = n m^T + m n^T$.
        m: Sym2<T>,
        /// $Y$.
        stiffness: T,
        /// $\beta = Y e_1 / (2(e_1 - e_2))$.
        shear: T,
    },
    /// Compressed every way: no stress, no stiffness.
    Slack,
}

/// Strain, stress and state of one evaluation.
#[derive(Clone, Copy, Debug)]
struct Response<T> {
    /// Green strain $E$.
    strain: Sym2<T>,
    /// Second Piola–Kirchhoff stress $S$ (force per length).
    stress: Sym2<T>,
    regime: Regime<T>,
}

/// A symmetric $2\times 2$ matrix `[m00, m01, m11]`.
type Sym2<T> = [T; 3];

/// The positive part $S^+$ of a symmetric $2\times 2$ matrix (negative eigenvalues set to
/// zero). With eigenvalues $\sigma_1 > 0 > \sigma_2$: $S^+ = \sigma_1 (S - \sigma_2 I) /
/// (\sigma_1 - \sigma_2)$, no eigenvectors needed and no division by zero. NaN stays NaN.
#[inline]
#[must_use]
fn positive_part<T: Real>(s: Sym2<T>) -> Sym2<T> {
    let mean = (s[0] + s[2]) * T::HALF;
    let half_diff = (s[0] - s[2]) * T::HALF;
    let radius = math::sqrt(half_diff * half_diff + s[1] * s[1]);
    let (hi, lo) = (mean + radius, mean - radius);
    if lo >= T::ZERO {
        s
    } else if hi <= T::ZERO {
        [T::ZERO; 3]
    } else {
        let c = hi / (hi - lo);
        [(s[0] - lo) * c, s[1] * c, (s[2] - lo) * c]
    }
}

/// Whether the longest edge of the rest triangle `u` is at least $\sqrt{\varepsilon}$ page
/// units ($3.5\cdot 10^{-4}$ in `f32`, $1.5\cdot 10^{-8}$ in `f64`). Below that,
/// $\lVert D_m^{-1}\rVert$ exceeds $1/\sqrt{\varepsilon}$ per unit and the quartic energy
/// overflows for ordinary coordinates: rest edges of $10^{-15}$ in `f32` gave an infinite
/// energy and Hessian at coordinates of order 1 (issue 20). A sheet's triangles are
/// fractions of a page unit, far above it.
#[must_use]
fn meaningful_size<T: Real>(u: [[T; 2]; 3]) -> bool {
    let sq = |a: [T; 2], b: [T; 2]| (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    let longest = [sq(u[0], u[1]), sq(u[1], u[2]), sq(u[2], u[0])]
        .into_iter()
        .fold(T::ZERO, |m, l| if l > m { l } else { m });
    longest >= T::EPSILON
}

impl<T: Real> Membrane<T> {
    /// From the rest triangle `[u0, u1, u2]` in the 2D pattern (page units,
    /// counter-clockwise), the 2D Young's modulus `stretch_modulus` $Y > 0$ (force per
    /// length) and Poisson's ratio `poisson` $\nu \in [0, 1/2)$.
    ///
    /// The rest triangle must satisfy $2A_0 > \sqrt{\varepsilon}\thinspace\ell_{\max}^2$ ($\ell_{\max}$
    /// its longest edge, $\varepsilon$ the precision's machine epsilon) and
    /// $\ell_{\max} \ge \sqrt{\varepsilon}$ page units (a rest shape far below any meaningful
    /// size has an energy that overflows for ordinary coordinates).
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] (`"pattern"`, `"stretch_modulus"`, `"poisson"`),
    /// [`KernelError::NonPositiveRestArea`] with `index` 0 for a degenerate, clockwise or
    /// sliver rest triangle, [`KernelError::OutOfRange`] for $Y \le 0$ or $\nu$ outside
    /// $[0, 1/2)$.
    pub fn new(pattern: [[T; 2]; 3], stretch_modulus: T, poisson: T) -> Result<Self, KernelError> {
        for p in pattern {
            for c in p {
                finite(c, "pattern")?;
            }
        }
        let y = finite(stretch_modulus, "stretch_modulus")?;
        let nu = finite(poisson, "poisson")?;
        if y <= T::ZERO {
            return Err(KernelError::OutOfRange {
                name: "stretch_modulus",
            });
        }
        if nu < T::ZERO || nu >= T::HALF {
            return Err(KernelError::OutOfRange { name: "poisson" });
        }
        let area2 = rest_triangle_area2(pattern, 0)?;
        let [u0, u1, u2] = pattern;
        if !meaningful_size(pattern) {
            return Err(KernelError::NonPositiveRestArea { index: 0 });
        }
        let (e1, e2) = (
            [u1[0] - u0[0], u1[1] - u0[1]],
            [u2[0] - u0[0], u2[1] - u0[1]],
        );
        let inv = T::ONE / area2;
        let dm_inv = [[e2[1] * inv, -e2[0] * inv], [-e1[1] * inv, e1[0] * inv]];
        if !dm_inv.iter().flatten().all(|v| v.is_finite()) {
            return Err(KernelError::NonPositiveRestArea { index: 0 });
        }
        Ok(Self {
            dm_inv,
            rest_area: area2 * T::HALF,
            mu: y / (T::TWO * (T::ONE + nu)),
            lambda: y * nu / ((T::ONE - nu) * (T::ONE + nu)),
            law: MembraneLaw::StVenantKirchhoff,
        })
    }

    /// The same triangle under `law`.
    #[must_use]
    pub fn with_law(self, law: MembraneLaw) -> Self {
        Self { law, ..self }
    }

    /// The two columns $(f_0, f_1)$ of the deformation gradient
    /// $F = [x_1 - x_0,\ x_2 - x_0]\thinspace D_m^{-1}$ ($3\times 2$, dimensionless): the images of the
    /// pattern's unit X and Y directions. $F^T$ maps a 3D force into the pattern.
    #[inline]
    #[must_use]
    pub fn deformation_gradient(&self, x: &NodeVecs<T, 3>) -> (T::Vec3, T::Vec3) {
        let (a, b) = (x[1] - x[0], x[2] - x[0]);
        let m = &self.dm_inv;
        (a * m[0][0] + b * m[1][0], a * m[0][1] + b * m[1][1])
    }

    /// $w_{ij} = \partial f_j / \partial x_i$ (module docs).
    #[inline]
    fn node_weights(&self) -> [[T; 2]; 3] {
        let m = &self.dm_inv;
        [[-(m[0][0] + m[1][0]), -(m[0][1] + m[1][1])], m[0], m[1]]
    }

    /// Strain, stress and state of the columns `f` under [`Membrane::law`] (module docs).
    #[inline]
    fn response(&self, f: (T::Vec3, T::Vec3)) -> Response<T> {
        let e = [
            (f.0.dot(f.0) - T::ONE) * T::HALF,
            f.0.dot(f.1) * T::HALF,
            (f.1.dot(f.1) - T::ONE) * T::HALF,
        ];
        let (mu, lambda) = (self.mu, self.lambda);
        let tr = e[0] + e[2];
        let taut = Response {
            strain: e,
            stress: [
                T::TWO * mu * e[0] + lambda * tr,
                T::TWO * mu * e[1],
                T::TWO * mu * e[2] + lambda * tr,
            ],
            regime: Regime::Taut,
        };
        if self.law == MembraneLaw::StVenantKirchhoff {
            return taut;
        }
        let half_diff = (e[0] - e[2]) * T::HALF;
        let radius = math::sqrt(half_diff * half_diff + e[1] * e[1]);
        let (hi, lo) = (tr * T::HALF + radius, tr * T::HALF - radius);
        if hi <= T::ZERO {
            return Response {
                strain: e,
                stress: [T::ZERO; 3],
                regime: Regime::Slack,
            };
        }
        let axial = T::TWO * mu + lambda;
        // Taut when the lower principal stress (2 mu + lambda) e2 + lambda e1 is not negative.
        // (NaN strain falls through to the wrinkled branch and gives NaN.)
        if axial * lo + lambda * hi >= T::ZERO {
            return taut;
        }
        // Wrinkled, so radius >= (1 + nu) e1 / 2 > 0. With D = (E - mean I) / radius =
        // [d0, d1; d1, -d0]: N = (E - e2 I) / (e1 - e2) = (I + D) / 2, M = [-d1, d0; d0, d1].
        let (d0, d1) = (half_diff / radius, e[1] / radius);
        let n = [
            (T::ONE + d0) * T::HALF,
            d1 * T::HALF,
            (T::ONE - d0) * T::HALF,
        ];
        let stiffness = T::TWO * T::TWO * mu * (mu + lambda) / axial;
        let tension = stiffness * hi;
        Response {
            strain: e,
            stress: [tension * n[0], tension * n[1], tension * n[2]],
            regime: Regime::Wrinkled {
                stretch: hi,
                n,
                m: [-d1, d0, d1],
                stiffness,
                // Y e1 / (2 (e1 - e2)), e1 - e2 = 2 radius.
                shear: tension / (T::TWO * T::TWO * radius),
            },
        }
    }

    /// $W$ of the response `r`, energy per pattern area (module docs).
    #[inline]
    fn density(&self, r: &Response<T>) -> T {
        match r.regime {
            Regime::Taut => {
                let e = r.strain;
                let tr = e[0] + e[2];
                self.mu * (e[0] * e[0] + T::TWO * e[1] * e[1] + e[2] * e[2])
                    + T::HALF * self.lambda * tr * tr
            }
            Regime::Wrinkled {
                stretch, stiffness, ..
            } => T::HALF * stiffness * stretch * stretch,
            Regime::Slack => T::ZERO,
        }
    }

    /// The blocks $C_{jk} = \partial p_j / \partial f_k$ of the response `r`, with the
    /// geometric stiffness built from `s` (exact: $S$; projected: $S^+$): `[C00, C01, C11]`.
    #[inline]
    fn tangent(&self, f: (T::Vec3, T::Vec3), r: &Response<T>, s: Sym2<T>) -> [T::Mat3; 3] {
        let (f0, f1) = f;
        let id = T::Mat3::IDENTITY;
        let geometric = [id * s[0], id * s[1], id * s[2]];
        match r.regime {
            Regime::Taut => {
                let (mu, lambda) = (self.mu, self.lambda);
                let f00 = T::Mat3::outer(f0, f0);
                let f11 = T::Mat3::outer(f1, f1);
                let ff = (f00 + f11) * mu;
                [
                    geometric[0] + f00 * (mu + lambda) + ff,
                    geometric[1] + T::Mat3::outer(f1, f0) * mu + T::Mat3::outer(f0, f1) * lambda,
                    geometric[2] + f11 * (mu + lambda) + ff,
                ]
            }
            Regime::Wrinkled {
                n,
                m,
                stiffness,
                shear,
                ..
            } => {
                let mut c = geometric;
                for (a, alpha) in [(n, stiffness), (m, shear)] {
                    // g_k = sum_j A_jk f_j adds alpha g_j g_k^T to C_jk.
                    let g0 = f0 * a[0] + f1 * a[1];
                    let g1 = f0 * a[1] + f1 * a[2];
                    c[0] += T::Mat3::outer(g0, g0) * alpha;
                    c[1] += T::Mat3::outer(g0, g1) * alpha;
                    c[2] += T::Mat3::outer(g1, g1) * alpha;
                }
                c
            }
            Regime::Slack => [T::Mat3::ZERO; 3],
        }
    }

    /// The Hessian of the response `r` with the geometric stiffness built from the stress
    /// `s` (exact: $S$; projected: $S^+$).
    #[inline]
    fn hessian_with(&self, f: (T::Vec3, T::Vec3), r: &Response<T>, s: Sym2<T>) -> Blocks<T, 3> {
        let [c00, c01, c11] = self.tangent(f, r, s);
        let c10 = c01.transposed();
        let w = self.node_weights();
        let a0 = self.rest_area;
        let mut h = zero_blocks::<T, 3>();
        for a in 0..3 {
            for b in a..3 {
                let (wa, wb) = (w[a], w[b]);
                let block = (c00 * (wa[0] * wb[0])
                    + c01 * (wa[0] * wb[1])
                    + c10 * (wa[1] * wb[0])
                    + c11 * (wa[1] * wb[1]))
                    * a0;
                h[a][b] = block;
                if b != a {
                    h[b][a] = block.transposed();
                }
            }
        }
        h
    }

    /// The Hessian with the geometric stiffness $S \otimes I_3$ replaced by
    /// $S^+ \otimes I_3$, $S^+$ the positive part of the stress (its negative principal
    /// stresses, i.e. compression, dropped): positive semi-definite, and equal to the exact
    /// Hessian when neither principal stress is negative (module docs).
    #[must_use]
    pub fn hessian_projected(&self, x: &NodeVecs<T, 3>) -> Blocks<T, 3> {
        let f = self.deformation_gradient(x);
        let r = self.response(f);
        self.hessian_with(f, &r, positive_part(r.stress))
    }
}

impl<T: Real> Membrane<T> {
    /// The second Piola–Kirchhoff stress $S$ at `x` under [`Membrane::law`], as
    /// $[S_{uu}, S_{uv}, S_{vv}]$ in the pattern (force per length; module docs).
    #[must_use]
    pub fn stress(&self, x: &NodeVecs<T, 3>) -> [T; 3] {
        self.response(self.deformation_gradient(x)).stress
    }

    /// The Eshelby energy-momentum tensor of the triangle in the pattern,
    /// $$\Sigma = W I - F^T P = W I - C S,\qquad C = F^T F,$$
    /// with $W = V / A_0$ the energy per pattern area and $P = F S$ the first
    /// Piola–Kirchhoff stress (force per length); symmetric, since $S$ shares $C$'s eigenvectors
    /// under either law (a polynomial in $C$, or $Y e_1 n n^T$) and so commutes with it. Returned as $[\Sigma_{uu},
    /// \Sigma_{uv}, \Sigma_{vv}]$.
    ///
    /// It is the stress of the pattern itself (Eshelby 1951; Gurtin, *Configurational
    /// Forces as Basic Concepts of Continuum Physics*, 2000, ch. 3): moving a rest corner
    /// $u_i$ of the triangle with the 3D positions held changes the energy by
    /// $$\frac{\partial V}{\partial u_i} = A_0\thinspace\Sigma\thinspace\nabla N_i,$$
    /// $N_i$ the corner's linear shape function in the pattern. A crack tip is such a
    /// point, so $\Sigma$ gives the energy a tear releases as it moves
    /// (`folio_tearing::release`). Units: force per length, like $S$.
    #[must_use]
    pub fn eshelby(&self, x: &NodeVecs<T, 3>) -> [T; 3] {
        let f = self.deformation_gradient(x);
        let r = self.response(f);
        let (s, w) = (r.stress, self.density(&r));
        let c = [f.0.dot(f.0), f.0.dot(f.1), f.1.dot(f.1)];
        [
            w - (c[0] * s[0] + c[1] * s[1]),
            -(c[0] * s[1] + c[1] * s[2]),
            w - (c[1] * s[1] + c[2] * s[2]),
        ]
    }
}

impl<T: Real> Potential<T, 3> for Membrane<T> {
    fn value(&self, x: &NodeVecs<T, 3>) -> T {
        let r = self.response(self.deformation_gradient(x));
        self.rest_area * self.density(&r)
    }

    fn gradient(&self, x: &NodeVecs<T, 3>) -> NodeVecs<T, 3> {
        let f = self.deformation_gradient(x);
        let s = self.response(f).stress;
        let a0 = self.rest_area;
        let p0 = (f.0 * s[0] + f.1 * s[1]) * a0;
        let p1 = (f.0 * s[1] + f.1 * s[2]) * a0;
        let m = &self.dm_inv;
        let g1 = p0 * m[0][0] + p1 * m[0][1];
        let g2 = p0 * m[1][0] + p1 * m[1][1];
        [-(g1 + g2), g1, g2]
    }

    fn hessian(&self, x: &NodeVecs<T, 3>) -> Blocks<T, 3> {
        let f = self.deformation_gradient(x);
        let r = self.response(f);
        self.hessian_with(f, &r, r.stress)
    }
}
