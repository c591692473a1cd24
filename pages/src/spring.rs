//! The mass-spring page of seed `003_…`: a grid of particles joined by Provot's stretch,
//! shear and bend springs (Sec. 2.1), advanced by semi-implicit Euler (Sec. 3.1) or, as an
//! alternative, implicit Euler, with the seed's three improvements:
//! - **synchronization** along the dog-ear line after every step (Sec. 2.2.1,
//!   [`Synchronizer`]),
//! - **Lagrange interpolation** of the render surface through the few particles
//!   (Sec. 2.2.2, [`LagrangeSurface`]; local stencils of a chosen degree, a documented
//!   departure for more than about 6 particles per side),
//! - **key frames** recorded while simulating and replayed without simulating (Sec. 2.2.3,
//!   [`KeyFrames`], [`ReplayPage`]).
//!
//! **Physical units** (issue 21, [`bending`]): Provot's bend springs have no linear bending
//! stiffness (their energy is quartic in the curvature, derived there), so a page described
//! by its bending stiffness $D$ and areal density ([`SpringSettings::physical`],
//! [`PhysicalPage`]) bends by a plate term of its own, with masses by area; clamped at the
//! spine ([`SpringSettings::clamped_spine`]) it sags like the cantilever elastica, within
//! 2 % on the default grid and 0.5 % at twice its resolution
//! (`tests/tests/elastica_spring.rs`). The default page keeps the seed's springs, equal
//! masses and a hinged spine ($D = 0$).
//!
//! **One frame** ([`PageModel::step`]), after the seed's flow (Sec. 3.1, Fig. 5), is $n$
//! substeps of $h/n$ ([`SpringSettings::substeps`]; the seed's experiment takes $n = 1$),
//! each:
//! 1. the gripped particles are placed on the way to the finger (below);
//! 2. the free particles are advanced by the integrator ([`explicit`], [`implicit`]) under the
//!    springs, the particle damping $c\thinspace v$ and gravity;
//! 3. synchronization (if on);
//! 4. the table (if on): a free particle on or under the plane $y = 0$ is put on it,
//!    $y = 0$, and loses its downward velocity, $v_y < 0 \Rightarrow v_y = 0$; a particle
//!    above it is left alone;
//! 5. Provot's correction (if [`SpringSettings::strain_limit`] is set, the default):
//!    stretch and shear springs put back within $\tau$ of their rest lengths, a row pushed
//!    together buckles ([`limit`]);
//!
//! and after the last substep a key frame is recorded every key-frame interval.
//!
//! A step that would leave a non-finite coordinate, or one beyond [`Real::COORD_MAX`] (or
//! whose implicit solve fails, or whose strain limit is not reached), restores the previous state and reports
//! [`PageStatus::Stalled`] (an explicit step past its stability limit ends there). A stalled
//! frame still counts: the frame clock and the key frames go on.
//!
//! **Touch.** A grab at the material point $(u, v)$ picks the particle column nearest $u$
//! ([`Grip::Edge`], the seed's moved edge, the default) or the particle nearest $(u, v)$
//! ([`Grip::Point`]); fixed particles are never gripped. While the finger is at $G$, a
//! gripped particle $k$ is kinematic with the target $\bar x_k + (G - P)$, $\bar x_k$ its rest
//! position and $P = (u, 0, v)$ the grabbed rest point: in substep $s$ of $n$ it is at
//! $x_k^0 + \tfrac{s}{n}(\bar x_k + G - P - x_k^0)$ ($x_k^0$ its position at the start of the
//! frame) with the velocity $(\bar x_k + G - P - x_k^0)/h$. With the strain limit on, the
//! translation $G - P$ is first cut to what the page can reach from its fixed spine
//! ([`limit::reach`]), and such a frame reports [`PageStatus::Unreachable`]: before, a
//! finger beyond the book dragged the held column along and the page stretched without
//! bound (render grid 89x for a finger 100 units out). A release frees the gripped
//! particles with the velocity they had; the page then moves under the springs and gravity
//! alone. The frame's finger gap is the distance from the held material point on the render
//! surface, $S(u, v)$, to the finger: zero (to rounding) for an edge grip on a particle
//! column, the lag of the page around the particle otherwise. With an edge grip the dog-ear
//! groups of the synchronization are the particle columns, whatever the finger does
//! ([`sync`] module docs).
//!
//! **The shared page turn** (`TouchScript::page_turn(12, 12√2, 10, 120, 240)`, the finger
//! carries the fore-edge point $(W, 0.2H)$ over the spine to its mirrored rest point and lets
//! go at frame 130; measured on a $24 \times 34$-quad render grid by
//! `tests/tests/page_spring.rs`, `shared_page_turn_variants` prints every variant). With the
//! earlier defaults (one step per frame, $k/m = 1800, 450, 450$, dog-ear groups
//! perpendicular to the finger's displacement for an edge grip too, a table that cancelled
//! every downward velocity, the global Lagrange polynomial) the render grid's max stretch
//! per frame averaged 820 % (worst 6700 %, render points down to $y = -25$), the particles'
//! 18 % (worst 95 %), and only 48 % of the page ended left of the spine: the released page
//! stood up. What each change did:
//! - **the table** touched every particle moving down, wherever it was: a lifted page could
//!   not fall (it crept down by one step of gravity per frame, $g h^2 = 0.0027$), hung
//!   taut in the air when the finger arrived and sprang back when let go. Contact only on
//!   or under the plane: the page lands flat on the left (96 % of the samples left of the
//!   spine, all but the spine column; every sample at $y = 0$ at the end);
//! - **dog-ear groups of an edge grip** (the columns, [`sync`]): the finger also moves along
//!   the spine (by up to $0.12H$), which tilted the groups by up to 60° and translated
//!   strips across the fixed spine rigidly; particle stretch mean 18 % → 9.3 %;
//! - **stiffer springs in 8 substeps** (same explicit stability margin,
//!   [`SpringSettings::default`]): particle stretch mean 9.3 % → 0.8 % (worst 2.8 %), render
//!   1.5 % (worst 6.0 %); a point grip instead measured 15 % (with synchronization) and
//!   1.2 % with a finger gap up to 0.21 (without);
//! - **a cubic render surface on local stencils** ([`lagrange`]) with the table's contact:
//!   the global polynomial on the same particles averaged 4.6 % (worst 27 %) and dipped to
//!   $y = -0.37$; the bare cubic dips to $-0.05$ where the page leaves the table, lifted onto
//!   it.
//!
//! Setup allocates (the network, the buffers, the recording, the solver's analysis at a grab
//! or a release for the implicit integrator); [`PageModel::step`] and [`PageModel::sample`]
//! do not.

pub mod bending;
pub mod energy;
pub mod explicit;
pub mod implicit;
pub mod keyframes;
pub mod lagrange;
pub mod limit;
pub mod network;
pub mod replay;
pub mod settings;
pub mod sync;

use alloc::vec::Vec;
use folio_geometry::{BlockSide, QuadGrid};
use folio_kernels::{Real, SettingError, Vec3Ops, math};

pub use energy::SpringEnergy;
pub use implicit::ImplicitStepper;
pub use keyframes::KeyFrames;
pub use lagrange::LagrangeSurface;
pub use limit::StrainLimit;
pub use network::{Role, SpringNetwork};
pub use replay::ReplayPage;
pub use settings::{
    Grip, Integrator, MAX_KEY_FRAMES, MAX_PARTICLES_PER_SIDE, MAX_SUBSTEPS, PhysicalPage,
    SpringSettings,
};
pub use sync::Synchronizer;

use super::{PageError, PageModel, PageStatus, PageStep, check_grab};
use crate::hold::{self, Hold, all_in_range};
use folio_solvers::step::State;
use network::zeros;

/// The mass-spring page (module docs).
#[derive(Clone, Debug)]
pub struct SpringPage<T: Real> {
    settings: SpringSettings<T>,
    network: SpringNetwork<T>,
    state: State<T>,
    previous: State<T>,
    forces: Vec<T::Vec3>,
    implicit: Option<ImplicitStepper<T>>,
    sync: Synchronizer<T>,
    surface: LagrangeSurface<T>,
    recording: KeyFrames<T>,
    limit: Option<StrainLimit<T>>,
    out_of_reach: bool,
    hold: Option<Hold<T>>,
    gripped: Vec<u32>,
    frame: u64,
}

impl<T: Real> SpringPage<T> {
    /// The page of `settings` flat at rest, its first key frame recorded.
    ///
    /// # Errors
    /// [`PageError::InvalidSetting`] naming the first bad setting
    /// ([`SpringSettings::validate`], and the implicit solver's own refusal).
    pub fn new(settings: SpringSettings<T>) -> Result<Self, PageError> {
        settings.validate()?;
        let network = SpringNetwork::new(&settings);
        let n = network.rest().len();
        let state = State::at_rest(network.rest().to_vec());
        let implicit = match settings.integrator {
            Integrator::SemiImplicitEuler => None,
            Integrator::ImplicitEuler => {
                let mut stepper = ImplicitStepper::new(settings.substep()).ok_or(
                    SettingError::new("time_step", "a substep the implicit solver takes"),
                )?;
                if !stepper.analyse(&network) {
                    let rule = "a particle grid the implicit solver can analyse";
                    return Err(SettingError::new("particles_across", rule).into());
                }
                Some(stepper)
            }
        };
        let size = [settings.width, settings.height];
        let mut sync = Synchronizer::new(n, size, settings.spacing());
        sync.group(network.rest(), [T::ONE, T::ZERO]);
        let mut recording = KeyFrames::with_capacity(
            n,
            settings.key_frame_stride(),
            settings.time_step,
            settings.key_frame_capacity,
        );
        recording.push(&state.x);
        let limit = settings
            .strain_limit
            .map(|tau| StrainLimit::new(&network, tau));
        Ok(Self {
            surface: LagrangeSurface::new(network.grid(), size, settings.interpolation_degree)
                .with_floor(settings.floor)
                .with_stretch_guard(settings.strain_limit),
            previous: state.clone(),
            forces: zeros::<T>(n),
            gripped: Vec::with_capacity(n),
            settings,
            network,
            state,
            implicit,
            sync,
            recording,
            limit,
            out_of_reach: false,
            hold: None,
            frame: 0,
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &SpringSettings<T> {
        &self.settings
    }

    /// The particles, springs and roles.
    #[must_use]
    pub fn network(&self) -> &SpringNetwork<T> {
        &self.network
    }

    /// Particle positions (page frame), index $i + n_x j$.
    #[must_use]
    pub fn positions(&self) -> &[T::Vec3] {
        &self.state.x
    }

    /// Particle velocities (page units per second).
    #[must_use]
    pub fn velocities(&self) -> &[T::Vec3] {
        &self.state.v
    }

    /// The energy of the particles ([`SpringEnergy`]).
    #[must_use]
    pub fn energy(&self) -> SpringEnergy<T> {
        SpringEnergy::of(&self.network, &self.state.x, &self.state.v)
    }

    /// Frames stepped since construction or [`SpringPage::set_state`].
    #[must_use]
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// The key frames recorded so far.
    #[must_use]
    pub fn recording(&self) -> &KeyFrames<T> {
        &self.recording
    }

    /// A player of the recording so far (clones it).
    ///
    /// # Errors
    /// As [`ReplayPage::new`] (never, for a recording of this page).
    pub fn replay(&self) -> Result<ReplayPage<T>, PageError> {
        ReplayPage::new(self.recording.clone(), self.surface.clone())
    }

    /// The render surface through the particles ([`LagrangeSurface`]: the interpolation
    /// degree of the settings, the table's contact when the table is on).
    #[must_use]
    pub fn surface(&self) -> &LagrangeSurface<T> {
        &self.surface
    }

    /// The dog-ear group of every particle at the last step ([`Synchronizer`]); computed
    /// whether or not synchronization is on.
    #[must_use]
    pub fn dog_ear_groups(&self) -> &[u32] {
        self.sync.groups()
    }

    /// The unit normal $\hat d$ (X, Z) of the dog-ear line at the last step.
    #[must_use]
    pub fn dog_ear_direction(&self) -> [T; 2] {
        self.sync.direction()
    }

    /// The gripped particles.
    #[must_use]
    pub fn gripped(&self) -> &[u32] {
        &self.gripped
    }

    /// The held material point, if any.
    #[must_use]
    pub fn held(&self) -> Option<[T; 2]> {
        self.hold.map(|h| h.at)
    }

    /// Starts a new run from positions `x` and velocities `v` (one per particle): fixed
    /// particles stay at rest with zero velocity, the frame count restarts at 0 and the
    /// recording restarts with this state. The grab, if any, is kept.
    ///
    /// # Errors
    /// [`PageError::InvalidInput`] for a wrong length or a coordinate that is not finite or
    /// beyond [`Real::COORD_MAX`]; nothing changes.
    pub fn set_state(&mut self, x: &[T::Vec3], v: &[T::Vec3]) -> Result<(), PageError> {
        let n = self.state.x.len();
        if x.len() != n || v.len() != n || !all_in_range::<T>(x) || !all_in_range::<T>(v) {
            return Err(PageError::InvalidInput {
                what: "state (one finite position and velocity per particle)",
            });
        }
        self.state.x.copy_from_slice(x);
        self.state.v.copy_from_slice(v);
        for ((xk, vk), (&rk, role)) in self
            .state
            .x
            .iter_mut()
            .zip(self.state.v.iter_mut())
            .zip(self.network.rest().iter().zip(self.network.roles()))
        {
            if *role == Role::Fixed {
                *xk = rk;
                *vk = T::Vec3::ZERO;
            }
        }
        self.frame = 0;
        self.recording.clear();
        self.recording.push(&self.state.x);
        Ok(())
    }

    /// Frees the gripped particles (their velocities stay).
    fn let_go(&mut self) {
        for &k in &self.gripped {
            self.network.set_role(k as usize, Role::Free);
        }
        self.gripped.clear();
        self.hold = None;
    }

    fn reanalyse(&mut self) {
        if let Some(stepper) = self.implicit.as_mut() {
            // A refusal shows up again (and stalls) at the next step.
            let _ = stepper.analyse(&self.network);
        }
    }

    /// Step 1 of substep `s` of `n` (module docs): each gripped particle on the straight
    /// line from its position at the start of the frame to its target $\bar x_k + (G - P)$,
    /// at the fraction $s/n$ (exactly on the target at $s = n$), with the frame's velocity
    /// $(x_k^{target} - x_k^{start})/h$; zero velocity while the finger has not moved yet.
    fn place_gripped(&mut self, s: u32, n: u32) {
        let h = self.settings.time_step;
        let mut shift = self.hold.and_then(|hold| hold.displacement());
        let mirrored = self.hold.is_some_and(|hold| hold.mirrored);
        if let (Some(d), Some(limit)) = (shift, self.limit.as_ref()) {
            let rho = T::ONE + limit.limit() * T::HALF;
            let s = limit::reach(
                d,
                &self.gripped,
                self.network.rest(),
                self.network.roles(),
                rho,
                mirrored,
            );
            if s < T::ONE {
                shift = Some(d * s);
                self.out_of_reach = true;
            }
        }
        let fraction = T::from_f64(f64::from(s) / f64::from(n.max(1)));
        let rest = self.network.rest();
        for &k in &self.gripped {
            let k = k as usize;
            let (Some(xk), Some(vk), Some(&rk), Some(&start)) = (
                self.state.x.get_mut(k),
                self.state.v.get_mut(k),
                rest.get(k),
                self.previous.x.get(k),
            ) else {
                continue;
            };
            let rk = if mirrored {
                T::Vec3::new(-rk.x(), rk.y(), rk.z())
            } else {
                rk
            };
            match shift {
                Some(d) => {
                    let target = rk + d;
                    *vk = (target - start) / h;
                    *xk = if s >= n {
                        target
                    } else {
                        start + (target - start) * fraction
                    };
                }
                None => *vk = T::Vec3::ZERO,
            }
        }
    }

    /// Step 2 of a substep (module docs): `false` when the integrator failed.
    fn integrate(&mut self) -> bool {
        let h = self.settings.substep();
        match self.implicit.as_mut() {
            None => {
                explicit::semi_implicit_euler(
                    &mut self.state.x,
                    &mut self.state.v,
                    &self.network,
                    self.settings.damping,
                    h,
                    &mut self.forces,
                );
                true
            }
            Some(stepper) => {
                // The solver gives eliminated particles v = 0; a gripped one keeps its own
                // (kept meanwhile in the force buffer, which the implicit path does not use).
                for &k in &self.gripped {
                    if let (Some(&vk), Some(f)) = (
                        self.state.v.get(k as usize),
                        self.forces.get_mut(k as usize),
                    ) {
                        *f = vk;
                    }
                }
                let any_free = self.network.roles().contains(&Role::Free);
                if any_free && !stepper.step(&mut self.network, &mut self.state) {
                    return false;
                }
                for &k in &self.gripped {
                    if let (Some(vk), Some(&f)) = (
                        self.state.v.get_mut(k as usize),
                        self.forces.get(k as usize),
                    ) {
                        *vk = f;
                    }
                }
                true
            }
        }
    }

    /// Steps 3-5 of a substep (module docs): `false` when Provot's correction did not reach
    /// its bound ([`StrainLimit::converged`]).
    fn constrain(&mut self) -> bool {
        let d = match self.settings.grip {
            // An edge grip moves its whole column as one: the dog-ear line is that column.
            Grip::Edge => None,
            Grip::Point => self.hold.and_then(|hold| {
                hold.finger
                    .map(|f| [f.x() - hold.rest_point.x(), f.z() - hold.rest_point.z()])
            }),
        };
        let direction = self.sync.direction_of(d);
        self.sync.group(self.network.rest(), direction);
        if self.settings.sync {
            self.sync.apply(
                &mut self.state.x,
                &mut self.state.v,
                self.network.rest(),
                self.network.roles(),
            );
        }
        if self.settings.floor {
            for ((xk, vk), role) in self
                .state
                .x
                .iter_mut()
                .zip(self.state.v.iter_mut())
                .zip(self.network.roles())
            {
                if *role != Role::Free {
                    continue;
                }
                // Only a particle on or under the table touches it: one above it falls freely.
                if xk.y() > T::ZERO {
                    continue;
                }
                *xk = T::Vec3::new(xk.x(), T::ZERO, xk.z());
                if vk.y() < T::ZERO {
                    *vk = T::Vec3::new(vk.x(), T::ZERO, vk.z());
                }
            }
        }
        if let Some(limit) = self.limit.as_mut() {
            limit.apply(
                &mut self.state.x,
                &mut self.state.v,
                self.network.roles(),
                self.settings.floor,
                self.settings.substep(),
            );
            return limit.converged();
        }
        true
    }
}

impl<T: Real> PageModel<T> for SpringPage<T> {
    fn name(&self) -> &'static str {
        "mass-spring"
    }

    fn size(&self) -> [T; 2] {
        [self.settings.width, self.settings.height]
    }

    /// Grips the particle column (or particle) nearest `at` (module docs), letting go of any
    /// earlier grab first.
    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError> {
        check_grab(at, self.size())?;
        self.let_go();
        let grid = self.network.grid();
        let nearest = |t: T, extent: T, n: usize| {
            let r = (t / extent).to_f64() * (n - 1) as f64 + 0.5;
            if r > 0.0 { (r as usize).min(n - 1) } else { 0 }
        };
        let i = nearest(at[0], self.settings.width, grid.nx);
        let j = nearest(at[1], self.settings.height, grid.nz);
        let rows = match self.settings.grip {
            Grip::Edge => 0..grid.nz,
            Grip::Point => j..j + 1,
        };
        for row in rows {
            let k = grid.index(i, row);
            if self.network.roles().get(k) == Some(&Role::Free) {
                self.network.set_role(k, Role::Gripped);
                self.gripped.push(k as u32);
            }
        }
        self.hold = Some(Hold::new(at));
        self.reanalyse();
        Ok(())
    }

    /// Left of the spine when its particles' mean X is negative.
    fn lying_side(&self) -> BlockSide {
        crate::lying_side::<T>(&self.state.x)
    }

    fn taken_from(&mut self, side: BlockSide) {
        hold::taken_from(&mut self.hold, side);
    }

    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError> {
        hold::drag(&mut self.hold, finger)
    }

    fn release(&mut self) {
        if self.hold.is_some() {
            self.let_go();
            self.reanalyse();
        }
    }

    fn step(&mut self) -> Result<PageStep<T>, PageError> {
        self.previous.x.copy_from_slice(&self.state.x);
        self.previous.v.copy_from_slice(&self.state.v);
        let mut status = PageStatus::Moved;
        self.out_of_reach = false;
        let n = self.settings.substeps.max(1);
        for s in 1..=n {
            self.place_gripped(s, n);
            if !self.integrate() || !self.constrain() {
                status = PageStatus::Stalled;
                break;
            }
        }
        if status == PageStatus::Stalled
            || !all_in_range::<T>(&self.state.x)
            || !all_in_range::<T>(&self.state.v)
        {
            self.state.x.copy_from_slice(&self.previous.x);
            self.state.v.copy_from_slice(&self.previous.v);
            status = PageStatus::Stalled;
        } else if self.out_of_reach {
            status = PageStatus::Unreachable;
        }
        self.frame += 1;
        if self.frame % u64::from(self.recording.stride()) == 0 {
            self.recording.push(&self.state.x);
        }
        let finger_gap = self.hold.and_then(|hold| {
            hold.finger
                .map(|f| math::length::<T>(self.surface.eval(&self.state.x, hold.at) - f))
        });
        Ok(PageStep { status, finger_gap })
    }

    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError> {
        self.surface.sample(&self.state.x, grid, out)
    }
}
