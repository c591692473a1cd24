//! Gestures in sequence and books that must settle: many turns back and forth, thick
//! books, slow slides, grabs on either side, stacks, and the refusals of models that cannot
//! take a gesture.

use folio_book::BookSettings;
use folio_geometry::QuadGrid;
use folio_pages::cone::{ConePage, ConeSettings};
use folio_pages::dog::DogPage;
use folio_pages::spring::{SpringPage, SpringSettings};
use folio_pages::touch::Touch;
use folio_pages::{BlockSide, GestureError, PageError, PageModel};

/// Page size of every model here (the seed's page).
const WIDTH: f64 = 12.0;
const HEIGHT: f64 = 12.0 * core::f64::consts::SQRT_2;

/// Frames the finger rests at the end of a turn before it lets go.
const REST: u32 = 15;

/// The finger over `held + REST` frames of a turn from `side` to the other: the shared
/// page turn's arc (`TouchScript::page_turn`) from the fore-edge point $(\pm W, 0, 0.2H)$
/// over the spine to its mirror image in `held` frames, then resting there.
fn turn_path(side: BlockSide, held: u32) -> Vec<[f64; 3]> {
    let sign = if side == BlockSide::Right { 1.0 } else { -1.0 };
    let v0 = 0.2 * HEIGHT;
    (0..held + REST)
        .map(|k| {
            let s = (f64::from(k) / f64::from(held - 1)).min(1.0);
            let phi = core::f64::consts::PI * s * s * (3.0 - 2.0 * s);
            [
                sign * WIDTH * (1.0 - 0.1 * phi.sin()) * phi.cos(),
                0.7 * WIDTH * phi.sin(),
                v0 + 0.12 * HEIGHT * phi.sin(),
            ]
        })
        .collect()
}

/// What one turn of the DOG page showed.
struct Turned {
    /// Frames from the release to the merge.
    settle_frames: u32,
    /// Largest max edge stretch of the render grid over the turn.
    stretch: f64,
}

/// A 12 x 17 render grid (one sample per page unit).
fn render_grid() -> QuadGrid {
    QuadGrid::new(12, 17).unwrap()
}

/// Turns a one-page `model` from `side` over `held` frames, lets go, and steps `settle`
/// frames more; asserts every sample finite and returns the largest max edge stretch.
fn turn(
    model: &mut dyn PageModel<f64>,
    side: BlockSide,
    held: u32,
    settle: u32,
) -> Result<f64, PageError> {
    let grid = render_grid();
    let mut samples = vec![glam::DVec3::ZERO; grid.len()];
    let mut stretch: f64 = 0.0;
    let path = turn_path(side, held);
    let frames = path.len() as u32 + settle;
    for f in 0..frames {
        match f as usize {
            0 => take(model, side, 1, path[0])?,
            k if k < path.len() => Touch::Drag(path[k]).apply(model)?,
            k if k == path.len() => Touch::Release.apply(model)?,
            _ => {}
        }
        model.step().expect("a step");
        model.sample(grid, &mut samples).unwrap();
        assert!(samples.iter().all(|p| p.is_finite()), "a non-finite sample");
        let m = folio_pages::frame_metrics(grid, model.size(), &samples).unwrap();
        stretch = folio_tests::worst(stretch, m.max_stretch);
    }
    Ok(stretch)
}

/// Grabs `pages` pages of `model` on `side` at the fore-edge point $(W, 0.2H)$, the finger
/// at `finger`.
fn take(
    model: &mut dyn PageModel<f64>,
    side: BlockSide,
    pages: u32,
    finger: [f64; 3],
) -> Result<(), PageError> {
    Touch::Take {
        side,
        pages,
        at: [WIDTH, 0.2 * HEIGHT],
        finger,
    }
    .apply(model)
}

/// Steps `page` until its released page merges, at most `frames` frames.
fn settle(page: &mut DogPage<f64>, frames: u32) {
    for _ in 0..frames {
        page.step().unwrap();
        if page.book().counts().active == 0 {
            break;
        }
    }
}

/// The DOG page on a book with `pages` pages of `thickness`, half on each side.
fn dog(pages: u32, thickness: f64) -> DogPage<f64> {
    let mut s = BookSettings::<f64>::default();
    s.params.total_pages = pages;
    s.params.left_pages = pages / 2;
    s.params.page_thickness = thickness;
    DogPage::new(s).expect("book")
}

/// Turns one page of the DOG `page` from `side` over `held` frames, lets go, and steps
/// until the page merges (at most `max_settle` frames); asserts every sample finite.
fn dog_turn(page: &mut DogPage<f64>, side: BlockSide, held: u32, max_settle: u32) -> Turned {
    let grid = render_grid();
    let mut samples = vec![glam::DVec3::ZERO; grid.len()];
    let mut stretch: f64 = 0.0;
    let path = turn_path(side, held);
    Touch::Take {
        side,
        pages: 1,
        at: [WIDTH, 0.2 * HEIGHT],
        finger: path[0],
    }
    .apply(page)
    .expect("the grab");
    let mut frames = 0;
    loop {
        if frames > 0 && (frames as usize) < path.len() {
            Touch::Drag(path[frames as usize]).apply(page).unwrap();
        }
        if frames as usize == path.len() {
            Touch::Release.apply(page).unwrap();
        }
        page.step().expect("a step");
        page.sample(grid, &mut samples).unwrap();
        assert!(samples.iter().all(|p| p.is_finite()), "a non-finite sample");
        let m = folio_pages::frame_metrics(grid, page.size(), &samples).unwrap();
        stretch = folio_tests::worst(stretch, m.max_stretch);
        frames += 1;
        if frames as usize > path.len() && page.book().counts().active == 0 {
            break;
        }
        if frames >= held + REST + max_settle {
            break;
        }
    }
    Turned {
        settle_frames: frames.saturating_sub(held + REST),
        stretch,
    }
}

/// Hard: 50 turns back and forth on one book, each taking the page the turn before
/// brought over (contact springs, merges and re-grabs that never rest). Asserts that every
/// turn merges on the far side within 4 s of its release (measured: at most 193 frames), that the pages are conserved
/// (left + right = 100, one page moved each time), that every sample stays finite and that
/// the render grid's max edge stretch stays within 15 % (measured: 9.5 %).
#[test]
fn fifty_turns_back_and_forth_conserve_pages_and_each_merges() {
    let mut page = dog(100, 0.0075);
    let mut side = BlockSide::Right;
    let mut worst_settle = 0;
    let mut worst_stretch: f64 = 0.0;
    for k in 0..50 {
        let before = page.book().counts();
        let t = dog_turn(&mut page, side, 60, 240);
        let c = page.book().counts();
        assert_eq!(
            c.active, 0,
            "turn {k}: the page did not merge in 240 frames"
        );
        assert_eq!(c.left + c.right, 100, "turn {k}: pages lost");
        let moved = if side == BlockSide::Right {
            (c.left, c.right) == (before.left + 1, before.right - 1)
        } else {
            (c.left, c.right) == (before.left - 1, before.right + 1)
        };
        assert!(moved, "turn {k} from {side:?}: {before:?} -> {c:?}");
        worst_settle = folio_tests::worst(worst_settle, t.settle_frames);
        worst_stretch = folio_tests::worst(worst_stretch, t.stretch);
        side = if side == BlockSide::Right {
            BlockSide::Left
        } else {
            BlockSide::Right
        };
    }
    println!(
        "50 turns: slowest merge {worst_settle} frames after the release, max stretch {worst_stretch:.4}"
    );
    assert_eq!(page.book().counts().left, 50);
    assert!(worst_stretch <= 0.15, "max stretch {worst_stretch}");
}

/// Hard: a thick book (100 pages 0.01 thick, and 400 of 0.0075), whose released page used
/// to rock against the first kink of the block forever. Asserts the merge within 240
/// frames (4 s) of the release and a stretch within 15 %.
#[test]
fn a_thick_book_settles_within_four_seconds() {
    for (pages, thickness) in [(100, 0.01), (400, 0.0075)] {
        let mut page = dog(pages, thickness);
        let t = dog_turn(&mut page, BlockSide::Right, 120, 240);
        println!(
            "{pages} x {thickness}: merged {} frames after the release, max stretch {:.4}",
            t.settle_frames, t.stretch
        );
        assert_eq!(page.book().counts().active, 0, "{pages} x {thickness}");
        assert!(t.settle_frames <= 240);
        assert!(t.stretch <= 0.15, "{pages} x {thickness}: {}", t.stretch);
    }
}

/// Hard: a slow slide: the page carried over the spine in 10 s and laid down gently on a
/// 100-page book of 0.01, so it reaches the block slowly and creeps along it. Asserts the
/// merge within 240 frames of the release, on the left.
#[test]
fn a_slow_slide_settles() {
    let mut page = dog(100, 0.01);
    let t = dog_turn(&mut page, BlockSide::Right, 600, 240);
    println!(
        "slow slide: merged {} frames after the release",
        t.settle_frames
    );
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (51, 49, 0));
    assert!(t.settle_frames <= 240);
}

/// Hard: two gestures on opposite sides on every model: a turn to the left, then the same
/// page (the one-page models) or the top of the left block (the DOG book) turned back.
/// Asserts finite samples, that every model ends with its page on the right (the DOG book
/// at 50 / 50), and a stretch bound per model (DOG 15 %, cone 1 %: an isometry up to the
/// sampling, mass-spring 10 %, the guard; measured 5.6 %).
#[test]
fn two_gestures_on_opposite_sides() {
    let mut page = dog(100, 0.0075);
    for side in [BlockSide::Right, BlockSide::Left] {
        let t = dog_turn(&mut page, side, 60, 240);
        assert!(t.stretch <= 0.15, "dog from {side:?}: {}", t.stretch);
    }
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (50, 50, 0));

    let mut cone = ConePage::<f64>::new(ConeSettings::default()).unwrap();
    for side in [BlockSide::Right, BlockSide::Left] {
        let stretch = turn(&mut cone, side, 60, 40).expect("the cone turns");
        assert!(stretch <= 0.01, "cone from {side:?}: {stretch}");
    }
    assert_eq!(cone.side(), BlockSide::Right);

    let mut spring = SpringPage::<f64>::new(SpringSettings::default()).unwrap();
    for side in [BlockSide::Right, BlockSide::Left] {
        let stretch = turn(&mut spring, side, 90, 120).expect("the spring page turns");
        println!("mass-spring from {side:?}: max stretch {stretch:.3}");
        assert!(stretch <= 0.1, "mass-spring from {side:?}: {stretch}");
    }
    let grid = render_grid();
    let mut samples = vec![glam::DVec3::ZERO; grid.len()];
    spring.sample(grid, &mut samples).unwrap();
    let right = samples.iter().filter(|p| p.x > 0.0).count() as f64 / samples.len() as f64;
    assert!(
        right >= 0.75,
        "only {right:.2} of the spring page came back"
    );
}

/// Hard: a one-page model asked for a page on the side where it has none, or for a stack.
/// Asserts the typed refusal and that the model keeps its state (the next frame equals the
/// one of a twin that was never asked).
#[test]
fn a_one_page_model_refuses_a_grab_where_its_page_is_not() {
    let mut cone = ConePage::<f64>::new(ConeSettings::default()).unwrap();
    turn(&mut cone, BlockSide::Right, 60, 40).unwrap();
    assert_eq!(cone.side(), BlockSide::Left);
    let twin = cone;
    assert_eq!(
        cone.grab_page(BlockSide::Right, 1, [WIDTH, 3.0]),
        Err(PageError::Gesture(GestureError::NoPage {
            side: BlockSide::Right,
            model: "cone"
        }))
    );
    assert_eq!(
        cone.grab_page(BlockSide::Left, 3, [WIDTH, 3.0]),
        Err(PageError::Gesture(GestureError::Stack { pages: 3 }))
    );
    assert_eq!(cone, twin);
    let mut spring = SpringPage::<f64>::new(SpringSettings::default()).unwrap();
    assert_eq!(
        spring.grab_page(BlockSide::Left, 1, [WIDTH, 3.0]),
        Err(PageError::Gesture(GestureError::NoPage {
            side: BlockSide::Left,
            model: "mass-spring"
        }))
    );
    assert_eq!(spring.held(), None);
}

/// Hard: a grab on one side while the page released on the other still falls (a reader
/// faster than the paper). Asserts the typed refusal, the page counts unchanged, and that
/// the released page still merges afterwards.
#[test]
fn a_grab_while_the_released_page_still_moves_is_refused() {
    let mut page = dog(100, 0.0075);
    let path = turn_path(BlockSide::Right, 45);
    take(&mut page, BlockSide::Right, 1, path[0]).unwrap();
    for &finger in &path {
        Touch::Drag(finger).apply(&mut page).unwrap();
        page.step().unwrap();
    }
    page.release();
    page.step().unwrap();
    let before = page.book().counts();
    assert_eq!(
        page.grab_page(BlockSide::Right, 1, [WIDTH, 3.0]),
        Err(PageError::Gesture(GestureError::Unsettled {
            side: BlockSide::Right
        }))
    );
    assert_eq!(page.book().counts(), before);
    settle(&mut page, 240);
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (51, 49, 0));
}

/// Hard: a stack of 10 pages turned, then one page of it turned back (gestures of
/// different sizes in one sequence, the binding parameter moving with each). Asserts the
/// counts after each merge (60 / 40, then 59 / 41) and a stretch within 15 %.
#[test]
fn a_stack_forward_then_one_page_back() {
    let mut page = dog(100, 0.0075);
    let path = turn_path(BlockSide::Right, 90);
    take(&mut page, BlockSide::Right, 10, path[0]).unwrap();
    for &finger in &path[1..] {
        Touch::Drag(finger).apply(&mut page).unwrap();
        page.step().unwrap();
    }
    page.release();
    settle(&mut page, 300);
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (60, 40, 0));
    let t = dog_turn(&mut page, BlockSide::Left, 60, 240);
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (59, 41, 0));
    assert!(t.stretch <= 0.15, "{}", t.stretch);
}

/// Hard: more pages than the block holds. Asserts the typed refusal and no page taken.
#[test]
fn a_grab_of_more_pages_than_the_block_holds_is_refused() {
    let mut page = dog(6, 0.0075);
    assert_eq!(
        page.grab_page(BlockSide::Right, 4, [WIDTH, 3.0]),
        Err(PageError::Gesture(GestureError::NoPage {
            side: BlockSide::Right,
            model: "dog"
        }))
    );
    let c = page.book().counts();
    assert_eq!((c.left, c.right, c.active), (3, 3, 0));
}
