//! [`SheetSettings`]: the tearing sheet's size, mesh, material and effects.
//!
//! **Units.** Lengths in sheet units, time in seconds, masses and forces in the units in
//! which the seed's fracture constant $c = 0.005$ (eq. 3) is given: the seed leaves them
//! open. The defaults make paper of thickness $e = 0.01$ that tears when its lips are
//! stretched by a few tenths of a percent (a real sheet fails near 1-3 % strain, but the
//! coarse mesh spreads the stress concentration at a tip over a whole triangle).

use crate::TearSettings;
use folio_geometry::sheet::ConeLayerSettings;
use folio_kernels::Real;
use folio_kernels::membrane::MembraneLaw;

use folio_kernels::setting::{
    SettingError, require, require_non_negative, require_positive, require_range, require_time_step,
};

/// The effects a tearing scene may call for; what is off builds no term and does no work.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SheetEffects {
    /// Gravity on the nodes.
    pub gravity: bool,
    /// The bending energy (hinges).
    pub bending: bool,
    /// The generalized-cone layer and its remesh (junction points need it).
    pub cones: bool,
    /// Tearing (seed `002_…`).
    pub tearing: bool,
}

impl SheetEffects {
    /// Every effect of the tearing sheet by its scene name, in the order scenes and reports
    /// list them: the one list of the names.
    pub const NAMES: [&'static str; 4] = ["gravity", "bending", "cones", "tearing"];

    /// None at all: the bare membrane.
    pub const NONE: Self = Self {
        gravity: false,
        bending: false,
        cones: false,
        tearing: false,
    };

    /// Switches the effect named `name` on; `false` for a name that is none of
    /// [`SheetEffects::NAMES`].
    pub fn enable(&mut self, name: &str) -> bool {
        let flags = [
            &mut self.gravity,
            &mut self.bending,
            &mut self.cones,
            &mut self.tearing,
        ];
        let at = Self::NAMES.iter().position(|n| *n == name);
        match at.and_then(|i| flags.into_iter().nth(i)) {
            Some(flag) => {
                *flag = true;
                true
            }
            None => false,
        }
    }
}

impl Default for SheetEffects {
    /// Bending, cones and tearing on; gravity off (the hands hold the sheet).
    fn default() -> Self {
        Self {
            gravity: false,
            bending: true,
            cones: true,
            tearing: true,
        }
    }
}

/// What the hinges' bending energy counts ([`folio_kernels::hinge`]).
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HingeBending {
    /// The paper's quadratic energy $c\lVert s\rVert^2$ (Bergou et al. 2006): folds, and
    /// also in-plane deformations that are not affine, which stiffens a tear tip's field on
    /// every finer mesh.
    Bergou,
    /// Only the fold: $c(\hat n \cdot s)^2$ with the hinge's normal set at the start of each
    /// step; the membrane alone carries in-plane deformation, so the energy a tear releases
    /// converges with the mesh (`folio_tearing::release`).
    Folds,
}

/// Settings of [`super::TearingSheet`].
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SheetSettings<T: Real> {
    /// Pattern width $W$ (sheet units).
    pub width: T,
    /// Pattern height $H$ (sheet units).
    pub height: T,
    /// Quads across (two triangles each).
    pub nx: usize,
    /// Quads up.
    pub ny: usize,
    /// 2D Young's modulus $Y$ of the membrane (force per sheet unit).
    pub stretch_modulus: T,
    /// Poisson's ratio $\nu \in [0, 0.5)$.
    pub poisson: T,
    /// Weight of the hinge bending energy (force times sheet unit).
    pub bending: T,
    /// What the hinges count.
    pub hinge_bending: HingeBending,
    /// Whether the membrane wrinkles under compression: the relaxed, tension-field energy
    /// ([`MembraneLaw::TensionField`]), in which a compressed direction carries no stress
    /// (paper buckles at a compressive stress far below its tensile stiffness, into wrinkles
    /// finer than the mesh, and its bending decides their shape); `false` resists
    /// compression like tension (Saint Venant–Kirchhoff). Experimental with tearing: the
    /// tear estimators assume a linear-elastic field at the tip, and with wrinkling the tear
    /// scenes branch or stall (`docs/scenes.md`).
    pub wrinkling: bool,
    /// Mass per pattern area.
    pub density: T,
    /// Gravitational acceleration along −Y (sheet units / s²), when gravity is on.
    pub gravity: T,
    /// Time step (seconds).
    pub time_step: T,
    /// Radius of a finger's pad (sheet units): a finger holds every vertex within this
    /// pattern distance of its point, so that its pull does not depend on the mesh (a
    /// single pinched vertex is a point load, whose stiffness falls like $1/\ln(L/h)$ as the
    /// cells shrink). 0 holds the one vertex at the point.
    pub finger_radius: T,
    /// Propagations per frame at most, each followed by a relaxation step (seed Fig. 4,
    /// step 4).
    pub max_propagations: u32,
    /// Vertices the sheet makes room for at setup beyond its mesh's (tears and finger pads
    /// add vertices): in the mesh, the model, the cone layer, the tearing step and the
    /// solver ([`folio_solvers::step::Solver::reserve`]), so that a frame that tears
    /// allocates nothing while the mesh stays within them, including a split, whose new
    /// topology the solver analyses again in its reserved buffers. In [0, 1 048 576].
    /// Default 256 (a tear adds at most three per propagation).
    pub reserved_vertices: usize,
    /// The effects.
    pub effects: SheetEffects,
    /// The cone layer's thresholds.
    pub cones: ConeLayerSettings<T>,
    /// The tearing step's parameters.
    pub tearing: TearSettings,
}

impl<T: Real> Default for SheetSettings<T> {
    /// A 12 x 9 sheet of 8 x 6 quads (96 triangles), $Y = 0.003$, $\nu = 0.3$, bending
    /// $10^{-5}$, density $10^{-8}$ (stiff at $h = 1/60$: $Y h^2 / m \approx 70$ per node),
    /// gravity 9.81 when on, finger pads of radius 0.7 (one vertex on this mesh; about 1.4 cm
    /// if the sheet is an A4 page's 21 cm across), two propagations per frame, room for 256
    /// more vertices.
    fn default() -> Self {
        Self {
            width: T::from_f64(12.0),
            height: T::from_f64(9.0),
            nx: 8,
            ny: 6,
            stretch_modulus: T::from_f64(3e-3),
            poisson: T::from_f64(0.3),
            bending: T::from_f64(1e-5),
            hinge_bending: HingeBending::Bergou,
            wrinkling: false,
            density: T::from_f64(1e-8),
            gravity: T::from_f64(9.81),
            time_step: T::from_f64(1.0 / 60.0),
            finger_radius: T::from_f64(0.7),
            max_propagations: 2,
            reserved_vertices: 256,
            effects: SheetEffects::default(),
            cones: ConeLayerSettings::default(),
            tearing: TearSettings::default(),
        }
    }
}

impl<T: Real> SheetSettings<T> {
    /// The membrane's law: [`MembraneLaw::TensionField`] when [`SheetSettings::wrinkling`].
    #[must_use]
    pub fn membrane_law(&self) -> MembraneLaw {
        if self.wrinkling {
            MembraneLaw::TensionField
        } else {
            MembraneLaw::StVenantKirchhoff
        }
    }

    /// Checks every field.
    ///
    /// # Errors
    /// The first bad field by its path from these settings (`nx`, `cones.flip_margin`,
    /// `tearing.fibers.scale`), its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let real = |x: T| x.to_f64();
        for (field, v) in [
            ("width", self.width),
            ("height", self.height),
            ("stretch_modulus", self.stretch_modulus),
            ("density", self.density),
        ] {
            require_positive(field, real(v))?;
        }
        for (field, n) in [("nx", self.nx), ("ny", self.ny)] {
            require((1..=64).contains(&n), field, "from 1 to 64", n as f64)?;
        }
        let poisson = self.poisson;
        require(
            poisson.is_finite() && poisson >= T::ZERO && poisson < T::HALF,
            "poisson",
            "in [0, 0.5)",
            real(poisson),
        )?;
        require_non_negative("bending", real(self.bending))?;
        let gravity = real(self.gravity);
        require(gravity.is_finite(), "gravity", "finite", gravity)?;
        require_time_step(real(self.time_step))?;
        let r = self.finger_radius;
        require(
            r.is_finite() && r >= T::ZERO && r <= self.width + self.height,
            "finger_radius",
            "finite, >= 0 and at most width + height",
            real(r),
        )?;
        require(
            self.max_propagations <= 64,
            "max_propagations",
            "at most 64",
            f64::from(self.max_propagations),
        )?;
        require(
            self.reserved_vertices <= 1 << 20,
            "reserved_vertices",
            "at most 1 048 576",
            self.reserved_vertices as f64,
        )?;
        let c = &self.cones;
        require_non_negative("cones.flat_curvature", real(c.flat_curvature))?;
        require_range("cones.flip_margin", real(c.flip_margin), 0.0, 1.0)?;
        self.tearing.validate().map_err(|e| e.within("tearing"))
    }
}

#[cfg(test)]
mod tests {
    use super::SheetEffects;

    /// Each name switches on its own flag and no other.
    #[test]
    fn each_name_is_its_own_flag() {
        let flags = |e: SheetEffects| [e.gravity, e.bending, e.cones, e.tearing];
        for (i, name) in SheetEffects::NAMES.into_iter().enumerate() {
            let mut e = SheetEffects::NONE;
            assert!(e.enable(name), "{name}");
            let on = flags(e);
            assert!(on[i] && on.iter().filter(|f| **f).count() == 1, "{name}");
        }
        let mut none = SheetEffects::NONE;
        assert!(!none.enable("glue"));
    }
}
