#!/usr/bin/env bash
# The Slurm stage of scripts/test.sh: a city's response run as a job array on a single-node Slurm
# cluster (scripts/slurm/cluster.sh) through scripts/slurm/submit-response.sh must publish exactly
# what a one-machine run publishes, and must publish nothing while a part is missing or failed.
#
#   QUAKEVIEW_PREP=path/to/quakeview-prep bash scripts/slurm/test-slurm.sh
#
# 1. a synthetic city of 4,000 buildings, A, and an identical copy, B; the one-machine response on A;
# 2. B, parts 1, 2 and 4 of 4 and the merge: the parts run, the merge refuses and names part 3,
#    B's tileset.json is unchanged;
# 3. B, part 3 cancelled while it runs (scancel), then part 3 killed while it runs (SIGKILL to the
#    tool, as on a crashed node): each time Slurm cancels the merge (its dependency can never be
#    met), a merge submitted alone refuses and names part 3, and B is unchanged;
# 4. B, part 3 alone and the merge: published; A and B equal byte for byte (tileset.json and every
#    file of the response folder: diff -r, the staging folder aside).
# 5. A catalogue of 2 scenarios (written into the test's folder, with a districts file named
#    relative to it) on a city C of 2,000 buildings through scripts/slurm/submit-catalogue.sh C 2:
#    one array of 4 tasks and a merge per scenario, each depending only on its own scenario's two
#    tasks (scontrol's Dependency); then C's scenarios.json lists both names, scenario-1.json,
#    scenario-2.json and tileset.json (== scenario-1.json) exist, staging/ is gone, and C equals
#    byte for byte a copy D on which the two scenarios ran on one machine (every manifest and every
#    response folder, no normalisation: D runs the scenarios in the order C's merges took their
#    folder numbers, scenario 1 then 2 unless the merges raced the other way, so that each
#    scenario's folder has the same name in both cities).
# Every job is checked in Slurm itself (scontrol show job: state, exit code, node) and by its
# output file. Prints PASS/FAIL lines and a summary; exits 1 if any check failed. Needs root and
# Debian's slurm-wlm and munge (scripts/setup.sh). Keeps its folder (printed) when a check fails.
# Settings: QUAKEVIEW_PREP (default build/native-clang/preprocess/app/quakeview-prep),
# QUAKEVIEW_SLURM_TEST_TIMEOUT (seconds to wait for a set of jobs, default 300),
# QUAKEVIEW_SLURM_PORT (the test cluster's port, scripts/slurm/cluster.sh).
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
slurm_scripts="$root/scripts/slurm"
prep_src=${QUAKEVIEW_PREP:-$root/build/native-clang/preprocess/app/quakeview-prep}
wait_limit=${QUAKEVIEW_SLURM_TEST_TIMEOUT:-300}
started=$(date +%s)
work="(none)"  # the test's folder, once made

passed=0
failed=0
pass() { passed=$((passed + 1)); printf 'PASS: %s\n' "$*"; }
fail() { failed=$((failed + 1)); printf 'FAIL: %s\n' "$*"; }
note() { printf '[slurm-test] %s\n' "$*"; }
# Shows the end of a file under a FAIL line.
show() { [ -f "$1" ] && { printf '  ---- %s ----\n' "$1"; tail -n "${2:-15}" "$1" | sed 's/^/  | /'; }; }

finish() {
  local elapsed=$(($(date +%s) - started))
  if [ "$failed" -eq 0 ]; then
    note "Slurm test: ALL PASSED ($passed checks in ${elapsed}s)"
    exit 0
  fi
  local kept=
  [ "$work" = "(none)" ] || kept="; files kept in $work"
  note "Slurm test: FAILED ($failed of $((passed + failed)) checks failed in ${elapsed}s$kept)"
  exit 1
}
# A failure that ends the test (nothing after it can run).
abort() { fail "$*"; finish; }

if [ ! -x "$prep_src" ]; then
  abort "quakeview-prep not found at '$prep_src' (set QUAKEVIEW_PREP, or build the native-clang preset)"
fi

# (The help text captured first: grep -q stopping early would fail the pipeline under pipefail.)
help_text=$("$prep_src" response --help 2>&1) || true
if grep -q -- '--shard' <<<"$help_text"; then
  pass "quakeview-prep response offers --shard ($prep_src)"
else
  abort "quakeview-prep response has no --shard option ($prep_src): this build predates sharded responses"
fi
work=$(mktemp -d /tmp/qv-slurm-test.XXXXXX)
cluster="$work/cluster"
# shellcheck disable=SC2317 # run by the EXIT trap
cleanup() {
  local status=$?
  bash "$slurm_scripts/cluster.sh" stop "$cluster" >"$work/cluster-stop.log" 2>&1 || cat "$work/cluster-stop.log" >&2
  if [ "$status" -eq 0 ] && [ "$failed" -eq 0 ]; then rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# The jobs run a copy: a rebuild of the tool during the test must not change it between parts.
mkdir -p "$work/bin"
cp "$prep_src" "$work/bin/quakeview-prep"
prep="$work/bin/quakeview-prep"

note "starting a single-node Slurm cluster in $cluster"
if ! start_out=$(bash "$slurm_scripts/cluster.sh" start "$cluster" 2>&1); then
  printf '%s\n' "$start_out"
  abort "the test cluster did not start (scripts/slurm/cluster.sh start: output above)"
fi
printf '%s\n' "$start_out" | sed 's/^/  /'
export SLURM_CONF="$cluster/slurm.conf"
node=$(hostname -s)
pass "single-node Slurm cluster up: node $node idle"

# --- The city, its copy, and the one-machine response -------------------------------------------
# shellcheck disable=SC2054 # the commas are the epicentre's
options=(--synthetic 7 8 --epicentre -74.005,40.705,8 --magnitude 6.6)
A="$work/A"
B="$work/B"
note "making a city of 4,000 buildings (synth-city --seed 21)"
if ! "$prep" synth-city --buildings 4000 --seed 21 --max-leaf-buildings 300 --out "$A" >"$work/synth.log" 2>&1; then
  show "$work/synth.log"
  abort "quakeview-prep synth-city failed"
fi
cp -a "$A" "$B"
t0=$(date +%s)
if ! "$prep" response --city "$A" "${options[@]}" >"$work/one-machine.log" 2>&1; then
  show "$work/one-machine.log"
  abort "the one-machine response on A failed: $prep response --city $A ${options[*]}"
fi
pass "one-machine response on A in $(($(date +%s) - t0))s"
cp "$B/tileset.json" "$work/B-tileset.before.json"
listing() { (cd "$1" && find . -path ./staging -prune -o -print | LC_ALL=C sort); }
listing "$B" >"$work/B-files.before"

# B as it was before any merge: the same tileset.json and no new file outside staging/.
b_unchanged() {
  local what=$1
  if cmp -s "$B/tileset.json" "$work/B-tileset.before.json" && listing "$B" | cmp -s - "$work/B-files.before"; then
    pass "$what: B unchanged (tileset.json and every file outside staging/)"
  else
    fail "$what: B changed although nothing may be published"
    diff <(listing "$B") "$work/B-files.before" | head -n 10 | sed 's/^/  | /'
  fi
}

# --- Slurm helpers -------------------------------------------------------------------------------
submit() { # submit-response.sh ARGS...; prints its machine-readable line
  local out
  out=$(QUAKEVIEW_PREP="$prep" QUAKEVIEW_SLURM_LOGS="$work/logs" bash "$slurm_scripts/submit-response.sh" "$@" 2>"$work/submit.err")
  local status=$?
  sed 's/^/  /' "$work/submit.err" >&2
  [ "$status" -eq 0 ] || return "$status"
  printf '%s\n' "$out"
}
field() { sed -nE "s/.*(^| )$1=([^ ]*).*/\2/p" | head -n 1; }
# One line per job (or array task), as scontrol prints it with -o.
job_lines() { timeout 10 scontrol show job -o "$1" 2>/dev/null; }
job_field() { job_lines "$1" | field "$2"; }
terminal_state() {
  case "$1" in COMPLETED | FAILED | CANCELLED | TIMEOUT | OUT_OF_MEMORY | NODE_FAIL | PREEMPTED | BOOT_FAIL | DEADLINE) return 0 ;; esac
  return 1
}
# Waits until every job named (array ids cover their tasks) has ended; 1 on time-out.
wait_jobs() {
  local deadline=$(($(date +%s) + wait_limit)) id line state all_done
  while [ "$(date +%s)" -lt "$deadline" ]; do
    all_done=1
    for id in "$@"; do
      line=$(job_lines "$id") || line=
      [ -n "$line" ] || { all_done=0; continue; }
      while read -r state; do
        terminal_state "$state" || all_done=0
      done < <(printf '%s\n' "$line" | sed -nE 's/.*JobState=([A-Z_]+).*/\1/p')
    done
    [ "$all_done" -eq 1 ] && return 0
    sleep 1
  done
  return 1
}
# Checks that array task ID_K ran on this cluster's node and ended with STATE (and its log says so).
check_part() {
  local array=$1 k=$2 want=$3 what=$4 line state exit_code nodes log
  line=$(job_lines "${array}_$k")
  state=$(printf '%s\n' "$line" | field JobState)
  exit_code=$(printf '%s\n' "$line" | field ExitCode)
  nodes=$(printf '%s\n' "$line" | field NodeList)
  log="$work/logs/qv-response-${array}_$k.out"
  if [ "$state" = "$want" ] && [ "$nodes" = "$node" ] && grep -q "^\[quakeview\] part $k/4 of .* on $node" "$log" 2>/dev/null; then
    pass "$what: Slurm array task ${array}_$k ran part $k/4 on $node: $state (exit $exit_code)"
  else
    fail "$what: array task ${array}_$k is '${state:-unknown}' (exit ${exit_code:-?}) on '${nodes:-?}', expected $want on $node"
    show "$log"
  fi
}
check_merge() { # ID WANT_STATE WHAT
  local id=$1 want=$2 what=$3 line state exit_code reason
  line=$(job_lines "$id")
  state=$(printf '%s\n' "$line" | field JobState)
  exit_code=$(printf '%s\n' "$line" | field ExitCode)
  reason=$(printf '%s\n' "$line" | field Reason)
  if [ "$state" = "$want" ]; then
    pass "$what: merge job $id $state (exit $exit_code, reason $reason)"
  else
    fail "$what: merge job $id is '${state:-unknown}' (exit ${exit_code:-?}, reason ${reason:-?}), expected $want"
    show "$work/logs/qv-response-merge-$id.out"
  fi
}
# The merge's log names part 3 as the reason it refused.
check_merge_names_part3() {
  local id=$1 what=$2 log="$work/logs/qv-response-merge-$1.out"
  if grep -v '^\[quakeview\]' "$log" 2>/dev/null | grep -iE 'part 3( of 4)?\b' >/dev/null; then
    pass "$what: the merge's refusal names part 3: $(grep -v '^\[quakeview\]' "$log" | grep -iE 'part 3' | head -n 1)"
  else
    fail "$what: the merge's log does not name part 3"
    show "$log"
  fi
}

# --- (a) Parts 1, 2 and 4 of 4, then the merge: refused ------------------------------------------
step="(a) parts 1,2,4 of 4"
note "$step: submitting"
if ids=$(submit --parts 1,2,4 "$B" 4 "${options[@]}"); then
  array=$(printf '%s\n' "$ids" | field array)
  merge=$(printf '%s\n' "$ids" | field merge)
  pass "$step: submitted ($ids)"
  if wait_jobs "$array" "$merge"; then
    for k in 1 2 4; do check_part "$array" "$k" COMPLETED "$step"; done
    check_merge "$merge" FAILED "$step"
    check_merge_names_part3 "$merge" "$step"
  else
    fail "$step: the jobs did not end within ${wait_limit}s"
    timeout 10 squeue | sed 's/^/  | /'
  fi
  b_unchanged "$step"
else
  fail "$step: submit-response.sh failed"
fi

# --- (b) Part 3 failing while it writes: the merge never runs, and alone it refuses --------------
# MODE cancel: scancel, as a user or a time limit ends a job (Slurm: CANCELLED); MODE kill: the
# tool killed with SIGKILL, as on a crashed node (the task FAILED). Either way once the part has
# begun writing into B/staging/.
failed_part() {
  local mode=$1 step=$2 want ids array merge deadline state jid pid reason
  note "$step: submitting (1 core, to leave time to stop it)"
  if ! ids=$(QUAKEVIEW_SLURM_CPUS=1 submit --parts 3 "$B" 4 "${options[@]}"); then
    fail "$step: submit-response.sh failed"
    return
  fi
  array=$(printf '%s\n' "$ids" | field array)
  merge=$(printf '%s\n' "$ids" | field merge)
  pass "$step: submitted ($ids)"
  # Held until the part has ended: should the part finish before it can be stopped, its merge
  # must not publish (that would end the test's later steps).
  timeout 10 scontrol hold "$merge" || note "$step: could not hold the merge job $merge"
  deadline=$(($(date +%s) + wait_limit))
  state=
  while [ "$(date +%s)" -lt "$deadline" ]; do
    state=$(job_field "${array}_3" JobState)
    [ "$state" = PENDING ] || [ -z "$state" ] || break
    sleep 0.2
  done
  # Until the part has begun writing (its folder or temporary folder in staging/; 20 s at most).
  for _ in $(seq 100); do
    [ -z "$(find "$B/staging" -maxdepth 1 -name '*3-of-4*' -newer "$work/B-tileset.before.json" 2>/dev/null)" ] || break
    sleep 0.2
  done
  if [ "$mode" = cancel ]; then
    want=CANCELLED
    timeout 10 scancel "$array"
  else
    want=FAILED
    jid=$(job_lines "${array}_3" | sed -nE 's/^JobId=([0-9]+).*/\1/p')
    pid=
    for p in $(timeout 10 scontrol listpids "$jid" 2>/dev/null | awk 'NR > 1 {print $1}'); do
      [ "$(cat "/proc/$p/comm" 2>/dev/null)" = quakeview-prep ] && pid=$p
    done
    if [ -n "$pid" ]; then kill -KILL "$pid"; else note "$step: no quakeview-prep process in job $jid to kill"; fi
  fi
  if ! wait_jobs "$array"; then
    fail "$step: part 3 did not end within ${wait_limit}s"
    return
  fi
  state=$(job_field "${array}_3" JobState)
  if [ "$state" = COMPLETED ]; then
    # The part ended before it could be stopped: nothing was tested here (no failure either).
    timeout 10 scancel "$merge"
    printf 'SKIP: %s\n' "$step: part 3 ended ($state) before it could be stopped; its checks were not run"
    return
  fi
  timeout 10 scontrol release "$merge" || note "$step: could not release the merge job $merge"
  if ! wait_jobs "$merge"; then
    fail "$step: the merge did not end within ${wait_limit}s"
    return
  fi
  check_part "$array" 3 "$want" "$step"
  check_merge "$merge" CANCELLED "$step"
  reason=$(job_field "$merge" Reason)
  if [ "$reason" = DependencyNeverSatisfied ]; then
    pass "$step: Slurm cancelled the merge: DependencyNeverSatisfied (--kill-on-invalid-dep=yes)"
  else
    fail "$step: the merge's reason is '$reason', expected DependencyNeverSatisfied"
  fi
  if [ -f "$work/logs/qv-response-merge-$merge.out" ]; then
    fail "$step: the cancelled merge has an output file: it ran"
    show "$work/logs/qv-response-merge-$merge.out"
  else
    pass "$step: the merge never started (no output file)"
  fi
  b_unchanged "$step"
  # The merge alone, every other part in place: it must refuse and name part 3.
  note "$step: submitting the merge alone"
  if ids=$(submit --merge-only "$B" 4); then
    merge=$(printf '%s\n' "$ids" | field merge)
    if wait_jobs "$merge"; then
      check_merge "$merge" FAILED "$step, then the merge alone"
      check_merge_names_part3 "$merge" "$step, then the merge alone"
    else
      fail "$step: the merge alone did not end within ${wait_limit}s"
    fi
    b_unchanged "$step, then the merge alone"
  else
    fail "$step: submit-response.sh --merge-only failed"
  fi
}
failed_part cancel "(b) part 3 cancelled while running"
failed_part kill "(b') part 3 killed while running"

# --- (c) Part 3 alone, then the merge: published, equal to the one-machine run -------------------
step="(c) part 3 re-run"
note "$step: submitting"
if ids=$(submit --parts 3 "$B" 4 "${options[@]}"); then
  array=$(printf '%s\n' "$ids" | field array)
  merge=$(printf '%s\n' "$ids" | field merge)
  pass "$step: submitted ($ids)"
  if wait_jobs "$array" "$merge"; then
    check_part "$array" 3 COMPLETED "$step"
    check_merge "$merge" COMPLETED "$step"
    if grep -q "^\[quakeview\] merge .* on $node" "$work/logs/qv-response-merge-$merge.out" 2>/dev/null; then
      pass "$step: the merge's output file shows it ran on $node"
    else
      fail "$step: the merge's output file does not show it ran"
      show "$work/logs/qv-response-merge-$merge.out"
    fi
  else
    fail "$step: the jobs did not end within ${wait_limit}s"
  fi
else
  fail "$step: submit-response.sh failed"
fi

# --- A and B byte for byte -----------------------------------------------------------------------
step="A (one machine) and B (Slurm)"
if cmp "$A/tileset.json" "$B/tileset.json"; then
  pass "$step: tileset.json identical"
else
  fail "$step: tileset.json differs"
fi
response_dirs=$(cd "$A" && find . -mindepth 1 -maxdepth 1 -type d -name 'response-*' -printf '%f\n' | LC_ALL=C sort)
if [ -z "$response_dirs" ]; then
  fail "$step: A has no response-* folder after the one-machine run"
fi
for d in $response_dirs; do
  n_files=$(find "$A/$d" -type f | wc -l)
  if [ -d "$B/$d" ] && diff -r "$A/$d" "$B/$d" >"$work/diff-$d.txt" 2>&1; then
    pass "$step: $d identical ($n_files files)"
  else
    fail "$step: $d differs or is missing in B"
    head -n 10 "$work/diff-$d.txt" | sed 's/^/  | /'
  fi
done
if diff -r --exclude=staging "$A" "$B" >"$work/diff-all.txt" 2>&1; then
  pass "$step: the whole city identical (diff -r, staging/ aside; $(find "$A" -type f | wc -l) files)"
else
  fail "$step: the cities differ (diff -r --exclude=staging)"
  head -n 20 "$work/diff-all.txt" | sed 's/^/  | /'
fi
if [ -e "$B/staging" ]; then
  note "B/staging/ is still there after the merge ($(find "$B/staging" -type f | wc -l) files); the comparison leaves it aside"
else
  note "B/staging/ is gone after the merge"
fi

# --- (d) A catalogue of two scenarios: one array, a merge per scenario -------------------------
# C through Slurm (submit-catalogue.sh), D on one machine; a smaller city than A's: two scenarios.
step="(d) catalogue"
C="$work/C"
D="$work/D"
catalogue_dir="$work/catalogue"
catalogue="$catalogue_dir/catalogue.json"
names=("M6.6 under Lower Manhattan" "M5.0 to the north-east, by day")
catalogue_ok=1
note "$step: making a city of 2,000 buildings (synth-city --seed 22) and a catalogue of 2 scenarios"
mkdir -p "$catalogue_dir"
if ! cp "$root/tests/e2e/data/districts.geojson" "$catalogue_dir/districts.geojson"; then
  fail "$step: cannot copy tests/e2e/data/districts.geojson"
  catalogue_ok=0
fi
cat >"$catalogue" <<CATALOGUE
{"options": {"synthetic": [7], "time-of-day": "night", "districts": "districts.geojson"},
 "scenarios": [
  {"name": "${names[0]}", "epicentre": "-74.005,40.705,8", "magnitude": 6.6},
  {"name": "${names[1]}", "epicentre": "-73.99,40.72,8", "magnitude": 5.0, "time-of-day": "day"}]}
CATALOGUE
if ! "$prep" synth-city --buildings 2000 --seed 22 --max-leaf-buildings 300 --out "$C" >"$work/synth-C.log" 2>&1; then
  show "$work/synth-C.log"
  fail "$step: quakeview-prep synth-city failed"
  catalogue_ok=0
fi
cp -a "$C" "$D"
if list=$("$prep" response --catalogue "$catalogue" --list 2>"$work/list.err") &&
  [ "$list" = "$(printf '1\t%s\n2\t%s' "${names[0]}" "${names[1]}")" ]; then
  pass "$step: quakeview-prep response --catalogue --list names both scenarios"
else
  fail "$step: quakeview-prep response --catalogue --list: '${list:-}' (expected the 2 scenarios)"
  show "$work/list.err"
  catalogue_ok=0
fi

# The array's tasks are scenario I's part K at index (I-1)*2 + K-1.
check_catalogue_task() { # ARRAY T
  local array=$1 t=$2 line state exit_code nodes log scenario part
  scenario=$((t / 2 + 1))
  part=$((t % 2 + 1))
  line=$(job_lines "${array}_$t")
  state=$(printf '%s\n' "$line" | field JobState)
  exit_code=$(printf '%s\n' "$line" | field ExitCode)
  nodes=$(printf '%s\n' "$line" | field NodeList)
  log="$work/logs/qv-catalogue-${array}_$t.out"
  if [ "$state" = COMPLETED ] && [ "$nodes" = "$node" ] &&
    grep -q "^\[quakeview\] scenario $scenario part $part/2 of .* on $node" "$log" 2>/dev/null; then
    pass "$step: array task ${array}_$t ran scenario $scenario part $part/2 on $node: $state (exit $exit_code)"
  else
    fail "$step: array task ${array}_$t (scenario $scenario part $part/2) is '${state:-unknown}' (exit ${exit_code:-?}) on '${nodes:-?}', expected COMPLETED on $node"
    show "$log"
  fi
}
# The folder a manifest's response is in (every file it names is in that one folder).
folder_of() { grep -o '"response-[0-9]*/' "$1" 2>/dev/null | sort -u | tr -d '"/'; }

merges=()
if [ "$catalogue_ok" -eq 1 ]; then
  note "$step: submitting"
  if ids=$(QUAKEVIEW_PREP="$prep" QUAKEVIEW_SLURM_LOGS="$work/logs" bash "$slurm_scripts/submit-catalogue.sh" "$C" 2 "$catalogue" 2>"$work/submit.err"); then
    sed 's/^/  /' "$work/submit.err" >&2
    array=$(printf '%s\n' "$ids" | field array)
    IFS=, read -r -a merges <<<"$(printf '%s\n' "$ids" | field merges)"
    if [[ "$array" =~ ^[0-9]+$ ]] && [ "${#merges[@]}" -eq 2 ]; then
      pass "$step: submitted ($ids)"
    else
      fail "$step: submit-catalogue.sh printed '$ids', expected array=<id> merges=<id>,<id>"
      catalogue_ok=0
    fi
  else
    sed 's/^/  /' "$work/submit.err" >&2
    fail "$step: submit-catalogue.sh failed"
    catalogue_ok=0
  fi
fi
if [ "$catalogue_ok" -eq 1 ]; then
  # Each merge waits on its own scenario's tasks only: Slurm's record, read at once (a task's
  # entry leaves the list when it has succeeded, so a list may be shorter, never another's).
  for i in 0 1; do
    want=$(printf '%s_%s\n' "$array" $((2 * i)) "$array" $((2 * i + 1)))
    got=$(job_field "${merges[$i]}" Dependency | tr ',' '\n' | sed -nE 's/^afterok:([0-9]+_[0-9]+)\(.*/\1/p')
    if [ -n "$got" ] && [ -z "$(comm -13 <(printf '%s\n' "$want" | sort) <(printf '%s\n' "$got" | sort))" ]; then
      pass "$step: scenario $((i + 1))'s merge ${merges[$i]} depends on its own tasks only: $(printf '%s' "$got" | paste -sd' ' -) (afterok)"
    else
      fail "$step: scenario $((i + 1))'s merge ${merges[$i]} depends on '$(job_field "${merges[$i]}" Dependency)', expected afterok on $(printf '%s' "$want" | paste -sd' ' -)"
    fi
  done
  if wait_jobs "$array" "${merges[@]}"; then
    for t in 0 1 2 3; do check_catalogue_task "$array" "$t"; done
    for i in 0 1; do
      check_merge "${merges[$i]}" COMPLETED "$step, scenario $((i + 1))"
      log="$work/logs/qv-catalogue-merge-$((i + 1))-${merges[$i]}.out"
      if grep -q "^\[quakeview\] merge of scenario $((i + 1)) of .* on $node" "$log" 2>/dev/null; then
        pass "$step: the merge's output file shows it merged scenario $((i + 1)) on $node"
      else
        fail "$step: the output file of scenario $((i + 1))'s merge does not show it ran"
        show "$log"
      fi
    done
  else
    fail "$step: the jobs did not end within ${wait_limit}s"
    timeout 10 squeue | sed 's/^/  | /'
    catalogue_ok=0
  fi
fi
if [ "$catalogue_ok" -eq 1 ]; then
  missing=
  for f in scenario-1.json scenario-2.json tileset.json scenarios.json; do [ -f "$C/$f" ] || missing+=" $f"; done
  if [ -z "$missing" ]; then
    pass "$step: C has scenario-1.json, scenario-2.json, tileset.json and scenarios.json"
  else
    fail "$step: C lacks$missing"
  fi
  if grep -qF "\"${names[0]}\"" "$C/scenarios.json" 2>/dev/null && grep -qF "\"${names[1]}\"" "$C/scenarios.json"; then
    pass "$step: scenarios.json lists both: $(cat "$C/scenarios.json")"
  else
    fail "$step: scenarios.json does not list both scenarios' names"
    show "$C/scenarios.json"
  fi
  if cmp -s "$C/tileset.json" "$C/scenario-1.json"; then
    pass "$step: tileset.json is scenario-1.json (byte for byte)"
  else
    fail "$step: tileset.json differs from scenario-1.json"
  fi
  if [ -e "$C/staging" ]; then
    fail "$step: C/staging/ is still there after both merges: $(find "$C/staging" | head -n 5 | paste -sd' ' -)"
  else
    pass "$step: C/staging/ is gone after both merges"
  fi
  folder1=$(folder_of "$C/scenario-1.json")
  folder2=$(folder_of "$C/scenario-2.json")
  if [[ "$folder1" =~ ^response-[0-9]+$ ]] && [[ "$folder2" =~ ^response-[0-9]+$ ]] && [ "$folder1" != "$folder2" ]; then
    pass "$step: each scenario in its own folder: scenario 1 $folder1, scenario 2 $folder2"
  else
    fail "$step: the scenarios' folders are '$folder1' and '$folder2': expected one folder each, not the same"
    catalogue_ok=0
  fi
fi
if [ "$catalogue_ok" -eq 1 ]; then
  # D, one machine: each scenario takes the next free folder number, so the scenarios run in the
  # order C's merges numbered them (1 then 2, unless the merges raced the other way).
  order=(1 2)
  if [ "${folder2#response-}" -lt "${folder1#response-}" ]; then
    order=(2 1)
    note "$step: C's merges published scenario 2 first ($folder2, scenario 1 $folder1): D runs scenario 2 first"
  fi
  for s in "${order[@]}"; do
    t0=$(date +%s)
    if "$prep" response --city "$D" --catalogue "$catalogue" --scenario "$s" >"$work/one-machine-D-$s.log" 2>&1; then
      pass "$step: one-machine run of scenario $s on D in $(($(date +%s) - t0))s"
    else
      show "$work/one-machine-D-$s.log"
      fail "$step: one-machine run of scenario $s on D failed: $prep response --city $D --catalogue $catalogue --scenario $s"
    fi
  done
  for f in scenario-1.json scenario-2.json tileset.json scenarios.json; do
    if cmp "$D/$f" "$C/$f"; then
      pass "$step: $f identical (one machine and Slurm)"
    else
      fail "$step: $f differs between D (one machine) and C (Slurm)"
    fi
  done
  for s in 1 2; do
    d=$(folder_of "$C/scenario-$s.json")
    n_files=$(find "$D/$d" -type f 2>/dev/null | wc -l)
    if [ "$(folder_of "$D/scenario-$s.json")" = "$d" ] && [ -d "$D/$d" ] && diff -r "$D/$d" "$C/$d" >"$work/diff-C-$d.txt" 2>&1; then
      pass "$step: scenario $s's $d identical ($n_files files)"
    else
      fail "$step: scenario $s's $d differs or is missing (D's scenario-$s.json shows $(folder_of "$D/scenario-$s.json"))"
      head -n 10 "$work/diff-C-$d.txt" | sed 's/^/  | /'
    fi
  done
  if diff -r "$D" "$C" >"$work/diff-C-all.txt" 2>&1; then
    pass "$step: the whole city identical (diff -r; $(find "$C" -type f | wc -l) files)"
  else
    fail "$step: the cities differ (diff -r D C)"
    head -n 20 "$work/diff-C-all.txt" | sed 's/^/  | /'
  fi
fi

finish
