#!/usr/bin/env bash
# Makes the browser tests' city with a scenario catalogue (scenarios.test.mjs) from two runs of
# quakeview-prep, in the layout the tool will write itself (docs/formats.md, "Scenario catalogue"):
#
#   OUT/tileset.json        the default view: scenario 1's manifest
#   OUT/scenario-1.json     scenario 1 (M6.6 near the city's south-west corner): a copy of tileset.json
#   OUT/scenario-2.json     scenario 2 (M5.0 to the north-east): the same city, its files in response-2/
#   OUT/response-1/         scenario 1's results
#   OUT/response-2/         scenario 2's results
#   OUT/scenarios.json      the catalogue naming both
#
# Usage: make-scenario-city.sh QUAKEVIEW_PREP OUT
# The second run goes into a copy of the city (the tool keeps one response folder a city), whose
# results are then moved in beside the first's.
set -Eeuo pipefail

prep=${1:?usage: make-scenario-city.sh QUAKEVIEW_PREP OUT}
out=${2:?usage: make-scenario-city.sh QUAKEVIEW_PREP OUT}
copy="$out.second"
trap 'rm -rf "$copy"' EXIT
rm -rf "$out" "$copy"

"$prep" synth-city --buildings 2000 --seed 3 --max-leaf-buildings 300 --out "$out" >/dev/null
cp -r "$out" "$copy"
"$prep" response --city "$out" --synthetic 7 --epicentre -74.005,40.705,8 --magnitude 6.6 >/dev/null
"$prep" response --city "$copy" --synthetic 7 --epicentre -73.99,40.72,8 --magnitude 5.0 >/dev/null

# Both runs write response-1/; the second's becomes response-2/, its manifest naming the files there.
[ -d "$copy/response-1" ] || { echo "make-scenario-city.sh: no response-1/ in $copy" >&2; exit 1; }
cp -r "$copy/response-1" "$out/response-2"
sed 's#"response-1/#"response-2/#g' "$copy/tileset.json" >"$out/scenario-2.json"
if grep -q '"response-1/' "$out/scenario-2.json"; then
  echo "make-scenario-city.sh: scenario-2.json still names response-1/" >&2
  exit 1
fi
cp "$out/tileset.json" "$out/scenario-1.json"
cat >"$out/scenarios.json" <<'JSON'
{"format":"quakeview-scenarios","version":1,"scenarios":[
{"index":1,"name":"M6.6 scenario, Lower Manhattan","manifest":"scenario-1.json"},
{"index":2,"name":"M5.0 scenario, Lower East Side","manifest":"scenario-2.json"}]}
JSON
