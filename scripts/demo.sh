#!/usr/bin/env bash
# Sets up whatever is missing, builds the viewer and the tools, prepares the embedded default
# scenario (a 100,000-building synthetic city and a synthetic earthquake with an epicentre), and
# serves the site on http://127.0.0.1:8080 (PORT overrides) until interrupted.
#
# QUAKEVIEW_DATA=DIR serves that prepared city (the output of quakeview-prep city/response)
# instead of the default one.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
export NODE_PATH=/usr/share/nodejs
port=${PORT:-8080}
jobs=${QUAKEVIEW_JOBS:-$(nproc)}
# shellcheck source=SCRIPTDIR/lib/demo-recipe.sh
source "$root/scripts/lib/demo-recipe.sh"

bash scripts/setup.sh
echo "[demo] building the viewer (WebAssembly) and quakeview-prep (native)"
cmake --preset wasm-release >/dev/null
cmake --build --preset wasm-release -j "$jobs" --target site
cmake --preset native-release >/dev/null
cmake --build --preset native-release -j "$jobs" --target quakeview-prep
prep="$root/build/native-release/preprocess/app/quakeview-prep"
site="$root/build/wasm-release/site"

if [ -n "${QUAKEVIEW_DATA:-}" ]; then
  data=$(cd "$QUAKEVIEW_DATA" && pwd)
  [ -f "$data/tileset.json" ] || { echo "[demo] $data has no tileset.json: not a prepared city" >&2; exit 1; }
  echo "[demo] serving the city in $data"
else
  # The default scenario, prepared once (the stamp records the parameters it was made with).
  data="$root/build/demo-data/default"
  qv_demo_prepare "$prep" "$data"
fi

echo "[demo] open http://127.0.0.1:${port}/ in a browser (Ctrl-C stops)"
exec node web/serve.mjs --root "$site" --port "$port" --mount "/data/default=$data"
