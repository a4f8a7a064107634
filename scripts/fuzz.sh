#!/usr/bin/env bash
# Builds the libFuzzer targets (preset `fuzz`: clang 14, AddressSanitizer + UBSan), prepares their
# seed corpora in build/fuzz/seeds/, and runs every target for a bounded time. Prints a table
# (target, executions, result) and exits non-zero if any target crashed, leaked, timed out or ran
# out of memory. Crash inputs are kept in build/fuzz/crashes/<target>/.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET]     (default 20)
#
# Environment: QUAKEVIEW_FUZZ_TARGETS="fuzz_city_tile fuzz_osm" runs only those targets;
# QUAKEVIEW_JOBS (default 2) targets run at once; QUAKEVIEW_FUZZ_JOBS (default 1) runs that many
# fuzzing processes per target (-fork);
# QUAKEVIEW_PREP points at a quakeview-prep to write seed files with (default: built here).
# The longer run is documented in docs/fuzzing.md.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
seconds=${1:-20}
jobs=${QUAKEVIEW_JOBS:-2}
fuzz_jobs=${QUAKEVIEW_FUZZ_JOBS:-1}
build="$root/build/fuzz"
# Stack traces for UBSan reports too (ASan prints them by default).
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:suppressions=$root/tests/fuzz/ubsan-suppressions.txt}

case "$seconds" in
  '' | *[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS_PER_TARGET]" >&2; exit 2 ;;
esac

echo "==== building the fuzz targets (preset fuzz) ===="
if ! cmake --preset fuzz >/dev/null || ! cmake --build --preset fuzz -j "$jobs" --target fuzzers; then
  echo "QuakeView fuzzing: FAILED (build)"
  exit 1
fi

prep=${QUAKEVIEW_PREP:-}
if [ -z "$prep" ]; then
  echo "==== building quakeview-prep (seed files) ===="
  if cmake --build --preset fuzz -j "$jobs" --target quakeview-prep; then
    prep="$build/preprocess/app/quakeview-prep"
  else
    echo "[fuzz] warning: quakeview-prep did not build; fewer seeds" >&2
  fi
fi

echo "==== seed corpora ===="
bash "$root/tests/fuzz/make-seeds.sh" "$build/seeds" "$prep"

targets=${QUAKEVIEW_FUZZ_TARGETS:-$(cat "$build/fuzz-targets.txt")}
rows_dir="$build/rows"
rm -rf "$rows_dir" && mkdir -p "$rows_dir"

# One target's bounded run; its table row goes to rows/<target>.row (and rows/<target>.failed when
# it failed, after printing the end of its log).
run_target() {
  local target=$1
  local what=${target#fuzz_}
  local exe="$build/tests/fuzz/$target"
  local corpus="$build/corpus/$what"
  local crashes="$build/crashes/$what"
  local log="$build/logs/$what.log"
  # A target without seeds starts from an empty seed folder (libFuzzer refuses a missing one).
  rm -rf "$crashes" && mkdir -p "$corpus" "$crashes" "$build/seeds/$what" "$(dirname "$log")"
  echo "==== $target: ${seconds}s ===="
  # The working corpus keeps what earlier runs found; the seeds are read alongside it.
  local extra_args=()
  [ "$fuzz_jobs" -gt 1 ] && extra_args=(-fork="$fuzz_jobs" -ignore_crashes=0)
  local dict="$root/tests/fuzz/dicts/$what.dict"
  [ -f "$dict" ] && extra_args+=(-dict="$dict")
  "$exe" "$corpus" "$build/seeds/$what" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$crashes/" -print_final_stats=1 "${extra_args[@]}" >"$log" 2>&1
  local rc=$?
  local runs cov result kind
  runs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  [ -z "$runs" ] && runs=$(grep -oE '#[0-9]+' "$log" | tail -n 1 | tr -d '#')
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -n 1 | awk '{print $2}')
  if [ "$rc" -eq 0 ]; then
    result="ok"
  else
    kind=$(grep -oE 'ERROR: (AddressSanitizer|UndefinedBehaviorSanitizer|LeakSanitizer|libFuzzer): [a-zA-Z-]+' "$log" |
      head -n 1 | sed -E 's/ERROR: //')
    [ -z "$kind" ] && kind=$(grep -oE 'runtime error: .*|fuzz contract broken: .*' "$log" | head -n 1 | cut -c1-60)
    result="FAILED (${kind:-exit $rc}; input in ${crashes#"$root"/}, log ${log#"$root"/})"
    echo "==== $target FAILED: the end of its log ===="
    tail -n 40 "$log"
    : >"$rows_dir/$target.failed"
  fi
  printf '%-28s %12s %8s  %s\n' "$target" "${runs:-?}" "${cov:-?}" "$result" >"$rows_dir/$target.row"
}

# As many targets at once as there are jobs (each fuzzer uses one core).
running=0
for target in $targets; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
  run_target "$target" &
  running=$((running + 1))
done
wait

declare -a rows=()
failed=0
for target in $targets; do
  if [ -f "$rows_dir/$target.row" ]; then
    rows+=("$(cat "$rows_dir/$target.row")")
  else
    rows+=("$(printf '%-28s %12s %8s  %s' "$target" "?" "?" "FAILED (no result)")")
    failed=1
  fi
  [ -f "$rows_dir/$target.failed" ] && failed=1
done

echo
printf '%-28s %12s %8s  %s\n' "target" "runs" "cov" "result"
printf '%s\n' "${rows[@]}"
if [ "$failed" -ne 0 ]; then
  echo "QuakeView fuzzing: FAILED"
  exit 1
fi
echo "QuakeView fuzzing: ALL PASSED (${seconds}s per target)"
