//! Settings of the position-based page ([`super::XpbdPage`]).
//!
//! **Units** are those of the other page models: lengths in page units (the book page is 12
//! wide), time in seconds, masses in page masses (the book's page weighs 1). Derived:
//! areal density in page masses per page unit², gravity in page units/s², the bending
//! stiffness $D$ in page masses · page units²/s² (an energy: the bending moment per unit
//! width per unit curvature, the plate's $D$), compliances in inverse stiffness.
//!
//! **The default page is the DOG book's page**: $W = 12$, $H = 12\sqrt2$, unit page mass
//! ($\rho = 1/(WH)$), $g = 9.81$, and $D = 344 = 2\,w_{\mathrm{bend3D}}$, the plate stiffness
//! of the book's default page bending weight $w_{\mathrm{bend3D}} = 172$ with its Laplacian
//! terms weighted by area (`folio_book::quadrature::bending_stiffness`; the test
//! `page_models::the_xpbd_page_is_the_book_page` holds the two together). Its load number
//! is $\rho g W^3 / D = 0.242$: a nearly rigid page, a card for its weight.

use folio_kernels::Real;

use folio_kernels::setting::{
    SettingError, require, require_non_negative, require_positive, require_time_step,
};

use crate::require_page_size;

/// Most quads per side of the particle grid.
pub const MAX_QUADS_PER_SIDE: usize = 256;

/// Most substeps per frame ([`XpbdSettings::substeps`]).
pub const MAX_SUBSTEPS: u32 = 1024;

/// Most constraint iterations per substep ([`XpbdSettings::iterations`]).
pub const MAX_ITERATIONS: u32 = 64;

/// How the spine column ($u = 0$) holds the page.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Spine {
    /// The spine particles are fixed at rest and the page turns freely about them: a hinge
    /// that carries no bending moment, as the mass-spring page's fixed spine and the DOG
    /// book's binding. The default: a page that can be turned.
    Hinge,
    /// The spine particles are fixed and the page's tangent across the spine is held in the
    /// rest plane: a glued gutter, the cantilever's clamp. Bending at the spine column uses a
    /// mirrored ghost column ([`super::constraints`]). A clamped page cannot be turned over.
    Clamp,
}

/// Settings of an [`super::XpbdPage`] (module docs for units);
/// [`XpbdSettings::validate`] checks them.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct XpbdSettings<T: Real> {
    /// Quads across the page, $n_x$ (particles $n_x + 1$), in $[2, 256]$.
    pub quads_across: usize,
    /// Quads along the spine, $n_z$ (particles $n_z + 1$), in $[2, 256]$.
    pub quads_along: usize,
    /// Page width $W$ (page units), finite, $> 0$.
    pub width: T,
    /// Page height $H$ (page units), finite, $> 0$.
    pub height: T,
    /// Areal density $\rho$ (page masses per page unit²), finite, $> 0$. Particle $v$
    /// carries $\rho A_v$, $A_v$ its dual cell ([`super::constraints::dual_area`]).
    pub areal_density: T,
    /// Gravity $g$ along −Y (page units/s²), finite, $\ge 0$.
    pub gravity: T,
    /// Bending stiffness $D$ of the plate energy $\frac D2\int\kappa^2\,dA$ (page masses ·
    /// page units²/s²), finite, $\ge 0$; 0 switches bending off. Each bending constraint
    /// gets the compliance $1/(D A_v)$ ([`super::constraints`]).
    pub bending_stiffness: T,
    /// Compliance $\alpha = 1/k$ of the distance constraints along grid edges ($k$ the
    /// edge's stiffness, page masses/s²), finite, $\ge 0$; 0 is inextensible.
    pub stretch_compliance: T,
    /// Compliance of the distance constraints across cell diagonals (shear), finite,
    /// $\ge 0$; 0 is rigid in shear. Default $10^{-6}$ (a diagonal stiffness of $10^6$ page
    /// masses/s²; its relative stretch under the page's own weight is below $10^{-4}$): with
    /// rigid diagonals a cell's four edges and two diagonals are six rigid links on four
    /// particles, one more than a flat cell needs, and one Gauss-Seidel sweep per substep
    /// over such redundant links never settled a heavily loaded page at small substeps
    /// (the clamped page at load $\rho g W^3/D = 10$, 96 or 192 substeps: particles still
    /// moving 0.1 to 0.5 page units a frame after 20000 frames, tip 3 to 7 % off; with
    /// $10^{-6}$ it settles in 185 frames, `tests/tests/elastica_xpbd.rs`).
    pub shear_compliance: T,
    /// Linear drag rate $c$ (1/s), finite, $\ge 0$: every substep the free particles'
    /// velocity is $v \leftarrow v/(1 + c h) + h g$, implicit in the drag, so any rate is
    /// stable. The mass-spring page's default rate, 0.7125 s⁻¹ (seed `003_…` Sec. 3.1), by
    /// default: the two pages move through the same air.
    pub damping: T,
    /// Time step of one frame (seconds), finite, $> 0$. Default $1/60$.
    pub time_step: T,
    /// Substeps per frame, in $[1, 1024]$: XPBD's small steps (Macklin et al. 2019). See the
    /// default for the cost and the accuracy they buy.
    pub substeps: u32,
    /// Constraint sweeps per substep, in $[1, 64]$; Macklin et al. 2019 take one and spend
    /// the budget on substeps instead.
    pub iterations: u32,
    /// How the spine column holds the page.
    pub spine: Spine,
    /// A table under the page: the plane $y = 0$ as a one-sided inelastic, frictionless
    /// contact for the free particles, matching the mass-spring page's (after the
    /// constraints of a substep a free particle under the plane is put on it, and a free
    /// particle on it loses its downward velocity).
    pub floor: bool,
}

impl<T: Real> Default for XpbdSettings<T> {
    /// The book page (module docs) on the mass-spring page's grid, $8 \times 11$ quads
    /// ($9 \times 12$ particles), hinged at the spine, over the table, inextensible in
    /// stretch (nearly so in shear), at $h = 1/60$ in 29 substeps of one sweep each (chosen from the
    /// figures in [`super`]'s module docs: the cantilever's tip within 3 % of the elastica).
    fn default() -> Self {
        let (width, height) = (12.0, 12.0 * core::f64::consts::SQRT_2);
        Self {
            quads_across: 8,
            quads_along: 11,
            width: T::from_f64(width),
            height: T::from_f64(height),
            areal_density: T::from_f64(1.0 / (width * height)),
            gravity: T::from_f64(9.81),
            bending_stiffness: T::from_f64(344.0),
            stretch_compliance: T::ZERO,
            shear_compliance: T::from_f64(1e-6),
            damping: T::from_f64(0.7125),
            time_step: T::from_f64(1.0 / 60.0),
            substeps: 29,
            iterations: 1,
            spine: Spine::Hinge,
            floor: true,
        }
    }
}

impl<T: Real> XpbdSettings<T> {
    /// Particle spacing across and along, $(h_x, h_z) = (W/n_x, H/n_z)$.
    #[must_use]
    pub fn spacing(&self) -> [T; 2] {
        let n = |q: usize| T::from_f64(q.max(1) as f64);
        [
            self.width / n(self.quads_across),
            self.height / n(self.quads_along),
        ]
    }

    /// The substep $h/n$ (seconds).
    #[must_use]
    pub fn substep(&self) -> T {
        self.time_step / T::from_f64(f64::from(self.substeps.max(1)))
    }

    /// Checks every field against its documented range, and that the derived constants
    /// (particle masses, inverse masses, stencil weights, compliances over the squared
    /// substep) are finite and nonzero in `T`.
    ///
    /// # Errors
    /// The first bad field, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let quads = |n: usize| (2..=MAX_QUADS_PER_SIDE).contains(&n);
        let real = |x: T| x.to_f64();
        for (field, n) in [
            ("quads_across", self.quads_across),
            ("quads_along", self.quads_along),
        ] {
            require(quads(n), field, "from 2 to 256", n as f64)?;
        }
        require_page_size(self.width, self.height)?;
        require_positive("areal_density", real(self.areal_density))?;
        for (field, v) in [
            ("gravity", self.gravity),
            ("bending_stiffness", self.bending_stiffness),
            ("stretch_compliance", self.stretch_compliance),
            ("shear_compliance", self.shear_compliance),
            ("damping", self.damping),
        ] {
            require_non_negative(field, real(v))?;
        }
        require_time_step(real(self.time_step))?;
        require(
            (1..=MAX_SUBSTEPS).contains(&self.substeps),
            "substeps",
            "from 1 to 1024",
            f64::from(self.substeps),
        )?;
        require(
            (1..=MAX_ITERATIONS).contains(&self.iterations),
            "iterations",
            "from 1 to 64",
            f64::from(self.iterations),
        )?;
        self.check_derived()
    }

    /// The derived constants of [`XpbdSettings::validate`], computed in `f64` and required
    /// to be finite and nonzero once rounded to `T`.
    fn check_derived(&self) -> Result<(), SettingError> {
        let usable = |x: f64| {
            let t = T::from_f64(x);
            x.is_finite() && x > 0.0 && t.is_finite() && t > T::ZERO
        };
        let [hx, hz] = self.spacing().map(T::to_f64);
        let h = self.substep().to_f64();
        // The corner's quarter cell is the smallest mass; the Laplacian's largest weight.
        let corner_mass = self.areal_density.to_f64() * hx * hz / 4.0;
        let weight = 2.0 / (hx * hx) + 2.0 / (hz * hz);
        require(
            usable(hx) && usable(hz) && usable(1.0 / (hx * hx)) && usable(1.0 / (hz * hz)),
            "width",
            "such that the particle spacing and its inverse square are representable (with \
             height)",
            self.width.to_f64(),
        )?;
        require(
            usable(corner_mass) && usable(1.0 / corner_mass),
            "areal_density",
            "such that the particle masses are representable (with width and height)",
            self.areal_density.to_f64(),
        )?;
        require(
            usable(h * h) && usable(weight * weight / corner_mass),
            "substeps",
            "such that the squared substep and the stencil weights are representable (with \
             time_step)",
            f64::from(self.substeps),
        )?;
        let d = self.bending_stiffness.to_f64();
        require(
            d == 0.0 || usable(1.0 / (d * corner_mass / self.areal_density.to_f64() * h * h)),
            "bending_stiffness",
            "such that its compliance over the squared substep is representable",
            d,
        )?;
        for (field, alpha) in [
            ("stretch_compliance", self.stretch_compliance),
            ("shear_compliance", self.shear_compliance),
        ] {
            let a = alpha.to_f64();
            require(
                a == 0.0 || usable(a / (h * h)),
                field,
                "such that it is representable over the squared substep",
                a,
            )?;
        }
        Ok(())
    }
}
