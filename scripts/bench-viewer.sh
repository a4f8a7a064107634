#!/usr/bin/env bash
# Benchmark of the viewer in headless browsers on software WebGL (this machine has no GPU),
# 1280x720, default settings (on these renderers: the weak-device preset). Prints markdown tables
# (tests/e2e/bench-viewer.mjs) of FPS, frame times, triangles and pixels per frame, draw calls:
#   1. the ?bench flight of the NYC city (~18k buildings) and of the 100k-building demo, Chromium
#      (SwiftShader);
#   2. the NYC city's overview poses (1.8 km from its centre, pitch 56°, eight headings), Chromium;
#   3. the same flight of both cities in Firefox ESR (llvmpipe).
# Each browser's tables end with the reference: a bare WebGL2 page drawing 30,000 and 100,000 small
# triangles, measured in the same run (this machine's speed varies from hour to hour).
# Takes 10-20 minutes on 2 cores; run it on a quiet machine (`nice` keeps it polite).
#
# Builds nothing: it needs the site (cmake --build --preset wasm-release --target site) and a
# quakeview-prep binary (build/native-release or build/native-clang; QUAKEVIEW_PREP overrides).
# Prepares the cities once:
#   - build/bench-data/nyc: `city` on ../shared/data/osm/nyc-manhattan-south-buildings.osm.pbf and
#     its `response` to the NYC ShakeMap scenario (as in README "Your own city"); made again when
#     the prep binary is newer than it;
#   - build/demo-data/default: the demo's city and earthquake (scripts/lib/demo-recipe.sh), shared
#     with scripts/demo.sh.
#
#   bash scripts/bench-viewer.sh [--seconds 20] [--pose-seconds 5]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
# shellcheck source=SCRIPTDIR/lib/demo-recipe.sh
source "$root/scripts/lib/demo-recipe.sh"
shared=${QUAKEVIEW_SHARED_DATA:-$root/../shared/data}
site=${QUAKEVIEW_SITE:-$root/build/wasm-release/site}
seconds=20 pose_seconds=5
while [ $# -gt 0 ]; do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --pose-seconds) pose_seconds=$2; shift 2 ;;
    *) echo "usage: bash scripts/bench-viewer.sh [--seconds 20] [--pose-seconds 5]" >&2; exit 2 ;;
  esac
done

prep=${QUAKEVIEW_PREP:-}
if [ -z "$prep" ]; then
  for p in build/native-release build/native-clang; do
    if [ -x "$root/$p/preprocess/app/quakeview-prep" ]; then prep="$root/$p/preprocess/app/quakeview-prep"; break; fi
  done
fi
if [ -z "$prep" ] || [ ! -x "$prep" ]; then
  echo "bench-viewer: no quakeview-prep (cmake --build --preset native-release --target quakeview-prep, or QUAKEVIEW_PREP=...)" >&2
  exit 1
fi
[ -f "$site/quakeview-engine.wasm" ] || {
  echo "bench-viewer: no site in $site (cmake --build --preset wasm-release --target site)" >&2
  exit 1
}
[ -d tests/e2e/node_modules ] || { echo "bench-viewer: tests/e2e/node_modules missing (bash scripts/setup.sh)" >&2; exit 1; }

# The NYC city and its ShakeMap scenario.
nyc="$root/build/bench-data/nyc"
osm="$shared/osm/nyc-manhattan-south-buildings.osm.pbf"
shakemap="$shared/shakemap/nyc-m5.8-scenario-grid.xml"
motions=("$shared/ground-motions/elCentro.AT2" "$shared/ground-motions/TAK000.AT2")
nyc_recipe="city --input $osm; response --shakemap $shakemap --motion ${motions[*]}"
if [ "$(cat "$nyc/.recipe" 2>/dev/null)" != "$nyc_recipe" ] || [ "$prep" -nt "$nyc/.recipe" ]; then
  echo "[bench-viewer] preparing the NYC city in $nyc (about a minute on 2 cores)"
  rm -rf "$nyc" && mkdir -p "$(dirname "$nyc")"
  "$prep" city --input "$osm" --out "$nyc" >/dev/null
  "$prep" response --city "$nyc" --shakemap "$shakemap" --motion "${motions[@]}" >/dev/null
  echo "$nyc_recipe" >"$nyc/.recipe"
fi
buildings=$("$prep" info "$nyc" --json | sed -nE 's/.*"buildings":([0-9]+).*/\1/p')
if [ -z "$buildings" ] || [ "$buildings" -lt 15000 ] || [ "$buildings" -gt 21000 ]; then
  echo "bench-viewer: $nyc has ${buildings:-no} buildings, expected about 18,000" >&2
  exit 1
fi

# The demo's city and earthquake (reused from scripts/demo.sh when there).
demo="$root/build/demo-data/default"
qv_demo_prepare "$prep" "$demo" "[bench-viewer]"

bench() { (cd tests/e2e && node bench-viewer.mjs "$@"); }
echo "[bench-viewer] NYC has $buildings buildings; prep: $prep; site: $site"
bench "nyc=$nyc" "demo=$demo" --seconds "$seconds" --browser chromium
bench "nyc=$nyc" --poses overview --pose-seconds "$pose_seconds" --browser chromium
bench "nyc=$nyc" "demo=$demo" --seconds "$seconds" --browser firefox
