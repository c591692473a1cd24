//! Timed input events of a scene (`[[input.events]]`): any number of gestures in sequence
//! (a grab, drags, a release, then the next grab), in page coordinates, on either side of
//! the spine, checked and turned into [`Gestures`] that every page model follows.

use core::ops::Range;

use folio_pages::gestures::side_name;
use folio_pages::{BlockSide, Gesture, Gestures, PageError};
use toml::Spanned;

use crate::scene::{EventSpec, ModelKind, Scene};

/// Frames per second of every scene.
pub const FPS: f64 = 60.0;

/// Frames a scene with events runs after its last event when it sets no `frames`.
pub const SETTLE_FRAMES: u32 = 240;

/// The largest event frame (the scene's `frames` limit).
const MAX_FRAME: u32 = 1_000_000;

/// The most pages one grab may take (the scene's page limit, `book::MAX_PAGES`).
const MAX_STACK: u32 = crate::book::MAX_PAGES;

pub use crate::scene::Side;

impl From<Side> for BlockSide {
    fn from(side: Side) -> Self {
        match side {
            Side::Left => BlockSide::Left,
            Side::Right => BlockSide::Right,
        }
    }
}

/// What one event does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum What {
    Grab {
        at: [f64; 2],
        side: BlockSide,
        pages: u32,
    },
    Drag([f64; 3]),
    Release,
}

type Problem = (Range<usize>, String);

/// An event's frame and action, or the span and message of what is wrong with it.
fn read(e: &Spanned<EventSpec>) -> Result<(u32, What), Problem> {
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
    let grab_keys = [
        spec.side.as_ref().map(Spanned::span),
        spec.pages.as_ref().map(Spanned::span),
    ];
    let what = match (&spec.grab, &spec.drag, &spec.release) {
        (Some(g), None, None) => {
            let pages = spec.pages.as_ref().map_or(1, |p| *p.get_ref());
            if !(1..=MAX_STACK).contains(&pages) {
                let span = spec.pages.as_ref().map_or(whole(), Spanned::span);
                return Err((span, format!("pages must be between 1 and {MAX_STACK}")));
            }
            What::Grab {
                at: *g.get_ref(),
                side: spec
                    .side
                    .as_ref()
                    .map_or(BlockSide::Right, |s| (*s.get_ref()).into()),
                pages,
            }
        }
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
    if !matches!(what, What::Grab { .. }) {
        if let Some(span) = grab_keys.into_iter().flatten().next() {
            return Err((span, "`side` and `pages` belong to a grab".into()));
        }
    }
    Ok((frame, what))
}

/// Checks `events` for a page of size `[W, H]` and `model`: frames strictly increasing;
/// gestures in sequence, each a grab on the page, drags, and a release before the next
/// grab (the last may hold to the end); no drag or release while nothing is held; a stack
/// (`pages > 1`) for the DOG book only; the first grab of a one-page model on the right,
/// where its page starts.
///
/// # Errors
/// The span of the offending event or value and what is wrong.
pub fn check(
    events: &Spanned<Vec<Spanned<EventSpec>>>,
    size: [f64; 2],
    model: ModelKind,
) -> Result<(), Problem> {
    let list = events.get_ref();
    if list.is_empty() {
        return Err((events.span(), "input.events is empty".into()));
    }
    let mut last: Option<u32> = None;
    // The frame of the grab that holds the page, while held.
    let mut held: Option<u32> = None;
    for (k, e) in list.iter().enumerate() {
        let (frame, what) = read(e)?;
        if last.is_some_and(|f| frame <= f) {
            return Err((e.span(), "event frames must increase".into()));
        }
        last = Some(frame);
        let spec = e.get_ref();
        match (what, held) {
            (What::Grab { .. }, Some(at)) => {
                let message = format!(
                    "a second grab while the page grabbed at frame {at} is held: \
                     release it first (`release = true`)"
                );
                return Err((e.span(), message));
            }
            (What::Grab { at, side, pages }, None) => {
                let inside = (0.0..=size[0]).contains(&at[0]) && (0.0..=size[1]).contains(&at[1]);
                if !inside {
                    let span = spec.grab.as_ref().map_or(e.span(), Spanned::span);
                    let message = format!(
                        "the grab point must lie on the {} x {} page",
                        crate::number::show(size[0]),
                        crate::number::show(size[1])
                    );
                    return Err((span, message));
                }
                let one_page = model != ModelKind::Dog;
                if one_page && pages > 1 {
                    let span = spec.pages.as_ref().map_or(e.span(), Spanned::span);
                    let message = format!(
                        "the {} model turns one page: a stack (pages > 1) needs model = \"dog\"",
                        model.name()
                    );
                    return Err((span, message));
                }
                if one_page && k == 0 && side == BlockSide::Left {
                    let span = spec.side.as_ref().map_or(e.span(), Spanned::span);
                    let message = format!(
                        "the {} model's page starts on the right: the first grab is there",
                        model.name()
                    );
                    return Err((span, message));
                }
                held = Some(frame);
            }
            (What::Drag(_), None) => {
                return Err((
                    e.span(),
                    "a drag needs a grab before it: nothing is held".into(),
                ));
            }
            (What::Release, None) => {
                return Err((
                    e.span(),
                    "a release needs a grab before it: nothing is held".into(),
                ));
            }
            (What::Drag(_), Some(_)) => {}
            (What::Release, Some(_)) => held = None,
        }
    }
    Ok(())
}

/// The [`Gestures`] of checked `events`: in each gesture the finger starts on the flat page
/// at the grabbed point, $(u, 0, v)$ on the right and $(-u, 0, v)$ on the left, moves in a
/// straight line to each drag point by its frame, stays at the last one, and lets go at the
/// release (the last gesture without one at the end). `frames`: the scene's, else the last
/// event's frame plus [`SETTLE_FRAMES`]; gestures are cut at it.
///
/// # Errors
/// As [`check`] (call it first; this re-reads the events).
pub fn touch_script(
    events: &[Spanned<EventSpec>],
    frames: Option<u32>,
) -> Result<Gestures, Problem> {
    let read: Vec<(u32, What)> = events.iter().map(read).collect::<Result<_, _>>()?;
    let last_frame = read.last().map_or(0, |e| e.0);
    let frames = frames.unwrap_or(last_frame.saturating_add(SETTLE_FRAMES));
    let mut gestures = Vec::new();
    let mut k = 0;
    while k < read.len() {
        let (grab_frame, What::Grab { at, side, pages }) = read[k] else {
            return Err((events[k].span(), "a drag or release needs a grab".into()));
        };
        let x0 = if side == BlockSide::Left {
            -at[0]
        } else {
            at[0]
        };
        // Waypoints: the grab on the flat page, then every drag up to the release.
        let mut points = vec![(grab_frame, [x0, 0.0, at[1]])];
        k += 1;
        let mut release = frames;
        while k < read.len() {
            match read[k] {
                (f, What::Drag(p)) => points.push((f, p)),
                (f, What::Release) => {
                    release = f;
                    k += 1;
                    break;
                }
                (_, What::Grab { .. }) => break,
            }
            k += 1;
        }
        let release = release.min(frames);
        if release <= grab_frame {
            break;
        }
        gestures.push(Gesture {
            side,
            pages,
            grab: at,
            grab_frame,
            path: (grab_frame..release)
                .map(|f| finger_at(&points, f))
                .collect(),
        });
    }
    Gestures::new(frames, gestures).map_err(|e| (0..0, e.to_string()))
}

/// Where a run's refusal at `frame` comes from: the grab event of the gesture at that frame
/// (`input.events[k]`, 1-based as the file lists them) with its line and column in `text`,
/// and `error`.
#[must_use]
pub fn refusal(scene: &Scene, text: Option<&str>, frame: u32, error: &PageError) -> String {
    let grab = scene.input.get_ref().events.as_ref().and_then(|events| {
        events
            .get_ref()
            .iter()
            .enumerate()
            .filter_map(|(k, e)| read(e).ok().map(|(f, w)| (k, f, w, e.span())))
            .rfind(|&(_, f, w, _)| f <= frame && matches!(w, What::Grab { .. }))
    });
    match grab {
        Some((k, f, What::Grab { side, .. }, span)) => {
            let place = text.map_or(String::new(), |t| {
                let (line, column) = crate::scene::line_column(t, span.start);
                format!("line {line}, column {column}, ")
            });
            format!(
                "{place}input.events[{}] (the grab on the {} at frame {f}): {error}",
                k + 1,
                side_name(side)
            )
        }
        _ => format!("frame {frame}: {error}"),
    }
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
    use crate::scene::Scene;
    use folio_pages::BlockSide;
    use folio_pages::touch::Touch;

    #[test]
    fn the_finger_moves_linearly_between_waypoints_and_holds_after() {
        let points = [(10, [0.0, 0.0, 0.0]), (20, [10.0, 5.0, 0.0])];
        assert_eq!(finger_at(&points, 5), [0.0, 0.0, 0.0]);
        assert_eq!(finger_at(&points, 15), [5.0, 2.5, 0.0]);
        assert_eq!(finger_at(&points, 20), [10.0, 5.0, 0.0]);
        assert_eq!(finger_at(&points, 99), [10.0, 5.0, 0.0]);
    }

    const HEAD: &str = "name = \"g\"\nmodel = \"dog\"\n";

    fn event(line: &str) -> String {
        format!("[[input.events]]\n{line}\n")
    }

    fn scene(events: &[&str]) -> Result<Scene, crate::scene::SceneError> {
        let body: String = events.iter().map(|e| event(e)).collect();
        Scene::parse(&format!("{HEAD}{body}"))
    }

    #[test]
    fn gestures_follow_each_other_on_either_side() {
        let s = scene(&[
            "frame = 1\ngrab = [11.0, 3.0]",
            "frame = 5\ndrag = [-11.0, 0.0, 3.0]",
            "frame = 6\nrelease = true",
            "frame = 9\ngrab = [11.0, 3.0]\nside = \"left\"\npages = 2",
            "frame = 12\ndrag = [11.0, 0.0, 3.0]",
        ])
        .unwrap();
        let events = s.input.get_ref().events.as_ref().unwrap().get_ref();
        let g = super::touch_script(events, None).unwrap();
        assert_eq!(g.gestures().len(), 2);
        let second = &g.gestures()[1];
        assert_eq!((second.side, second.pages), (BlockSide::Left, 2));
        // Held from frame 9 to the end (no release): 12 + 240 frames in all.
        assert_eq!(g.frames, 252);
        assert_eq!(second.release_frame(), 252);
        // The finger starts on the left page, mirrored.
        assert_eq!(
            g.at(9),
            Touch::Take {
                side: BlockSide::Left,
                pages: 2,
                at: [11.0, 3.0],
                finger: [-11.0, 0.0, 3.0]
            }
        );
        assert_eq!(g.at(6), Touch::Release);
        assert_eq!(g.at(7), Touch::None);
        assert_eq!(g.at(12), Touch::Drag([11.0, 0.0, 3.0]));
    }

    /// Line and message of the error of `events`.
    fn refused(model: &str, events: &[&str]) -> (usize, String) {
        let body: String = events.iter().map(|e| event(e)).collect();
        let text = format!("name = \"g\"\nmodel = \"{model}\"\n{body}");
        let e = Scene::parse(&text).expect_err(&text);
        (e.line, e.message)
    }

    #[test]
    fn a_gesture_out_of_order_is_refused_at_its_event() {
        let grab = "frame = 1\ngrab = [11.0, 3.0]";
        // A drag without a grab: the first event, at its table (line 3).
        let (line, message) = refused("dog", &["frame = 1\ndrag = [1.0, 2.0, 3.0]"]);
        assert_eq!(line, 3, "{message}");
        assert!(message.contains("needs a grab"), "{message}");
        // Two grabs without a release: the second, at line 6.
        let (line, message) = refused("dog", &[grab, "frame = 2\ngrab = [10.0, 3.0]"]);
        assert_eq!(line, 6, "{message}");
        assert!(message.contains("release it first"), "{message}");
        // A release with nothing held.
        let (line, message) = refused(
            "dog",
            &[
                grab,
                "frame = 2\nrelease = true",
                "frame = 3\nrelease = true",
            ],
        );
        assert_eq!(line, 9, "{message}");
        assert!(message.contains("nothing is held"), "{message}");
        // A drag after the release.
        let (line, message) = refused(
            "cone",
            &[
                grab,
                "frame = 2\nrelease = true",
                "frame = 3\ndrag = [1.0, 1.0, 1.0]",
            ],
        );
        assert_eq!(line, 9, "{message}");
        assert!(message.contains("nothing is held"), "{message}");
        // A stack on a one-page model, at its `pages` key.
        let (line, message) = refused("mass-spring", &["frame = 1\ngrab = [11.0, 3.0]\npages = 3"]);
        assert_eq!(line, 6, "{message}");
        assert!(message.contains("one page"), "{message}");
        // A one-page model's first grab on the left, at its `side` key.
        let (line, message) = refused("cone", &["frame = 1\ngrab = [11.0, 3.0]\nside = \"left\""]);
        assert_eq!(line, 6, "{message}");
        assert!(message.contains("starts on the right"), "{message}");
        // `side` on a drag, zero pages, an unknown side.
        let (line, message) = refused(
            "dog",
            &[grab, "frame = 2\ndrag = [1.0, 1.0, 1.0]\nside = \"left\""],
        );
        assert_eq!(line, 9, "{message}");
        assert!(message.contains("belong to a grab"), "{message}");
        let (line, message) = refused("dog", &["frame = 1\ngrab = [11.0, 3.0]\npages = 0"]);
        assert_eq!(line, 6, "{message}");
        assert!(message.contains("pages must be"), "{message}");
        let (line, _) = refused("dog", &["frame = 1\ngrab = [11.0, 3.0]\nside = \"up\""]);
        assert_eq!(line, 6);
    }
}
