//! The constraints of the position-based page: distance constraints on the grid's edges
//! and cell diagonals, isometric bending at the particles, and their XPBD projection.
//!
//! **XPBD** (Macklin, Müller and Chentanez 2016, *XPBD: Position-Based Simulation of
//! Compliant Constrained Dynamics*, eq. 17-18). A constraint $C(x)$ with compliance
//! $\alpha$ stands for the energy $U = \frac{1}{2\alpha} C^2$. With
//! $\tilde\alpha = \alpha/h^2$ ($h$ the substep) and the multiplier $\lambda$ of the
//! substep (0 at its start), one projection is
//! $$\Delta\lambda = \frac{-C(x) - \tilde\alpha\lambda}{\sum_j w_j\lVert\nabla_j C\rVert^2 +
//!   \tilde\alpha},\qquad \Delta x_j = w_j \nabla_j C\,\Delta\lambda,\qquad
//!   \lambda \mathrel{+}= \Delta\lambda,$$
//! $w_j = 1/m_j$ the inverse mass (0 for a fixed or gripped particle). A projection whose
//! denominator is 0 (every particle immovable and $\alpha = 0$) is skipped.
//!
//! **Distance** ($C = \lVert x_a - x_b\rVert - L^0$, gradient $\pm\hat n$): every grid edge
//! with the stretch compliance, both diagonals of every cell with the shear compliance. A
//! pair closer than [`Real::LENGTH_FLOOR`] has no direction and is skipped (the documented
//! fallback).
//!
//! **Bending: isometric bending** (Bergou, Wardetzky, Harmon, Zorin and Grinspun 2006, *A
//! Quadratic Bending Model for Inextensible Surfaces*). For a deformation that keeps
//! lengths, the Laplace-Beltrami operator of the rest surface stays that of the deformed
//! one, so the Willmore-type energy $\frac D2\int (2H)^2\,dA = \frac D2\int\kappa^2\,dA$
//! (a developable page has one principal curvature $\kappa$; $\Delta x = 2H n$) is a
//! quadratic form $\frac12 x^\top Q x$ with a constant $Q$ built from the rest mesh's
//! cotangent Laplacian. On the particle grid split along cell diagonals the cotangent
//! weights are $\frac12(\cot 45° + \cot 45°) = 1$ on grid edges and
//! $\frac12(\cot 90° + \cot 90°) = 0$ on diagonals, so the Laplacian is the five-point
//! stencil: at particle $v$ with spacings $h_x, h_z$,
//! $$\Delta_h x_v = \frac{x_{i+1,j} - 2x_v + x_{i-1,j}}{h_x^2} +
//!   \frac{x_{i,j+1} - 2x_v + x_{i,j-1}}{h_z^2},\qquad
//!   E = \frac D2\sum_v A_v\,\lVert\Delta_h x_v\rVert^2,$$
//! $A_v$ the particle's dual cell ([`dual_area`]: $h_x h_z$ inside, half on an edge, a
//! quarter at a corner), Bergou's isometric bending on this grid. A particle on the page's border sees only the second difference
//! along its border line, which is exact where the curvature across the border vanishes:
//! the free edge, which carries no moment, and a page bent about an axis across the edge.
//! Corners carry no term. (The same quadrature as the DOG page's calibrated bending on
//! branch `units`, `book::quadrature`.)
//!
//! **The Hessian form.** A quadratic form that equals the bending energy on isometric
//! deformations is free off them, and the Laplacian above gives a saddle
//! ($\kappa_1 = -\kappa_2$) zero energy, resisted only by the distance constraints, to
//! second order in the deflection: a clamped page with it sagged 52 % too far (module docs
//! of [`super`]). So the page uses the other quadratic form with the same value on
//! isometric deformations, the squared Hessian: for a developable surface parametrized by
//! arc length, $x_{uu}$, $x_{uv}$, $x_{vv}$ are normal and
//! $\lVert x_{uu}\rVert^2 + 2\lVert x_{uv}\rVert^2 + \lVert x_{vv}\rVert^2
//!   = \kappa_1^2 + \kappa_2^2 = (2H)^2 - 2K = \kappa^2$ ($K = 0$). It is the plate energy
//! $\frac D2\int[(2H)^2 - 2(1 - \nu)K]\,dA$ at Poisson's ratio $\nu = 0$ (Timoshenko and
//! Woinowsky-Krieger, *Theory of Plates and Shells*, 1959), where the Laplacian
//! is $\nu = 1$; in geometry processing, the Hessian energy (Stein, Grinspun, Wardetzky
//! and Jacobson 2018, *Natural Boundary Conditions for Smoothing in Geometry Processing*).
//! Discretized on the grid with the same quadrature:
//! $$E = \frac D2\Big[\sum_v A_v\big(\lVert\partial^2_x x_v\rVert^2 +
//!   \lVert\partial^2_z x_v\rVert^2\big) + 2\sum_c h_x h_z\lVert\partial_{xz} x_c\rVert^2\Big],$$
//! $\partial^2_x x_v = (x_{i+1,j} - 2x_v + x_{i-1,j})/h_x^2$ at particles off the spine and
//! fore-edge columns, $\partial^2_z$ likewise off the top and bottom rows (a border particle
//! keeps its border line's difference: the boundary rule above), and the twist of cell $c$,
//! $\partial_{xz} x_c = (x_{i+1,j+1} - x_{i+1,j} - x_{i,j+1} + x_{i,j})/(h_x h_z)$.
//!
//! **As XPBD constraints.** Bergou's energy suggests the scalar constraint
//! $C = \sqrt{x^\top Q_v x}$ with compliance $1/(D A_v)$. Its gradient has no direction
//! where $Q_v x = 0$, at the flat page every page starts from; so each term is a vector
//! constraint, linear in $x$, with the same energy $\frac{1}{2\alpha}\lVert C\rVert^2$:
//! $C = \partial^2_x x_v$ and $C = \partial^2_z x_v$ with
//! $$\alpha_v = \frac{1}{D\,A_v}\qquad(D = \frac{1}{\alpha_v A_v}),$$
//! and $C = \partial_{xz} x_c$ with $\alpha_c = 1/(2 D h_x h_z)$, each projected per
//! component (three scalar constraints with constant gradients, the stencil's weights). At
//! $h \to 0$ a projection tends to the force $-\nabla\frac{1}{2\alpha}\lVert C\rVert^2$.
//!
//! **Clamp** ([`Spine::Clamp`]). A page clamped in its rest plane along the spine is either
//! half of a page twice as wide, mirrored by $R(x, y, z) = (-x, y, z)$ across the spine,
//! whose spine column is held. Its spine particles then have a difference across the
//! spine whose left neighbour is the ghost $R\,x_{1,j}$; since the spine is fixed at
//! $x = 0$, $x_{1,j} + R\,x_{1,j}$ has no X, and the stencil's weight on $x_{1,j}$ is
//! $(0, 2, 2)/h_x^2$ per axis. The spine particle keeps its own dual cell, half of the
//! mirrored page's, and the twist of the mirrored cells is the other half's, so the
//! mirrored page's energy is twice this page's.

use alloc::vec::Vec;
use folio_geometry::QuadGrid;
use folio_kernels::{Real, Vec3Ops, math};

use super::settings::{Spine, XpbdSettings};

/// The dual-cell area of particle $(i, j)$ on `grid` with spacings `[hx, hz]`: the rest
/// cell around it, $c_i c_j h_x h_z$ with $c = \frac12$ on the border and 1 inside. The
/// areas sum to the page's.
#[must_use]
pub fn dual_area<T: Real>(grid: QuadGrid, spacing: [T; 2], i: usize, j: usize) -> T {
    let share = |at: usize, n: usize| {
        if at == 0 || at + 1 == n {
            T::HALF
        } else {
            T::ONE
        }
    };
    share(i, grid.nx) * share(j, grid.nz) * spacing[0] * spacing[1]
}

/// A distance constraint.
#[derive(Clone, Copy, Debug)]
pub struct Distance<T> {
    /// The two particles.
    pub nodes: [u32; 2],
    /// Rest length $L^0$.
    pub rest: T,
    /// Compliance $\alpha$.
    pub compliance: T,
}

/// Most particles in a bending stencil (a cell's twist).
pub const STENCIL: usize = 4;

/// A bending constraint: $C_v = \sum_j w_j \odot x_j$ (per-axis weights).
#[derive(Clone, Copy, Debug)]
pub struct Bending<T: Real> {
    /// The stencil's particles; the first `len` are used.
    pub nodes: [u32; STENCIL],
    /// Per-axis weights (X, Y, Z) of each particle.
    pub weights: [T::Vec3; STENCIL],
    /// Particles in the stencil.
    pub len: usize,
    /// Compliance $\alpha_v = 1/(D A_v)$.
    pub compliance: T,
}

/// `a ⊙ b`, component by component.
#[inline]
#[must_use]
fn times<T: Real>(a: T::Vec3, b: T::Vec3) -> T::Vec3 {
    T::Vec3::new(a.x() * b.x(), a.y() * b.y(), a.z() * b.z())
}

/// The distance constraints of validated `settings` on the particle grid `grid` with rest
/// positions `rest` (module docs); pairs of two spine particles, fixed in both holds, are
/// left out.
#[must_use]
pub fn distances<T: Real>(
    grid: QuadGrid,
    rest: &[T::Vec3],
    settings: &XpbdSettings<T>,
) -> Vec<Distance<T>> {
    let mut out = Vec::new();
    let mut add = |a: usize, b: usize, compliance: T| {
        if grid.coords(a).0 == 0 && grid.coords(b).0 == 0 {
            return;
        }
        out.push(Distance {
            nodes: [a as u32, b as u32],
            rest: math::length::<T>(rest[a] - rest[b]),
            compliance,
        });
    };
    for j in 0..grid.nz {
        for i in 0..grid.nx {
            let k = grid.index(i, j);
            if i + 1 < grid.nx {
                add(k, grid.index(i + 1, j), settings.stretch_compliance);
            }
            if j + 1 < grid.nz {
                add(k, grid.index(i, j + 1), settings.stretch_compliance);
            }
            if i + 1 < grid.nx && j + 1 < grid.nz {
                add(k, grid.index(i + 1, j + 1), settings.shear_compliance);
                add(
                    grid.index(i + 1, j),
                    grid.index(i, j + 1),
                    settings.shear_compliance,
                );
            }
        }
    }
    out
}

/// The bending constraints of validated `settings` on `grid` (module docs): the
/// second differences across ($\partial^2_x$) and along ($\partial^2_z$) at the particles,
/// and the twist of every cell; none when $D = 0$. Differences whose particles are all on
/// the spine move nothing and are left out.
#[must_use]
pub fn bendings<T: Real>(grid: QuadGrid, settings: &XpbdSettings<T>) -> Vec<Bending<T>> {
    let mut out = Vec::new();
    let d = settings.bending_stiffness;
    if d <= T::ZERO {
        return out;
    }
    let spacing = settings.spacing();
    let wx = T::ONE / (spacing[0] * spacing[0]);
    let wz = T::ONE / (spacing[1] * spacing[1]);
    let wt = T::ONE / (spacing[0] * spacing[1]);
    let all = |w: T| T::Vec3::new(w, w, w);
    let clamp = settings.spine == Spine::Clamp;
    let mut push = |nodes: &[(usize, T::Vec3)], compliance: T| {
        let mut b = Bending {
            nodes: [0; STENCIL],
            weights: [T::Vec3::ZERO; STENCIL],
            len: nodes.len().min(STENCIL),
            compliance,
        };
        for (slot, &(k, w)) in nodes.iter().take(STENCIL).enumerate() {
            b.nodes[slot] = k as u32;
            b.weights[slot] = w;
        }
        out.push(b);
    };
    for j in 0..grid.nz {
        for i in 0..grid.nx {
            let k = grid.index(i, j);
            let compliance = T::ONE / (d * dual_area(grid, spacing, i, j));
            if i > 0 && i + 1 < grid.nx {
                let across = [
                    (grid.index(i - 1, j), all(wx)),
                    (k, all(-(wx + wx))),
                    (grid.index(i + 1, j), all(wx)),
                ];
                push(&across, compliance);
            } else if i == 0 && clamp {
                // The mirrored ghost R x_{1,j} folded into x_{1,j}.
                let ghost = T::Vec3::new(T::ZERO, wx + wx, wx + wx);
                push(
                    &[(k, all(-(wx + wx))), (grid.index(1, j), ghost)],
                    compliance,
                );
            }
            if i > 0 && j > 0 && j + 1 < grid.nz {
                let along = [
                    (grid.index(i, j - 1), all(wz)),
                    (k, all(-(wz + wz))),
                    (grid.index(i, j + 1), all(wz)),
                ];
                push(&along, compliance);
            }
            if i + 1 < grid.nx && j + 1 < grid.nz {
                let twist = [
                    (k, all(wt)),
                    (grid.index(i + 1, j), all(-wt)),
                    (grid.index(i, j + 1), all(-wt)),
                    (grid.index(i + 1, j + 1), all(wt)),
                ];
                let cell = spacing[0] * spacing[1];
                push(&twist, T::ONE / (T::TWO * d * cell));
            }
        }
    }
    out
}

/// One XPBD projection of `c` (module docs) with $\tilde\alpha$ = `alpha_tilde`, updating
/// its multiplier `lambda`.
#[inline]
pub fn project_distance<T: Real>(
    x: &mut [T::Vec3],
    lambda: &mut T,
    c: &Distance<T>,
    inverse_mass: &[T],
    alpha_tilde: T,
) {
    let [a, b] = c.nodes.map(|k| k as usize);
    let (Some(&wa), Some(&wb), Some(&xa), Some(&xb)) =
        (inverse_mass.get(a), inverse_mass.get(b), x.get(a), x.get(b))
    else {
        return;
    };
    let denominator = wa + wb + alpha_tilde;
    let d = xa - xb;
    let length = math::length::<T>(d);
    if denominator <= T::ZERO || length <= T::LENGTH_FLOOR {
        return;
    }
    let n = d / length;
    let dl = (c.rest - length - alpha_tilde * *lambda) / denominator;
    *lambda += dl;
    x[a] += n * (wa * dl);
    x[b] -= n * (wb * dl);
}

/// One XPBD projection of the three components of `c` (module docs) with
/// $\tilde\alpha$ = `alpha_tilde`, updating its multipliers `lambda`.
#[inline]
pub fn project_bending<T: Real>(
    x: &mut [T::Vec3],
    lambda: &mut T::Vec3,
    c: &Bending<T>,
    inverse_mass: &[T],
    alpha_tilde: T,
) {
    let nodes = &c.nodes[..c.len];
    let mut value = T::Vec3::ZERO;
    let mut norm = T::Vec3::ZERO;
    for (&k, &w) in nodes.iter().zip(&c.weights) {
        let (Some(&xk), Some(&wk)) = (x.get(k as usize), inverse_mass.get(k as usize)) else {
            return;
        };
        value += times::<T>(w, xk);
        norm += times::<T>(w, w) * wk;
    }
    let step = |v: T, n: T, l: T| {
        let denominator = n + alpha_tilde;
        if denominator > T::ZERO {
            (-v - alpha_tilde * l) / denominator
        } else {
            T::ZERO
        }
    };
    let l = *lambda;
    let dl = T::Vec3::new(
        step(value.x(), norm.x(), l.x()),
        step(value.y(), norm.y(), l.y()),
        step(value.z(), norm.z(), l.z()),
    );
    *lambda += dl;
    for (&k, &w) in nodes.iter().zip(&c.weights) {
        if let (Some(xk), Some(&wk)) = (x.get_mut(k as usize), inverse_mass.get(k as usize)) {
            *xk += times::<T>(w, dl) * wk;
        }
    }
}
