//! Progress of a run: a run that lasts longer than a second shows where it is, whatever
//! the model (a 64 x 64 tearing sheet takes seconds per frame). On a terminal a progress
//! bar (stderr); otherwise (a log, CI) one line per second on stderr. A watcher thread
//! wakes ten times a second, so a frame that takes several seconds still shows.

use alloc::sync::Arc;
use core::sync::atomic::{AtomicU32, Ordering};
use core::time::Duration;
use std::io::IsTerminal;
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Nothing shows before the run has lasted this long, unless the environment variable
/// `FOLIO_PROGRESS_AFTER` gives other seconds ([`quiet`]).
const QUIET: Duration = Duration::from_secs(1);

/// Seconds between two progress lines off a terminal.
const LINE: Duration = Duration::from_secs(1);

/// How often the watcher wakes.
const TICK: Duration = Duration::from_millis(100);

/// The frame done and the frames in all.
#[derive(Default)]
struct Count {
    frame: AtomicU32,
    frames: AtomicU32,
}

/// The progress of one run (module docs); [`Progress::finish`] it.
pub struct Progress {
    count: Arc<Count>,
    stop: Sender<()>,
    watcher: Option<JoinHandle<()>>,
}

impl Progress {
    /// Starts watching the run of scene `name`.
    #[must_use]
    pub fn start(name: &str) -> Self {
        let count = Arc::new(Count::default());
        let (stop, stopped) = mpsc::channel::<()>();
        let seen = Arc::clone(&count);
        let name = name.to_string();
        let terminal = std::io::stdout().is_terminal();
        let quiet = quiet();
        let watcher = std::thread::spawn(move || {
            let started = Instant::now();
            let mut bar: Option<ProgressBar> = None;
            let mut next_line = quiet;
            while let Err(RecvTimeoutError::Timeout) = stopped.recv_timeout(TICK) {
                let elapsed = started.elapsed();
                if elapsed < quiet {
                    continue;
                }
                let frame = seen.frame.load(Ordering::Relaxed);
                let frames = seen.frames.load(Ordering::Relaxed);
                if terminal {
                    let bar = bar.get_or_insert_with(|| new_bar(&name));
                    bar.set_length(u64::from(frames));
                    bar.set_position(u64::from(frame));
                } else if elapsed >= next_line {
                    next_line = elapsed + LINE;
                    let percent = 100.0 * f64::from(frame) / f64::from(frames.max(1));
                    eprintln!(
                        "{name}: frame {frame}/{frames} ({percent:.0} %), {:.0} s",
                        elapsed.as_secs_f64()
                    );
                }
            }
            if let Some(bar) = bar {
                bar.finish_and_clear();
            }
        });
        Self {
            count,
            stop,
            watcher: Some(watcher),
        }
    }

    /// `frame` of `frames` are done.
    pub fn set(&self, frame: u32, frames: u32) {
        self.count.frames.store(frames, Ordering::Relaxed);
        self.count.frame.store(frame, Ordering::Relaxed);
    }

    /// Stops the watcher and clears the bar.
    pub fn finish(mut self) {
        let _ = self.stop.send(());
        if let Some(w) = self.watcher.take() {
            let _ = w.join();
        }
    }
}

/// How long a run stays quiet: `FOLIO_PROGRESS_AFTER` seconds (a non-negative number; the
/// tests set 0 to see the progress of a short run on any machine), else [`QUIET`].
fn quiet() -> Duration {
    std::env::var("FOLIO_PROGRESS_AFTER")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .unwrap_or(QUIET)
}

/// The bar of scene `name`, drawn on stderr.
fn new_bar(name: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} frames, {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(name.to_string());
    bar
}
