#!/usr/bin/env bash
# The long fuzz run (docs/fuzzing.md): runs each target until its coverage has not grown for
# PLATEAU_MINUTES (default 30) of the fuzzer's own CPU time or it has used CPU_MINUTES of CPU
# (default 60), SLOTS targets at a time (default 2), at the lowest CPU priority (so the plateau is
# counted in CPU time, not wall time: a fuzzer starved by other work has not been fuzzing). Needs
# the fuzz build and its seeds (run `scripts/fuzz.sh 1` once first). Prints one row per target:
# wall minutes, CPU minutes, executions, coverage at start and end, CPU minutes since coverage
# last grew, and the result.
#
#   scripts/fuzz-plateau.sh fuzz_tileset fuzz_osm ...
#
# A target written as fuzz_NAME:MINUTES gets its own CPU cap (for example the rest of an hour
# that an earlier run started: the bar is one CPU-hour per target in total).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/fuzz"
plateau=$((${PLATEAU_MINUTES:-30} * 60))
cpu_cap=$((${CPU_MINUTES:-60} * 60))
slots=${SLOTS:-2}
# libFuzzer's -timeout is wall time: a niced fuzzer starved by other work for a while would report
# a false hang with the short run's 10 s. Real hangs still stop it; slow inputs are listed.
timeout=${UNIT_TIMEOUT_SECONDS:-120}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:suppressions=$root/tests/fuzz/ubsan-suppressions.txt}
[ $# -gt 0 ] || { echo "usage: scripts/fuzz-plateau.sh fuzz_TARGET[:MINUTES]..." >&2; exit 2; }
for arg in "$@"; do
  [[ $arg =~ ^fuzz_[a-z_]+(:[1-9][0-9]*)?$ ]] || { echo "fuzz-plateau.sh: '$arg' is not fuzz_NAME or fuzz_NAME:MINUTES" >&2; exit 2; }
done
ticks=$(getconf CLK_TCK)

run_one() {
  local target=${1%%:*} cpu_cap=$cpu_cap
  [ "$target" != "$1" ] && cpu_cap=$((${1#*:} * 60))
  local what=${target#fuzz_}
  local exe="$build/tests/fuzz/$target" corpus="$build/corpus/$what" crashes="$build/crashes/$what"
  local log="$build/logs/$what.long.log"
  mkdir -p "$corpus" "$crashes" "$(dirname "$log")"
  local extra=()
  [ -f "$root/tests/fuzz/dicts/$what.dict" ] && extra=(-dict="$root/tests/fuzz/dicts/$what.dict")
  nice -n 19 "$exe" "$corpus" "$build/seeds/$what" -timeout="$timeout" -report_slow_units=10 -rss_limit_mb=2048 -artifact_prefix="$crashes/" \
    -print_final_stats=1 "${extra[@]}" >"$log" 2>&1 &
  local pid=$! start=$SECONDS last_growth=0 cov0="" cov="" cpu=0
  while kill -0 "$pid" 2>/dev/null; do
    sleep 20
    local now_cov
    now_cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -n 1 | awk '{print $2}')
    [ -z "$cov0" ] && cov0=$now_cov
    if [ -r "/proc/$pid/stat" ]; then
      cpu=$(awk -v t="$ticks" '{print int(($14 + $15) / t)}' "/proc/$pid/stat")
    fi
    if [ -n "$now_cov" ] && [ "$now_cov" != "$cov" ]; then cov=$now_cov; last_growth=$cpu; fi
    if [ $((cpu - last_growth)) -ge "$plateau" ] || [ "$cpu" -ge "$cpu_cap" ]; then
      kill -INT "$pid"
      break
    fi
  done
  wait "$pid"
  local rc=$?
  local runs result
  runs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  [ -z "$runs" ] && runs=$(grep -oE '#[0-9]+' "$log" | tail -n 1 | tr -d '#')
  if grep -qE 'ERROR: (AddressSanitizer|UndefinedBehaviorSanitizer|LeakSanitizer|libFuzzer)|runtime error:|fuzz contract broken' "$log"; then
    result="FAILED (see ${log#"$root"/}, inputs in ${crashes#"$root"/})"
  else
    result="ok (exit $rc)"
  fi
  printf '%-28s %6.1f %6.1f %12s %7s %7s %6.1f  %s\n' "$target" "$(echo "($SECONDS - $start) / 60" | bc -l)" \
    "$(echo "$cpu / 60" | bc -l)" "${runs:-?}" "${cov0:-?}" "${cov:-?}" "$(echo "($cpu - $last_growth) / 60" | bc -l)" "$result"
}

printf '%-28s %6s %6s %12s %7s %7s %6s  %s\n' target wall_m cpu_m runs cov0 cov idle_cpu_m result
running=0
for target in "$@"; do
  run_one "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$slots" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait
