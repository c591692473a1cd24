//! One frame of the `f32` page turn under a profiler: plays the fixture on the default book
//! with the firmware's settings (no final-residual diagnostic, `embedded/src/turn.rs`) up
//! to frame `FRAME`, and steps that frame in `measured_step`, which callgrind can be told
//! to count alone. The `f32` run on x86 takes the firmware's path frame for frame
//! (`embedded/README.md`), so the frame numbers of its `step` lines apply:
//!
//! ```sh
//! cargo build --release -p folio-bench --example frame_profile
//! valgrind --tool=callgrind --collect-atstart=no \
//!   --toggle-collect='frame_profile::measured_step' \
//!   target/release/examples/frame_profile 152
//! callgrind_annotate --inclusive=yes callgrind.out.*
//! ```

use std::process::ExitCode;

use folio_bench::book::PAGE_TURN;
use folio_book::{Book, BookSettings, Script};

/// The step callgrind counts.
#[inline(never)]
fn measured_step(book: &mut Book<f32>) -> bool {
    book.step().is_ok_and(|r| r.solver.status.advanced())
}

fn main() -> ExitCode {
    let Some(Ok(target)) = std::env::args().nth(1).map(|a| a.parse::<u32>()) else {
        eprintln!("usage: frame_profile FRAME (a frame of the page-turn fixture)");
        return ExitCode::from(2);
    };
    let script = Script::parse(PAGE_TURN).expect("the fixture parses");
    if target >= script.frames {
        eprintln!(
            "frame {target} is past the fixture's {} frames",
            script.frames
        );
        return ExitCode::from(2);
    }
    let mut settings = BookSettings::<f32>::default();
    settings.solver.check_final_residual = false;
    let mut book = Book::new(settings).expect("the default book");
    for frame in 0..=target {
        for e in script.events_at(frame) {
            if let Err(e) = book.apply(script.camera, script.forward, e.action) {
                eprintln!("frame {frame}: input refused: {e}");
                return ExitCode::FAILURE;
            }
        }
        if frame < target {
            if let Err(e) = book.step() {
                eprintln!("frame {frame}: {e}");
                return ExitCode::FAILURE;
            }
        } else if !measured_step(&mut book) {
            eprintln!("frame {frame}: the step did not advance");
            return ExitCode::FAILURE;
        }
    }
    println!("frame {target} stepped; phase {:?}", book.phase());
    ExitCode::SUCCESS
}
