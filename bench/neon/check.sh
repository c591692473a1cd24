#!/usr/bin/env bash
# The NEON check of issue 19: the aarch64 release build's hot loops use fused multiply-adds.
#
#   bench/neon/check.sh [BINARY]
#
# Disassembles BINARY (default: the C example's page turn, built by examples/c/build.sh
# aarch64, which links the f32 and the f64 book) and counts, per instance of each hot function
# below, the vector fmla/fmls and scalar fmadd/fmsub inside its loops (bench/neon/count.awk).
# Prints a Markdown table (the one in bench/README.md) and fails when a hot function has no
# fused multiply-add in a loop, or the conjugate-gradient solve no vector one.
set -euo pipefail
cd "$(dirname "$0")/../.."

# name tail[=least vector fmla/fmls]
hot=(
  'Columns<T>::eliminate'                     # the factor's column update (sparse scatter)
  'Ldlt<T>::solve_paired'                     # triangular solves (scatter, then gather)
  'kkt::symmetric_product'                    # K z (refinement residuals, CG products)
  'NormalEquations<T>::assemble'              # J W^-1 J^T, column by column
  'NormalEquations<T>::back_substitute'       # -W^-1 J^T mu
  'NormalEquations<T>::solve=1'               # CG: contiguous axpys, vector fmla/fmls
  'Assemble<T>::scatter_hessian'              # term Hessian blocks into the KKT values
  'Assemble<T> as folio_solvers::model::TermVisitor<T>>::potentials' # gradients, energy
)

binary=${1:-}
if [ -z "${binary}" ]; then
  binary=$(examples/c/build.sh aarch64 | tail -n 1)
fi
objdump=aarch64-linux-gnu-objdump
command -v "${objdump}" >/dev/null || objdump=llvm-objdump
names=$(
  IFS=';'
  echo "${hot[*]}"
)
rows=$(mktemp)
trap 'rm -f "${rows}"' EXIT
rc=0
"${objdump}" -d --no-show-raw-insn -C "${binary}" |
  awk -v names="${names}" -f bench/neon/count.awk >"${rows}" || rc=$?
head -n 2 "${rows}"
tail -n +3 "${rows}" | sort
if [ "${rc}" -ne 0 ]; then
  echo "bench/neon/check.sh: a hot loop of ${binary} has no fused multiply-add" >&2
fi
exit "${rc}"
