#!/usr/bin/env bash
# Prepares the seed corpora of the fuzz targets in OUT/<target>/ (a build folder; nothing here is
# committed): real data from ../shared/data, the repository's own test fixtures, small hand-written
# seeds (tests/fuzz/seeds/), a few ground tiles (make-ground-seeds.py), and files written by
# quakeview-prep (tiles, ground tiles, manifests, search indexes, response tiles of a small
# synthetic city and of an OSM cut).
#   usage: make-seeds.sh OUT [QUAKEVIEW_PREP]
# Missing tools (osmium, quakeview-prep) only mean fewer seeds, with a warning.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:?usage: make-seeds.sh OUT [QUAKEVIEW_PREP]}
prep=${2:-}
shared="$root/../shared/data"
work="$out/.work"

warn() { printf '[seeds] warning: %s\n' "$*" >&2; }

rm -rf "$out" && mkdir -p "$out" "$work"
# Every target that gets seeds written below, and every target with hand-written seeds committed.
committed=()
for d in "$root"/tests/fuzz/seeds/*/; do committed+=("$(basename "$d")"); done
for t in city_tile city_tile_roundtrip ground_tile ground_tile_roundtrip tileset consequences search_index \
         search_index_roundtrip response_summary response_history response_roundtrip ground_motion osm geojson \
         response_import cityjson obj shakemap "${committed[@]}"; do
  mkdir -p "$out/$t"
  if [ -d "$root/tests/fuzz/seeds/$t" ]; then cp "$root/tests/fuzz/seeds/$t"/* "$out/$t/" 2>/dev/null; fi
done

# A stored file as written, and expanded when it is a Zstandard frame (zstd from Debian's package).
add_stored() {  # add_stored TARGET TAG FILE
  local dest
  dest="$out/$1/$2-$(basename "$3")"
  cp "$3" "$dest"
  if command -v zstd >/dev/null 2>&1 && zstd -t -q "$3" 2>/dev/null; then
    zstd -d -q -c "$3" >"$dest.raw" || warn "cannot expand $3"
  fi
}

# Ground tiles: a few valid ones written from docs/formats.md by an independent writer (python3), and
# below what quakeview-prep writes.
if command -v python3 >/dev/null 2>&1; then
  python3 "$root/tests/fuzz/make-ground-seeds.py" "$out/ground_tile" || warn "make-ground-seeds.py failed"
  # One of them in its stored form too (a Zstandard frame, as quakeview-prep may store it).
  if command -v zstd >/dev/null 2>&1 && [ -f "$out/ground_tile/park-river-street.qvg" ]; then
    zstd -q -6 -c "$out/ground_tile/park-river-street.qvg" >"$out/ground_tile/park-river-street.qvg.zst" ||
      warn "cannot compress a ground tile seed"
  fi
else
  warn "no python3: no hand-made ground tile seeds"
fi

# Ground motions: the first byte of an input chooses the caller's options (FuzzGroundMotion.cpp):
# 0 = auto, units and step from the file; 36 = auto, units g, step 0.02 s.
add_motion() {  # add_motion OPTION_BYTE FILE
  local name
  name=$(basename "$2")
  { printf "\\$(printf '%03o' "$1")"; cat "$2"; } >"$out/ground_motion/$1-$name"
}
for f in "$shared"/ground-motions/*.AT2 "$root"/tests/seismic/data/*; do
  [ -f "$f" ] && add_motion 0 "$f"
done
for f in "$shared"/ground-motions/*.txt "$root"/tests/seismic/data/*.txt; do
  [ -f "$f" ] && add_motion 36 "$f"
done

# OSM and GeoJSON: the ingest fixtures, and small cuts of the real Midtown file (XML and PBF)
# around the Empire State Building, with their `osmium export` GeoJSON.
cp "$root"/tests/ingest/data/*.osm "$out/osm/" 2>/dev/null
cp "$root"/tests/ingest/data/*.geojson "$out/geojson/" 2>/dev/null
midtown="$shared/osm/fixture-midtown-empire-state.osm"
cut_osm=""
if command -v osmium >/dev/null 2>&1 && [ -f "$midtown" ] &&
   osmium tags-filter "$midtown" nwr/building nwr/building:part r/type=building -o "$work/buildings.osm" \
     --overwrite --no-progress; then
  i=0
  for box in -73.9865,40.7477,-73.9848,40.7490 -73.9900,40.7500,-73.9880,40.7512 -73.9840,40.7460,-73.9825,40.7472; do
    i=$((i + 1))
    if osmium extract -s complete_ways -b "$box" "$work/buildings.osm" -o "$work/cut$i.osm" --overwrite --no-progress &&
       osmium cat "$work/cut$i.osm" -o "$work/cut$i.osm.pbf" --overwrite --no-progress; then
      cp "$work/cut$i.osm" "$work/cut$i.osm.pbf" "$out/osm/"
      osmium export "$work/cut$i.osm" -o "$out/geojson/cut$i.geojson" --overwrite --no-progress ||
        warn "osmium export failed for cut $i"
      [ -z "$cut_osm" ] && cut_osm="$work/cut$i.osm"
    else
      warn "osmium extract failed for $box"
    fi
  done
else
  warn "osmium or $midtown missing: no OSM cuts"
fi

# LOD2 models: the real CityJSON files (the two small ones whole, the larger ones as they are:
# libFuzzer truncates to -max_len) and the LOD2 test fixtures.
for f in "$shared"/cityjson/*.json "$root"/tests/lod2/data/*.json; do
  [ -f "$f" ] && cp "$f" "$out/cityjson/"
done
for f in "$root"/tests/lod2/data/*.obj; do
  [ -f "$f" ] && cp "$f" "$out/obj/"
done

# Files the tools write.
if [ -n "$prep" ] && [ -x "$prep" ]; then
  cities=()
  if "$prep" synth-city --buildings 60 --seed 5 --max-leaf-buildings 12 --out "$work/synth" >/dev/null &&
     "$prep" response --city "$work/synth" --synthetic 7 --epicentre -74.005,40.705,8 --magnitude 6.6 >/dev/null; then
    cities+=("$work/synth")
  else
    warn "quakeview-prep synth-city/response failed"
  fi
  if [ -n "$cut_osm" ] &&
     "$prep" city --input "$cut_osm" --max-leaf-buildings 8 --out "$work/osmcity" >/dev/null 2>&1 &&
     "$prep" response --city "$work/osmcity" --synthetic 3 >/dev/null 2>&1; then
    cities+=("$work/osmcity")
  else
    warn "quakeview-prep city/response on the OSM cut failed"
  fi
  for c in "${cities[@]}"; do
    tag=$(basename "$c")
    cp "$c/tileset.json" "$out/tileset/$tag-tileset.json"
    # City files as written (Zstandard frames) and expanded (the decoder behind the frame).
    [ -f "$c/search.qvi" ] && add_stored search_index "$tag" "$c/search.qvi"
    for f in "$c"/tiles/*.qvt; do [ -f "$f" ] && add_stored city_tile "$tag" "$f"; done
    for f in "$c"/ground/*.qvg; do [ -f "$f" ] && add_stored ground_tile "$tag" "$f"; done
    for f in "$c"/response-*/*.qvs; do [ -f "$f" ] && add_stored response_summary "$tag" "$f"; done
    for f in "$c"/response-*/*.qvh; do [ -f "$f" ] && add_stored response_history "$tag" "$f"; done
    for f in "$c"/response-*/consequences.json; do [ -f "$f" ] && cp "$f" "$out/consequences/$tag-consequences.json"; done
  done
else
  warn "no quakeview-prep: no seeds of city tiles, manifests, search indexes or response tiles"
fi
rm -rf "$work"
for d in "$out"/*/; do printf '[seeds] %-24s %4d files\n' "$(basename "$d")" "$(find "$d" -type f | wc -l)"; done
