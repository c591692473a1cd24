//! The health of a run: every frame is held to bounds, and a run with any bad frame is a
//! bad run (`folio run` exits with [`crate::exit::BAD_RUN`]).
//!
//! A frame is bad when its step's input or its state is non-finite, its step failed or was
//! refused beyond the scene's allowance (`expect.failed_steps`, default 0), an input of
//! the frame did nothing (a grab that missed the page), a block's top page did not settle
//! (`book.gutter = "top-page"`: that block met the seed's walls), or a measure crossed its
//! bound:
//! the max edge stretch $\max \lvert \ell/\ell_0 - 1\rvert$ (default [`MAX_STRETCH`]), the DOG
//! residual $\max \lvert C_{\mathrm{DOG}}\rvert$ (default [`DOG_RESIDUAL`]) and the page's
//! penetration into a block (default one page thickness; held only when the scene
//! simulates `collisions`, without which the page passes through the blocks). A scene sets
//! its own bounds in `[expect]` (`max_stretch`, `dog_residual_max`, `penetration_max`,
//! `failed_steps`).

use folio_scene::number::{short, show};
use folio_scene::scene::Scene;

use crate::report::{Bounds, FirstBad, FrameRecord, Health};

/// Default bound on a frame's max edge stretch: 10 % (paper barely stretches).
pub const MAX_STRETCH: f64 = 0.10;

/// Default bound on a frame's DOG residual (page units).
pub const DOG_RESIDUAL: f64 = 1e-2;

impl Bounds {
    /// The bounds of `scene`: its `[expect]`, else the defaults (module docs); the default
    /// penetration bound is the scene's page thickness, and none without `collisions`.
    #[must_use]
    pub fn of(scene: &Scene) -> Self {
        let e = &scene.expect;
        let thickness = scene.page_thickness();
        Self {
            max_stretch: e.max_stretch.unwrap_or(MAX_STRETCH),
            dog_residual: e.dog_residual_max.unwrap_or(DOG_RESIDUAL),
            penetration: scene
                .has_effect("collisions")
                .then(|| e.penetration_max.unwrap_or(thickness)),
            failed_steps: e.failed_steps.unwrap_or(0),
        }
    }
}

/// `value` above `bound`, or not a number: a crossing.
fn over(value: Option<f64>, bound: f64) -> Option<f64> {
    value.filter(|v| v.is_nan() || *v > bound)
}

/// Holds every record to `bounds`: writes each frame's problems into its `problems` and
/// counts them.
pub fn judge(records: &mut [FrameRecord], bounds: Bounds) -> Health {
    let mut h = Health {
        bounds,
        bad_frames: 0,
        failed_steps: 0,
        nonfinite_input_frames: 0,
        nonfinite_state_frames: 0,
        input_problems: 0,
        stretch_over: 0,
        dog_residual_over: 0,
        penetration_over: 0,
        gutter_failures: 0,
        first_bad: None,
    };
    for r in records.iter_mut() {
        let mut p = Vec::new();
        let failures = r.gutter_failures.unwrap_or(0);
        if failures > h.gutter_failures {
            p.push(format!(
                "{} block top page(s) did not settle: the seed's walls stood in",
                failures - h.gutter_failures
            ));
            h.gutter_failures = failures;
        }
        if r.nonfinite_input {
            h.nonfinite_input_frames += 1;
            p.push("the step's input was non-finite".to_string());
        }
        if r.nonfinite {
            h.nonfinite_state_frames += 1;
            p.push("a coordinate is non-finite".to_string());
        }
        if r.failed {
            h.failed_steps += 1;
            if h.failed_steps > bounds.failed_steps {
                p.push(format!("the step failed ({})", r.status));
            }
        }
        h.input_problems += r.inputs.len();
        p.extend(r.inputs.iter().cloned());
        let measures = [
            (
                "max edge stretch",
                r.max_stretch,
                Some(bounds.max_stretch),
                &mut h.stretch_over,
            ),
            (
                "DOG residual",
                r.dog_residual,
                Some(bounds.dog_residual),
                &mut h.dog_residual_over,
            ),
            (
                "penetration",
                r.penetration,
                bounds.penetration,
                &mut h.penetration_over,
            ),
        ];
        for (what, value, bound, count) in measures {
            let Some(bound) = bound else { continue };
            if let Some(v) = over(value, bound) {
                *count += 1;
                p.push(format!(
                    "{what} {} above the bound {}",
                    short(v),
                    show(bound)
                ));
            }
        }
        if !p.is_empty() {
            h.bad_frames += 1;
            if h.first_bad.is_none() {
                h.first_bad = Some(FirstBad {
                    frame: r.frame,
                    why: p.join("; "),
                });
            }
        }
        r.problems = p;
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(frame: u32, status: &str) -> FrameRecord {
        FrameRecord::new(frame, 1, 0.1, status.to_string(), false)
    }

    const BOUNDS: Bounds = Bounds {
        max_stretch: MAX_STRETCH,
        dog_residual: DOG_RESIDUAL,
        penetration: Some(0.0075),
        failed_steps: 0,
    };

    /// The defect of issue 20: every step reported non-finite input, the summary said 0.
    #[test]
    fn non_finite_input_is_counted_on_every_frame_and_makes_the_run_bad() {
        let mut records: Vec<FrameRecord> = (0..100)
            .map(|f| FrameRecord {
                nonfinite_input: true,
                failed: true,
                ..record(f, "NonFiniteInput")
            })
            .collect();
        let h = judge(&mut records, BOUNDS);
        assert_eq!(
            (h.nonfinite_input_frames, h.failed_steps, h.bad_frames),
            (100, 100, 100)
        );
        assert!(!h.good());
        let first = h.first_bad.expect("a first bad frame");
        assert_eq!(first.frame, 0);
        assert!(first.why.contains("non-finite"), "{}", first.why);
    }

    #[test]
    fn failed_steps_within_the_allowance_are_counted_but_not_bad() {
        let mut records: Vec<FrameRecord> = (0..120)
            .map(|f| FrameRecord {
                failed: f >= 10,
                ..record(
                    f,
                    if f >= 10 {
                        "LineSearchFailed"
                    } else {
                        "Converged"
                    },
                )
            })
            .collect();
        let h = judge(&mut records.clone(), BOUNDS);
        assert_eq!((h.failed_steps, h.bad_frames), (110, 110));
        assert_eq!(h.first_bad.map(|b| b.frame), Some(10));
        let allow = Bounds {
            failed_steps: 100,
            ..BOUNDS
        };
        let h = judge(&mut records, allow);
        assert_eq!((h.failed_steps, h.bad_frames), (110, 10));
        assert_eq!(h.first_bad.map(|b| b.frame), Some(110));
    }

    #[test]
    fn each_bound_and_a_nan_measure_make_a_frame_bad() {
        let cases = [
            (
                Some(0.11),
                None,
                None,
                "max edge stretch 0.11 above the bound 0.1",
            ),
            (Some(f64::NAN), None, None, "max edge stretch NaN"),
            (
                Some(0.01),
                Some(0.02),
                None,
                "DOG residual 0.02 above the bound 0.01",
            ),
            (
                None,
                None,
                Some(0.008),
                "penetration 0.008 above the bound 0.0075",
            ),
        ];
        for (stretch, dog, depth, why) in cases {
            let mut records = vec![
                record(0, "Converged"),
                FrameRecord {
                    max_stretch: stretch,
                    dog_residual: dog,
                    penetration: depth,
                    ..record(1, "Converged")
                },
            ];
            let h = judge(&mut records, BOUNDS);
            assert_eq!(h.bad_frames, 1, "{why}");
            let first = h.first_bad.expect("bad");
            assert_eq!(first.frame, 1);
            assert!(first.why.starts_with(why), "{}", first.why);
        }
        let mut good = vec![FrameRecord {
            max_stretch: Some(0.1),
            dog_residual: Some(1e-3),
            penetration: Some(0.0),
            ..record(0, "IterationLimit")
        }];
        assert!(judge(&mut good, BOUNDS).good());
    }

    #[test]
    fn a_top_page_that_did_not_settle_makes_its_frame_bad() {
        let with = |frame: u32, failures: u32| FrameRecord {
            gutter_failures: Some(failures),
            ..record(frame, "Converged")
        };
        let mut records = vec![with(0, 0), with(1, 0), with(2, 1), with(3, 1), with(4, 3)];
        let h = judge(&mut records, BOUNDS);
        // The count is the book's running total: frames 2 and 4 are where it grew.
        assert_eq!((h.gutter_failures, h.bad_frames), (3, 2));
        let first = h.first_bad.expect("bad");
        assert_eq!(first.frame, 2);
        assert!(first.why.contains("did not settle"), "{}", first.why);
        assert!(records[3].problems.is_empty());
        assert!(
            records[4].problems[0].starts_with("2 block"),
            "{:?}",
            records[4].problems
        );
    }

    #[test]
    fn a_missed_grab_is_a_bad_frame_named_in_the_summary() {
        let mut records = vec![
            record(0, "Converged"),
            FrameRecord {
                inputs: vec!["grab at frame 1 missed the page".into()],
                ..record(1, "Converged")
            },
        ];
        let h = judge(&mut records, BOUNDS);
        assert_eq!((h.input_problems, h.bad_frames), (1, 1));
        assert_eq!(
            h.first_bad.map(|b| b.why),
            Some("grab at frame 1 missed the page".to_string())
        );
    }
}
