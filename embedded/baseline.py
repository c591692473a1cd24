#!/usr/bin/env python3
"""The firmware's regression gate: compares the page-turn figures of the three firmware runs
(the default book in f32 on the Cortex-M4F and in f64 on the Cortex-M7, the
microcontroller book of `page-turn-mcu` in f32 on the Cortex-M4F, under QEMU with
-icount shift=0, so the figures repeat exactly) with the committed baseline,
embedded/baseline.toml.

    python3 embedded/baseline.py                  # check out/embedded-{m4,m7,mcu}.log
    python3 embedded/baseline.py --run            # run the firmwares first, then check
    python3 embedded/baseline.py --run --update   # run them, rewrite the baseline

It prints one table (figure, baseline, now, change) and fails when a cost figure grows by
more than 3 % (the page turn's largest DOG residual and edge stretch included, which
must also stay under issue 40's bounds) or the merge frame changes at all (a result, not a
cost). Figures that shrink pass, with a reminder to update the baseline in the same commit. The figures are read from
each log's `summary:` line (src/report.rs). Standard library only (tomllib: Python 3.11).
"""

import argparse
import subprocess
import sys
import tomllib
from pathlib import Path

EMBEDDED = Path(__file__).resolve().parent
BASELINE = EMBEDDED / "baseline.toml"
DEFAULT_LOGS = EMBEDDED.parent / "out"

# The runs: cargo arguments (from embedded/) and what their summary line must name: the
# default book on the M4F in f32 and on the M7 in f64, and the microcontroller book
# (`page-turn-mcu`, feature `mcu`) on the M4F.
RUNS = {
    "m4": {"args": ["--release"], "precision": "f32", "machine": "mps2-an386", "grid": "8x11"},
    "m7": {
        "args": [
            "--release",
            "--no-default-features",
            "--features",
            "an500,f64",
            "--config",
            ".cargo/cortex-m7.toml",
        ],
        "precision": "f64",
        "machine": "mps2-an500",
        "grid": "8x11",
    },
    "mcu": {
        "args": ["--release", "--features", "mcu"],
        "precision": "f32",
        "machine": "mps2-an386",
        "grid": "3x4",
    },
}

# Tracked figures, in table order, with their unit (a comment in baseline.toml).
COSTS = {
    "active_median": "instructions per active step, median",
    "active_p99": "instructions per active step, 99th percentile (nearest rank)",
    "active_max": "instructions per active step, max",
    "resting_median": "instructions per resting step, median",
    "resting_p99": "instructions per resting step, 99th percentile (nearest rank)",
    "resting_max": "instructions per resting step, max",
    "setup": "instructions of Book::new, the blocks' settling included",
    "heap_peak": "bytes, most heap held at once",
    "flash": "bytes, .vector_table + .text + .rodata",
    "stack": "bytes, stack high-water mark",
}
# Accuracy over the page turn's active steps: gated like a cost (growth over the
# tolerance fails) and held under issue 40's bounds, whatever the baseline says.
ACCURACY = {
    "dog_residual_e9": "largest DOG residual after an active step, 1e-9 units",
    "stretch_ppm": "largest edge stretch after an active step, parts per million",
    "stretch_mean_ppm": "mean over the active steps of each one's largest edge stretch, ppm",
}
# Issue 40: "the default page turn's max DOG residual stays <= 2e-4, its max edge stretch
# no worse than today's 0.55 %" (book_report's "mean max stretch": the mean over the active
# frames of each frame's largest stretch).
BOUNDS = {"dog_residual_e9": 200_000, "stretch_mean_ppm": 5_500}
# Issue 40's bounds on one run's costs that it meets, held like the accuracy bounds:
# `page-turn-mcu`'s median active step of at most 1.5 M instructions on the M4F.
RUN_BOUNDS = {"mcu": {"active_median": 1_500_000}}
# Results: any change fails (update the baseline when the change is meant).
EXACT = {"merge_frame": "frame of the page's merge into the left block"}
FIGURES = {**COSTS, **ACCURACY, **EXACT}

# Largest growth of a cost figure that passes (per cent).
TOLERANCE_PERCENT = 3.0
# The summary's clock resolution: instruction counts are whole SysTick ticks of this many
# instructions, so a count grows by up to one tick with the code's layout alone (a resting
# step asleep, 200 instructions, read 240 after a change elsewhere): growth within one tick
# passes whatever its percentage.
TICK = "instructions_per_tick"


class GateError(Exception):
    """A log or the baseline cannot be read."""


def log_path(logs, run):
    return logs / f"embedded-{run}.log"


def run_firmware(logs):
    """Builds and runs the firmwares into their logs; prints each log without its
    per-step lines. Raises GateError when a run fails (its whole log is printed)."""
    logs.mkdir(parents=True, exist_ok=True)
    for run, spec in RUNS.items():
        path = log_path(logs, run)
        print(f"running the {run} firmware: cargo run -q {' '.join(spec['args'])}", flush=True)
        with path.open("w") as out:
            status = subprocess.run(
                ["cargo", "run", "-q", *spec["args"]],
                cwd=EMBEDDED,
                stdout=out,
                stderr=subprocess.STDOUT,
                check=False,
            ).returncode
        text = path.read_text()
        if status != 0:
            print(text)
            raise GateError(f"the {run} firmware failed (exit status {status}), log {path}")
        print("".join(line for line in text.splitlines(True) if not line.startswith("step ")))


def read_summary(path, run):
    """The figures of the `summary:` line of the log at `path`."""
    try:
        text = path.read_text()
    except OSError as e:
        raise GateError(f"cannot read {path}: {e} (run with --run, or run the firmware)")
    lines = [line for line in text.splitlines() if line.startswith("summary: ")]
    if len(lines) != 1:
        raise GateError(f"{path}: expected one `summary:` line, found {len(lines)}")
    words = lines[0].split()[1:]
    spec = RUNS[run]
    if words[:2] != [spec["precision"], spec["machine"]]:
        raise GateError(f"{path}: the summary is of {words[:2]}, not the {run} run")
    pairs = dict(word.split("=", 1) for word in words[2:] if "=" in word)
    if pairs.get("grid") != spec["grid"]:
        raise GateError(f"{path}: the summary is of the {pairs.get('grid')} grid, not the {run} run's")
    if pairs.get("checks") != "pass":
        raise GateError(f"{path}: the firmware's result checks did not pass")
    figures = {}
    for name in [*FIGURES, TICK]:
        value = pairs.get(name)
        if value is None or not value.isdigit():
            raise GateError(f"{path}: no whole number {name}= in the summary line")
        figures[name] = int(value)
    return figures


def write_baseline(now):
    """Rewrites embedded/baseline.toml with the figures `now` (per run)."""
    lines = [
        "# The Cortex-M firmware's page-turn figures (embedded/README.md, \"Baseline\"), under",
        "# QEMU with -icount shift=0, where they repeat exactly. CI fails when a cost figure",
        f"# grows by more than {TOLERANCE_PERCENT:g} % over this file, or the merge frame changes.",
        "# Rewrite it in the same commit as the change that moves a figure:",
        "#     python3 embedded/baseline.py --run --update",
        "# Its git history is the record.",
    ]
    for run, spec in RUNS.items():
        lines += ["", f"[{run}]", f'precision = "{spec["precision"]}"']
        lines.append(f'machine = "{spec["machine"]}"')
        lines.append(f'grid = "{spec["grid"]}"')
        width = max(len(f"{name} = {now[run][name]}") for name in FIGURES)
        for name, unit in FIGURES.items():
            lines.append(f"{f'{name} = {now[run][name]}':<{width}}  # {unit}")
    BASELINE.write_text("\n".join(lines) + "\n")
    print(f"wrote {BASELINE}")


def read_baseline():
    try:
        with BASELINE.open("rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise GateError(f"cannot read {BASELINE}: {e}")


def within_tick(name, growth, figures):
    """Whether `growth` of instruction count `name` is within one tick of the clock."""
    counts_instructions = COSTS.get(name, "").startswith("instructions")
    return counts_instructions and growth <= figures[TICK]


def compare(baseline, now):
    """Prints the table; returns (regressions, changes that pass but should be recorded)."""
    failures, moved = [], []
    header = f"{'run':<4} {'figure':<15} {'baseline':>12} {'now':>12} {'change':>9}  verdict"
    print(header)
    print("-" * len(header))
    for run in RUNS:
        base = baseline.get(run, {})
        bounds = {**BOUNDS, **RUN_BOUNDS.get(run, {})}
        for name in FIGURES:
            value, old = now[run][name], base.get(name)
            if not isinstance(old, int):
                verdict, change = "NOT IN BASELINE", "n/a"
                failures.append(f"{run} {name}: not in the baseline")
            else:
                percent = (value - old) * 100.0 / old if old else (0.0 if value == 0 else 100.0)
                change = f"{percent:+.2f} %"
                if name in bounds and value > bounds[name]:
                    verdict = f"OVER the bound {bounds[name]}"
                    failures.append(f"{run} {name}: {value} over the bound {bounds[name]}")
                elif value == old:
                    verdict = "same"
                elif name in EXACT:
                    verdict = "CHANGED"
                    failures.append(f"{run} {name}: {old} -> {value}")
                elif percent > TOLERANCE_PERCENT and not within_tick(name, value - old, now[run]):
                    verdict = f"REGRESSED (over +{TOLERANCE_PERCENT:g} %)"
                    failures.append(f"{run} {name}: {old} -> {value} ({change})")
                elif value > old:
                    verdict = "worse, within tolerance"
                    moved.append(f"{run} {name}")
                else:
                    verdict = "better"
                    moved.append(f"{run} {name}")
            shown = "-" if old is None else str(old)
            print(f"{run:<4} {name:<15} {shown:>12} {value:>12} {change:>9}  {verdict}")
    return failures, moved


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--run", action="store_true", help="build and run the firmwares first")
    parser.add_argument(
        "--update", action="store_true", help="rewrite embedded/baseline.toml from the logs"
    )
    parser.add_argument(
        "--logs",
        type=Path,
        default=DEFAULT_LOGS,
        help="directory of the runs' logs, embedded-RUN.log (default: <repo>/out)",
    )
    options = parser.parse_args()
    try:
        if options.run:
            run_firmware(options.logs)
        now = {run: read_summary(log_path(options.logs, run), run) for run in RUNS}
        if options.update:
            write_baseline(now)
            return 0
        baseline = read_baseline()
        print(f"== firmware figures against {BASELINE.relative_to(EMBEDDED.parent)} ==")
        failures, moved = compare(baseline, now)
    except GateError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    update = "python3 embedded/baseline.py --run --update"
    if failures:
        print(f"FAIL: {len(failures)} figure(s) regressed or changed: {'; '.join(failures)}")
        print(f"If the change is meant, update the baseline in the same commit: {update}")
        return 1
    if moved:
        print(f"pass; {len(moved)} figure(s) moved within the gate ({', '.join(moved)}):")
        print(f"update the baseline in the same commit to record them: {update}")
    else:
        print("pass: every figure equals the baseline")
    return 0


if __name__ == "__main__":
    sys.exit(main())
