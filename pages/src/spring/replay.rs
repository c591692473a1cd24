//! A recorded page turn played back frame by frame without simulating (seed `003_…`
//! Sec. 2.2.3): each frame writes the key-frame interpolation of [`KeyFrames::replay_frame`]
//! into the particles, and [`PageModel::sample`] interpolates them with the same Lagrange
//! surface as the simulated page. A frame costs one blend of the particle positions instead
//! of the spring forces, the integration and the synchronization.
//!
//! A recording does not answer the finger: grab, drag and release are checked like every
//! page model's input (typed errors for bad input) and otherwise ignored.

use alloc::vec::Vec;
use folio_geometry::QuadGrid;
use folio_kernels::Real;

use super::keyframes::KeyFrames;
use super::lagrange::LagrangeSurface;
use super::network::zeros;
use crate::{PageError, PageModel, PageStatus, PageStep, check_finger, check_grab};

/// Plays a [`KeyFrames`] recording of a mass-spring page (module docs).
#[derive(Clone, Debug)]
pub struct ReplayPage<T: Real> {
    recording: KeyFrames<T>,
    surface: LagrangeSurface<T>,
    size: [T; 2],
    particles: Vec<T::Vec3>,
    frame: u64,
}

impl<T: Real> ReplayPage<T> {
    /// The player of `recording`, rendered by `surface` (the recorded page's
    /// [`SpringPage::surface`](super::SpringPage::surface), which knows the particle grid,
    /// the page size, the interpolation degree and the table), positioned at the first key
    /// frame.
    ///
    /// # Errors
    /// [`PageError::InvalidInput`] for an empty recording, one whose particle count is not
    /// the surface's particle grid's, or a grid beyond [`super::MAX_PARTICLES_PER_SIDE`].
    pub fn new(recording: KeyFrames<T>, surface: LagrangeSurface<T>) -> Result<Self, PageError> {
        let particles = surface.particles();
        let side = 2..=super::MAX_PARTICLES_PER_SIDE;
        if recording.particles() != particles.len()
            || !side.contains(&particles.nx)
            || !side.contains(&particles.nz)
        {
            return Err(PageError::InvalidInput {
                what: "recording (particle count differs from the particle grid)",
            });
        }
        let mut x = zeros::<T>(particles.len());
        recording.replay_frame(0, &mut x)?;
        Ok(Self {
            size: surface.size(),
            surface,
            recording,
            particles: x,
            frame: 0,
        })
    }

    /// The frame shown (0 at the first key frame).
    #[must_use]
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// `true` once the last key frame is shown.
    #[must_use]
    pub fn finished(&self) -> bool {
        self.frame >= self.recording.frames()
    }

    /// Back to the first key frame.
    pub fn rewind(&mut self) {
        self.frame = 0;
        let _ = self.recording.replay_frame(0, &mut self.particles);
    }

    /// The particle positions shown.
    #[must_use]
    pub fn particles(&self) -> &[T::Vec3] {
        &self.particles
    }

    /// The recording played.
    #[must_use]
    pub fn recording(&self) -> &KeyFrames<T> {
        &self.recording
    }
}

impl<T: Real> PageModel<T> for ReplayPage<T> {
    fn name(&self) -> &'static str {
        "mass-spring replay"
    }

    fn size(&self) -> [T; 2] {
        self.size
    }

    fn grab(&mut self, at: [T; 2]) -> Result<(), PageError> {
        check_grab(at, self.size)
    }

    fn drag(&mut self, finger: T::Vec3) -> Result<(), PageError> {
        check_finger::<T>(finger)
    }

    fn release(&mut self) {}

    /// Shows the next frame of the recording (the last key frame once past it).
    fn step(&mut self) -> Result<PageStep<T>, PageError> {
        let next = self.frame.saturating_add(1).min(self.recording.frames());
        self.recording.replay_frame(next, &mut self.particles)?;
        self.frame = next;
        Ok(PageStep {
            status: PageStatus::Moved,
            finger_gap: None,
        })
    }

    fn sample(&self, grid: QuadGrid, out: &mut [T::Vec3]) -> Result<(), PageError> {
        self.surface.sample(&self.particles, grid, out)
    }
}
