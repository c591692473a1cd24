//! Instruction counts of a variant's frames, for figures that repeat on any machine: the
//! variant's scene runs under callgrind (`valgrind --tool=callgrind`) as `folio trace`, with
//! collection switched on only inside the frames' stepping functions
//! ([`crate::run::FRAME_FUNCTION`], `--toggle-collect`). The count holds every instruction
//! of the model's steps (the solver, collisions, the projection) and nothing of the run's
//! setup, sampling or outputs; divided by the run's frames it is the mean instructions of a
//! 1/60 s frame. A wall-clock time on a busy machine moves by tens of percent from run to
//! run; the count does not (`cli/tests/instructions.rs`).
//!
//! Valgrind is optional: without it on the `PATH` the atlas says so and leaves the counts
//! out.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::run::FRAME_FUNCTION;

/// Whether `valgrind` runs here.
#[must_use]
pub fn available() -> bool {
    Command::new("valgrind")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The instructions callgrind collected, from its output file's `totals:` line (or
/// `summary:` when there is none): the first event, `Ir`, the default.
///
/// # Errors
/// No such line, or a count that is not a number.
pub fn parse_total(callgrind_out: &str) -> Result<u64, String> {
    let line = callgrind_out
        .lines()
        .find(|l| l.starts_with("totals:"))
        .or_else(|| callgrind_out.lines().find(|l| l.starts_with("summary:")))
        .ok_or("no totals: line in the callgrind output")?;
    let count = line
        .split_whitespace()
        .nth(1)
        .ok_or_else(|| format!("no count in {line:?}"))?;
    count
        .parse()
        .map_err(|e| format!("count {count:?} in {line:?}: {e}"))
}

/// Runs the scene file `scene` with the `folio` binary `folio` under callgrind, collecting
/// only inside the function that steps a frame (module docs), the output file in `dir`
/// (created; the file is removed once read). Returns the instructions of all the run's
/// frames.
///
/// # Errors
/// Valgrind did not run, the run failed (its stderr's last lines), or the output could not
/// be read.
pub fn count(folio: &Path, scene: &Path, dir: &Path) -> Result<u64, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let stem = scene
        .file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    let out: PathBuf = dir.join(format!("{stem}.callgrind"));
    let run = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--toggle-collect=*{FRAME_FUNCTION}*"))
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(folio)
        .arg("trace")
        .arg(scene)
        .output()
        .map_err(|e| format!("valgrind: {e}"))?;
    // `folio trace` exits with the run's status: a bad run (exit 3 after its summary line)
    // still stepped every frame, and its count stands.
    let finished = String::from_utf8_lossy(&run.stdout).contains(" frames, ");
    if !(run.status.success() || finished) {
        let stderr = String::from_utf8_lossy(&run.stderr);
        let tail: Vec<&str> = stderr.lines().rev().take(5).collect();
        return Err(format!(
            "callgrind run of {} failed ({}): {}",
            scene.display(),
            run.status,
            tail.into_iter().rev().collect::<Vec<_>>().join(" / ")
        ));
    }
    let text = std::fs::read_to_string(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let _ = std::fs::remove_file(&out);
    parse_total(&text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_total_is_read_from_the_totals_line() {
        let text = "version: 1\ncreator: callgrind-3.19.0\nevents: Ir\nsummary: 900\n\nfn=(1) main\n3 7\ntotals: 123456\n";
        assert_eq!(parse_total(text), Ok(123_456));
        assert_eq!(parse_total("events: Ir\nsummary: 42\n"), Ok(42));
        assert!(parse_total("events: Ir\n").is_err());
        assert!(parse_total("totals: many\n").is_err());
    }
}
