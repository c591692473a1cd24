#!/usr/bin/env bash
# Builds the C example against Folio's static library and prints the program's path.
#   examples/c/build.sh           host (x86_64): target/release/page_turn
#   examples/c/build.sh aarch64   aarch64 Linux: target/aarch64-unknown-linux-gnu/release/page_turn
#                                 (run it with qemu-aarch64 -L /usr/aarch64-linux-gnu)
# CC overrides the host compiler. The library is always built with --release.
set -euo pipefail
cd "$(dirname "$0")/../.."

case "${1:-host}" in
  host)
    cargo build -q -p folio-capi --release
    lib=target/release
    cc=${CC:-gcc}
    ;;
  aarch64)
    cargo build -q -p folio-capi --release --target aarch64-unknown-linux-gnu
    lib=target/aarch64-unknown-linux-gnu/release
    cc=aarch64-linux-gnu-gcc
    ;;
  *)
    echo "usage: $0 [host|aarch64]" >&2
    exit 2
    ;;
esac

"${cc}" -std=c11 -Wall -Wextra -Werror -pedantic -O2 -g -I capi/include \
  examples/c/page_turn.c "${lib}/libfolio_capi.a" -lm -lpthread -ldl -o "${lib}/page_turn"
echo "${lib}/page_turn"
