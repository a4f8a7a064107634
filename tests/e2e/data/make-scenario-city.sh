#!/usr/bin/env bash
# Makes the browser tests' city with a scenario catalogue (scenarios.test.mjs) the way a user does:
# `quakeview-prep response --catalogue` (docs/cluster.md, "Many scenarios"). Three scenarios:
#
#   1  M6.6 near the city's south-west corner, run on one machine  -> response-<n>/, scenario-1.json,
#                                                                      and tileset.json (the default view)
#   2  M5.0 to the north-east, run as 2 parts and merged           -> response-<n>/, scenario-2.json
#   3  M7.2, listed but never run                                   -> no scenario-3.json: "not ready"
#
# scenarios.json lists all three.
# Usage: make-scenario-city.sh QUAKEVIEW_PREP OUT
set -Eeuo pipefail

prep=${1:?usage: make-scenario-city.sh QUAKEVIEW_PREP OUT}
out=${2:?usage: make-scenario-city.sh QUAKEVIEW_PREP OUT}
catalogue="$out.catalogue.json"
trap 'rm -f "$catalogue"' EXIT
rm -rf "$out"

"$prep" synth-city --buildings 2000 --seed 3 --max-leaf-buildings 300 --out "$out" >/dev/null
cat >"$catalogue" <<'JSON'
{"options": {"synthetic": [7]},
 "scenarios": [
  {"name": "M6.6 scenario, Lower Manhattan", "epicentre": "-74.005,40.705,8", "magnitude": 6.6},
  {"name": "M5.0 scenario, Lower East Side", "epicentre": "-73.99,40.72,8", "magnitude": 5.0},
  {"name": "M7.2 scenario, not yet run", "epicentre": "-74.0,40.7,10", "magnitude": 7.2}
 ]}
JSON
"$prep" response --city "$out" --catalogue "$catalogue" --scenario 1 >/dev/null
"$prep" response --city "$out" --catalogue "$catalogue" --scenario 2 --shard 2/2 >/dev/null
"$prep" response --city "$out" --catalogue "$catalogue" --scenario 2 --shard 1/2 >/dev/null
"$prep" response --city "$out" --merge --scenario 2 >/dev/null

for file in tileset.json scenario-1.json scenario-2.json scenarios.json; do
  [ -f "$out/$file" ] || { echo "make-scenario-city.sh: the tool wrote no $file in $out" >&2; exit 1; }
done
if [ -e "$out/scenario-3.json" ]; then
  echo "make-scenario-city.sh: scenario 3 was never run, yet $out/scenario-3.json exists" >&2
  exit 1
fi
