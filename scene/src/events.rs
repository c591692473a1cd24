//! Timed input events of a scene (`[[input.events]]`): one gesture (a grab, drags, a
//! release) in page coordinates, checked and turned into a [`TouchScript`] that every page
//! model follows.

use core::ops::Range;

use folio_pages::TouchScript;
use toml::Spanned;

use crate::scene::EventSpec;

/// Frames per second of every scene.
pub const FPS: f64 = 60.0;

/// Frames a scene with events runs after its last event when it sets no `frames`.
pub const SETTLE_FRAMES: u32 = 240;

/// The largest event frame (the scene's `frames` limit).
const MAX_FRAME: u32 = 1_000_000;

/// What one event does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum What {
    Grab([f64; 2]),
    Drag([f64; 3]),
    Release,
}

/// An event's frame and action, or the span and message of what is wrong with it.
fn read(e: &Spanned<EventSpec>) -> Result<(u32, What), (Range<usize>, String)> {
    let spec = e.get_ref();
    let whole = || e.span();
    let frame = match (&spec.frame, &spec.time) {
        (Some(f), None) => *f.get_ref(),
        (None, Some(t)) => {
            let seconds = *t.get_ref();
            if !(seconds.is_finite() && (0.0..=f64::from(MAX_FRAME) / FPS).contains(&seconds)) {
                return Err((t.span(), "time must be in [0, 16666] seconds".into()));
            }
            (seconds * FPS).round() as u32
        }
        _ => {
            return Err((
                whole(),
                "an event needs exactly one of `frame` and `time`".into(),
            ));
        }
    };
    if frame >= MAX_FRAME {
        return Err((whole(), format!("an event frame must be below {MAX_FRAME}")));
    }
    let what = match (&spec.grab, &spec.drag, &spec.release) {
        (Some(g), None, None) => What::Grab(*g.get_ref()),
        (None, Some(d), None) => {
            let p = *d.get_ref();
            if !p.iter().all(|c| c.is_finite() && c.abs() <= 1e6) {
                return Err((d.span(), "a drag point must be finite (|x| <= 1e6)".into()));
            }
            What::Drag(p)
        }
        (None, None, Some(r)) if *r.get_ref() => What::Release,
        (None, None, Some(r)) => return Err((r.span(), "write `release = true`".into())),
        _ => {
            return Err((
                whole(),
                "an event needs exactly one of `grab`, `drag` and `release`".into(),
            ));
        }
    };
    Ok((frame, what))
}

/// Checks `events` for a page of size `[W, H]`: one grab first, on the page; drags after
/// it; at most one release, last; frames strictly increasing.
///
/// # Errors
/// The span of the offending event or value and what is wrong.
pub fn check(
    events: &Spanned<Vec<Spanned<EventSpec>>>,
    size: [f64; 2],
) -> Result<(), (Range<usize>, String)> {
    let list = events.get_ref();
    if list.is_empty() {
        return Err((events.span(), "input.events is empty".into()));
    }
    let mut last: Option<u32> = None;
    for (k, e) in list.iter().enumerate() {
        let (frame, what) = read(e)?;
        if last.is_some_and(|f| frame <= f) {
            return Err((e.span(), "event frames must increase".into()));
        }
        last = Some(frame);
        match what {
            What::Grab(at) if k == 0 => {
                let inside = (0.0..=size[0]).contains(&at[0]) && (0.0..=size[1]).contains(&at[1]);
                if !inside {
                    let span = e.get_ref().grab.as_ref().map_or(e.span(), Spanned::span);
                    let message = format!(
                        "the grab point must lie on the {} x {} page",
                        crate::number::show(size[0]),
                        crate::number::show(size[1])
                    );
                    return Err((span, message));
                }
            }
            What::Grab(_) => {
                return Err((e.span(), "one gesture: only the first event grabs".into()));
            }
            _ if k == 0 => return Err((e.span(), "the first event must be a grab".into())),
            What::Release if k + 1 != list.len() => {
                return Err((e.span(), "the release must be the last event".into()));
            }
            What::Drag(_) | What::Release => {}
        }
    }
    Ok(())
}

/// The [`TouchScript`] of checked `events`: the finger starts on the flat page at the
/// grabbed point $(u, 0, v)$, moves in a straight line to each drag point by its frame,
/// stays at the last one, and lets go at the release (else at the end). `frames`: the
/// scene's, else the last event's frame plus [`SETTLE_FRAMES`].
///
/// # Errors
/// As [`check`] (call it first; this re-reads the events).
pub fn touch_script(
    events: &[Spanned<EventSpec>],
    frames: Option<u32>,
) -> Result<TouchScript, (Range<usize>, String)> {
    let read: Vec<(u32, What)> = events.iter().map(read).collect::<Result<_, _>>()?;
    let Some(&(grab_frame, What::Grab(at))) = read.first() else {
        return Err((0..0, "the first event must be a grab".into()));
    };
    let last_frame = read.last().map_or(grab_frame, |e| e.0);
    let frames = frames.unwrap_or(last_frame.saturating_add(SETTLE_FRAMES));
    let release = match read.last() {
        Some(&(f, What::Release)) => f,
        _ => frames,
    }
    .min(frames);
    // Waypoints: the grab on the flat page, then every drag.
    let mut points = vec![(grab_frame, [at[0], 0.0, at[1]])];
    points.extend(read.iter().filter_map(|&(f, w)| match w {
        What::Drag(p) => Some((f, p)),
        _ => None,
    }));
    let path = (grab_frame..release.max(grab_frame))
        .map(|f| finger_at(&points, f))
        .collect();
    Ok(TouchScript {
        frames,
        grab: at,
        grab_frame,
        path,
    })
}

/// The finger at frame `f` on the piecewise-linear path through `points` (frames
/// increasing): before the first point at it, after the last at the last.
fn finger_at(points: &[(u32, [f64; 3])], f: u32) -> [f64; 3] {
    let next = points.iter().position(|p| p.0 >= f);
    match next {
        Some(0) => points[0].1,
        Some(k) => {
            let ((f0, a), (f1, b)) = (points[k - 1], points[k]);
            let s = f64::from(f - f0) / f64::from(f1 - f0);
            [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]))
        }
        None => points.last().map_or([0.0; 3], |p| p.1),
    }
}

#[cfg(test)]
mod tests {
    use super::finger_at;

    #[test]
    fn the_finger_moves_linearly_between_waypoints_and_holds_after() {
        let points = [(10, [0.0, 0.0, 0.0]), (20, [10.0, 5.0, 0.0])];
        assert_eq!(finger_at(&points, 5), [0.0, 0.0, 0.0]);
        assert_eq!(finger_at(&points, 15), [5.0, 2.5, 0.0]);
        assert_eq!(finger_at(&points, 20), [10.0, 5.0, 0.0]);
        assert_eq!(finger_at(&points, 99), [10.0, 5.0, 0.0]);
    }
}
