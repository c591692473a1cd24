//! The page in physical units: its size (m), areal density (kg/m²), thickness (m) and
//! bending stiffness $D$ (N·m), and the one place where they become the book's
//! solver-facing settings ([`Paper::apply`]).
//!
//! **What decides the shape.** A page of width $L$ bending under its own weight is set by
//! one number, the sag number
//! $$\alpha = \frac{\rho\thinspace g\thinspace L^3}{D}$$
//! (the load parameter of the cantilever elastica under uniform self-weight): the bending
//! energy $\frac{D}{2}\int\kappa^2\thinspace dA$ against the potential energy
//! $\int\rho\thinspace g\thinspace y\thinspace dA$, both over the page, with lengths in
//! units of $L$. Two pages of one $\alpha$ take the same shapes at rest, whatever their
//! units. The book's discrete bending converges to $\frac{D}{2}\int\kappa^2 dA$ with
//! $D = 2 w_{\mathrm{bend3D}}$ ([`crate::quadrature`]), its masses to $\rho$ per area.
//!
//! **The book's units.** The book works in page units (the seed's page is 12 wide), page
//! masses (one page weighs 1 by default) and a gravity of 9.81 page units per second².
//! [`Paper::apply`] keeps the page width, the gravity, the page mass and every weight but
//! the page's bending: the soft isometry, the pull and its grip, the glue, the blocks'
//! bending and the contacts are penalties tuned against the page's *weight* (measured: a
//! novel page given its sag number by a 46 times heavier page mass, those weights kept,
//! could not be lifted off its block; with them scaled by the same 46 it turned). So it sets
//! the bending weight that gives the book's page the paper's $\alpha$, and the thickness
//! and the aspect ratio, and, for a page softer than the exact isometry Hessian holds
//! (`bend_page` below 30, every book paper), it asks for the projected one
//! ([`crate::IsometryHessian`]). A book of page units
//! $\ell = L/W_{pu}$ (m) and gravity $g_b$ then runs its seconds at
//! $\tau = \sqrt{g_b\thinspace\ell / g}$ real seconds ([`BookUnits`]): the book shows a
//! real page's shapes at a $1/\tau$ slower pace (the default book of an A5 page:
//! $\ell$ = 12.3 mm, $\tau$ = 0.11 s, nine times slower).
//!
//! **The default paper** ([`Paper::default`]) is an uncoated book paper of 80 g/m² on an
//! A5 page (148 x 210 mm, ISO 216), 0.1 mm thick (a density of 800 kg/m³), with Young's
//! modulus $E$ = 4 GPa and Poisson's ratio 0.3: $D = E t^3 / (12(1 - \nu^2))$ =
//! 3.66e-4 N·m, $\alpha$ = 6.9. The modulus is a mid value of the 2 to 8 GPa of
//! machine-made papers (in-plane moduli in Alava and Niskanen, *The physics of paper*,
//! Rep. Prog. Phys. 69 (2006) 669), the density a usual one for uncoated papers. The
//! default *book* ([`crate::BookSettings::default`]) is not this paper: its page has
//! $\alpha$ = 0.24 (page mass 1, $D$ = 344 page-unit energies), as stiff against its
//! weight as a card of about 400 g/m² of the same make, the page that the seed's weights
//! and the built-in gestures were tuned on. [`Paper::apply`] gives a book the real page,
//! and [`crate::Stock`] names the usual papers.

use core::fmt;

use folio_kernels::Real;
use folio_kernels::setting::{SettingError, require, require_range};

use super::error::BookError;
use super::quadrature;
use super::settings::BookSettings;

/// Standard gravity (m/s²) of the physical units.
pub const GRAVITY: f64 = 9.81;

/// A page's paper in physical units (module docs).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paper {
    /// Page width $L$ from the binding to the fore-edge (m).
    pub width: f64,
    /// Page height along the binding (m).
    pub height: f64,
    /// Sheet thickness $t$ (m).
    pub thickness: f64,
    /// Mass per area $\rho$ (kg/m², the grammage over 1000).
    pub areal_density: f64,
    /// Bending stiffness $D$ (N·m): the bending moment per unit width per unit curvature.
    pub bending_stiffness: f64,
}

impl Default for Paper {
    /// 80 g/m² book paper on an A5 page (module docs).
    fn default() -> Self {
        Self::from_modulus(0.148, 0.210, 1e-4, 0.080, 4e9, 0.3)
    }
}

/// How the book's units relate to the physical ones for one paper ([`Paper::units`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BookUnits {
    /// Metres per page unit, $\ell = L / W_{pu}$.
    pub length: f64,
    /// Real seconds per book second, $\tau = \sqrt{g_b \ell / g}$.
    pub time: f64,
    /// Kilograms per book mass unit: the page's mass over the book's page mass.
    pub mass: f64,
}

impl Paper {
    /// A paper from its elastic moduli: $D = E t^3 / (12 (1 - \nu^2))$, the plate bending
    /// stiffness of a sheet of Young's modulus `young` (Pa), Poisson's ratio `poisson`
    /// and thickness `thickness` (m). Sizes in m, `areal_density` in kg/m².
    #[must_use]
    pub fn from_modulus(
        width: f64,
        height: f64,
        thickness: f64,
        areal_density: f64,
        young: f64,
        poisson: f64,
    ) -> Self {
        let t3 = thickness * thickness * thickness;
        Self {
            width,
            height,
            thickness,
            areal_density,
            bending_stiffness: young * t3 / (12.0 * (1.0 - poisson * poisson)),
        }
    }

    /// `Ok` when every figure is finite and positive, the thickness below a tenth of the
    /// smaller side.
    ///
    /// # Errors
    /// The first figure that is not, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let figures = [
            ("paper.width", self.width),
            ("paper.height", self.height),
            ("paper.thickness", self.thickness),
            ("paper.areal_density", self.areal_density),
            ("paper.bending_stiffness", self.bending_stiffness),
        ];
        for (field, v) in figures {
            positive(field, v)?;
        }
        require(
            self.thickness <= 0.1 * self.width.min(self.height),
            "paper.thickness",
            "at most a tenth of the page's smaller side",
            self.thickness,
        )
    }

    /// The sag number $\alpha = \rho g L^3 / D$ (module docs).
    #[must_use]
    pub fn sag_number(&self) -> f64 {
        self.areal_density * GRAVITY * self.width * self.width * self.width / self.bending_stiffness
    }

    /// The book units of `settings` with this paper applied ([`BookUnits`]).
    #[must_use]
    pub fn units<T: Real>(&self, settings: &BookSettings<T>) -> BookUnits {
        let length = self.width / settings.params.page_width;
        let page_mass = self.areal_density * self.width * self.height;
        BookUnits {
            length,
            time: math_sqrt(settings.gravity.to_f64() * length / GRAVITY),
            mass: page_mass / settings.page_mass.to_f64(),
        }
    }

    /// Gives `settings`' page this paper (module docs): the aspect ratio $H/L$, the
    /// thickness $t/\ell$ in page units, the bending weight that makes the book's sag number
    /// $\rho_b g_b W_{pu}^3 / D_b$ this paper's $\alpha$, with $D_b = 2 w_{\mathrm{bend3D}}$
    /// and $\rho_b$ the page mass over the page's area in page units, and the projected
    /// isometry Hessian when that weight is below the exact Hessian's range (30). The page
    /// width, the gravity, the page mass and every other weight stay.
    ///
    /// # Errors
    /// As [`Paper::validate`]; [`BookError::InvalidSetting`] for settings whose page width,
    /// gravity or page mass is not positive and finite, or for a paper whose bending weight
    /// would leave its range (a sag number above about 167 at the default page mass:
    /// [`crate::SOFT_BEND_PAGE_MIN`]).
    pub fn apply<T: Real>(&self, settings: &mut BookSettings<T>) -> Result<(), BookError> {
        self.validate()?;
        let width = settings.params.page_width;
        let gravity = settings.gravity.to_f64();
        let mass = settings.page_mass.to_f64();
        positive("page_width", width)?;
        positive("gravity", gravity)?;
        positive("page_mass", mass)?;
        let aspect = self.height / self.width;
        let density = mass / (width * width * aspect);
        let stiffness = density * gravity * width * width * width / self.sag_number();
        let bend_page = stiffness / quadrature::bending_stiffness(1.0);
        let (lo, hi) = (crate::SOFT_BEND_PAGE_MIN, crate::WEIGHT_RANGES[0].2);
        require_range("weights.bend_page", bend_page, lo, hi)?;
        settings.params.aspect_ratio = aspect;
        settings.params.page_thickness = self.thickness * width / self.width;
        settings.weights.bend_page = T::from_f64(bend_page);
        if crate::IsometryHessian::for_bend_page(bend_page) == crate::IsometryHessian::Projected {
            settings.isometry_hessian = crate::IsometryHessian::Projected;
        }
        Ok(())
    }
}

impl fmt::Display for Paper {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:.0} x {:.0} mm, {:.0} g/m², {:.0} µm, D = {:.3e} N·m (sag number {:.2})",
            1e3 * self.width,
            1e3 * self.height,
            1e3 * self.areal_density,
            1e6 * self.thickness,
            self.bending_stiffness,
            self.sag_number()
        )
    }
}

/// `Ok` for a positive finite `v`, else the error naming `field`.
fn positive(field: &'static str, v: f64) -> Result<(), SettingError> {
    require(v.is_finite() && v > 0.0, field, "finite and > 0", v)
}

/// $\sqrt{x}$ in `f64` without `std`.
fn math_sqrt(x: f64) -> f64 {
    folio_kernels::math::sqrt(x)
}

#[cfg(test)]
mod tests {
    use super::{GRAVITY, Paper};
    use crate::BookSettings;
    use crate::quadrature::bending_stiffness;

    /// The plate formula by hand: 4e9 * 1e-12 / (12 * 0.91) = 3.663e-4 N·m.
    #[test]
    fn the_default_paper_has_the_plate_stiffness_of_its_modulus() {
        let p = Paper::default();
        assert!((p.bending_stiffness - 3.663e-4).abs() < 1e-7, "{p}");
        let alpha = 0.08 * 9.81 * 0.148f64.powi(3) / 3.663e-4;
        assert!(
            (p.sag_number() - alpha).abs() < 1e-3 * alpha,
            "{}",
            p.sag_number()
        );
        assert_eq!(p.validate(), Ok(()));
    }

    /// The book given a paper has the paper's sag number, computed from the book's own
    /// figures (page mass over area, gravity, width, D = 2 w_bend3D), for papers from a
    /// card to a tissue.
    #[test]
    fn a_book_given_a_paper_has_its_sag_number() {
        for grammage in [30.0, 80.0, 300.0] {
            let t = grammage * 1.25e-6;
            let paper = Paper::from_modulus(0.15, 0.23, t, grammage * 1e-3, 4e9, 0.3);
            let mut s = BookSettings::<f64>::default();
            paper.apply(&mut s).unwrap();
            let p = s.params;
            let rho = s.page_mass / (p.page_width * p.page_height());
            let d = bending_stiffness(s.weights.bend_page);
            let alpha = rho * s.gravity * p.page_width.powi(3) / d;
            assert!(
                (alpha / paper.sag_number() - 1.0).abs() < 1e-12,
                "{grammage}"
            );
            assert!((p.page_height() / p.page_width - 0.23 / 0.15).abs() < 1e-12);
            assert!((p.page_thickness / p.page_width - t / 0.15).abs() < 1e-15);
            let soft = crate::IsometryHessian::for_bend_page(s.weights.bend_page)
                == crate::IsometryHessian::Projected;
            let projected = s.isometry_hessian == crate::IsometryHessian::Projected;
            assert_eq!(projected, soft, "{grammage}");
            assert_eq!(s.page_mass, 1.0, "the page mass stays");
            let u = paper.units(&s);
            // The book's clock: g_b = g tau^2 / l.
            assert!((s.gravity - GRAVITY * u.time * u.time / u.length).abs() < 1e-9);
            assert_eq!(s.validate(), Ok(()));
        }
    }

    #[test]
    fn bad_paper_is_named() {
        let field = |p: Paper| match p.validate() {
            Err(e) => e.path.field(),
            other => panic!("{other:?}"),
        };
        let p = Paper::default();
        assert_eq!(
            field(Paper {
                width: f64::NAN,
                ..p
            }),
            "paper.width"
        );
        assert_eq!(field(Paper { height: 0.0, ..p }), "paper.height");
        assert_eq!(
            field(Paper {
                areal_density: -1.0,
                ..p
            }),
            "paper.areal_density"
        );
        assert_eq!(
            field(Paper {
                bending_stiffness: f64::INFINITY,
                ..p
            }),
            "paper.bending_stiffness"
        );
        assert_eq!(
            field(Paper {
                thickness: 0.05,
                ..p
            }),
            "paper.thickness"
        );
        let mut s = BookSettings::<f64> {
            page_mass: 0.0,
            ..BookSettings::default()
        };
        assert!(p.apply(&mut s).is_err());
        // A tissue of 12 g/m^2, 30 um, on an A3 page: a sag number of about 620, softer than
        // the book holds; refused at the bending weight it would need, the book unchanged.
        let tissue = Paper::from_modulus(0.297, 0.42, 30e-6, 0.012, 2e9, 0.3);
        let mut s = BookSettings::<f64>::default();
        let e = tissue.apply(&mut s).unwrap_err();
        assert!(e.to_string().contains("weights.bend_page"), "{e}");
        assert_eq!(s, BookSettings::default());
    }
}
