//! The DOG book stays bounded across its documented weight ranges (issue 20): weights drawn
//! log-uniformly across each range of [`folio_book::WEIGHT_RANGES`], with random gestures
//! (a grab anywhere on the page, waypoints over and beyond the book at speeds up to a
//! flick, back and forth, a release, a second grab), and after every step a finite state,
//! stretch at most 10 %, penetration at most one page thickness and every page accounted
//! for.
//!
//! A case runs about 300 steps of the default 8 x 11 book (a fraction of a second in the
//! test profile); the case counts keep each property under a minute.

use folio_book::{Book, BookSettings, GrabOutcome, IsometryHessian, Phase, WEIGHT_RANGES, Weights};
use folio_geometry::BlockSide;
use glam::DVec3;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError};

/// The stretch bound of issue 20.
const MAX_STRETCH: f64 = 0.1;

/// A weight drawn log-uniformly over `[lo, hi]` from `t` in [0, 1]; for `lo = 0` over
/// `[hi 1e-6, hi]`, and exactly 0 when `t` falls in the lowest eighth.
fn log_uniform(lo: f64, hi: f64, t: f64) -> f64 {
    if lo == 0.0 {
        if t < 0.125 {
            return 0.0;
        }
        let s = (t - 0.125) / 0.875;
        return hi * 1e-6f64.powf(1.0 - s);
    }
    lo * (hi / lo).powf(t)
}

fn weights(t: [f64; 5]) -> Weights<f64> {
    let w: Vec<f64> = WEIGHT_RANGES
        .iter()
        .zip(t)
        .map(|(&(_, lo, hi), t)| log_uniform(lo, hi, t))
        .collect();
    Weights {
        bend_page: w[0],
        bend_blocks: w[1],
        glue: w[2],
        iso_page: w[3],
        pull: w[4],
    }
}

/// One finger move: to `to` (fractions of the page width W across and up, of the page
/// height H along) in `frames` frames.
#[derive(Clone, Copy, Debug)]
struct Move {
    to: [f64; 3],
    frames: u32,
}

/// A gesture: grab the material point `at` (fractions of W and H), move through `moves`,
/// release, wait `rest` frames.
#[derive(Clone, Debug)]
struct Gesture {
    at: [f64; 2],
    moves: Vec<Move>,
    rest: u32,
}

fn moves() -> impl Strategy<Value = Vec<Move>> {
    let one = (
        (-1.3..1.3f64, 0.0..1.0f64, -0.2..1.2f64),
        // Two frames across the book is a flick (about 7 widths per second).
        2u32..40,
    )
        .prop_map(|((x, y, z), frames)| Move {
            to: [x, y, z],
            frames,
        });
    proptest::collection::vec(one, 1..4)
}

fn gesture() -> impl Strategy<Value = Gesture> {
    ((0.0..=1.0f64, 0.0..=1.0f64), moves(), 30u32..120).prop_map(|((u, v), moves, rest)| Gesture {
        at: [u, v],
        moves,
        rest,
    })
}

/// Checks the bounds after one step.
fn check(book: &Book<f64>, total: u32, frame: u32) -> Result<(), TestCaseError> {
    let s = book.state();
    let finite = s.x.iter().chain(&s.v).all(|p| p.is_finite());
    prop_assert!(finite, "frame {frame}: non-finite state");
    let c = book.counts();
    prop_assert_eq!(c.left + c.right + c.active, total, "frame {}: pages", frame);
    if let Some((max, _)) = book.stretch() {
        prop_assert!(max <= MAX_STRETCH, "frame {frame}: stretch {max:.4}");
        let pen = book.penetration().unwrap_or(0.0);
        let t = book.layout().params.page_thickness;
        prop_assert!(pen <= t, "frame {frame}: penetration {pen:.3e} > {t}");
    }
    Ok(())
}

/// Plays `gestures` on `book` (each grabs the block holding pages, the right one first),
/// checking the bounds after every step.
fn play(mut book: Book<f64>, gestures: &[Gesture]) -> Result<(), TestCaseError> {
    let total = book.layout().params.total_pages;
    let [w, h] = book.page_size();
    let mut frame = 0;
    for g in gestures {
        let side = if book.counts().right > 0 {
            BlockSide::Right
        } else {
            BlockSide::Left
        };
        let outcome = book
            .grab_at(side, [g.at[0] * w, g.at[1] * h], 1)
            .map_err(|e| TestCaseError::fail(format!("grab: {e:?}")))?;
        prop_assert!(
            matches!(outcome, GrabOutcome::Grabbed { .. }),
            "grab {outcome:?}"
        );
        let node = book.held_node().expect("held");
        let mut from = book.page().expect("page")[node];
        for m in &g.moves {
            let mirror = if side == BlockSide::Left { -1.0 } else { 1.0 };
            let to = DVec3::new(mirror * m.to[0] * w, m.to[1] * w, m.to[2] * h);
            for k in 1..=m.frames {
                let target = from.lerp(to, f64::from(k) / f64::from(m.frames));
                book.drag_to(target)
                    .map_err(|e| TestCaseError::fail(format!("drag: {e:?}")))?;
                book.step()
                    .map_err(|e| TestCaseError::fail(format!("step: {e:?}")))?;
                frame += 1;
                check(&book, total, frame)?;
            }
            from = to;
        }
        book.release();
        for _ in 0..g.rest {
            book.step()
                .map_err(|e| TestCaseError::fail(format!("step: {e:?}")))?;
            frame += 1;
            check(&book, total, frame)?;
        }
        // A page still settling is taken up again by the next grab.
        if book.phase() == Phase::Held {
            book.release();
        }
    }
    Ok(())
}

/// `cases` cases from a fixed seed (reproducible in CI, as `bounded_pages`), no persistence
/// files.
fn config(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20),
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// Every weight of the documented box, random gestures.
    #[test]
    fn weights_across_their_ranges_stay_bounded(
        t in proptest::array::uniform5(0.0..=1.0f64),
        g in gesture(),
    ) {
        let settings = BookSettings { weights: weights(t), ..BookSettings::default() };
        let book = Book::new(settings).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        play(book, &[g])?;
    }
}

proptest! {
    #![proptest_config(config(12))]

    /// Small books (1 to 3 pages, either block) with two gestures each, at default weights.
    #[test]
    fn small_books_stay_bounded(
        pages in 1u32..=3,
        left in 0u32..=3,
        g in proptest::collection::vec(gesture(), 2),
    ) {
        let mut settings = BookSettings::<f64>::default();
        settings.params.total_pages = pages;
        settings.params.left_pages = left.min(pages);
        let book = Book::new(settings).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
        play(book, &g)?;
    }
}

/// A case the property found on a run with a random seed (before the seed was fixed): a
/// soft, weakly bent page (the first two weights near their lows) grabbed mid-page and pulled
/// over the spine in 23 frames, on the book of `isometry`.
fn soft_page_pulled_over_the_spine(isometry: IsometryHessian) -> Result<(), String> {
    let t = [
        0.037_100_856_537_563_05,
        0.305_522_472_707_318_47,
        0.251_295_441_056_984_15,
        0.466_505_248_096_029_67,
        0.942_672_822_178_388,
    ];
    let g = Gesture {
        at: [0.524_642_638_171_091_1, 0.397_552_551_090_870_57],
        moves: vec![Move {
            to: [
                -0.323_473_388_491_281_7,
                0.482_350_062_506_126_2,
                -0.010_215_664_693_582_118,
            ],
            frames: 23,
        }],
        rest: 30,
    };
    let settings = BookSettings {
        weights: weights(t),
        isometry_hessian: isometry,
        ..BookSettings::default()
    };
    let book = Book::new(settings).expect("book");
    play(book, &[g]).map_err(|e| e.to_string())
}

/// The case above under the seed's exact isometry Hessian: it stretched 11.35 % at frame 20
/// when it was found (2026-11-27), past the 10 % bound; on 2026-12-07 it stays within the
/// bound (1.9 % at most, measured; the commit that mended it was not traced), so it runs
/// again.
#[test]
fn a_soft_page_pulled_over_the_spine_stays_bounded() {
    if let Err(e) = soft_page_pulled_over_the_spine(IsometryHessian::Exact) {
        panic!("{e}");
    }
}

/// The same case under the projected isometry Hessian (`IsometryHessian::Projected`, the
/// one a page of real paper takes) stays within the bound too (2.3 % at most, measured).
#[test]
fn a_soft_page_pulled_over_the_spine_stays_bounded_under_the_projected_hessian() {
    if let Err(e) = soft_page_pulled_over_the_spine(IsometryHessian::Projected) {
        panic!("{e}");
    }
}

#[test]
fn log_uniform_covers_each_range() {
    for &(name, lo, hi) in &WEIGHT_RANGES {
        assert_eq!(log_uniform(lo, hi, 1.0), hi, "{name}");
        let low = log_uniform(lo, hi, 0.0);
        assert!(low == lo || (lo == 0.0 && low == 0.0), "{name}");
    }
    assert_eq!(log_uniform(0.0, 1e9, 0.125), 1e3);
}
