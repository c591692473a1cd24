#!/usr/bin/env bash
# Instructions per active step of the page turn on aarch64, under qemu-user.
#
#   bench/neon/steps.sh [BINARY]
#
# Runs BINARY (default: frame_work, built here for aarch64 in release) under qemu-aarch64
# with bench/neon/insn.c's counting plugin, which records the guest instruction count at
# each clock read; play_in reads the clock just before and just after each step, so the
# steps' counts are the differences of consecutive pairs. frame_work plays the page turn
# twice in f64, then twice in f32 (750 frames each); the second play of each is reported.
# Its N active frames end at its merge frame M (both from its own output), so they are
# frames M-N+1..M: in this fixture the first step above 1 M instructions is frame 30 in
# both precisions, and M-N+1 = 30 in both. Prints median, p99, max and total per active step.
set -euo pipefail
cd "$(dirname "$0")/../.."

binary=${1:-}
if [ -z "${binary}" ]; then
  cargo build -q --release -p folio-bench --example frame_work --target aarch64-unknown-linux-gnu
  binary=target/aarch64-unknown-linux-gnu/release/examples/frame_work
fi
work=$(mktemp -d)
trap 'rm -rf "${work}"' EXIT
gcc -O2 -Wall -Wextra -Werror -shared -fPIC -o "${work}/libinsn.so" bench/neon/insn.c
qemu-aarch64 -L /usr/aarch64-linux-gnu -plugin "${work}/libinsn.so,out=${work}/clock.txt" \
  "${binary}" >"${work}/stdout.txt"
python3 - "${work}/clock.txt" "${work}/stdout.txt" <<'PY'
import re
import sys

counts = [int(line) for line in open(sys.argv[1])]
steps = [counts[2 * i + 1] - counts[2 * i] for i in range(len(counts) // 2)]
frames = 750
if len(steps) != 4 * frames:
    sys.exit(f"expected {4 * frames} timed steps, got {len(steps)}")
runs = re.findall(r"^(f\w+), default: (\d+) active frames of \d+, merged at frame Some\((\d+)\)",
                  open(sys.argv[2]).read(), re.M)
print("| precision | active steps | median | p99 | max | total |")
print("|---|---|---|---|---|---|")
for (name, active, merged), play in zip(runs, (1, 3)):
    active, merged = int(active), int(merged)
    start = play * frames
    s = sorted(steps[start + merged - active + 1:start + merged + 1])
    q = lambda p: s[round((len(s) - 1) * p)]
    print(f"| {name} | {len(s)} | {q(0.5) / 1e6:.2f} M | {q(0.99) / 1e6:.2f} M "
          f"| {s[-1] / 1e6:.2f} M | {sum(s) / 1e6:.0f} M |")
PY
