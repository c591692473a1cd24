//! Where the heap goes: opens a book in `f32` (the default one, or `mcu` for
//! [`BookSettings::microcontroller`]) as the Cortex-M firmware does (without finger-bookmarking,
//! which the firmware does not compile in), twice, under an allocator that finds the heap's
//! peak in the first opening and, in the second, keeps every live allocation with the
//! backtrace that made it; it prints what was live at the peak, summed by the innermost
//! three Folio frames on each backtrace (a second or less, not minutes: only the live set at
//! the peak is symbolized, once). `usize` fields count 8 bytes
//! here and 4 on the Cortex-M, so the total is a little above the firmware's.
//!
//! ```sh
//! CARGO_PROFILE_RELEASE_DEBUG=line-tables-only \
//!   cargo run --release -p folio-bench --example heap_profile -- mcu
//! ```

use core::alloc::{GlobalAlloc, Layout};
use core::cell::Cell;
use std::alloc::System;
use std::backtrace::Backtrace;
use std::collections::HashMap;
use std::process::ExitCode;
use std::sync::Mutex;

use folio_book::{Book, BookSettings};

/// What the allocator keeps: in the first opening only the heap's size and peak; in the
/// second every live allocation with its (unresolved) backtrace, until the heap first
/// reaches the first opening's peak, when the live set's sites are resolved and kept. The
/// opening is deterministic, so the second reaches the same peak; resolving once, not at
/// every new peak, keeps the run linear.
#[derive(Default)]
struct Ledger {
    /// Backtraces are taken (the second opening).
    tracing: bool,
    live: HashMap<usize, (usize, Option<Backtrace>)>,
    current: usize,
    peak: usize,
    /// The peak to snapshot at (the first opening's).
    target: usize,
    at_peak: Vec<(usize, String)>,
}

static LEDGER: Mutex<Option<Ledger>> = Mutex::new(None);

thread_local! {
    /// Set while the allocator itself is recording (a backtrace allocates).
    static INSIDE: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` on the ledger, unless the allocator is already inside one (a backtrace and the
/// ledger's maps allocate).
fn with_ledger(f: impl FnOnce(&mut Ledger)) {
    if INSIDE.with(Cell::get) {
        return;
    }
    INSIDE.with(|i| i.set(true));
    if let Ok(mut guard) = LEDGER.lock() {
        if let Some(l) = guard.as_mut() {
            f(l);
        }
    }
    INSIDE.with(|i| i.set(false));
}

/// The innermost three frames of Folio's library crates on `trace` (function and
/// `file:line`, innermost first), past the allocation machinery (`alloc`, `core`, `std`,
/// this file).
fn site(trace: &Backtrace) -> String {
    const CRATES: [&str; 5] = [
        "/book/src/",
        "/solvers/src/",
        "/kernels/src/",
        "/geometry/src/",
        "/pages/src/",
    ];
    let trace = trace.to_string();
    let (mut name, mut frames) = ("", Vec::new());
    for line in trace.lines().map(str::trim) {
        if let Some(path) = line.strip_prefix("at ") {
            if let Some(at) = CRATES.iter().find_map(|c| path.find(c)) {
                frames.push(format!("{name} @ {}", &path[at + 1..]));
                if frames.len() == 3 {
                    break;
                }
            }
        } else if let Some((_, f)) = line.split_once(": ") {
            name = f;
        }
    }
    if frames.is_empty() {
        "(outside Folio)".to_owned()
    } else {
        frames.join(" < ")
    }
}

struct Recording;

// SAFETY: every call is forwarded to the system allocator unchanged; the bookkeeping only
// reads the returned pointer and the layout.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Recording {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded as is.
        let ptr = unsafe { System.alloc(layout) };
        record(ptr as usize, layout.size());
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        forget(ptr as usize);
        // SAFETY: forwarded as is.
        unsafe { System.dealloc(ptr, layout) };
    }
}

fn record(ptr: usize, size: usize) {
    if ptr == 0 {
        return;
    }
    with_ledger(|l| {
        let trace = l.tracing.then(Backtrace::force_capture);
        l.live.insert(ptr, (size, trace));
        l.current += size;
        l.peak = l.peak.max(l.current);
        if l.tracing && l.at_peak.is_empty() && l.current >= l.target {
            l.at_peak = l
                .live
                .values()
                .map(|(size, trace)| (*size, trace.as_ref().map_or_else(String::new, site)))
                .collect();
        }
    });
}

fn forget(ptr: usize) {
    with_ledger(|l| {
        if let Some((size, _)) = l.live.remove(&ptr) {
            l.current -= size;
        }
    });
}

#[global_allocator]
static HEAP: Recording = Recording;

fn main() -> ExitCode {
    let mut settings = match std::env::args().nth(1).as_deref() {
        None | Some("default") => BookSettings::<f32>::default(),
        Some("mcu") => BookSettings::<f32>::microcontroller(),
        Some(other) => {
            eprintln!("usage: heap_profile [default | mcu] (got {other:?})");
            return ExitCode::from(2);
        }
    };
    settings.effects.bookmarking = false;
    // The first opening finds the peak, the second snapshots the live set at it.
    let mut target = 0;
    for tracing in [false, true] {
        *LEDGER.lock().expect("the ledger") = Some(Ledger {
            tracing,
            target,
            ..Ledger::default()
        });
        let book = match Book::new(settings) {
            Ok(book) => book,
            Err(e) => {
                eprintln!("the book does not open: {e}");
                return ExitCode::FAILURE;
            }
        };
        let ledger = LEDGER.lock().expect("the ledger").take();
        drop(book);
        match ledger {
            Some(l) if !tracing => target = l.peak,
            Some(l) => return report(l),
            None => return ExitCode::FAILURE,
        }
    }
    ExitCode::FAILURE
}

/// Prints the live set at the peak, by site, largest first.
fn report(ledger: Ledger) -> ExitCode {
    if ledger.at_peak.is_empty() {
        eprintln!(
            "the second opening peaked at {} B, below the first's {} B: not deterministic",
            ledger.peak, ledger.target
        );
        return ExitCode::FAILURE;
    }
    let mut by_site: HashMap<String, (usize, usize)> = HashMap::new();
    for (size, at) in ledger.at_peak {
        let e = by_site.entry(at).or_default();
        e.0 += size;
        e.1 += 1;
    }
    let mut rows: Vec<_> = by_site.into_iter().collect();
    rows.sort_by_key(|(_, (bytes, _))| core::cmp::Reverse(*bytes));
    println!(
        "heap peak {} B while opening the book; live at the peak:",
        ledger.peak
    );
    for (at, (bytes, count)) in rows {
        println!("{bytes:>9} B {count:>4} blocks  {at}");
    }
    ExitCode::SUCCESS
}
