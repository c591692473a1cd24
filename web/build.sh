#!/usr/bin/env bash
# Builds Folio for the browser into web/dist/ and serves it on http://127.0.0.1:8000/
# (PORT=... to change; --no-serve to build only). Installs what it needs: the rustup target
# wasm32-unknown-unknown and wasm-bindgen-cli at the version folio-web's wasm-bindgen has in
# Cargo.lock (the CLI refuses a module of another version).
set -euo pipefail
cd "$(dirname "$0")/.."

serve=1
for arg in "$@"; do
  case "${arg}" in
    --no-serve) serve=0 ;;
    *) echo "usage: web/build.sh [--no-serve]" >&2; exit 2 ;;
  esac
done

rustup target add wasm32-unknown-unknown >/dev/null
version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
if [ -z "${version}" ]; then
  echo "no wasm-bindgen in Cargo.lock" >&2
  exit 1
fi
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }')" != "${version}" ]; then
  echo "installing wasm-bindgen-cli ${version} (a few minutes, once)"
  cargo install -q wasm-bindgen-cli --version "${version}"
fi

cargo build -q --profile web -p folio-web --target wasm32-unknown-unknown
rm -rf web/dist
wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section \
  --out-dir web/dist target/wasm32-unknown-unknown/web/folio_web.wasm
cp web/static/* web/dist/
wasm=web/dist/folio_web_bg.wasm
echo "web/dist/: $(wc -c <"${wasm}") bytes of wasm, $(gzip -9 -c "${wasm}" | wc -c) gzipped"

if [ "${serve}" = 1 ]; then
  port=${PORT:-8000}
  echo "serving web/dist/ on http://127.0.0.1:${port}/ (Ctrl-C to stop)"
  exec python3 -m http.server "${port}" --bind 127.0.0.1 --directory web/dist
fi
