#!/usr/bin/env bash
# Benchmark of a sharded response run (docs/cluster.md): the same city's response on one machine
# and as N parts run one after another on this machine, then merged: wall and CPU time, peak memory
# of each process, the overhead of sharding and merging, bytes of the response per building; and,
# on a smaller city under a suite of records, the CPU time per building and record of pass one
# (peaks under every record) and pass two (the stored history under one record, with its losses),
# with the core-hours they project for NHERI SimCenter's Bay Area testbed (1.84 M buildings x 25
# records). Prints markdown tables.
#
#   bash scripts/bench-shards.sh [PREP_BINARY]    (default build/native-clang/.../quakeview-prep)
#   BUILDINGS=1000000 PARTS=4 SUITE_BUILDINGS=50000 SUITE_RECORDS=3 WORK=/tmp/qv-bench-shards
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
prep=${1:-$root/build/native-clang/preprocess/app/quakeview-prep}
buildings=${BUILDINGS:-1000000}
parts=${PARTS:-4}
suite_buildings=${SUITE_BUILDINGS:-50000}
suite_records=${SUITE_RECORDS:-3}
[ -x "$prep" ] || { echo "bench-shards: $prep not built (cmake --build --preset native-clang --target quakeview-prep)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench-shards: /usr/bin/time missing (apt install time)" >&2; exit 1; }
work=${WORK:-$(mktemp -d)}
mkdir -p "$work"
[ -n "${WORK:-}" ] || trap 'rm -rf "$work"' EXIT
# The tool is copied: a rebuild during the run must not change it.
cp "$prep" "$work/prep"
prep="$work/prep"
quake=(--synthetic 7 --epicentre -74.005,40.705,8 --magnitude 6.6)

# Runs a command under /usr/bin/time; prints "wall_s cpu_s rss_mb" and keeps its output in $work/last.log.
measure() {
  /usr/bin/time -f '%e %U %S %M' -o "$work/time.txt" "$@" >"$work/last.log" 2>&1 ||
    { echo "bench-shards: failed: $*" >&2; tail -20 "$work/last.log" >&2; exit 1; }
  awk '{printf "%.1f %.1f %.0f\n", $1, $2 + $3, $4 / 1024}' "$work/time.txt"
}
# "solving X s (pass one Y s, pass two Z s)" from a response's output.
passes() {
  sed -nE 's/.*solving ([0-9.]+) s \(pass one ([0-9.]+) s, pass two ([0-9.]+) s\).*/\1 \2 \3/p' "$work/last.log" | head -1
}

echo "Sharded response: $buildings synthetic buildings x 1 record, one machine vs $parts parts run one"
echo "after another on this machine and merged ($(nproc) cores; all parts use every core)"
echo
if [ ! -f "$work/city/tileset.json" ]; then
  read -r w c m < <(measure "$prep" synth-city --buildings "$buildings" --seed 5 --out "$work/city")
  echo "synth-city: $w s, $m MB peak"
  echo
fi
# CPU seconds of the solver and the history encoder ("solving X s ... encoding Y s" in a whole run's
# output, "CPU X s solving ..., Y s encoding" in a part's): the same work in both runs (the same
# storey-steps), so what is left beside it is what sharding can add.
solver_cpu() {
  sed -nE -e 's/.*solving ([0-9.]+) s \(pass one [0-9.]+ s, pass two [0-9.]+ s\), encoding ([0-9.]+) s.*/\1 \2/p' \
    -e 's/.*CPU ([0-9.]+) s solving \(pass one [0-9.]+ s, pass two [0-9.]+ s\), ([0-9.]+) s encoding.*/\1 \2/p' \
    "$work/last.log" | head -1 | awk '{printf "%.1f\n", $1 + $2}'
}
# One whole run into $work/one (a fresh copy of the city): "wall_s cpu_s rss_mb solver_cpu_s".
whole_run() {
  rm -rf "$work/one"
  cp -a "$work/city" "$work/one"
  read -r w c m < <(measure "$prep" response --city "$work/one" "${quake[@]}")
  echo "$w $c $m $(solver_cpu)"
}
rm -rf "$work/sharded"
cp -a "$work/city" "$work/sharded"

# This machine's speed drifts by several per cent over minutes (a shared VM), more than the
# overhead measured: the whole run is measured before and after the parts and the parts compared
# with the mean of the two.
echo "| run | wall s | CPU s | of which solver and encoder, CPU s | peak memory MB | buildings |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
read -r one_w one_c one_m one_s < <(whole_run)
echo "| one machine, before the parts | $one_w | $one_c | $one_s | $one_m | $buildings |"
sum_w=0 sum_c=0 sum_s=0 max_m=0
for k in $(seq 1 "$parts"); do
  read -r w c m < <(measure "$prep" response --city "$work/sharded" "${quake[@]}" --shard "$k/$parts")
  s=$(solver_cpu)
  n=$(sed -nE 's/.*\(([0-9]+) buildings\).*/\1/p' "$work/last.log" | head -1)
  echo "| part $k of $parts | $w | $c | $s | $m | $n |"
  sum_w=$(awk -v a="$sum_w" -v b="$w" 'BEGIN {print a + b}')
  sum_c=$(awk -v a="$sum_c" -v b="$c" 'BEGIN {print a + b}')
  sum_s=$(awk -v a="$sum_s" -v b="$s" 'BEGIN {print a + b}')
  max_m=$(awk -v a="$max_m" -v b="$m" 'BEGIN {print (b > a) ? b : a}')
done
read -r merge_w merge_c merge_m < <(measure "$prep" response --city "$work/sharded" --merge)
echo "| merge | $merge_w | $merge_c | 0 | $merge_m | $buildings |"
total_w=$(awk -v a="$sum_w" -v b="$merge_w" 'BEGIN {print a + b}')
total_c=$(awk -v a="$sum_c" -v b="$merge_c" 'BEGIN {print a + b}')
echo "| parts + merge | $total_w | $total_c | $sum_s | $max_m (largest part) | |"
identical=no
if diff -rq "$work/one" "$work/sharded" >/dev/null; then identical=yes; fi
read -r two_w two_c two_m two_s < <(whole_run)
echo "| one machine, after the parts | $two_w | $two_c | $two_s | $two_m | $buildings |"
echo
if ! diff -rq "$work/one" "$work/sharded" >/dev/null; then identical=no; fi
folder=$(ls -d "$work/one"/response-* | head -1)
bytes=$(du -sb "$folder" | cut -f1)
awk -v ow1="$one_w" -v ow2="$two_w" -v oc1="$one_c" -v oc2="$two_c" -v os1="$one_s" -v os2="$two_s" \
    -v tw="$total_w" -v tc="$total_c" -v ts="$sum_s" -v mw="$merge_w" -v mc="$merge_c" -v pc="$sum_c" -v n="$buildings" \
    -v b="$bytes" -v p="$parts" -v id="$identical" 'BEGIN {
  ow = (ow1 + ow2) / 2; oc = (oc1 + oc2) / 2; os = (os1 + os2) / 2
  printf "| measure | value |\n| --- | ---: |\n"
  printf "| overhead of sharding and merging, CPU time (goal <= 5 %%), against the mean whole run | %.1f %% (parts %.1f %%, merge %.1f %%) |\n", \
    100 * (tc / oc - 1), 100 * (pc / oc - 1), 100 * mc / oc
  printf "| the same against each whole run (the machine drifting) | %.1f %% and %.1f %% |\n", 100 * (tc / oc1 - 1), 100 * (tc / oc2 - 1)
  printf "| CPU outside the solver and encoder: sharded vs whole | %.1f s vs %.1f s: %.1f %% of the whole run |\n", \
    tc - ts, oc - os, 100 * ((tc - ts) - (oc - os)) / oc
  printf "| overhead, wall time, against the mean whole run | %.1f %% |\n", 100 * (tw / ow - 1)
  printf "| the merge alone, wall | %.1f s (%.1f %% of the whole run) |\n", mw, 100 * mw / ow
  printf "| wall time on %d machines (parts at once, then the merge) | %.0f s (%.1fx faster) |\n", p, (tw - mw) / p + mw, ow / ((tw - mw) / p + mw)
  printf "| merged files byte-identical to the one-machine run (both whole runs) | %s |\n", id
  printf "| response files per building | %.0f bytes (%.1f MB in all) |\n", b / n, b / 1e6
}'
echo

echo "CPU time per building and record: $suite_buildings buildings under $suite_records records"
rm -rf "$work/suite"
"$prep" synth-city --buildings "$suite_buildings" --seed 6 --out "$work/suite" >/dev/null
seeds=$(seq 1 "$suite_records" | tr '\n' ' ')
# shellcheck disable=SC2086 # seeds is a word list
read -r sw sc sm < <(measure "$prep" response --city "$work/suite" --synthetic $seeds --epicentre -74.005,40.705,8 --magnitude 6.6)
read -r solve one two < <(passes)
awk -v n="$suite_buildings" -v r="$suite_records" -v s="$solve" -v p1="$one" -v p2="$two" -v c="$sc" -v w="$sw" 'BEGIN {
  a = 1000 * p1 / (n * r); b = 1000 * p2 / n; all = 1000 * c / n
  printf "| measure | value |\n| --- | ---: |\n"
  printf "| run | %.1f s wall, %.1f s CPU |\n", w, c
  printf "| pass one (peaks, every record), CPU per building and record | %.2f ms |\n", a
  printf "| pass two (history and losses under the shown record), CPU per building | %.2f ms |\n", b
  printf "| whole run, CPU per building (%d records) | %.2f ms |\n", r, all
  # Bay Area testbed: 1.84 M buildings x 25 records: pass one under 25 records, pass two once,
  # plus what the run spends outside the solver (encoding, losses, files) per building.
  other = all - a * r - b; if (other < 0) other = 0
  core_s = 1.84e6 * (25 * a + b + other) / 1000
  printf "| projected Bay Area testbed (1.84 M buildings x 25 records) | %.0f core-hours (SimCenter reported > 100,000) |\n", core_s / 3600
  printf "| the same on 100 nodes of 2 cores | %.1f hours |\n", core_s / 3600 / 200
}'
