#!/usr/bin/env bash
# Benchmark of the whole `quakeview-prep city` command (read, clean, project, infer, tile, write)
# against `osmium export` of the same file to GeoJSON (Debian osmium-tool) and, for OSM XML, the
# seed paper's approach (Python's XML parser and GeoPandas, scripts/paper-approach.py; needs
# Debian's python3-geopandas), side by side in one run (interleaved, median of RUNS, default 5),
# and of `synth-city` at 1M buildings (wall time, peak memory, tile bytes per building). Prints
# markdown tables.
#
#   bash scripts/bench-city.sh [PREP_BINARY]   (default: build/native-release/.../quakeview-prep)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
prep=${1:-$root/build/native-release/preprocess/app/quakeview-prep}
data=${QUAKEVIEW_SHARED_DATA:-$root/../shared/data}
runs=${RUNS:-5}
[ -x "$prep" ] || { echo "bench-city: $prep not built (cmake --build --preset native-release --target quakeview-prep)" >&2; exit 1; }
command -v osmium >/dev/null || { echo "bench-city: osmium-tool missing (apt install osmium-tool)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# seconds of wall time of a command (stdout/stderr discarded)
wall() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >/dev/null 2>&1 || { echo "bench-city: failed: $*" >&2; exit 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}' 
}
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

echo "quakeview-prep city vs osmium export (GeoJSON), wall seconds, median of $runs interleaved runs"
echo
echo "(city --no-lod2 does what osmium export does: footprints out; plain city also makes LOD2 models"
echo "of the buildings with building:parts)"
echo
paper=0
if /usr/bin/python3 -c 'import geopandas' 2>/dev/null; then paper=1; fi
echo "| file | size MB | buildings | city s | city --no-lod2 s | osmium export s | ratio --no-lod2 / osmium (goal <= 1.5) | paper's approach s | speed-up --no-lod2 over it (goal >= 8) |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for f in manhattan-midtown-buildings.osm nyc-manhattan-south-buildings.osm.pbf; do
  in="$data/osm/$f"
  [ -f "$in" ] || { echo "| $f | missing | | | | |"; continue; }
  city=() lod1=() osm=() py=()
  for _ in $(seq "$runs"); do
    city+=("$(wall "$prep" city --input "$in" --out "$work/city")")
    lod1+=("$(wall "$prep" city --no-lod2 --input "$in" --out "$work/city-lod1")")
    osm+=("$(wall osmium export "$in" -o "$work/export.geojson" --overwrite)")
    if [ "$paper" = 1 ] && [[ "$f" == *.osm ]]; then
      py+=("$(wall /usr/bin/python3 "$root/scripts/paper-approach.py" "$in" "$work/paper.json")")
    fi
  done
  mc=$(median "${city[@]}")
  ml=$(median "${lod1[@]}")
  mo=$(median "${osm[@]}")
  mp="" speedup=""
  if [ "${#py[@]}" -gt 0 ]; then
    mp=$(printf '%.3f' "$(median "${py[@]}")")
    speedup=$(awk -v a="$mp" -v b="$ml" 'BEGIN {printf "%.1fx", a / b}')
  elif [[ "$f" == *.osm ]]; then
    mp="skipped (apt install python3-geopandas)"
  fi
  buildings=$("$prep" info "$work/city" --json | sed -nE 's/.*"buildings":([0-9]+).*/\1/p')
  size=$(du -m --apparent-size "$in" | cut -f1)
  printf '| %s | %s | %s | %.3f | %.3f | %.3f | %.2fx | %s | %s |\n' "$f" "$size" "$buildings" "$mc" "$ml" "$mo" \
    "$(awk -v a="$ml" -v b="$mo" 'BEGIN {print a / b}')" "$mp" "$speedup"
done

echo
echo "synth-city (one run each)"
echo
echo "| buildings | wall s | peak RSS MB | tiles | tile bytes | bytes per building |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: |"
for n in ${SYNTH_SIZES:-100000 1000000}; do
  rm -rf "$work/synth"
  /usr/bin/time -f '%e %M' -o "$work/time" "$prep" synth-city --buildings "$n" --seed 1 --out "$work/synth" >/dev/null
  read -r secs kb <"$work/time"
  json=$("$prep" info "$work/synth" --json)
  tiles=$(echo "$json" | sed -nE 's/.*"tiles":([0-9]+).*/\1/p')
  bytes=$(echo "$json" | sed -nE 's/.*"bytes":([0-9]+).*/\1/p')
  printf '| %s | %.2f | %d | %s | %s | %.0f |\n' "$n" "$secs" "$((kb / 1024))" "$tiles" "$bytes" "$(awk -v a="$bytes" -v b="$n" 'BEGIN {print a / b}')"
done
