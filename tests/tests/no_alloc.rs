//! A step on an analysed topology allocates nothing (DESIGN.md: "setup allocates; stepping
//! does not"), held by a counting global allocator: the solver on its test models, and the
//! book over the recorded page turn (collisions with their broad phase, and the constraint
//! projection with its normal equations, included), and the XPBD page over the shared drag
//! (its steps and its sampling).

use folio_book::{Book, BookSettings, Script};
use folio_kernels::Real;
use folio_solvers::{Model, Settings, Solver, State};
use folio_tests::models::{Chain, DogSheet};

use folio_counting::{Counting, allocations};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `steps` steps after the first (setup) step.
fn allocations_after_setup<T: Real, M: Model<T>>(
    model: &M,
    state: &mut State<T>,
    settings: Settings<T>,
    steps: usize,
) -> usize {
    let mut solver = Solver::new(settings).unwrap();
    assert!(solver.step(model, state).unwrap().analysed);
    let before = allocations();
    for _ in 0..steps {
        let report = solver.step(model, state).unwrap();
        assert!(report.status.advanced(), "{report:?}");
    }
    allocations() - before
}

#[test]
fn steps_after_setup_do_not_allocate() {
    // Every case on this thread: the counter is per thread.
    let sheet = DogSheet::<f64>::new(11, 8, 12.0 / 11.0);
    let mut state = sheet.rolled(6.0);
    let n = allocations_after_setup(&sheet, &mut state, Settings::default(), 10);
    assert_eq!(n, 0, "f64 DOG sheet, default settings");

    let mut sheet = DogSheet::<f32>::new(11, 8, 12.0 / 11.0);
    let mut state = sheet.rolled(6.0);
    sheet.set_target(state.x[sheet.grabbed_node()]);
    let settings = Settings {
        newton_iterations: 3,
        constraint_hessian: true,
        ..Settings::default()
    };
    let n = allocations_after_setup(&sheet, &mut state, settings, 10);
    assert_eq!(
        n, 0,
        "f32 DOG sheet, three iterations with the constraint Hessian"
    );

    let chain = Chain::<f64>::new(10, 0.3, 0.1);
    let x = (0..=10)
        .map(|k| glam::DVec3::new(0.2 * k as f64, -0.1 * (k.min(10 - k) as f64), 0.0))
        .collect();
    let mut state = State::at_rest(x);
    let settings = Settings {
        newton_iterations: 4,
        line_search: true,
        ..Settings::default()
    };
    let n = allocations_after_setup(&chain, &mut state, settings, 10);
    assert_eq!(n, 0, "chain with line search");

    for (n, contact_tests) in [book_page_turn::<f64>(), book_page_turn::<f32>()] {
        assert!(contact_tests > 0, "the page met the blocks");
        assert_eq!(n, 0, "the book's page turn");
    }

    for (n, moved) in [xpbd_page_turn::<f64>(), xpbd_page_turn::<f32>()] {
        assert!(moved > 1.0, "the XPBD page moved");
        assert_eq!(n, 0, "the XPBD page's turn");
    }
}

/// Allocations inside the XPBD page's steps and samples over the shared drag (the grab,
/// the drags and the release included), and how far its fore-edge corner moved.
fn xpbd_page_turn<T: Real>() -> (usize, f64) {
    use folio_kernels::Vec3Ops;
    use folio_pages::xpbd::{XpbdPage, XpbdSettings};
    use folio_pages::{PageModel, TouchScript};
    let script = TouchScript::parse(include_str!("../fixtures/page_turn.touch")).unwrap();
    let mut page = XpbdPage::<T>::new(XpbdSettings::default()).unwrap();
    let grid = folio_geometry::QuadGrid::new(24, 34).unwrap();
    let mut samples = vec![T::Vec3::ZERO; grid.len()];
    let corner = page.grid().index(page.grid().nx - 1, 0);
    let start = page.positions()[corner];
    let mut in_steps = 0;
    for frame in 0..script.frames {
        let before = allocations();
        script.at(frame).apply(&mut page).unwrap();
        page.step().unwrap();
        page.sample(grid, &mut samples).unwrap();
        in_steps += allocations() - before;
    }
    let d = page.positions()[corner] - start;
    (in_steps, d.dot(d).to_f64().sqrt())
}

/// Allocations inside the book's steps over the recorded page turn, and the point-wall
/// tests they made.
fn book_page_turn<T: Real>() -> (usize, usize) {
    let script = Script::parse(include_str!("../fixtures/page_turn.input")).unwrap();
    let mut book = Book::<T>::new(BookSettings::default()).unwrap();
    let (mut in_steps, mut contact_tests) = (0, 0);
    for frame in 0..script.frames {
        for e in script.events_at(frame) {
            book.apply(script.camera, script.forward, e.action).unwrap();
        }
        let before = allocations();
        let report = book.step().unwrap();
        in_steps += allocations() - before;
        contact_tests += report.contacts.tested;
    }
    (in_steps, contact_tests)
}
