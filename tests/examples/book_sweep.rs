//! Counts the inputs of the `book` fuzz harness ([`folio_tests::fuzz::book::run`]) that
//! break one of its properties, over a seeded sweep: every other input random bytes (up to
//! 64), every other a committed corpus file (`fuzz/corpus/book/`) with one to four bytes
//! changed. Prints the first five failures with their bytes and the count by message; exits
//! with 1 when any input failed.
//!
//! ```sh
//! cargo run --release -p folio-tests --example book_sweep -- 3000
//! ```

extern crate alloc;

use std::process::ExitCode;

use folio_tests::Rng;
use folio_tests::fuzz::{corpus, sweep_input};

fn main() -> ExitCode {
    let inputs: usize = match std::env::args().nth(1).map(|a| a.parse()) {
        None => 3000,
        Some(Ok(n)) => n,
        Some(Err(e)) => {
            eprintln!("usage: book_sweep [INPUTS]: {e}");
            return ExitCode::from(2);
        }
    };
    let files = corpus("book");
    let seeds: Vec<Vec<u8>> = files
        .iter()
        .map(|f| std::fs::read(f).expect("readable"))
        .collect();
    // The harness reports by panicking; keep the sweep's output to the summary.
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng::new(0x5eed);
    let mut by_message = alloc::collections::BTreeMap::<String, usize>::new();
    let mut failed = 0;
    for k in 0..inputs {
        let data = sweep_input(&mut rng, k, &seeds, 64);
        if let Err(panic) = std::panic::catch_unwind(|| folio_tests::fuzz::book::run(&data)) {
            failed += 1;
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_string()))
                .unwrap_or_default();
            let kind = message.split_whitespace().next().unwrap_or("?").to_string();
            *by_message.entry(kind).or_default() += 1;
            if failed <= 5 {
                println!("input {k}: {message}\n  bytes {data:?}");
            }
        }
    }
    println!("{failed} of {inputs} inputs failed; by first word of the message: {by_message:?}");
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
