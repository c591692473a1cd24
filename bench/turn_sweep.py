#!/usr/bin/env python3
"""How robust a scene's page turns are: runs a built-in scene's file (by default
`scenes/three-and-back.toml`) with the middle point of every swipe moved to each height
`y` and every release moved to each delay after the finger stops, and counts the variants
whose final pages are the scene's expected ones. One line per grid and precision; each
cell is `passed/variants` at one height.

    cargo build --release -p folio
    python3 bench/turn_sweep.py                                  # 8 x 11, f64 and f32
    python3 bench/turn_sweep.py --grid 6x8 --grid 12x16 --precision f32
    python3 bench/turn_sweep.py --book 'solver.newton_iterations = 4' --book 'pull_reach = 2'
    python3 bench/turn_sweep.py --paper novel

A swipe is a `drag` event whose point has `|x| == 5` (the scene's middle points); its
height is replaced, the side (sign of x) and the rest kept. A release happens at the
finger's last `drag` time plus the delay. The runs are deterministic (a variant repeats
its pages exactly), so one run per variant is enough. Each variant's scene goes to a
temporary folder; nothing in the repository is written. Exit status 1 when the binary or
the scene is missing, 0 otherwise (the counts are the result, not a verdict).
Standard library only (tomllib: Python 3.11).
"""

import argparse
import re
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEIGHTS = [3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 9.5, 10.0]
DELAYS = [0.1, 0.25, 0.5]
PAGES = re.compile(r"pages at the end\s+left (\d+), right (\d+), held (\d+)")


def variant(text: str, height: float, delay: float, settings: str) -> str:
    """The scene `text` with each swipe's middle point at `height`, each release `delay`
    seconds after the last drag before it, and `settings` (root keys such as `precision`
    and dotted `book.` keys, one per line) put before its first table."""
    out, last_drag, lines = [], None, text.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r"drag = \[(-?5\.0), ([-0-9.]+), ([-0-9.]+)\]", line)
        if m:
            line = f"drag = [{m.group(1)}, {height}, {m.group(3)}]"
        t = re.match(r"time = ([0-9.]+)", line)
        if t and i + 1 < len(lines):
            if lines[i + 1].startswith("drag"):
                last_drag = float(t.group(1))
            elif lines[i + 1].startswith("release") and last_drag is not None:
                line = f"time = {last_drag + delay:.2f}"
        out.append(line)
    text = "\n".join(out) + "\n"
    first_table = re.search(r"^\[", text, re.MULTILINE)
    at = first_table.start() if first_table else len(text)
    return text[:at] + settings + text[at:]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", default=str(ROOT / "scenes" / "three-and-back.toml"))
    p.add_argument("--bin", default=str(ROOT / "target" / "release" / "folio"))
    p.add_argument("--grid", action="append", help="COLSxROWS, repeatable (default: the scene's)")
    p.add_argument("--precision", action="append", choices=["f64", "f32"])
    p.add_argument(
        "--book",
        action="append",
        default=[],
        help="a `[book]` setting for every variant, repeatable (e.g. 'solver.newton_iterations = 4')",
    )
    p.add_argument("--paper", help="the book's paper for every variant (`paper = NAME`)")
    args = p.parse_args()
    scene, binary = Path(args.scene), Path(args.bin)
    if not binary.is_file() or not scene.is_file():
        print(f"missing {binary if not binary.is_file() else scene}", file=sys.stderr)
        return 1
    text = scene.read_text()
    expected = tomllib.loads(text).get("expect", {}).get("final_pages")
    if expected is None:
        print(f"{scene} has no expect.final_pages", file=sys.stderr)
        return 1
    grids = args.grid or [None]
    precisions = args.precision or ["f64", "f32"]
    with tempfile.TemporaryDirectory() as tmp:
        for grid in grids:
            for precision in precisions:
                settings = f'precision = "{precision}"\n' + "".join(f"book.{line}\n" for line in args.book)
                if args.paper:
                    settings += f'paper = "{args.paper}"\n'
                if grid:
                    cols, rows = grid.split("x")
                    settings += f"book.quads_across = {int(cols)}\nbook.quads_along = {int(rows)}\n"
                cells, total = [], 0
                for height in HEIGHTS:
                    passed = 0
                    for delay in DELAYS:
                        path = Path(tmp) / f"v_{height}_{delay}.toml"
                        path.write_text(variant(text, height, delay, settings))
                        run = subprocess.run(
                            [str(binary), "run", str(path), "--out", str(Path(tmp) / "out")],
                            capture_output=True,
                            text=True,
                        )
                        m = PAGES.search(run.stdout + run.stderr)
                        if m and [int(g) for g in m.groups()] == expected:
                            passed += 1
                    total += passed
                    cells.append(f"y={height:g} {passed}/{len(DELAYS)}")
                label = f"{grid or 'scene grid'}, {precision}"
                print(f"{label}: {'  '.join(cells)}  all {total}/{len(HEIGHTS) * len(DELAYS)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
