#!/usr/bin/env bash
# Times Folio, faer, CHOLMOD and Eigen on the same DOG-sheet KKT matrices, in one run: for
# each grid, kkt_report exports the matrix, its right-hand side and Folio's AmdDelayedDuals
# permutation; kkt_peers times Folio (Amd, AmdDelayedDuals) and faer (supernodal,
# simplicial) after checking the exported file is its matrix; the C++ harness peers.cpp
# times CHOLMOD's simplicial LDL' and Eigen's SimplicialLDLT with their own AMD and with
# Folio's permutation. Prints one Markdown table per grid (median of REPS calls, in µs).
#
# Usage: bench/peers/run.sh [REPS]   (from the workspace root; REPS defaults to 21)
# Needs g++ and the Debian packages libsuitesparse-dev and libeigen3-dev (installed with
# apt-get when missing). Offline measurement: not run in CI.
set -euo pipefail

reps=${1:-21}
case $reps in '' | *[!0-9]* | 0) echo "run.sh: REPS must be a positive integer" >&2; exit 2 ;; esac
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$root/target/peers
grids=(11x8 16x12 22x16 32x24)
mkdir -p "$out"

if ! dpkg -s libsuitesparse-dev libeigen3-dev >/dev/null 2>&1; then
    sudo=$([ "$(id -u)" -eq 0 ] || echo sudo)
    $sudo apt-get install -y libsuitesparse-dev libeigen3-dev >&2
fi
g++ -O3 -march=native -DNDEBUG -std=c++17 -I/usr/include/eigen3 \
    "$root/bench/peers/peers.cpp" -o "$out/peers" -lcholmod 2>/dev/null
cargo build --release -q -p folio-bench --example kkt_report --example kkt_peers
examples=$root/target/release/examples

echo "Machine: $(nproc) cores, $(uname -m), load average $(cut -d' ' -f1-3 /proc/loadavg);" \
    "$(date -u +%Y-%m-%dT%H:%MZ); median of $reps calls"
echo "CHOLMOD $(dpkg-query -W -f '${Version}' libsuitesparse-dev) (SuiteSparse)," \
    "Eigen $(dpkg-query -W -f '${Version}' libeigen3-dev), g++ $(g++ -dumpversion) -O3 -march=native"
for grid in "${grids[@]}"; do
    matrix=$out/kkt_$grid.mtx rhs=$out/rhs_$grid.mtx perm=$out/perm_$grid.txt
    "$examples/kkt_report" --grid "$grid" --export "$matrix" --rhs "$rhs" \
        --perm "$perm" --ordering AmdDelayedDuals >/dev/null
    n=$(sed -n 3p "$matrix" | cut -d' ' -f1)
    echo
    echo "### $grid quads (n = $n)"
    echo
    echo "| solver | ordering | analysis µs | numeric factor µs | solve µs | nnz(L) | residual | status |"
    echo "|---|---|---:|---:|---:|---:|---:|---|"
    {
        "$examples/kkt_peers" --grid "$grid" --reps "$reps" --check "$matrix"
        "$out/peers" "$matrix" "$rhs" "$perm" "$reps"
    } | awk -F'\t' '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8 }'
done
