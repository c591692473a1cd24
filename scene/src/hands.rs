//! The hands of a sheet scene (`[[input.hands]]`): each hand pinches the sheet with one or
//! more fingers at the start and moves them as one rigid body, in timed segments of constant
//! velocity and spin, until it lets go.
//!
//! **Pose.** A hand's centre $c_0$ is the mean of its fingers' grabbed points $p_k$ (3D, on
//! the flat sheet at $(u, v, 0)$). Over its segments, in time order, the hand translates by
//! $\Delta c(t) = \sum_s v_s\thinspace d_s(t)$ and turns by $R(t) = \prod_s \exp([\omega_s]_\times
//! d_s(t))$ (later segments on the left), with $d_s(t)$ the time of segment $s$ elapsed by
//! $t$; finger $k$ is at $c_0 + \Delta c(t) + R(t)(p_k - c_0)$: the spin turns the fingers
//! about the moving centre. Times are simulated seconds: frame $f$ (1/60 s,
//! [`crate::clock::FRAME_SECONDS`] $= \Delta t$, whatever the sheet's `sheet.time_step`)
//! ends at $t = (f + 1)\thinspace\Delta t$, and the fingers are placed at that time before
//! the frame's steps. A release at time $r$ lets go before frame
//! $\mathrm{round}(r / \Delta t)$.

use core::ops::Range;

use folio_kernels::Vec3Ops;
use folio_tearing::sheet::{TearingSheet, TearingSheetError};
use toml::Spanned;

use crate::scene::{HandSpec, MoveSpec};

/// Largest time (seconds) a move or a release may name: the scene's frame limit at 60 fps.
const MAX_TIME: f64 = 1_000_000.0 / 60.0;

/// Largest speed (sheet units per second) and spin (radians per second).
const MAX_RATE: f64 = 1e3;

/// Most fingers on one hand.
const MAX_FINGERS: usize = 16;

/// Seconds a scene runs past its last move or release when it sets no `frames`.
pub const SETTLE_SECONDS: f64 = 1.0;

/// A 3x3 rotation, row-major.
type Rotation = [[f64; 3]; 3];

const IDENTITY: Rotation = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// A checked segment of motion.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Move {
    start: f64,
    /// `f64::INFINITY` for a move to the end of the run.
    end: f64,
    velocity: [f64; 3],
    spin: [f64; 3],
}

/// One hand of a run.
#[derive(Clone, Debug, PartialEq)]
struct Hand {
    /// The sheet's finger index of each finger (shifted as other hands let go).
    fingers: Vec<usize>,
    /// The grabbed points (3D).
    points: Vec<[f64; 3]>,
    /// Their mean.
    centre: [f64; 3],
    moves: Vec<Move>,
    /// The frame before which the hand lets go.
    release: Option<u32>,
    /// Let go already.
    released: bool,
}

/// The hands of a run, holding a [`TearingSheet`] (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Hands {
    hands: Vec<Hand>,
    time_step: f64,
}

type Problem = (Range<usize>, String);

fn finite3(v: [f64; 3]) -> bool {
    v.iter().all(|c| c.is_finite() && c.abs() <= MAX_RATE)
}

/// A time in seconds, or the problem with it.
fn seconds(t: &Spanned<f64>, key: &str) -> Result<f64, Problem> {
    let v = *t.get_ref();
    if v.is_finite() && (0.0..=MAX_TIME).contains(&v) {
        Ok(v)
    } else {
        Err((
            t.span(),
            format!("{key} must be in [0, {MAX_TIME:.0}] seconds"),
        ))
    }
}

/// The checked moves of one hand.
fn moves(specs: &[Spanned<MoveSpec>]) -> Result<Vec<Move>, Problem> {
    let mut out: Vec<Move> = Vec::with_capacity(specs.len());
    for spec in specs {
        let m = spec.get_ref();
        let start = seconds(&m.start, "a move's start")?;
        let end = match &m.end {
            Some(e) => seconds(e, "a move's end")?,
            None => f64::INFINITY,
        };
        if end <= start {
            let span = m.end.as_ref().map_or(spec.span(), Spanned::span);
            return Err((span, "a move's end must come after its start".into()));
        }
        if let Some(previous) = out.last() {
            if previous.end.is_infinite() {
                return Err((
                    spec.span(),
                    "a move without `end` must be the hand's last".into(),
                ));
            }
            if start < previous.end {
                return Err((
                    m.start.span(),
                    "moves must follow each other: this one starts before the previous ends".into(),
                ));
            }
        }
        let rate = |v: &Option<Spanned<[f64; 3]>>, key: &str| match v {
            Some(v) if finite3(*v.get_ref()) => Ok(*v.get_ref()),
            Some(v) => Err((
                v.span(),
                format!("{key} must be finite, each component at most {MAX_RATE} in size"),
            )),
            None => Ok([0.0; 3]),
        };
        let velocity = rate(&m.velocity, "velocity")?;
        let spin = rate(&m.spin, "spin")?;
        if m.velocity.is_none() && m.spin.is_none() {
            return Err((
                spec.span(),
                "a move needs `velocity`, `spin` or both".into(),
            ));
        }
        out.push(Move {
            start,
            end,
            velocity,
            spin,
        });
    }
    Ok(out)
}

/// Checks `hands` on a sheet of `size` `[W, H]`: at least one hand, each with 1 to 16
/// fingers on the sheet; moves in time order, each with a velocity or a spin; finite times.
///
/// # Errors
/// The span of the offending hand or value and what is wrong.
pub fn check(hands: &Spanned<Vec<Spanned<HandSpec>>>, size: [f64; 2]) -> Result<(), Problem> {
    if hands.get_ref().is_empty() {
        return Err((hands.span(), "input.hands is empty".into()));
    }
    for hand in hands.get_ref() {
        let h = hand.get_ref();
        let fingers = h.fingers.get_ref();
        if !(1..=MAX_FINGERS).contains(&fingers.len()) {
            return Err((
                h.fingers.span(),
                format!("a hand has 1 to {MAX_FINGERS} fingers"),
            ));
        }
        for f in fingers {
            let [u, v] = *f.get_ref();
            let on = (0.0..=size[0]).contains(&u) && (0.0..=size[1]).contains(&v);
            if !on {
                return Err((
                    f.span(),
                    format!(
                        "a finger must pinch the {w} x {h} sheet (0 <= u <= {w}, 0 <= v <= {h})",
                        w = crate::number::show(size[0]),
                        h = crate::number::show(size[1])
                    ),
                ));
            }
        }
        let m = moves(&h.moves)?;
        if let Some(r) = &h.release {
            let t = seconds(r, "release")?;
            if m.iter().any(|m| m.start >= t) {
                return Err((r.span(), "the hand lets go before a move starts".into()));
            }
        }
    }
    Ok(())
}

/// The frames a run of checked `hands` takes when the scene sets none: up to the last
/// move's end or release, plus [`SETTLE_SECONDS`], at `time_step` seconds per frame (a run
/// passes [`crate::clock::FRAME_SECONDS`]).
///
/// # Errors
/// A move without an end of a hand that never lets go (it runs to the end of the run, so
/// the run needs `frames`).
pub fn default_frames(hands: &[Spanned<HandSpec>], time_step: f64) -> Result<u32, Problem> {
    let mut last = 0.0f64;
    for hand in hands {
        let h = hand.get_ref();
        for m in &h.moves {
            match &m.get_ref().end {
                Some(e) => last = last.max(*e.get_ref()),
                None if h.release.is_some() => {}
                None => {
                    return Err((
                        m.span(),
                        "a move without `end` lasts to the end of the run: give the scene `frames`"
                            .into(),
                    ));
                }
            }
        }
        if let Some(r) = &h.release {
            last = last.max(*r.get_ref());
        }
    }
    let frames = ((last + SETTLE_SECONDS) / time_step).round();
    Ok(frames.clamp(1.0, 1_000_000.0) as u32)
}

/// $\exp([\omega]_\times\thinspace d)$ by Rodrigues' formula (the identity for no turn).
fn rotation(spin: [f64; 3], d: f64) -> Rotation {
    let norm = (spin[0] * spin[0] + spin[1] * spin[1] + spin[2] * spin[2]).sqrt();
    let angle = norm * d;
    if !(angle.is_finite() && angle != 0.0) {
        return IDENTITY;
    }
    let k = spin.map(|c| c / norm);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [
            c + t * k[0] * k[0],
            t * k[0] * k[1] - s * k[2],
            t * k[0] * k[2] + s * k[1],
        ],
        [
            t * k[1] * k[0] + s * k[2],
            c + t * k[1] * k[1],
            t * k[1] * k[2] - s * k[0],
        ],
        [
            t * k[2] * k[0] - s * k[1],
            t * k[2] * k[1] + s * k[0],
            c + t * k[2] * k[2],
        ],
    ]
}

fn multiply(a: &Rotation, b: &Rotation) -> Rotation {
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

fn apply(r: &Rotation, v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

/// The hand's translation and rotation at time `t` (module docs).
fn pose(moves: &[Move], t: f64) -> ([f64; 3], Rotation) {
    let mut shift = [0.0; 3];
    let mut turn = IDENTITY;
    for m in moves {
        let d = (t.min(m.end) - m.start).max(0.0);
        if d == 0.0 {
            continue;
        }
        for (s, v) in shift.iter_mut().zip(m.velocity) {
            *s += v * d;
        }
        turn = multiply(&rotation(m.spin, d), &turn);
    }
    (shift, turn)
}

impl Hands {
    /// Every hand of checked `specs` pinches `sheet`; the hands run at `time_step` seconds
    /// per frame (a run passes [`crate::clock::FRAME_SECONDS`]).
    ///
    /// # Errors
    /// The span of a finger the sheet refuses (off the sheet, or on a point another finger
    /// already holds) and why; the sheet may hold the fingers before it.
    pub fn grab(
        sheet: &mut TearingSheet<f64>,
        specs: &[Spanned<HandSpec>],
        time_step: f64,
    ) -> Result<Self, Problem> {
        let mut hands = Vec::with_capacity(specs.len());
        for spec in specs {
            let h = spec.get_ref();
            let mut fingers = Vec::new();
            let mut points = Vec::new();
            for f in h.fingers.get_ref() {
                let index = sheet.grab(*f.get_ref()).map_err(|e| {
                    let why = match e {
                        TearingSheetError::CoincidentFingers { .. } => {
                            "another finger already pinches this point (fingers closer than \
                             the snap distance share a vertex)"
                                .to_string()
                        }
                        e => e.to_string(),
                    };
                    (f.span(), why)
                })?;
                let x = sheet.fingers()[index].target;
                fingers.push(index);
                points.push([x.x(), x.y(), x.z()]);
            }
            let n = points.len().max(1) as f64;
            let centre = [0, 1, 2].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
            hands.push(Hand {
                fingers,
                points,
                centre,
                moves: moves(&h.moves)?,
                release: h
                    .release
                    .as_ref()
                    .map(|r| (*r.get_ref() / time_step).round() as u32),
                released: false,
            });
        }
        Ok(Self { hands, time_step })
    }

    /// Before the step of `frame`: lets go of the hands due, then places every held finger
    /// at its hand's pose at the frame's end (module docs).
    ///
    /// # Errors
    /// The sheet's refusal of a target (a non-finite pose).
    pub fn apply(
        &mut self,
        sheet: &mut TearingSheet<f64>,
        frame: u32,
    ) -> Result<(), TearingSheetError> {
        for k in 0..self.hands.len() {
            let due = self.hands[k].release.is_some_and(|r| frame >= r);
            if due && !self.hands[k].released {
                self.let_go(sheet, k)?;
            }
        }
        let t = f64::from(frame + 1) * self.time_step;
        for hand in self.hands.iter().filter(|h| !h.released) {
            let (shift, turn) = pose(&hand.moves, t);
            for (&index, p) in hand.fingers.iter().zip(&hand.points) {
                let offset = apply(&turn, [0, 1, 2].map(|k| p[k] - hand.centre[k]));
                let x = [0, 1, 2].map(|k| hand.centre[k] + shift[k] + offset[k]);
                sheet.move_finger(index, Vec3Ops::new(x[0], x[1], x[2]))?;
            }
        }
        Ok(())
    }

    /// Releases hand `k`'s fingers, highest index first, and renumbers the other hands'.
    fn let_go(&mut self, sheet: &mut TearingSheet<f64>, k: usize) -> Result<(), TearingSheetError> {
        let mut gone = self.hands[k].fingers.clone();
        gone.sort_unstable_by(|a, b| b.cmp(a));
        for &index in &gone {
            sheet.release(index)?;
            for hand in &mut self.hands {
                for f in &mut hand.fingers {
                    if *f > index {
                        *f -= 1;
                    }
                }
            }
        }
        self.hands[k].released = true;
        self.hands[k].fingers.clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    /// A quarter turn about +y takes +x to -z (right-handed).
    #[test]
    fn rotation_is_right_handed() {
        let r = rotation([0.0, 2.0, 0.0], core::f64::consts::FRAC_PI_4);
        assert!(close(apply(&r, [1.0, 0.0, 0.0]), [0.0, 0.0, -1.0]));
        assert_eq!(rotation([0.0; 3], 5.0), IDENTITY);
    }

    /// The hand is still before, between and after its moves; a spin turns the offsets.
    #[test]
    fn pose_integrates_the_segments() {
        let moves = [
            Move {
                start: 1.0,
                end: 2.0,
                velocity: [1.0, 0.0, 0.0],
                spin: [0.0; 3],
            },
            Move {
                start: 3.0,
                end: f64::INFINITY,
                velocity: [0.0, -1.0, 0.0],
                spin: [0.0, 0.0, 1.0],
            },
        ];
        assert!(close(pose(&moves, 0.5).0, [0.0; 3]));
        assert!(close(pose(&moves, 1.5).0, [0.5, 0.0, 0.0]));
        assert!(close(pose(&moves, 2.5).0, [1.0, 0.0, 0.0]));
        let (shift, turn) = pose(&moves, 3.0 + core::f64::consts::FRAC_PI_2);
        assert!(close(shift, [1.0, -core::f64::consts::FRAC_PI_2, 0.0]));
        assert!(close(apply(&turn, [1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]));
    }
}
