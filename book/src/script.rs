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
                    let frame = first
                        .parse::<u32>()
                        .map_err(|_| err("expected a keyword or a frame number"))?;
                    if !(header && frames && camera) {
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
                            let direction = numbers::<3>(&mut words, line)?;
                            let [pages] = numbers::<1>(&mut words, line)?;
                            let pages = whole(pages, 1.0e6)
                                .ok_or(err("pages must be a whole number in 1..=10^6"))?;
                            Action::Grab { direction, pages }
                        }
                        Some("drag") => Action::Drag {
                            direction: numbers::<3>(&mut words, line)?,
                        },
                        Some("release") => Action::Release,
                        Some("bookmark-add") => Action::BookmarkAdd,
                        Some("bookmark-remove") => Action::BookmarkRemove,
                        _ => return Err(err("unknown event")),
                    };
                    script.events.push(Event { frame, action });
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
