//! The exit status of `folio` (also in `folio --help`, the README and `docs/scenes.md`):
//! a bad scene file and a bad run have different codes, so that a script can tell a scene
//! that never ran from a run that ran and went wrong.

/// The run is good (or every file checked): every frame within its bounds, every
/// expectation met.
pub const GOOD: u8 = 0;

/// A scene does not check (or cannot be read, or a model refuses to start): nothing ran,
/// nothing was written.
pub const BAD_SCENE: u8 = 1;

/// Bad command-line arguments.
pub const USAGE: u8 = 2;

/// The run finished and is bad: a frame failed, went non-finite, crossed a health bound or
/// had an input that did nothing (a missed grab), or an expectation is unmet. Its outputs
/// and `report.json` are written, and the summary names the first bad frame and why.
pub const BAD_RUN: u8 = 3;

/// The run's outputs could not be written (the `--out` folder).
pub const OUTPUT: u8 = 4;

/// The exit codes, one line each, for `folio --help`.
pub const HELP: &str = "exit status:
  0  the run is good (every frame within its bounds, expectations met), or every file checks
  1  a scene does not check (its line and column are printed); nothing ran
  2  bad arguments
  3  the run is bad: a frame failed, went non-finite, crossed a bound (stretch, DOG residual,
     penetration) or had an input that did nothing, or an expectation is unmet;
     the summary names the first bad frame and report.json has every frame's problems
  4  the outputs could not be written";
