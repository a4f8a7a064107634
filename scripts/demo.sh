#!/usr/bin/env bash
# Sets up whatever is missing, builds the viewer, and serves it on http://127.0.0.1:8080 (PORT
# overrides) until interrupted.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
export NODE_PATH=/usr/share/nodejs
port=${PORT:-8080}
jobs=${QUAKEVIEW_JOBS:-$(nproc)}

bash scripts/setup.sh
echo "[demo] building the viewer (WebAssembly)"
cmake --preset wasm-release >/dev/null
cmake --build --preset wasm-release -j "$jobs" --target site

site="$root/build/wasm-release/site"
echo "[demo] open http://127.0.0.1:${port}/ in a browser"
exec node web/serve.mjs --root "$site" --port "$port"
