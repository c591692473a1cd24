//! Settings of the mass-spring page (seed `003_…` Sec. 2.1 and the experiment of Sec. 3.1).
//!
//! Units: lengths in page units, time in seconds, masses in page masses (the book's page weighs
//! 1; the seed's experiment gives each particle mass 1), forces in mass·length/s², spring
//! stiffness in force/length, the damping coefficient in force·time/length.

use folio_kernels::Real;

use folio_kernels::setting::{
    SettingError, require, require_non_negative, require_positive, require_time_step,
};

use crate::require_page_size;

/// Most particles per side: the sampler evaluates a Lagrange polynomial of degree up to
/// $n - 1$ per direction ([`super::LagrangeSurface`]), whose equispaced barycentric weights
/// $\binom{p}{k}$ stay finite in `f32` up to here; the global polynomial's Runge oscillation
/// is severe long before (module docs of [`super::lagrange`]), hence the local stencils of
/// [`SpringSettings::interpolation_degree`].
pub const MAX_PARTICLES_PER_SIDE: usize = 64;

/// Most integration substeps per frame ([`SpringSettings::substeps`]).
pub const MAX_SUBSTEPS: u32 = 64;

/// Most key frames a recording may be given (28 hours at 0.1 s); the recording is allocated
/// at setup, see [`super::KeyFrames`].
pub const MAX_KEY_FRAMES: usize = 1_000_000;

/// How a grab holds the page.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Grip {
    /// The whole particle column nearest the grabbed $u$ moves rigidly with the finger, as
    /// the seed's experiment moves its six edge particles (Sec. 3.1 step 2); the dog-ear
    /// groups of the synchronization are then the particle columns ([`super::sync`]). The
    /// default for the book page too: the held column is a rigid translate of its rest line,
    /// so the held material point follows the finger exactly (zero finger gap) and the
    /// finger's motion along the spine shears the page only as much as the springs let the
    /// free columns follow.
    Edge,
    /// Only the particle nearest the grabbed point moves with the finger; the dog-ear groups
    /// are perpendicular to the finger's displacement (seed Fig. 4, a dog ear). On a page
    /// turn one particle drags the whole page: on the shared page turn with the default
    /// springs the page stretches far more than with [`Grip::Edge`] and the held material
    /// point lags the finger (measured in the module docs of [`super`]).
    Point,
}

/// The time integrator of the free particles.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Integrator {
    /// The seed's semi-implicit (symplectic) Euler, Sec. 3.1 steps 3-5:
    /// $v^{n+1} = v^n + h F(x^n, v^n)/m$, $x^{n+1} = x^n + h v^{n+1}$. Explicit in the forces:
    /// stable only while $h\thinspace\omega_{max} < 2$ ($\omega_{max}^2 \approx 4 \sum k / m$ over the
    /// three spring families), $h$ the substep $h/n$ with [`SpringSettings::substeps`].
    SemiImplicitEuler,
    /// Implicit Euler by [`folio_solvers::Solver`] (seed `000_…` eq. 2-4) on the same springs, with the
    /// particle damping taken implicitly too ([`super::SpringNetwork`]); one Newton iteration
    /// with line search per frame. Unconditionally stable in the linearised sense; costs a
    /// sparse $LDL^\top$ factorization per frame.
    ImplicitEuler,
}

/// Settings of a [`super::SpringPage`] (module docs for units); [`SpringSettings::validate`]
/// checks them.
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpringSettings<T: Real> {
    /// Particles across the page, $n_x$, in $[2, 64]$ ([`MAX_PARTICLES_PER_SIDE`]).
    pub particles_across: usize,
    /// Particles along the spine, $n_z$, in $[2, 64]$.
    pub particles_along: usize,
    /// Page width $W$ (page units), finite, $> 0$.
    pub width: T,
    /// Page height $H$ (page units), finite, $> 0$.
    pub height: T,
    /// Mass of one particle $m$, finite, $> 0$.
    pub particle_mass: T,
    /// Stiffness $k$ of the stretch springs (grid neighbours), finite, $\ge 0$.
    pub stretch_stiffness: T,
    /// Stiffness $k$ of the shear springs (cell diagonals), finite, $\ge 0$.
    pub shear_stiffness: T,
    /// Stiffness $k$ of the bend springs (two apart along a grid line), finite, $\ge 0$.
    pub bend_spring_stiffness: T,
    /// Plate bending stiffness $D$ of the page (energy: mass·length²/s², N·m in SI), finite,
    /// $\ge 0$: the plate term $V_{\mathrm{bend}}$ of [`super::bending`] (second
    /// differences and cell twists on the rest grid), which tends to
    /// $\frac D2\int\kappa_1^2 + \kappa_2^2\,dA$ at every grid. Default 0
    /// (no term: the seed's page bends by its bend springs alone, which have no linear
    /// bending stiffness, see [`super::bending`]). Not the bend springs' `bend_spring_stiffness`.
    pub bending_stiffness: T,
    /// Particle masses by area ([`super::bending::mass_share`]): an inner particle weighs
    /// `particle_mass`, an edge particle half of it and a corner a quarter, and likewise
    /// `particle_weight`, so that a page of areal density $\rho$ is $\rho$ everywhere
    /// (`particle_mass` $= \rho h_x h_z$). Off (the default, the seed's): every particle
    /// weighs `particle_mass`. The particle damping $c\thinspace v$ stays one coefficient for
    /// every particle.
    pub area_masses: bool,
    /// Particle damping coefficient $c$ of $F = c\thinspace v$ (seed Sec. 3.1: $c = -0.7125$), finite,
    /// $\le 0$ (a positive coefficient would feed energy in).
    pub damping: T,
    /// Gravity force on one particle, $m g$, along −Y (seed Sec. 3.1: 0.00981), finite,
    /// $\ge 0$.
    pub particle_weight: T,
    /// Time step $h$ of one frame (seconds), finite, $> 0$. Default $1/60$.
    pub time_step: T,
    /// Integration substeps $n$ per frame, in $[1, 64]$ ([`MAX_SUBSTEPS`]): the integrator,
    /// the synchronization and the table run $n$ times per frame with the step $h/n$, the
    /// gripped particles moving on the straight line to their frame target. Numerics, not
    /// physics (the seed's experiment takes one step per frame, $n = 1$): the explicit
    /// integrator is stable while $(h/n)\thinspace\omega_{max} < 2$, so $n$ substeps allow springs
    /// $n^2$ times stiffer. With [`Integrator::ImplicitEuler`] each substep is one sparse
    /// solve; one per frame is already stable there. Default 8.
    pub substeps: u32,
    /// Seconds between key frames of the recording (seed Sec. 3.1 step 7: 0.1 s), finite,
    /// $> 0$; rounded to a whole number of frames, at least one.
    pub key_frame_interval: T,
    /// Key frames the recording holds, at most [`MAX_KEY_FRAMES`]; allocated at setup (see
    /// [`super::KeyFrames`] for the memory), 0 records nothing. Later key frames are dropped
    /// once it is full. Default 100 (10 s).
    pub key_frame_capacity: usize,
    /// What a grab holds.
    pub grip: Grip,
    /// The particle column at $u = 0$ is fixed at rest (the seed's fixed edge, Sec. 3.1
    /// step 2).
    pub fixed_spine: bool,
    /// With `fixed_spine` and a plate term ($D > 0$): the spine is a clamp, holding the
    /// page's tangent there along $\pm X$ by a ghost particle mirrored across the spine
    /// ([`super::bending::SpineClamp`]). Off (the default): a hinge.
    pub clamped_spine: bool,
    /// How the free particles are advanced.
    pub integrator: Integrator,
    /// Synchronize along the dog-ear line after each substep (seed Sec. 2.2.1,
    /// [`super::Synchronizer`]).
    pub sync: bool,
    /// A table under the page: the plane $y = 0$ as a one-sided inelastic, frictionless
    /// contact for free particles (after each substep a particle on or under it, $y \le 0$,
    /// is put on it, $y = 0$, and loses its downward velocity, $v_y < 0 \Rightarrow v_y = 0$;
    /// a particle above it falls freely), and for the points of the render surface
    /// ([`super::LagrangeSurface::with_floor`]). Not in the seed; without it an unheld page
    /// hangs from its spine.
    pub floor: bool,
    /// Degree $p \ge 1$ of the render surface's Lagrange interpolation per direction: each
    /// render point interpolates the $p + 1$ particles per direction nearest it
    /// ([`super::lagrange`]); at or above $n - 1$ particles in a direction this is the seed's
    /// global polynomial through all of them (Sec. 2.2.2). Default 3 (cubic): a departure
    /// from the seed for more than about 6 particles per side, where the global polynomial
    /// oscillates (Runge; measured on the book page in [`super::lagrange`]).
    pub interpolation_degree: usize,
    /// Provot's critical deformation rate $\tau$ ([`super::limit`]): after every substep no
    /// stretch or shear spring is left longer than $(1 + \tau)L^0$ or shorter than
    /// $(1 - \tau)L^0$, and the finger's translation of the gripped particles is cut to what
    /// the page can reach. In $[0.02, 0.08]$, or `None` for the seed's plain springs (which a
    /// quick finger stretched without bound: render grid 73x on a 3-frame flick). Default
    /// $0.08$: Provot takes 10 %, but the render surface between the links measures more than
    /// the links at folds (10.5 % with 10 % links on a flick, measured), and 10 % is the run's
    /// health bound; below 0.02 the sweeps stop short of the bound (a draw at $10^{-3}$
    /// measured 10.8 %).
    pub strain_limit: Option<T>,
}

impl<T: Real> Default for SpringSettings<T> {
    /// The shared book page: $W = 12$, $H = 12\sqrt2$, $9 \times 12$ particles, unit page mass
    /// spread over the particles ($m = 1/108$), gravity $9.81\thinspace m$ per particle, the seed's
    /// damping rate ($c = -0.7125\thinspace m$, i.e. $0.7125\thinspace\mathrm{s}^{-1}$), the spine fixed, an
    /// edge grip, semi-implicit Euler at $h = 1/60$ in 8 substeps with synchronization, a
    /// table under the page, and a cubic render surface.
    ///
    /// **Stiffness**, per unit particle mass, as stiff as the explicit integrator allows:
    /// $k/m = 115200, 28800, 28800\ \mathrm{s}^{-2}$ for stretch, shear and bend
    /// ($k = 1067, 267, 267$). The largest frequency of the flat network with the spine
    /// fixed, measured by power iteration on its stiffness matrix (`omega_max` in
    /// `tests/tests/page_spring.rs`), is $\omega_{max} = 756\ \mathrm{s}^{-1}$; with
    /// $n = 8$ substeps, $(h/n)\thinspace\omega_{max} = 1.58 < 2$ at $h = 1/60$ (the explicit
    /// stability bound, [`Integrator::SemiImplicitEuler`]). That is the same margin as the
    /// earlier default of one step per frame and $k/m = 1800, 450, 450$
    /// ($\omega_{max} = 94.5$, $h\thinspace\omega_{max} = 1.58$): stiffness grows with $n^2$.
    /// Stiffer springs are what keeps the page from stretching under the finger: on the
    /// shared page turn (`TouchScript::page_turn`, render grid $24 \times 34$ quads) the
    /// particle grid's max stretch per frame averages 0.8 % (worst 2.8 %) and the render
    /// grid's 1.5 % (worst 6.0 %), against 9.3 % and 14.7 % with the earlier springs and one
    /// step per frame, and 2.0 % and 3.5 % at $n = 4$ with $k/m$ 16 times the earlier. A page
    /// hanging at rest from its spine under its own weight (no table) stretches by 0.03 %,
    /// against 1.8 % with the earlier springs and 14 % with the seed's $k = 1$ at this mass
    /// (all measured). Cost: 8 evaluations of the 545 springs per frame.
    fn default() -> Self {
        let (nx, nz) = (9usize, 12usize);
        let mass = 1.0 / (nx * nz) as f64;
        Self {
            particles_across: nx,
            particles_along: nz,
            width: T::from_f64(12.0),
            height: T::from_f64(12.0 * core::f64::consts::SQRT_2),
            particle_mass: T::from_f64(mass),
            stretch_stiffness: T::from_f64(115_200.0 * mass),
            shear_stiffness: T::from_f64(28_800.0 * mass),
            bend_spring_stiffness: T::from_f64(28_800.0 * mass),
            bending_stiffness: T::ZERO,
            area_masses: false,
            damping: T::from_f64(-0.7125 * mass),
            particle_weight: T::from_f64(9.81 * mass),
            time_step: T::from_f64(1.0 / 60.0),
            substeps: 8,
            key_frame_interval: T::from_f64(0.1),
            key_frame_capacity: 100,
            grip: Grip::Edge,
            fixed_spine: true,
            clamped_spine: false,
            integrator: Integrator::SemiImplicitEuler,
            sync: true,
            floor: true,
            interpolation_degree: 3,
            strain_limit: Some(T::from_f64(0.08)),
        }
    }
}

/// A page by its physical properties (issue 21), for [`SpringSettings::physical`]; any
/// consistent units (SI: m, kg/m², N·m, m/s²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalPage<T> {
    /// Width $W$ across the page (from the spine), length.
    pub width: T,
    /// Height $H$ along the spine, length.
    pub height: T,
    /// Areal density $\rho$, mass per area.
    pub areal_density: T,
    /// Bending stiffness $D$, energy (N·m): the moment per unit width per unit curvature.
    pub bending_stiffness: T,
    /// Gravity $g$, length/s², along −Y.
    pub gravity: T,
    /// Membrane stiffness $Y$, force per length (N/m): the in-plane force per unit width
    /// per unit strain. Numerics more than paper: paper's $Et$ (about $10^5$–$10^6$ N/m) is
    /// far beyond what an explicit step can follow, so take it as stiff as the integrator
    /// allows; the page stretches by about $\rho g L/Y$ under its own weight. Unlike the
    /// default page's springs ($k/m$ fixed), $Y$ keeps the page's stretch the same at every
    /// grid.
    pub membrane_stiffness: T,
}

impl<T: Real> SpringSettings<T> {
    /// The experiment of seed `003_…` Sec. 3.1: $6 \times 6$ particles 5 apart (a
    /// $25 \times 25$ page; its $26 \times 26$ render points are the caller's render grid),
    /// gravity 0.00981 per particle, every spring constant 1.0, damping $-0.7125$, particle
    /// mass 1, the spine column fixed, the opposite edge column held ([`Grip::Edge`]),
    /// semi-implicit Euler at $h = 1/60$ in one step per frame with synchronization, key
    /// frames every 0.1 s, no table, and the seed's global Lagrange polynomial through all
    /// particles (degree 5).
    #[must_use]
    pub fn seed_experiment() -> Self {
        Self {
            particles_across: 6,
            particles_along: 6,
            width: T::from_f64(25.0),
            height: T::from_f64(25.0),
            particle_mass: T::ONE,
            stretch_stiffness: T::ONE,
            shear_stiffness: T::ONE,
            bend_spring_stiffness: T::ONE,
            bending_stiffness: T::ZERO,
            area_masses: false,
            damping: T::from_f64(-0.7125),
            particle_weight: T::from_f64(0.00981),
            time_step: T::from_f64(1.0 / 60.0),
            substeps: 1,
            key_frame_interval: T::from_f64(0.1),
            key_frame_capacity: 100,
            grip: Grip::Edge,
            fixed_spine: true,
            clamped_spine: false,
            integrator: Integrator::SemiImplicitEuler,
            sync: true,
            floor: false,
            interpolation_degree: 5,
            strain_limit: Some(T::from_f64(0.08)),
        }
    }

    /// A page described physically (issue 21, [`super::bending`]) on `particles`
    /// $= [n_x, n_z]$ particles: the size, areal density $\rho$, bending stiffness $D$ and
    /// gravity $g$ of `page` in one consistent set of units (SI: m, kg/m², N·m, m/s²). This is
    /// where the physical description becomes the solver-facing settings:
    /// - masses by area ([`SpringSettings::area_masses`]): `particle_mass` $= \rho h_x h_z$
    ///   and `particle_weight` $= \rho h_x h_z\thinspace g$ (an inner particle's);
    /// - `bending_stiffness` $= D$, the plate term of [`super::bending`];
    /// - no bend springs (`bend_spring_stiffness` 0): they have no linear bending stiffness and would
    ///   stiffen the page as it bends ([`super::bending::bend_spring_equivalent`]);
    /// - stretch springs of stiffness $Y$, the page's membrane stiffness
    ///   ([`PhysicalPage::membrane_stiffness`]; a spring of a square cell carries a strip as
    ///   wide as it is long, so $k = Y$ whatever the spacing), shear springs $Y/4$ (the
    ///   default's ratio);
    /// - the damping at the default's rate, $c/m = -0.7125\ \mathrm{s}^{-1}$.
    ///
    /// The rest are the defaults ([`SpringSettings::default`]: the spine fixed as a hinge;
    /// [`SpringSettings::clamped_spine`] makes it a clamp); the caller picks the
    /// integrator and substeps (the explicit one must pass [`SpringSettings::validate`]; a
    /// stiff page needs more substeps, [`super::bending::omega_squared_bound`]).
    #[must_use]
    pub fn physical(page: &PhysicalPage<T>, particles: [usize; 2]) -> Self {
        let [nx, nz] = particles;
        let s = Self {
            particles_across: nx,
            particles_along: nz,
            width: page.width,
            height: page.height,
            ..Self::default()
        };
        let [hx, hz] = s.spacing();
        let m = page.areal_density * hx * hz;
        Self {
            particle_mass: m,
            particle_weight: m * page.gravity,
            stretch_stiffness: page.membrane_stiffness,
            shear_stiffness: page.membrane_stiffness * T::from_f64(0.25),
            bend_spring_stiffness: T::ZERO,
            bending_stiffness: page.bending_stiffness,
            area_masses: true,
            damping: m * T::from_f64(-0.7125),
            ..s
        }
    }

    /// Particle spacing across and along, $(W/(n_x - 1), H/(n_z - 1))$.
    #[must_use]
    pub fn spacing(&self) -> [T; 2] {
        let gaps = |n: usize| T::from_f64(n.saturating_sub(1).max(1) as f64);
        [
            self.width / gaps(self.particles_across),
            self.height / gaps(self.particles_along),
        ]
    }

    /// What the flat page's plate term and stability bound read of these settings
    /// ([`super::bending::FlatPage`]).
    #[must_use]
    pub fn flat_page(&self) -> super::bending::FlatPage {
        super::bending::FlatPage {
            grid: folio_geometry::QuadGrid {
                nx: self.particles_across,
                nz: self.particles_along,
            },
            spacing: self.spacing().map(|h| h.to_f64()),
            clamped_spine: self.fixed_spine && self.clamped_spine,
            spring_stiffness: self.stretch_stiffness.to_f64()
                + self.shear_stiffness.to_f64()
                + self.bend_spring_stiffness.to_f64(),
            plate_stiffness: self.bending_stiffness.to_f64(),
            particle_mass: self.particle_mass.to_f64(),
            area_masses: self.area_masses,
        }
    }

    /// The flat page's largest $\omega^2$, bounded ([`super::bending::omega_squared_bound`]
    /// of [`SpringSettings::flat_page`]).
    #[must_use]
    pub fn omega_squared_bound(&self) -> f64 {
        super::bending::omega_squared_bound(&self.flat_page())
    }

    /// The integration step $h/n$ of one substep (seconds).
    #[must_use]
    pub fn substep(&self) -> T {
        self.time_step / T::from_f64(f64::from(self.substeps.max(1)))
    }

    /// Frames between key frames: $\max(1, \mathrm{round}(\text{interval}/h))$ (the interval
    /// rounded to whole frames; 6 for 0.1 s at 60 frames per second).
    #[must_use]
    pub fn key_frame_stride(&self) -> u32 {
        let r = (self.key_frame_interval / self.time_step).to_f64() + 0.5;
        if r.is_finite() && r >= 1.0 {
            if r >= f64::from(u32::MAX) {
                u32::MAX
            } else {
                r as u32
            }
        } else {
            1
        }
    }

    /// Checks every field against its documented range, and the explicit integrator's
    /// stability limits when it is chosen.
    ///
    /// # Errors
    /// The first bad field, its rule and its value.
    pub fn validate(&self) -> Result<(), SettingError> {
        let count = |n: usize| (2..=MAX_PARTICLES_PER_SIDE).contains(&n);
        let positive = |x: T| x.is_finite() && x > T::ZERO;
        let real = |x: T| x.to_f64();
        for (field, n) in [
            ("particles_across", self.particles_across),
            ("particles_along", self.particles_along),
        ] {
            require(count(n), field, "from 2 to 64", n as f64)?;
        }
        require_page_size(self.width, self.height)?;
        require_positive("particle_mass", real(self.particle_mass))?;
        for (field, v) in [
            ("stretch_stiffness", self.stretch_stiffness),
            ("shear_stiffness", self.shear_stiffness),
            ("bend_spring_stiffness", self.bend_spring_stiffness),
            ("bending_stiffness", self.bending_stiffness),
            ("particle_weight", self.particle_weight),
        ] {
            require_non_negative(field, real(v))?;
        }
        require(
            self.damping.is_finite() && self.damping <= T::ZERO,
            "damping",
            "finite and <= 0 (the force is c v)",
            real(self.damping),
        )?;
        require_time_step(real(self.time_step))?;
        require(
            (1..=MAX_SUBSTEPS).contains(&self.substeps),
            "substeps",
            "from 1 to 64",
            f64::from(self.substeps),
        )?;
        require_positive("key_frame_interval", real(self.key_frame_interval))?;
        let spacing = self.spacing();
        let small = T::from_f64(1e-3);
        require(
            positive(spacing[0] * small) && positive(spacing[1] * small),
            "width",
            "large enough that the particle spacing (and a thousandth of it) does not \
             underflow",
            real(self.width),
        )?;
        require(
            self.key_frame_capacity <= MAX_KEY_FRAMES,
            "key_frame_capacity",
            "at most 1000000",
            self.key_frame_capacity as f64,
        )?;
        require(
            self.interpolation_degree >= 1,
            "interpolation_degree",
            "at least 1",
            self.interpolation_degree as f64,
        )?;
        if let Some(tau) = self.strain_limit {
            let ok = tau.is_finite() && tau >= T::from_f64(0.02) && tau <= T::from_f64(0.08);
            require(ok, "strain_limit", "in [0.02, 0.08]", real(tau))?;
        }
        if self.integrator == Integrator::SemiImplicitEuler {
            self.check_explicit()?;
        }
        Ok(())
    }

    /// The explicit integrator's stability limits ([`Integrator::SemiImplicitEuler`]), with
    /// $h$ the substep: the springs $h\thinspace\omega_{max} \le 2$ with
    /// $\omega_{max}^2 = 4\sum k/m$ over the three families (an upper estimate: the default
    /// page measures $\omega_{max}^2 = 3.3\sum k/m$), with the plate term and the lighter
    /// edge particles of [`SpringSettings::area_masses`] added as in
    /// [`super::bending::omega_squared_bound`], and the particle damping
    /// $h\lvert c\rvert/m \le 1$ ($m/4$, a corner's, with area masses) (beyond it
    /// $v \mathrel{+}= h c v/m$ reverses the velocity instead of slowing it). Settings past
    /// either limit were accepted before and made every step blow up (and stall); they are
    /// refused here, at `substeps` (more substeps shorten $h$).
    ///
    /// # Errors
    /// The limit crossed, at `substeps`.
    fn check_explicit(&self) -> Result<(), SettingError> {
        let h = self.substep().to_f64();
        let lightest = if self.area_masses { 0.25 } else { 1.0 };
        let m = self.particle_mass.to_f64();
        let omega2 = self.omega_squared_bound();
        let spring_rate = h * folio_kernels::math::sqrt::<f64>(omega2);
        let substeps = f64::from(self.substeps);
        require(
            spring_rate <= 2.0,
            "substeps",
            "enough for the explicit integrator's springs: (time_step / substeps) * \
             sqrt(4 (k_stretch + k_shear + k_bend) / m) <= 2, with the plate bending and \
             area masses as in spring::bending::omega_squared_bound",
            substeps,
        )?;
        let damping_rate = h * -self.damping.to_f64() / (m * lightest);
        require(
            damping_rate <= 1.0,
            "substeps",
            "enough for the explicit integrator's damping: (time_step / substeps) * \
             |damping| / m <= 1",
            substeps,
        )
    }
}
