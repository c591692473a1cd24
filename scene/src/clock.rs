//! Frames are in time: a frame of a run is [`FRAME_SECONDS`] of simulated time, whatever
//! the model's own step $h$. The run applies a frame's inputs, then takes as many model
//! steps as keep the model's time on the frame's: after frame $f$ (0-based) the model has
//! taken $\mathrm{round}((f + 1)\thinspace \Delta t_{\mathrm{frame}} / h)$ steps in all
//! ([`steps_after`]), so at $h = 1/120$ s every frame takes two steps. A model without a
//! step (the cone) takes one per frame. A scene's $h$ is at most one frame (the scene
//! check refuses a longer time step, `book.solver.time_step` or the page model's `time_step`).

/// Simulated seconds per frame: 1/60 s, the rate of `frames`, of timed events
/// (`input.events`' `frame` and `time`) and of the hands of a sheet scene.
pub const FRAME_SECONDS: f64 = 1.0 / 60.0;

/// Model steps of length `h` (seconds) taken in all after `frames` frames:
/// $\mathrm{round}(\mathit{frames}\thinspace \Delta t_{\mathrm{frame}} / h)$, saturating; one
/// step per frame for an `h` that is not finite and positive.
#[must_use]
pub fn steps_after(frames: u32, h: f64) -> u64 {
    if !(h.is_finite() && h > 0.0) {
        return u64::from(frames);
    }
    // `as` saturates: a step far below the scene limit gives u64::MAX, not a wrap.
    (f64::from(frames) * FRAME_SECONDS / h).round() as u64
}

/// Model steps of length `h` that frame `frame` takes: the difference of [`steps_after`]
/// at its end and at its start, at least 1 (a step a little over a frame, within rounding,
/// would otherwise skip a frame) and at most `u32::MAX`.
#[must_use]
pub fn steps_in_frame(frame: u32, h: f64) -> u32 {
    let taken = steps_after(frame.saturating_add(1), h) - steps_after(frame, h);
    u32::try_from(taken.max(1)).unwrap_or(u32::MAX)
}

/// Steps of length `h` per frame, rounded, at least 1: the factor that turns a count of
/// steps meant at one step per frame into the same time at `h`.
#[must_use]
pub fn steps_per_frame(h: f64) -> u32 {
    steps_in_frame(0, h)
}

/// `true` when a step of `h` seconds is at most one frame (within a relative $10^{-9}$, so
/// that `1/60` written as a decimal passes).
#[must_use]
pub fn fits_in_frame(h: f64) -> bool {
    h <= FRAME_SECONDS * (1.0 + 1e-9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_takes_the_steps_that_keep_time() {
        assert_eq!(steps_after(750, FRAME_SECONDS), 750);
        assert_eq!(steps_after(750, 1.0 / 120.0), 1500);
        assert!((0..750).all(|f| steps_in_frame(f, 1.0 / 120.0) == 2));
        assert!((0..750).all(|f| steps_in_frame(f, FRAME_SECONDS) == 1));
        // 1/100 s: 5 steps every 3 frames, 2 1 2 (rounded), never drifting.
        let steps: Vec<u32> = (0..6).map(|f| steps_in_frame(f, 0.01)).collect();
        assert_eq!(steps, [2, 1, 2, 2, 1, 2]);
        assert_eq!(steps_after(6, 0.01), 10);
        assert_eq!(steps_per_frame(1.0 / 240.0), 4);
        assert_eq!(steps_per_frame(0.01), 2);
    }

    #[test]
    fn a_step_the_scene_refuses_still_gives_a_count() {
        assert_eq!(steps_in_frame(0, 1e-300), u32::MAX);
        assert_eq!(steps_in_frame(3, 1e-300), 1);
        assert_eq!(steps_in_frame(3, f64::NAN), 1);
        assert_eq!(steps_in_frame(3, 0.1), 1);
        assert!(fits_in_frame(0.016_666_666_666_666_666));
        assert!(fits_in_frame(1.0 / 60.0));
        assert!(!fits_in_frame(0.017));
    }
}
