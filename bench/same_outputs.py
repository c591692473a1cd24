#!/usr/bin/env python3
"""Checks that two builds of `folio` run every built-in scene the same.

    python3 bench/same_outputs.py [--added KEY ...] OLD_BIN NEW_BIN [SCENE ...]

Runs `folio run SCENE --out DIR` with both binaries (every built-in scene from `folio list`
unless scenes are named) and compares their outputs: `report.json` with its timings left out
(every key ending in `_ms`, the measured milliseconds of a step or a frame), and every other
output file byte for byte. Prints one line per scene and the first difference found; exits
1 when any scene differs or a run fails in one build and not the other (a run's own exit
status, 3 for a bad run, must be the same in both builds), 2 on bad arguments.
`--added KEY` (repeatable) leaves the report key KEY out of the comparison at any depth: a
field the change adds to `report.json`, whose other keys must still be the same.

A change that is meant to keep the bits (a refactor, a leaner data structure) shows it with
this: build the old commit in a worktree (`git worktree add --detach /tmp/old HEAD~1`,
`cargo build --release -p folio` there), then run this with both `target/release/folio`.
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path


ADDED = set()


def without_timings(value):
    """`value` with every key ending in `_ms`, and every key of `ADDED`, removed at any depth."""
    if isinstance(value, dict):
        return {
            k: without_timings(v)
            for k, v in value.items()
            if not k.endswith("_ms") and "_ms_" not in k and k not in ADDED
        }
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def without_time_plot(svg):
    """The timeline SVG without its step-time plot: from that plot's title to the next
    plot's title (the next bold text)."""
    start = svg.find("Step time per frame")
    if start < 0:
        return svg
    next_title = svg.find('font-weight="bold"', start)
    end = svg.rfind("<text", 0, next_title) if next_title >= 0 else len(svg)
    return svg[:start] + svg[end:]


def first_difference(a, b, path="report"):
    """The path of the first place where `a` and `b` differ, or None."""
    if type(a) is not type(b):
        return f"{path}: {a!r} vs {b!r}"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{path}.{key}: present in one build only"
            found = first_difference(a[key], b[key], f"{path}.{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} vs {len(b)} entries"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, f"{path}[{i}]")
            if found:
                return found
        return None
    return None if a == b else f"{path}: {a!r} vs {b!r}"


def run(binary, scene, out):
    done = subprocess.run([binary, "run", scene, "--out", str(out)], capture_output=True, text=True)
    return done.returncode


def compare(old, new, scene, work):
    outs = [work / f"{scene}-old", work / f"{scene}-new"]
    codes = [run(binary, scene, out) for binary, out in zip((old, new), outs)]
    if codes[0] != codes[1]:
        return f"exit status {codes[0]} vs {codes[1]}"
    names = sorted({p.name for out in outs for p in out.iterdir()})
    for name in names:
        a, b = (out / name for out in outs)
        if not (a.exists() and b.exists()):
            return f"{name}: written by one build only"
        if name == "report.json":
            found = first_difference(*(without_timings(json.loads(p.read_text())) for p in (a, b)))
            if found:
                return found
        elif name.endswith(".svg"):
            # The timeline's first plot is each step's measured time: compared without it.
            if without_time_plot(a.read_text()) != without_time_plot(b.read_text()):
                return f"{name} differs beyond its step-time plot"
        elif a.read_bytes() != b.read_bytes():
            return f"{name} differs"
    return None


def main():
    args = sys.argv[1:]
    while len(args) >= 2 and args[0] == "--added":
        ADDED.add(args[1])
        args = args[2:]
    if len(args) < 2 or any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 2
    old, new, scenes = args[0], args[1], args[2:]
    if not scenes:
        listed = subprocess.run([new, "list"], capture_output=True, text=True, check=True).stdout
        scenes = [line.split()[0] for line in listed.splitlines() if line.strip()]
    differ = 0
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            found = compare(old, new, scene, Path(tmp))
            print(f"{scene:18} {'same' if found is None else 'DIFFERS: ' + found}", flush=True)
            differ += found is not None
    print(f"{len(scenes) - differ} of {len(scenes)} scenes the same")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
