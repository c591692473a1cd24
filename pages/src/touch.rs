//! Recorded touch input for page models: where the page is grabbed, where the finger is on
//! every held frame, when it lets go. One script drives every [`super::PageModel`].
//!
//! Text format (line based, `#` comments):
//! ```text
//! folio-touch 1
//! frames 240
//! grab 12 8.485 at 10          # material point (u, v), first held frame
//! 10 10.8 0 8.485              # frame, finger x y z (page frame), one line per held frame
//! ...
//! release 130
//! ```

use alloc::vec::Vec;
use folio_kernels::{Real, Vec3Ops, math};

use super::{PageError, PageModel};

/// A recorded touch input (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TouchScript {
    /// Frames to run.
    pub frames: u32,
    /// The grabbed material point $(u, v)$ (page units).
    pub grab: [f64; 2],
    /// The frame of the grab (the first held frame).
    pub grab_frame: u32,
    /// Finger positions (page frame), one per frame from `grab_frame` on.
    pub path: Vec<[f64; 3]>,
}

/// Why a touch script does not parse.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TouchScriptError {
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub message: &'static str,
}

impl core::fmt::Display for TouchScriptError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl core::error::Error for TouchScriptError {}

/// What the script asks for at one frame, before the step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Touch {
    /// Grab `at` with the finger at `finger`.
    Grab {
        /// Material point.
        at: [f64; 2],
        /// Finger position.
        finger: [f64; 3],
    },
    /// Grab `pages` pages lying on `side` at `at` with the finger at `finger` (a gesture of a
    /// [`super::Gestures`] sequence; [`super::PageModel::grab_page`]).
    Take {
        /// The side the page lies on.
        side: folio_geometry::BlockSide,
        /// Pages taken at once.
        pages: u32,
        /// Material point.
        at: [f64; 2],
        /// Finger position.
        finger: [f64; 3],
    },
    /// Move the finger.
    Drag([f64; 3]),
    /// Let go.
    Release,
    /// Nothing.
    None,
}

impl Touch {
    /// Feeds this input to `model` (grab, then drag to the finger; drag; release).
    ///
    /// # Errors
    /// As [`super::PageModel::grab`], [`super::PageModel::grab_page`] and
    /// [`super::PageModel::drag`].
    pub fn apply<T: Real>(self, model: &mut dyn PageModel<T>) -> Result<(), PageError> {
        let point =
            |p: [f64; 3]| T::Vec3::new(T::from_f64(p[0]), T::from_f64(p[1]), T::from_f64(p[2]));
        match self {
            Self::Grab { at, finger } => {
                model.grab([T::from_f64(at[0]), T::from_f64(at[1])])?;
                model.drag(point(finger))
            }
            Self::Take {
                side,
                pages,
                at,
                finger,
            } => {
                model.grab_page(side, pages, [T::from_f64(at[0]), T::from_f64(at[1])])?;
                model.drag(point(finger))
            }
            Self::Drag(finger) => model.drag(point(finger)),
            Self::Release => {
                model.release();
                Ok(())
            }
            Self::None => Ok(()),
        }
    }
}

impl TouchScript {
    /// The frame of the release (the first frame not held).
    #[must_use]
    pub fn release_frame(&self) -> u32 {
        self.grab_frame + self.path.len() as u32
    }

    /// The input at `frame`.
    #[must_use]
    pub fn at(&self, frame: u32) -> Touch {
        if frame < self.grab_frame {
            return Touch::None;
        }
        let k = (frame - self.grab_frame) as usize;
        match self.path.get(k) {
            Some(&finger) if k == 0 => Touch::Grab {
                at: self.grab,
                finger,
            },
            Some(&finger) => Touch::Drag(finger),
            None if k == self.path.len() && !self.path.is_empty() => Touch::Release,
            None => Touch::None,
        }
    }

    /// The shared page turn on a `width` x `height` page: the fore-edge point
    /// $(W, v_0)$, $v_0 = 0.2 H$ (near the bottom corner, where readers take a page), is
    /// grabbed at frame `grab_frame` and carried over the spine for `held` frames on
    /// $$x = W (1 - 0.1 \sin\varphi)\cos\varphi,\quad y = 0.7 W \sin\varphi,\quad
    ///   z = v_0 + 0.12 H \sin\varphi,\qquad \varphi = \pi\thinspace\mathrm{smoothstep}(s),$$
    /// from its rest position to its mirror image $(-W, 0, v_0)$ (both exactly where a flat
    /// page puts it), then released; `frames` in all.
    #[must_use]
    pub fn page_turn(width: f64, height: f64, grab_frame: u32, held: u32, frames: u32) -> Self {
        let v0 = 0.2 * height;
        let path = (0..held)
            .map(|k| {
                let s = f64::from(k) / f64::from(held.max(2) - 1);
                let phi = core::f64::consts::PI * s * s * (3.0 - 2.0 * s);
                let (sin, cos) = (math::sin::<f64>(phi), math::cos::<f64>(phi));
                [
                    width * (1.0 - 0.1 * sin) * cos,
                    0.7 * width * sin,
                    v0 + 0.12 * height * sin,
                ]
            })
            .collect();
        Self {
            frames,
            grab: [width, v0],
            grab_frame,
            path,
        }
    }

    /// Parses the text format (module docs).
    ///
    /// # Errors
    /// The first bad line: a missing header, an unknown line, a non-finite number, frames
    /// out of order or with gaps, a path that runs past `frames`.
    pub fn parse(text: &str) -> Result<Self, TouchScriptError> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l.split('#').next().unwrap_or("").trim()))
            .filter(|(_, l)| !l.is_empty());
        let bad = |line, message| Err(TouchScriptError { line, message });
        match lines.next() {
            Some((_, "folio-touch 1")) => {}
            Some((line, _)) => return bad(line, "expected the header `folio-touch 1`"),
            None => return bad(1, "empty script"),
        }
        let mut script = Self {
            frames: 0,
            grab: [0.0; 2],
            grab_frame: 0,
            path: Vec::new(),
        };
        let (mut has_frames, mut has_grab, mut released) = (false, false, false);
        for (line, text) in lines {
            let words: Vec<&str> = text.split_whitespace().collect();
            let numbers = |from: usize| -> Option<Vec<f64>> {
                words[from..]
                    .iter()
                    .map(|w| w.parse::<f64>().ok().filter(|v| v.is_finite()))
                    .collect()
            };
            match words.as_slice() {
                ["frames", n] => {
                    let Some(n) = whole(n) else {
                        return bad(line, "frames: expected a whole number");
                    };
                    script.frames = n;
                    has_frames = true;
                }
                ["grab", u, v, "at", f] => {
                    let (Some(u), Some(v), Some(f)) = (number(u), number(v), whole(f)) else {
                        return bad(line, "grab: expected `grab U V at FRAME`");
                    };
                    script.grab = [u, v];
                    script.grab_frame = f;
                    has_grab = true;
                }
                ["release", f] => {
                    if whole(f) != Some(script.release_frame()) || !has_grab {
                        return bad(line, "release: must follow the last path frame");
                    }
                    released = true;
                }
                [_, _, _, _] if has_grab && !released => {
                    let (Some(f), Some(p)) = (whole(words[0]), numbers(1)) else {
                        return bad(line, "path: expected `FRAME X Y Z` with finite numbers");
                    };
                    if f != script.release_frame() {
                        return bad(line, "path: frames must follow each other from the grab");
                    }
                    script.path.push([p[0], p[1], p[2]]);
                }
                _ => return bad(line, "unknown line"),
            }
        }
        if !(has_frames && has_grab && released) || script.path.is_empty() {
            return bad(0, "a script needs `frames`, `grab`, a path and `release`");
        }
        if script.release_frame() > script.frames {
            return bad(0, "the path runs past `frames`");
        }
        Ok(script)
    }

    /// The script in the text format; [`TouchScript::parse`] reads it back exactly.
    #[must_use]
    pub fn to_text(&self) -> alloc::string::String {
        use core::fmt::Write;
        let mut s = alloc::string::String::new();
        let _ = writeln!(s, "folio-touch 1\nframes {}", self.frames);
        let _ = writeln!(
            s,
            "grab {} {} at {}",
            self.grab[0], self.grab[1], self.grab_frame
        );
        for (k, p) in self.path.iter().enumerate() {
            let _ = writeln!(
                s,
                "{} {} {} {}",
                self.grab_frame as usize + k,
                p[0],
                p[1],
                p[2]
            );
        }
        let _ = writeln!(s, "release {}", self.release_frame());
        s
    }
}

fn number(w: &str) -> Option<f64> {
    w.parse::<f64>().ok().filter(|v| v.is_finite())
}

fn whole(w: &str) -> Option<u32> {
    w.parse::<u32>().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCRIPT: &str = "folio-touch 1\nframes 6  # a comment\n\ngrab 11 3 at 2\n\
        2 10 1 3\n3 9 2 3\nrelease 4\n";

    #[test]
    fn a_script_reads_back_what_it_writes() {
        let script = TouchScript::parse(SCRIPT).unwrap();
        assert_eq!(
            (script.frames, script.grab, script.grab_frame),
            (6, [11.0, 3.0], 2)
        );
        assert_eq!(script.path, [[10.0, 1.0, 3.0], [9.0, 2.0, 3.0]]);
        assert_eq!(script.release_frame(), 4);
        assert_eq!(TouchScript::parse(&script.to_text()).unwrap(), script);
    }

    #[test]
    fn every_bad_line_is_named() {
        let cases = [
            ("", 1),
            ("folio-touch 2\n", 1),
            ("folio-touch 1\nframes -1\n", 2),
            ("folio-touch 1\nframes 6\ngrab 1 2 at x\n", 3),
            ("folio-touch 1\nframes 6\ngrab 1 2 at 0\n0 1 2 inf\n", 4),
            ("folio-touch 1\nframes 6\ngrab 1 2 at 0\n1 1 2 3\n", 4),
            (
                "folio-touch 1\nframes 6\ngrab 1 2 at 0\n0 1 2 3\nrelease 3\n",
                5,
            ),
            ("folio-touch 1\nframes 6\nwave\n", 3),
            (
                "folio-touch 1\nframes 1\ngrab 1 2 at 0\n0 1 2 3\n1 1 2 3\nrelease 2\n",
                0,
            ),
            ("folio-touch 1\nframes 6\ngrab 1 2 at 0\n", 0),
        ];
        for (text, line) in cases {
            let e = TouchScript::parse(text).expect_err(text);
            assert_eq!(e.line, line, "{text:?}: {}", e.message);
        }
    }

    #[test]
    fn numbers_are_finite_and_frames_whole() {
        assert_eq!(number("2.5"), Some(2.5));
        assert_eq!(number("NaN"), None);
        assert_eq!(whole("7"), Some(7));
        assert_eq!(whole("-7"), None);
        assert_eq!(whole("7.0"), None);
    }
}
