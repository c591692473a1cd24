//! A sleeping book (issue 40): a book at rest whose blocks have been still for
//! `sleep_frames` steps does no solver work until an input makes a page active, and the
//! page turn it wakes for ends as an awake book's does.

use folio_book::{Book, BookError, BookSettings, Phase, Script};
use folio_geometry::BlockSide;
use folio_kernels::Real;

const PAGE_TURN: &str = include_str!("../fixtures/page_turn.input");

/// The fastest block or cover node of `book` (page units per second).
fn block_speed<T: Real>(book: &Book<T>) -> f64 {
    let po = book.nodes().page_offset();
    book.state().v[..po]
        .iter()
        .map(|v| folio_kernels::math::length::<T>(*v).to_f64())
        .fold(0.0, folio_tests::worst)
}

/// What a run of the page-turn fixture did, frame by frame.
struct Turn {
    asleep: Vec<bool>,
    speeds: Vec<f64>,
    merged: Vec<(u32, BlockSide)>,
    book_asleep_at_end: bool,
    pages: [u32; 3],
}

fn turn<T: Real>(settings: BookSettings<T>) -> Turn {
    let script = Script::parse(PAGE_TURN).expect("fixture parses");
    let mut book = Book::<T>::new(settings).expect("book");
    let mut out = Turn {
        asleep: Vec::new(),
        speeds: Vec::new(),
        merged: Vec::new(),
        book_asleep_at_end: false,
        pages: [0; 3],
    };
    for frame in 0..script.frames {
        for e in script.events_at(frame) {
            book.apply(script.camera, script.forward, e.action)
                .expect("fixture input is valid");
        }
        let before = book.state().x.clone();
        let r = book.step().expect("step");
        assert!(r.solver.status.advanced(), "frame {frame} did not advance");
        if r.asleep {
            // Nothing solved, nothing moved, nothing moving.
            assert_eq!((r.phase, r.dofs, r.constraint_rows), (Phase::AtRest, 0, 0));
            assert!(
                before == book.state().x,
                "a sleeping book moved at frame {frame}"
            );
            assert_eq!(block_speed(&book), 0.0);
        }
        out.asleep.push(r.asleep);
        out.speeds.push(block_speed(&book));
        if let Some(side) = r.merged {
            out.merged.push((frame, side));
        }
    }
    let c = book.counts();
    out.pages = [c.left, c.right, c.active];
    out.book_asleep_at_end = book.is_asleep();
    out
}

/// Every first frame of a sleep followed `sleep_frames` awake frames at rest whose blocks
/// were all slower than `sleep_speed` (read off the state, not off the book's counter).
fn check_falls_asleep_only_when_still(t: &Turn, speed: f64, frames: usize) {
    for (i, pair) in t.asleep.windows(2).enumerate() {
        if pair[1] && !pair[0] {
            let quiet = &t.speeds[i + 1 - frames..=i];
            // The step that falls asleep zeroes the velocities it measured.
            let measured = &quiet[..frames - 1];
            assert!(
                measured.iter().all(|&s| s < speed),
                "fell asleep after frame {i} with block speeds {quiet:?}"
            );
        }
    }
}

fn sleeps_through_the_page_turn<T: Real>() {
    let settings = BookSettings::<T>::default();
    let (speed, frames) = (
        settings.sleep_speed.to_f64(),
        settings.sleep_frames as usize,
    );
    let t = turn(settings);
    // The page turned as it does awake (`book.rs`): once, into the left block.
    assert_eq!(t.merged.len(), 1, "{:?}", t.merged);
    assert_eq!(t.merged[0].1, BlockSide::Left);
    assert_eq!(t.pages, [51, 49, 0]);
    // Asleep before the grab at frame 30 (the settled book is still) and again at the end.
    assert!(
        t.asleep[frames..30].iter().all(|&a| a),
        "{:?}",
        &t.asleep[..30]
    );
    assert!(t.book_asleep_at_end);
    // Never while a page is active: from the grab to the merge.
    let merge = t.merged[0].0 as usize;
    assert!(t.asleep[30..=merge].iter().all(|&a| !a));
    // Not right after the merge either: the blocks rock for a while.
    assert!(!t.asleep[merge + 1]);
    check_falls_asleep_only_when_still(&t, speed, frames);
    let asleep = t.asleep.iter().filter(|&&a| a).count();
    assert!(asleep > 300, "only {asleep} of 750 frames asleep");
}

#[test]
fn the_page_turn_sleeps_at_rest_and_wakes_for_the_grab() {
    sleeps_through_the_page_turn::<f64>();
    sleeps_through_the_page_turn::<f32>();
}

#[test]
fn a_book_kept_awake_never_sleeps_and_turns_alike() {
    let awake = BookSettings::<f64> {
        sleep_speed: 0.0,
        ..BookSettings::default()
    };
    let t = turn(awake);
    assert!(t.asleep.iter().all(|&a| !a));
    assert!(!t.book_asleep_at_end);
    assert_eq!(t.merged.len(), 1);
    assert_eq!(t.merged[0].1, BlockSide::Left);
    assert_eq!(t.pages, [51, 49, 0]);
}

#[test]
fn a_fussy_book_falls_asleep_later() {
    // A hundred times stricter: the rocking after the merge must die down further.
    let strict = BookSettings::<f64> {
        sleep_speed: 1e-5,
        ..BookSettings::default()
    };
    let (loose, fussy) = (turn(BookSettings::<f64>::default()), turn(strict));
    let first_after = |t: &Turn| {
        let merge = t.merged[0].0 as usize;
        t.asleep[merge..].iter().position(|&a| a).map(|i| i + merge)
    };
    let (a, b) = (first_after(&loose), first_after(&fussy));
    assert!(a.is_some() && (b.is_none() || b > a), "{a:?} vs {b:?}");
    check_falls_asleep_only_when_still(&fussy, 1e-5, 10);
}

#[test]
fn bad_sleep_settings_are_refused() {
    let field = |f: &dyn Fn(&mut BookSettings<f64>)| {
        let mut s = BookSettings::<f64>::default();
        f(&mut s);
        match Book::new(s) {
            Err(BookError::InvalidSetting(e)) => e.path.to_string(),
            other => panic!("expected an invalid setting, got {other:?}"),
        }
    };
    assert_eq!(field(&|s| s.sleep_frames = 0), "sleep_frames");
    for bad in [-1e-3, f64::NAN, f64::INFINITY] {
        assert_eq!(field(&|s| s.sleep_speed = bad), "sleep_speed");
    }
}
