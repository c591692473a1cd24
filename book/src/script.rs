//! Recorded user input (the fixtures of the page-turn, peek and bookmarking sequences): a
//! camera and timed grab / drag / release / bookmark events, one per line.
//!
//! ```text
//! folio-input 1
//! frames 750
//! camera <ox> <oy> <oz> <fx> <fy> <fz>   # camera position and forward direction
//! <frame> grab <dx> <dy> <dz> <pages>    # ray from the camera along d; grab `pages` pages
//! <frame> drag <dx> <dy> <dz>
//! <frame> release
//! <frame> bookmark-add                   # finger-bookmarking: one more page into the grip
//! <frame> bookmark-remove
//! ```
//! `#` starts a comment; frames are non-decreasing. Lengths in page units.

use alloc::vec::Vec;
use core::fmt;

/// One input.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Action {
    /// Grab along the camera ray with this direction, taking `pages` pages.
    Grab {
        /// Ray direction.
        direction: [f64; 3],
        /// Pages to take.
        pages: u32,
    },
    /// Drag along the camera ray with this direction.
    Drag {
        /// Ray direction.
        direction: [f64; 3],
    },
    /// Let go.
    Release,
    /// Finger-bookmarking: flip one more page into the grip.
    BookmarkAdd,
    /// Finger-bookmarking: let one page go back out of the grip.
    BookmarkRemove,
}

/// An input at a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Frame index (0-based) before whose step the input applies.
    pub frame: u32,
    /// The input.
    pub action: Action,
}

/// A recorded input sequence (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    /// Frames to simulate.
    pub frames: u32,
    /// Camera position.
    pub camera: [f64; 3],
    /// Camera forward direction (the drag plane's normal).
    pub forward: [f64; 3],
    /// Events in frame order.
    pub events: Vec<Event>,
}

/// A malformed script line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScriptError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub message: &'static str,
}

impl fmt::Display for ScriptError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "input script line {}: {}", self.line, self.message)
    }
}

#[cfg(feature = "std")]
impl core::error::Error for ScriptError {}

fn numbers<const N: usize>(
    words: &mut core::str::SplitWhitespace<'_>,
    line: usize,
) -> Result<[f64; N], ScriptError> {
    let mut out = [0.0; N];
    for v in &mut out {
        let word = words.next().ok_or(ScriptError {
            line,
            message: "missing number",
        })?;
        *v = word
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or(ScriptError {
                line,
                message: "not a finite number",
            })?;
    }
    Ok(out)
}

/// `n` as a whole number in `1..=max`.
fn whole(n: f64, max: f64) -> Option<u32> {
    let k = n as u32;
    ((1.0..=max).contains(&n) && f64::from(k) == n).then_some(k)
}

/// The event of a line that starts with the frame number `first`, the rest of the line in
/// `words`; `script` holds the lines before, `ready` when they gave the header, frames and
/// camera lines.
fn parse_event(
    script: &Script,
    first: &str,
    words: &mut core::str::SplitWhitespace<'_>,
    line: usize,
    ready: bool,
) -> Result<Event, ScriptError> {
    let err = |message| ScriptError { line, message };
    let frame = first
        .parse::<u32>()
        .map_err(|_| err("expected a keyword or a frame number"))?;
    if !ready {
        return Err(err(
            "events must follow the folio-input, frames and camera lines",
        ));
    }
    if frame >= script.frames {
        return Err(err("event frame beyond the last frame"));
    }
    if script.events.last().is_some_and(|e| e.frame > frame) {
        return Err(err("event frames must not decrease"));
    }
    let action = match words.next() {
        Some("grab") => {
            let direction = numbers::<3>(words, line)?;
            let [pages] = numbers::<1>(words, line)?;
            let pages =
                whole(pages, 1.0e6).ok_or(err("pages must be a whole number in 1..=10^6"))?;
            Action::Grab { direction, pages }
        }
        Some("drag") => Action::Drag {
            direction: numbers::<3>(words, line)?,
        },
        Some("release") => Action::Release,
        Some("bookmark-add") => Action::BookmarkAdd,
        Some("bookmark-remove") => Action::BookmarkRemove,
        _ => return Err(err("unknown event")),
    };
    Ok(Event { frame, action })
}

impl Script {
    /// Parses `text` (module docs).
    ///
    /// # Errors
    /// The first malformed line.
    pub fn parse(text: &str) -> Result<Self, ScriptError> {
        let mut script = Script {
            frames: 0,
            camera: [0.0; 3],
            forward: [0.0; 3],
            events: Vec::new(),
        };
        let (mut header, mut frames, mut camera) = (false, false, false);
        for (index, raw) in text.lines().enumerate() {
            let line = index + 1;
            let content = raw.split('#').next().unwrap_or("");
            let mut words = content.split_whitespace();
            let Some(first) = words.next() else { continue };
            let err = |message| ScriptError { line, message };
            match first {
                "folio-input" => {
                    if words.next() != Some("1") {
                        return Err(err("unsupported format version (expected 1)"));
                    }
                    header = true;
                }
                "frames" => {
                    let [n] = numbers::<1>(&mut words, line)?;
                    script.frames =
                        whole(n, 1.0e7).ok_or(err("frames must be a whole number in 1..=10^7"))?;
                    frames = true;
                }
                "camera" => {
                    let v = numbers::<6>(&mut words, line)?;
                    script.camera = [v[0], v[1], v[2]];
                    script.forward = [v[3], v[4], v[5]];
                    camera = true;
                }
                _ => {
                    let ready = header && frames && camera;
                    let event = parse_event(&script, first, &mut words, line, ready)?;
                    script.events.push(event);
                }
            }
            if words.next().is_some() {
                return Err(err("unexpected words at the end of the line"));
            }
        }
        if !(header && frames && camera) {
            return Err(ScriptError {
                line: text.lines().count().max(1),
                message: "missing folio-input, frames or camera line",
            });
        }
        Ok(script)
    }

    /// The events of `frame`.
    #[must_use]
    pub fn events_at(&self, frame: u32) -> &[Event] {
        let start = self.events.partition_point(|e| e.frame < frame);
        let end = self.events.partition_point(|e| e.frame <= frame);
        &self.events[start..end]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "folio-input 1\nframes 10\ncamera 0 1 2 0 0 -1\n";

    fn parse(events: &str) -> Result<Script, ScriptError> {
        Script::parse(&alloc::format!("{HEAD}{events}"))
    }

    fn error(text: &str) -> (usize, &'static str) {
        let e = Script::parse(text).unwrap_err();
        (e.line, e.message)
    }

    #[test]
    fn parses_the_header_and_every_event() {
        let s = parse(
            "# a comment line\n0 grab 1 -1 0 2 # trailing comment\n0 drag 1 -1 0.5\n\
             3 bookmark-add\n3 bookmark-remove\n9 release\n",
        )
        .unwrap();
        assert_eq!(s.frames, 10);
        assert_eq!((s.camera, s.forward), ([0.0, 1.0, 2.0], [0.0, 0.0, -1.0]));
        let actions: Vec<Action> = s.events.iter().map(|e| e.action).collect();
        assert_eq!(
            actions,
            [
                Action::Grab {
                    direction: [1.0, -1.0, 0.0],
                    pages: 2
                },
                Action::Drag {
                    direction: [1.0, -1.0, 0.5]
                },
                Action::BookmarkAdd,
                Action::BookmarkRemove,
                Action::Release,
            ]
        );
        assert_eq!(s.events_at(0).len(), 2);
        assert_eq!(s.events_at(3).len(), 2);
        assert!(s.events_at(5).is_empty());
        assert_eq!(s.events_at(9)[0].action, Action::Release);
    }

    #[test]
    fn an_empty_script_has_no_header() {
        assert_eq!(error("").0, 1);
        assert_eq!(
            error("frames 3\n").1,
            "missing folio-input, frames or camera line"
        );
        assert_eq!(
            error("folio-input 2\n").1,
            "unsupported format version (expected 1)"
        );
    }

    #[test]
    fn refuses_malformed_lines_by_number() {
        assert_eq!(
            error("folio-input 1\n0 release\n"),
            (
                2,
                "events must follow the folio-input, frames and camera lines"
            )
        );
        let at = |line: &str| error(&alloc::format!("{HEAD}{line}\n"));
        assert_eq!(at("10 release"), (4, "event frame beyond the last frame"));
        assert_eq!(at("x release"), (4, "expected a keyword or a frame number"));
        assert_eq!(at("1 jump"), (4, "unknown event"));
        assert_eq!(
            at("1 release now"),
            (4, "unexpected words at the end of the line")
        );
        assert_eq!(at("1 drag 1 2"), (4, "missing number"));
        assert_eq!(at("1 drag 1 2 inf"), (4, "not a finite number"));
        assert_eq!(
            at("1 grab 0 -1 0 1.5"),
            (4, "pages must be a whole number in 1..=10^6")
        );
        assert_eq!(
            error(&alloc::format!("{HEAD}2 release\n1 release\n")),
            (5, "event frames must not decrease")
        );
        assert_eq!(
            error("folio-input 1\nframes 0\n"),
            (2, "frames must be a whole number in 1..=10^7")
        );
    }

    #[test]
    fn whole_takes_exact_counts_in_range() {
        assert_eq!(whole(1.0, 10.0), Some(1));
        assert_eq!(whole(10.0, 10.0), Some(10));
        assert_eq!(whole(0.0, 10.0), None);
        assert_eq!(whole(11.0, 10.0), None);
        assert_eq!(whole(2.5, 10.0), None);
        assert_eq!(whole(f64::NAN, 10.0), None);
    }
}
