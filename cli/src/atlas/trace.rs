//! One variant run as `folio run` runs it, with the page's surface recorded at fixed
//! material points every frame (the atlas compares variants there).

use folio_geometry::QuadGrid;
use folio_scene::scene::Scene;

use crate::error::RunError;
use crate::report::Report;
use crate::run;

/// The material points every variant is sampled at: the nodes of a 12 x 16 quad grid over
/// the page (13 x 17 points; node $(12, 8)$ is the fore-edge's middle, the page tip).
pub const SAMPLES: (usize, usize) = (12, 16);

/// The sample grid of [`SAMPLES`].
#[must_use]
pub fn sample_grid() -> QuadGrid {
    QuadGrid {
        nx: SAMPLES.0 + 1,
        nz: SAMPLES.1 + 1,
    }
}

/// The index of the page tip, the middle of the fore-edge, among the samples.
#[must_use]
pub fn tip() -> usize {
    sample_grid().index(SAMPLES.0, SAMPLES.1 / 2)
}

/// A run with its page surface per frame.
#[derive(Clone, Debug)]
pub struct Trace {
    /// The page at the sample points after every frame, in the frame of the scene's model
    /// (`None` until the run has had a page; afterwards the last page seen is kept, so a page
    /// that merged into a block stays where it came to rest).
    pub frames: Vec<Option<Vec<[f64; 3]>>>,
    /// The run's report (step times, stretch, DOG residual, penetration, health).
    pub report: Report,
}

/// Runs `scene`, recording the page every frame; `progress(frames)` is called after every
/// frame with the frames the run takes.
///
/// # Errors
/// A scene whose model refuses to start ([`run::run`]).
pub fn trace(scene: &Scene, mut progress: impl FnMut(u32)) -> Result<Trace, RunError> {
    let grid = sample_grid();
    let mut frames: Vec<Option<Vec<[f64; 3]>>> = Vec::new();
    let mut points = Vec::with_capacity(grid.len());
    let report = run::run(
        scene,
        |_, frames| progress(frames),
        |_, _, shape| {
            let now = if shape.page_points(grid, &mut points) {
                Some(points.clone())
            } else {
                frames.last().cloned().flatten()
            };
            frames.push(now);
        },
    )?;
    Ok(Trace { frames, report })
}
