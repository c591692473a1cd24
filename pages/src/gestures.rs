//! Any number of gestures in sequence: grab, drag, release, grab again, on either side of
//! the spine, one page or a stack. A [`TouchScript`] holds one gesture of one page from the
//! right; [`Gestures`] holds a list of them, each with the side its page lies on and the
//! pages it takes, one after the other, and drives every [`super::PageModel`] frame by frame
//! ([`Gestures::at`]). The models that cannot take a gesture refuse it with
//! [`GestureError`] ([`super::PageModel::grab_page`]).
//!
//! Frames: gesture $k$ holds the page from its `grab_frame` for `path.len()` frames (one
//! finger position per held frame, page frame of [`super`]) and lets go at
//! `grab_frame + path.len()`; the next gesture grabs at that frame or later.

use alloc::vec::Vec;
use folio_geometry::BlockSide;

use super::touch::{Touch, TouchScript};

/// One grab, the finger's path while held, and the release (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Gesture {
    /// The side of the spine the grabbed page lies on (where the finger starts:
    /// $(u, 0, v)$ on the right, $(-u, 0, v)$ on the left).
    pub side: BlockSide,
    /// Pages taken at once (a stack: the DOG book; 1 for the one-page models).
    pub pages: u32,
    /// The grabbed material point $(u, v)$ (page units).
    pub grab: [f64; 2],
    /// The first held frame.
    pub grab_frame: u32,
    /// Finger positions (page frame), one per held frame; not empty.
    pub path: Vec<[f64; 3]>,
}

impl Gesture {
    /// The frame of the release (the first frame not held).
    #[must_use]
    pub fn release_frame(&self) -> u32 {
        self.grab_frame
            .saturating_add(u32::try_from(self.path.len()).unwrap_or(u32::MAX))
    }
}

/// Why a model refused a gesture, or why a sequence does not hold together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GestureError {
    /// No page to take on `side`: a one-page model whose page lies on the other side, or a
    /// block with too few pages.
    NoPage {
        /// The side of the grab.
        side: BlockSide,
        /// The model's name.
        model: &'static str,
    },
    /// A stack on a model of one page.
    Stack {
        /// The pages asked for.
        pages: u32,
    },
    /// The page released by the gesture before still moves on the other side.
    Unsettled {
        /// The side of the grab.
        side: BlockSide,
    },
    /// Gesture `index` (0-based) holds no frame, takes no page, or starts before the gesture
    /// before it let go.
    Sequence {
        /// The offending gesture.
        index: usize,
    },
}

/// The name of a side in messages and scene files.
#[must_use]
pub fn side_name(side: BlockSide) -> &'static str {
    match side {
        BlockSide::Left => "left",
        BlockSide::Right => "right",
    }
}

impl core::fmt::Display for GestureError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::NoPage { side, model } => write!(
                f,
                "the {model} model has no page to grab on the {}",
                side_name(side)
            ),
            Self::Stack { pages } => {
                write!(f, "a stack of {pages} pages: this model turns one page")
            }
            Self::Unsettled { side } => write!(
                f,
                "the page released before still moves on the other side; a grab on the {} \
                 waits until it settles",
                side_name(side)
            ),
            Self::Sequence { index } => write!(
                f,
                "gesture {}: no held frame, no page, or a grab before the previous release",
                index + 1
            ),
        }
    }
}

impl core::error::Error for GestureError {}

/// Gestures in sequence (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Gestures {
    /// Frames to run.
    pub frames: u32,
    gestures: Vec<Gesture>,
}

impl Gestures {
    /// `gestures` in frame order over `frames` frames.
    ///
    /// # Errors
    /// [`GestureError::Sequence`] for a gesture with an empty path or no pages, or one that
    /// grabs before the one before it let go.
    pub fn new(frames: u32, gestures: Vec<Gesture>) -> Result<Self, GestureError> {
        let mut free_from = 0;
        for (index, g) in gestures.iter().enumerate() {
            if g.path.is_empty() || g.pages == 0 || g.grab_frame < free_from {
                return Err(GestureError::Sequence { index });
            }
            free_from = g.release_frame();
        }
        Ok(Self { frames, gestures })
    }

    /// The gestures, in frame order.
    #[must_use]
    pub fn gestures(&self) -> &[Gesture] {
        &self.gestures
    }

    /// The gesture holding or grabbing at `frame` (the last one that grabbed at or before
    /// it), with its index.
    #[must_use]
    pub fn gesture_at(&self, frame: u32) -> Option<(usize, &Gesture)> {
        let k = self.gestures.partition_point(|g| g.grab_frame <= frame);
        k.checked_sub(1).map(|i| (i, &self.gestures[i]))
    }

    /// The input at `frame`: [`Touch::Take`] at a grab, [`Touch::Drag`] while held,
    /// [`Touch::Release`] at the frame after the last held one, else [`Touch::None`].
    #[must_use]
    pub fn at(&self, frame: u32) -> Touch {
        let Some((_, g)) = self.gesture_at(frame) else {
            return Touch::None;
        };
        let k = (frame - g.grab_frame) as usize;
        match g.path.get(k) {
            Some(&finger) if k == 0 => Touch::Take {
                side: g.side,
                pages: g.pages,
                at: g.grab,
                finger,
            },
            Some(&finger) => Touch::Drag(finger),
            None if k == g.path.len() => Touch::Release,
            None => Touch::None,
        }
    }
}

impl From<TouchScript> for Gestures {
    /// The one gesture of `script`: one page from the right.
    fn from(script: TouchScript) -> Self {
        let gestures = if script.path.is_empty() {
            Vec::new()
        } else {
            alloc::vec![Gesture {
                side: BlockSide::Right,
                pages: 1,
                grab: script.grab,
                grab_frame: script.grab_frame,
                path: script.path,
            }]
        };
        Self {
            frames: script.frames,
            gestures,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gesture(side: BlockSide, grab_frame: u32, held: usize) -> Gesture {
        Gesture {
            side,
            pages: 1,
            grab: [10.0, 3.0],
            grab_frame,
            path: alloc::vec![[1.0, 2.0, 3.0]; held],
        }
    }

    #[test]
    fn each_gesture_grabs_drags_and_lets_go_in_turn() {
        let g = Gestures::new(
            20,
            alloc::vec![
                gesture(BlockSide::Right, 2, 3),
                gesture(BlockSide::Left, 5, 2)
            ],
        )
        .unwrap();
        let take = |side| Touch::Take {
            side,
            pages: 1,
            at: [10.0, 3.0],
            finger: [1.0, 2.0, 3.0],
        };
        let drag = Touch::Drag([1.0, 2.0, 3.0]);
        let seen: Vec<Touch> = (0..9).map(|f| g.at(f)).collect();
        assert_eq!(
            seen,
            [
                Touch::None,
                Touch::None,
                take(BlockSide::Right),
                drag,
                drag,
                // The second grab comes at the first frame the first lets go: a grab.
                take(BlockSide::Left),
                drag,
                Touch::Release,
                Touch::None,
            ]
        );
        assert_eq!(g.gesture_at(6).map(|(k, _)| k), Some(1));
        assert_eq!(g.gesture_at(1), None);
    }

    #[test]
    fn a_sequence_that_overlaps_or_holds_nothing_is_refused() {
        let overlap = alloc::vec![
            gesture(BlockSide::Right, 2, 3),
            gesture(BlockSide::Left, 4, 2)
        ];
        assert_eq!(
            Gestures::new(20, overlap),
            Err(GestureError::Sequence { index: 1 })
        );
        let empty = alloc::vec![gesture(BlockSide::Right, 2, 0)];
        assert_eq!(
            Gestures::new(20, empty),
            Err(GestureError::Sequence { index: 0 })
        );
    }

    #[test]
    fn a_touch_script_is_one_gesture_from_the_right() {
        let script = TouchScript::page_turn(12.0, 17.0, 10, 5, 40);
        let g = Gestures::from(script.clone());
        assert_eq!(g.gestures().len(), 1);
        assert_eq!(g.gestures()[0].side, BlockSide::Right);
        assert_eq!(g.gestures()[0].release_frame(), script.release_frame());
        assert_eq!(g.at(15), Touch::Release);
    }
}
