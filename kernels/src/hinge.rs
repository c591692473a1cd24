//! Bending of a tearing sheet across one interior edge: the quadratic isometric bending
//! energy of Bergou, Wardetzky, Harmon, Zorin and Grinspun, *A quadratic bending model for
//! inextensible surfaces* (SGP 2006), for a sheet whose rest shape is its flat 2D pattern:
//! the sheet that seed `002_…` tears. (Its tear step itself uses only the in-plane forces of
//! [`crate::membrane`], Sec. 5.1, paper's bending forces being very low; this term keeps the
//! sheet's shape smooth.)
//!
//! Nodes `[x0, x1, x2, x3]`: the edge $e = (x_0, x_1)$, triangle $a = (x_0, x_1, x_2)$ and
//! triangle $b = (x_1, x_0, x_3)$, both counter-clockwise in the pattern (so $x_2$ and $x_3$
//! lie on opposite sides of the edge). With rest areas $A_a, A_b$ and the interior pattern
//! angles $\alpha_0, \alpha_1$ of triangle $a$ and $\beta_0, \beta_1$ of triangle $b$ at
//! $x_0$ and $x_1$:
//! $$V = \frac{3}{A_a + A_b}\thinspace\Bigl\lVert \sum_{i=0}^{3} K_i x_i \Bigr\rVert^2,\qquad
//!   K = \bigl(\cot\alpha_1 + \cot\beta_1,\ \cot\alpha_0 + \cot\beta_0,~
//!   -\cot\alpha_0 - \cot\alpha_1,\ -\cot\beta_0 - \cot\beta_1\bigr).$$
//! In the paper's notation ($e_0$ the edge, $e_1, e_2$ from $x_0$ and $e_3, e_4$ from $x_1$
//! to $x_2, x_3$, $c_{0j}$ the cotangent of the interior angle between $e_0$ and $e_j$) this is
//! $K = (c_{03} + c_{04},\ c_{01} + c_{02},\ -c_{01} - c_{03},\ -c_{02} - c_{04})$.
//!
//! Derivation. Split $s = \sum_i K_i x_i$ by triangle:
//! $s = s_a + s_b$, $s_a = \cot\alpha_1 (x_0 - x_2) + \cot\alpha_0 (x_1 - x_2)$ and
//! $s_b = \cot\beta_1 (x_0 - x_3) + \cot\beta_0 (x_1 - x_3)$. Put triangle $a$ in its plane
//! with $x_0 = 0$, $x_1 = (\ell, 0)$, $x_2 = (p, h)$, $h > 0$: then $\cot\alpha_0 = p/h$,
//! $\cot\alpha_1 = (\ell - p)/h$ and
//! $s_a = \tfrac{\ell - p}{h}(-p, -h) + \tfrac{p}{h}(\ell - p, -h) = (0, -\ell)$, i.e.
//! $s_a = -\ell\thinspace m_a$ with $\ell = \lVert e\rVert$ and $m_a$ the unit vector in the plane of
//! $a$, normal to $e$, pointing into $a$; likewise $s_b = -\ell\thinspace m_b$. This holds for any
//! rigid placement of each triangle, so for an isometric deformation that folds the two
//! triangles about the edge by the dihedral angle $\theta$ ($\theta = 0$ flat, $m_b = -m_a$):
//! $\lVert s\rVert = \ell \lVert m_a + m_b\rVert = 2\ell\sin(\theta/2)$ and
//! $$V = \frac{12\thinspace\ell^2 \sin^2(\theta/2)}{A_a + A_b} \approx \frac{3\thinspace\ell^2}{A_a + A_b}\thinspace\theta^2,$$
//! the discrete-shell hinge energy $\ell^2\theta^2/\bar A$ with $\bar A = (A_a+A_b)/3$.
//! Moreover $\sum_i K_i = 0$ and $\sum_i K_i u_i = 0$ for the pattern points $u_i$ (the two
//! triangle parts cancel in the flat pattern), so $s$ vanishes for every affine image
//! $x_i = M u_i + t$ of the pattern ($M \in \mathbb{R}^{3\times 2}$): zero energy for the flat
//! rest shape under any rigid motion (and any in-plane stretch: this term measures bending
//! only).
//!
//! Unweighted: the family weight is the bending
//! stiffness. Units: $K$ dimensionless, $c$ per page unit², $V$ dimensionless.
//!
//! **Only bending.** The paper's $\lVert s\rVert^2$ also grows under in-plane deformations
//! that are not affine ($s$ is then the cotangent Laplacian of the in-plane displacement, in
//! the sheet's plane), which the membrane alone should carry. At a tear tip, whose field is
//! singular, that in-plane part stiffens the sheet on every finer mesh: the energy a notch
//! releases (`folio_tearing::release`) is 1.26e-7, 1.42e-7 and 1.48e-7 without it
//! (converging), but 1.00e-7, 0.80e-7 and 0.45e-7 with it, at 16, 32 and 64 quads across. So only the component of $s$ along the hinge's
//! normal $\hat n$ counts:
//! $$V = c\thinspace(\hat n \cdot s)^2,\qquad c = \frac{3}{A_a + A_b},$$
//! with $\hat n$ the two triangles' mean unit normal, set by [`Hinge::orient`] at the start
//! of each step and held during it (so $V$ stays quadratic). For an isometric fold $s$ lies
//! along that normal ($m_a + m_b$ bisects the two triangles' normals), so the energy is the
//! paper's, $12\ell^2\sin^2(\theta/2)/(A_a + A_b)$; an in-plane deformation costs nothing.
//! $\nabla_{x_i} V = 2c\thinspace K_i\thinspace(\hat n\cdot s)\thinspace\hat n$ and
//! $\nabla^2_{x_a x_b} V = 2c\thinspace K_a K_b\thinspace \hat n \hat n^T$, constant within the
//! step.
//!
//! Degenerate input: the constructor refuses non-finite patterns and degenerate, sliver or
//! clockwise triangles (overlapping triangles: $x_3$ on the same side of the edge as $x_2$),
//! so $\lvert\cot\rvert < 1/\sqrt{\varepsilon}$ and evaluation is a fixed linear map: finite
//! for any finite positions up to [`Real::COORD_MAX`]; NaN input propagates.

use crate::error::{KernelError, finite, rest_triangle_area2};
use crate::real::{Mat3Ops, Real, Vec3Ops};
use crate::term::{Blocks, NodeVecs, Potential, add_scalar_kron, zero_blocks};

/// Quadratic isometric bending energy of one interior edge of a flat-rest sheet (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hinge<T: Real> {
    /// The stencil $K$ (dimensionless cotangent sums), in node order `[x0, x1, x2, x3]`.
    pub stencil: [T; 4],
    /// $c = 3/(A_a + A_b)$, per page unit².
    pub scale: T,
    /// $\hat n$, the unit normal along which $s$ counts (module docs), set by
    /// [`Hinge::orient`]; `None`: all of $s$ counts, the paper's $c\lVert s\rVert^2$.
    pub normal: Option<T::Vec3>,
}

impl<T: Real> Hinge<T> {
    /// From the rest pattern `[u0, u1, u2, u3]` (page units): edge `(u0, u1)`, triangles
    /// `(u0, u1, u2)` (index 0) and `(u1, u0, u3)` (index 1), both counter-clockwise, i.e.
    /// `u2` left and `u3` right of the edge direction `u1 - u0`. Each triangle must pass the
    /// area guard of [`crate::membrane::Membrane::new`]. A pattern that is clockwise
    /// throughout (mirrored) is refused; swapping `u2` and `u3` (and the nodes `x2`, `x3`)
    /// describes the same hinge counter-clockwise.
    ///
    /// # Errors
    /// [`KernelError::NonFiniteParameter`] (`"pattern"`);
    /// [`KernelError::NonPositiveRestArea`] naming the degenerate, sliver or clockwise
    /// triangle. Overlapping triangles ($u_3$ on the same side as $u_2$) make triangle 1
    /// clockwise and are refused with `index` 1; a pattern so small that $3/(A_a + A_b)$
    /// overflows is refused with `index` 0.
    pub fn new(pattern: [[T; 2]; 4]) -> Result<Self, KernelError> {
        for p in pattern {
            for c in p {
                finite(c, "pattern")?;
            }
        }
        let [u0, u1, u2, u3] = pattern;
        let area2_a = rest_triangle_area2([u0, u1, u2], 0)?;
        let area2_b = rest_triangle_area2([u1, u0, u3], 1)?;
        let sub = |p: [T; 2], q: [T; 2]| [p[0] - q[0], p[1] - q[1]];
        let dot = |p: [T; 2], q: [T; 2]| p[0] * q[0] + p[1] * q[1];
        let (e, back) = (sub(u1, u0), sub(u0, u1));
        // cot = cos / sin = (d1 . d2) / (d1 x d2), with d1 x d2 = 2A > 0.
        let cot_a0 = dot(e, sub(u2, u0)) / area2_a;
        let cot_a1 = dot(back, sub(u2, u1)) / area2_a;
        let cot_b0 = dot(e, sub(u3, u0)) / area2_b;
        let cot_b1 = dot(back, sub(u3, u1)) / area2_b;
        let stencil = [
            cot_a1 + cot_b1,
            cot_a0 + cot_b0,
            -cot_a0 - cot_a1,
            -cot_b0 - cot_b1,
        ];
        let scale = T::from_f64(3.0) / (area2_a * T::HALF + area2_b * T::HALF);
        if !scale.is_finite() || !stencil.iter().all(|k| k.is_finite()) {
            return Err(KernelError::NonPositiveRestArea { index: 0 });
        }
        Ok(Self {
            stencil,
            scale,
            normal: None,
        })
    }

    /// Sets $\hat n$ to the mean of the two triangles' unit normals at `x` (module docs), so
    /// that only folds count from now on; keeps the old one where a triangle is degenerate
    /// or the two normals cancel (a hinge folded flat onto itself), and the flat pattern's
    /// $+Z$ if it had none.
    pub fn orient(&mut self, x: &NodeVecs<T, 4>) {
        let [x0, x1, x2, x3] = *x;
        let unit = |v: T::Vec3| {
            let len = crate::math::length::<T>(v);
            (len > T::ZERO && len.is_finite()).then(|| v * (T::ONE / len))
        };
        let mean = match (
            unit((x1 - x0).cross(x2 - x0)),
            unit((x0 - x1).cross(x3 - x1)),
        ) {
            (Some(a), Some(b)) => unit(a + b),
            _ => None,
        };
        let z = T::Vec3::new(T::ZERO, T::ZERO, T::ONE);
        self.normal = mean.or(self.normal).or(Some(z));
    }

    /// $s = \sum_i K_i x_i$: zero for the flat pattern under any affine map, length
    /// $2\ell\sin(\theta/2)$ for an isometric fold by the dihedral angle $\theta$ (page units).
    #[inline]
    #[must_use]
    pub fn apply(&self, x: &NodeVecs<T, 4>) -> T::Vec3 {
        let mut s = T::Vec3::ZERO;
        for (&k, &p) in self.stencil.iter().zip(x) {
            s += p * k;
        }
        s
    }
}

impl<T: Real> Potential<T, 4> for Hinge<T> {
    const CONSTANT_HESSIAN: bool = true;

    fn value(&self, x: &NodeVecs<T, 4>) -> T {
        let s = self.apply(x);
        match self.normal {
            None => self.scale * s.dot(s),
            Some(n) => self.scale * n.dot(s) * n.dot(s),
        }
    }

    fn gradient(&self, x: &NodeVecs<T, 4>) -> NodeVecs<T, 4> {
        let s = self.apply(x);
        let g = match self.normal {
            None => s,
            Some(n) => n * n.dot(s),
        } * (T::TWO * self.scale);
        self.stencil.map(|k| g * k)
    }

    fn hessian(&self, _x: &NodeVecs<T, 4>) -> Blocks<T, 4> {
        let mut h = zero_blocks::<T, 4>();
        let Some(n) = self.normal else {
            add_scalar_kron(&mut h, &self.stencil, T::TWO * self.scale);
            return h;
        };
        let nn = T::Mat3::outer(n, n) * (T::TWO * self.scale);
        for (row, &ka) in h.iter_mut().zip(&self.stencil) {
            for (block, &kb) in row.iter_mut().zip(&self.stencil) {
                *block = nn * (ka * kb);
            }
        }
        h
    }
}
