#!/usr/bin/env bash
# Sets up whatever is missing, builds, and runs every QuakeView test:
#   1. native unit tests (Catch2, AddressSanitizer + UBSan, warnings as errors) and the layering check
#   2. the same pure-library tests compiled to WebAssembly, run under node
#   (the native code is also compiled with clang 14, optimized, warnings as errors; its
#   quakeview-prep prepares the browser tests' cities)
#   3. browser end-to-end tests (playwright-core + Debian's headless Chromium, pages served over HTTP),
#      then the core of them again in Debian's headless Firefox ESR (puppeteer-core, WebDriver BiDi)
#   4. a bounded run of every libFuzzer target (scripts/fuzz.sh: clang 14, ASan + UBSan, 20 s each)
# Ends with one summary line; exits non-zero if anything failed. Every stage runs even after a
# failure so one run shows everything that is wrong.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
export NODE_PATH=/usr/share/nodejs
jobs=${QUAKEVIEW_JOBS:-$(nproc)}
# shellcheck source=SCRIPTDIR/lib/demo-recipe.sh
source "$root/scripts/lib/demo-recipe.sh"

bash scripts/setup.sh || { echo "QuakeView tests: FAILED (set-up failed)"; exit 1; }

declare -a failures=()
declare -A counts=()
start=$(date +%s)

# Each stage's start, for the table of times at the end (where a slow run spent its time).
declare -a stage_names=() stage_starts=()
stage() {
  stage_names+=("$*")
  stage_starts+=("$(date +%s)")
  printf '\n==== %s ====\n' "$*"
}

# ctest prints "N% tests passed, F tests failed out of T"; keep T and F.
run_ctest() {
  local name=$1 preset=$2
  local log
  log=$(mktemp)
  ctest --preset "$preset" -j "$jobs" 2>&1 | tee "$log"
  local total failed
  total=$(sed -nE 's/.*tests failed out of ([0-9]+).*/\1/p' "$log" | tail -n 1)
  failed=$(sed -nE 's/.* ([0-9]+) tests failed out of.*/\1/p' "$log" | tail -n 1)
  counts[$name]="${total:-0}"
  if [ -z "$total" ] || [ "${failed:-1}" != 0 ]; then failures+=("$name"); fi
  rm -f "$log"
}

stage "native build (debug, ASan + UBSan, -Werror)"
if cmake --preset native-debug >/dev/null && cmake --build --preset native-debug -j "$jobs"; then
  stage "native unit tests"
  run_ctest native native-debug
else
  failures+=("native build")
fi

stage "native build with clang 14, release (-Werror: warning-free under both compilers)"
if ! (cmake --preset native-clang >/dev/null && cmake --build --preset native-clang -j "$jobs"); then
  failures+=("clang build")
fi

stage "fuzzing: every libFuzzer target for ${QUAKEVIEW_FUZZ_SECONDS:-20} s (clang 14, ASan + UBSan)"
if QUAKEVIEW_PREP="$root/build/native-clang/preprocess/app/quakeview-prep" \
   bash scripts/fuzz.sh "${QUAKEVIEW_FUZZ_SECONDS:-20}"; then
  counts[fuzz]=$(wc -l < "$root/build/fuzz/fuzz-targets.txt")
else
  failures+=("fuzz")
fi

# Small cities for the browser tests, made with the tools just built (the optimized clang build:
# the response step runs a solver per building). The demo's city (without its earthquake, to keep
# this short) is the triangle-budget test's.
stage "preparing the end-to-end test cities"
e2e_data="$root/build/e2e-data"
prep="$root/build/native-clang/preprocess/app/quakeview-prep"
rm -rf "$e2e_data" && mkdir -p "$e2e_data"
# shellcheck disable=SC2086 # the demo's recipe is a word list
if ! "$prep" synth-city --buildings 3000 --seed 3 --max-leaf-buildings 300 --out "$e2e_data/synth" >/dev/null ||
   ! "$prep" response --city "$e2e_data/synth" --synthetic 7 --epicentre -74.005,40.705,8 --magnitude 6.6 >/dev/null ||
   ! "$prep" info "$e2e_data/synth" --building s1 --json >"$e2e_data/synth-s1.json" ||
   ! "$prep" city --input ../shared/data/osm/fixture-midtown-empire-state.osm --out "$e2e_data/midtown" >/dev/null ||
   ! "$prep" response --city "$e2e_data/midtown" --synthetic 7 --epicentre -73.99,40.74,8 --magnitude 6.6 >/dev/null ||
   ! "$prep" info "$e2e_data/midtown" --building w34633854 --json >"$e2e_data/midtown-esb.json" ||
   ! "$prep" synth-city --buildings 50000 --seed 5 --max-leaf-buildings 500 --max-coarse-buildings 5000 \
       --out "$e2e_data/large" >/dev/null ||
   ! "$prep" synth-city --buildings 300 --seed 12 --no-ground --out "$e2e_data/noground" >/dev/null ||
   ! "$prep" synth-city --buildings 1500 --seed 11 --out "$e2e_data/lod2" >/dev/null ||
   ! "$prep" lod2 --city "$e2e_data/lod2" --input ../shared/data/cityjson/DH_01_subs.city.json \
       --place -74.0,40.71 >/dev/null ||
   ! "$prep" response --city "$e2e_data/lod2" --synthetic 7 >/dev/null ||
   ! "$prep" info "$e2e_data/lod2" --json >"$e2e_data/lod2-info.json" ||
   ! "$prep" city --input tests/e2e/data/hostile-names.geojson --out "$e2e_data/hostile" >/dev/null ||
   ! "$prep" response --city "$e2e_data/hostile" --synthetic 7 >/dev/null ||
   ! "$prep" city --input tests/e2e/data/critical-facilities.geojson --out "$e2e_data/critical" >/dev/null ||
   ! "$prep" response --city "$e2e_data/critical" --synthetic 7 >/dev/null ||
   ! "$prep" city --input tests/e2e/data/hostile-names.geojson --name "Actual-event test" \
       --out "$e2e_data/actual" >/dev/null ||
   ! "$prep" response --city "$e2e_data/actual" --shakemap tests/e2e/data/actual-shakemap.xml --synthetic 7 8 \
       --time-of-day night --districts tests/e2e/data/districts.geojson >/dev/null ||
   ! "$prep" info "$e2e_data/actual" --json >"$e2e_data/actual-info.json" ||
   ! "$prep" $QV_DEMO_CITY_RECIPE --out "$e2e_data/demo" >/dev/null ||
   ! bash tests/e2e/data/make-scenario-city.sh "$prep" "$e2e_data/scenarios"; then
  failures+=("e2e data")
fi
# The cities a user meets first, for the shaking test (shaking.test.mjs): the README demo with its
# earthquake (made once and kept, shared with scripts/demo.sh: two to three minutes), and the city
# built from the shared Manhattan OpenStreetMap file under the shared NYC ShakeMap (README "Your
# own city"; about a minute and a half).
demo_data="$root/build/demo-data/default"
if ! qv_demo_prepare "$prep" "$demo_data" "[test]" ||
   ! "$prep" city --input ../shared/data/osm/nyc-manhattan-south-buildings.osm.pbf --out "$e2e_data/manhattan" >/dev/null ||
   ! "$prep" response --city "$e2e_data/manhattan" --shakemap ../shared/data/shakemap/nyc-m5.8-scenario-grid.xml \
       --motion ../shared/data/ground-motions/elCentro.AT2 ../shared/data/ground-motions/TAK000.AT2 >/dev/null; then
  failures+=("e2e data (demo, Manhattan)")
fi
# The situation reports the tool writes, which the viewer's must equal (report.test.mjs).
for city in "$e2e_data/actual" "$e2e_data/manhattan" "$demo_data"; do
  name=$(basename "$city")
  [ "$city" = "$demo_data" ] && name=demo
  if ! "$prep" report "$city" --out "$e2e_data/$name-report.html" >/dev/null; then failures+=("e2e data (report of $name)"); fi
done

stage "Slurm: a city's response as a job array on a single-node cluster"
log=$(mktemp)
QUAKEVIEW_PREP="$prep" bash scripts/slurm/test-slurm.sh 2>&1 | tee "$log"
if [ "${PIPESTATUS[0]}" -ne 0 ]; then failures+=("slurm"); fi
counts[slurm]=$(grep -c '^PASS' "$log")
rm -f "$log"

stage "WebAssembly build (release, -Werror)"
if cmake --preset wasm-release >/dev/null && cmake --build --preset wasm-release -j "$jobs"; then
  stage "WebAssembly unit tests under node"
  run_ctest wasm wasm-release

  stage "browser end-to-end tests (headless Chromium)"
  log=$(mktemp)
  (cd tests/e2e && QUAKEVIEW_SITE="$root/build/wasm-release/site" QUAKEVIEW_E2E_DATA="$e2e_data" \
    QUAKEVIEW_DEMO_DATA="$demo_data" node --test --test-reporter=tap ./*.test.mjs) 2>&1 | tee "$log"
  e2e_pass=$(sed -nE 's/^# pass ([0-9]+)/\1/p' "$log" | tail -n 1)
  e2e_fail=$(sed -nE 's/^# fail ([0-9]+)/\1/p' "$log" | tail -n 1)
  counts[e2e]="${e2e_pass:-0}"
  if [ -z "$e2e_pass" ] || [ "${e2e_fail:-1}" != 0 ]; then failures+=("e2e"); fi
  rm -f "$log"

  # The same tests of what a user meets first (first light, the city with its broken tiles,
  # interaction on a real city, weak-device detection, taps and swipes on a phone and a tablet,
  # the city shaking at its opening view, the picture of the view, the situation report, the 2D
  # city without WebGL2, with touch emulation, switching between a city's scenarios, the map under
  # the city with its names) in a second
  # engine: Debian's Firefox ESR, WebGL2 on llvmpipe,
  # driven by puppeteer-core over WebDriver BiDi (tests/e2e/lib/browser.mjs). A few minutes.
  stage "browser end-to-end tests (headless Firefox ESR)"
  log=$(mktemp)
  (cd tests/e2e && QUAKEVIEW_BROWSER=firefox QUAKEVIEW_SITE="$root/build/wasm-release/site" \
    QUAKEVIEW_E2E_DATA="$e2e_data" QUAKEVIEW_DEMO_DATA="$demo_data" \
    node --test --test-reporter=tap first-light.test.mjs city.test.mjs interaction.test.mjs weak-device.test.mjs touch.test.mjs \
      shaking.test.mjs images.test.mjs report.test.mjs map2d.test.mjs scenarios.test.mjs map.test.mjs) 2>&1 | tee "$log"
  e2e_pass=$(sed -nE 's/^# pass ([0-9]+)/\1/p' "$log" | tail -n 1)
  e2e_fail=$(sed -nE 's/^# fail ([0-9]+)/\1/p' "$log" | tail -n 1)
  counts[e2e_firefox]="${e2e_pass:-0}"
  if [ -z "$e2e_pass" ] || [ "${e2e_fail:-1}" != 0 ]; then failures+=("e2e-firefox"); fi
  rm -f "$log"
else
  failures+=("wasm build")
fi

end=$(date +%s)
elapsed=$(( end - start ))
printf '\n%8s  %s\n' "seconds" "stage"
for i in "${!stage_names[@]}"; do
  next=$end
  [ $((i + 1)) -lt "${#stage_starts[@]}" ] && next=${stage_starts[$((i + 1))]}
  printf '%8d  %s\n' $(( next - stage_starts[i] )) "${stage_names[$i]}"
done
summary="native ${counts[native]:-0}, wasm ${counts[wasm]:-0}, e2e ${counts[e2e]:-0} tests, e2e-firefox ${counts[e2e_firefox]:-0} tests, fuzz ${counts[fuzz]:-0} targets, slurm ${counts[slurm]:-0} checks in ${elapsed}s"
if [ "${#failures[@]}" -eq 0 ]; then
  echo "QuakeView tests: ALL PASSED ($summary)"
else
  echo "QuakeView tests: FAILED in ${failures[*]} ($summary)"
  exit 1
fi
