#!/usr/bin/env bash
# Submits every scenario of a catalogue (docs/cluster.md, "Many scenarios: a catalogue") to Slurm:
# ONE job array of S x N tasks (S scenarios, N parts each) and one merge job per scenario, each
# merge waiting only for its own scenario's tasks; then exits. Prints one machine-readable line:
#
#   array=<array job id> merges=<merge job id of scenario 1>,<of scenario 2>,...
#
# Usage:
#   scripts/slurm/submit-catalogue.sh [--scenarios I,J,...] [--parts K,K,...] CITY_DIR N CATALOGUE
#   scripts/slurm/submit-catalogue.sh [--scenarios I,J,...] --merge-only CITY_DIR N CATALOGUE
#
#   CITY_DIR   a city prepared by quakeview-prep (CITY_DIR/tileset.json must exist)
#   N          how many parts per scenario; each analyses about 1/N of the buildings
#   CATALOGUE  the catalogue (JSON); every scenario's options come from it, so no response options
#              are given here. The script reads its scenarios with
#              `quakeview-prep response --catalogue CATALOGUE --list` before submitting anything,
#              and stops with the tool's message when the catalogue is refused.
#
# Array task t (0 .. S*N-1) runs part K = t%N+1 of scenario I = t/N+1:
#   quakeview-prep response --city CITY_DIR --catalogue CATALOGUE --scenario I --threads C --shard K/N
# which writes it into CITY_DIR/staging/scenario-I/. Scenario I's merge job
# (`--dependency=afterok:<array>_<t>:<array>_<t'>...` on its own N tasks, `--kill-on-invalid-dep=yes`)
# runs `quakeview-prep response --city CITY_DIR --merge --scenario I`, which checks its parts and
# publishes response-<n>/, CITY_DIR/scenario-I.json (scenario 1 also tileset.json) and
# CITY_DIR/scenarios.json, byte-identical to a one-machine run of that scenario. A scenario whose
# parts are done is merged while the others still run; a part that fails cancels only its own
# scenario's merge (Slurm: DependencyNeverSatisfied), and the other scenarios are published.
#
# Options (or the environment variables QUAKEVIEW_SLURM_SCENARIOS, QUAKEVIEW_SLURM_PARTS):
#   --scenarios I,J   only these scenarios (numbers as --list prints them): their parts and merges
#   --parts K,K       only these parts (of every scenario, or of those of --scenarios), then their
#                     scenarios' merges: to run again parts that failed, e.g.
#                       scripts/slurm/submit-catalogue.sh --scenarios 2 --parts 3 CITY_DIR 4 CATALOGUE
#                     The parts that succeeded stay in CITY_DIR/staging/scenario-I/.
#   --merge-only      only the merges (of every scenario, or of those of --scenarios), without
#                     dependencies, when every part is in place but a merge was cancelled or failed
#                     for a reason of its own; prints `merges=<id>,...`
#
# A task's number stays its scenario's and part's whatever is submitted (scenario 2's part 3 of 4
# is always task 6), so scenario I of N parts needs I*N-1 below the cluster's MaxArraySize.
# Do not edit the catalogue while its jobs run: every task reads it when it starts (parts run with
# other options are refused by the merge).
#
# Cores, memory, time, partition, account, the quakeview-prep binary, the log folder and extra sbatch
# options are those of scripts/slurm/submit-response.sh (see its header and docs/cluster.md): the
# environment variables QUAKEVIEW_PREP, QUAKEVIEW_SLURM_CPUS, _MEM, _MERGE_MEM, _PARTITION,
# _ACCOUNT, _TIME, _MERGE_TIME, _MAX_RUNNING (a throttle on the whole array), _LOGS, _JOB_NAME
# (default here qv-catalogue), _SBATCH_ARGS. The catalogue, like the city, the binary and every file
# the catalogue names, must be on storage every node mounts at the same path.
#
# Logs: <logs>/<name>-<array id>_<t>.out for task t (its first line names the scenario and part),
# <logs>/<name>-merge-<I>-<job id>.out for scenario I's merge.
# Exit status: 0 when submitted, 1 when sbatch refused or failed (or the catalogue was refused),
# 2 on a usage error.
set -euo pipefail

prog="submit-catalogue.sh"
usage_error() {
  printf '%s: %s\n' "$prog" "$*" >&2
  printf 'usage: %s [--scenarios I,J,...] [--parts K,K,...] CITY_DIR N CATALOGUE\n       %s [--scenarios I,J,...] --merge-only CITY_DIR N CATALOGUE\n' "$0" "$0" >&2
  printf '(the header of %s explains every option and setting)\n' "$0" >&2
  exit 2
}
# shellcheck source=SCRIPTDIR/lib.sh
. "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || { printf '%s: error: %s\n' "$prog" "lib.sh is missing beside $0" >&2; exit 1; }

scenarios_spec=${QUAKEVIEW_SLURM_SCENARIOS:-}
parts_spec=${QUAKEVIEW_SLURM_PARTS:-}
merge_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --scenarios) [ $# -ge 2 ] || usage_error "--scenarios needs a list such as 2 or 1,3"; scenarios_spec=$2; shift 2 ;;
    --scenarios=*) scenarios_spec=${1#--scenarios=}; shift ;;
    --parts) [ $# -ge 2 ] || usage_error "--parts needs a list such as 3 or 1,3"; parts_spec=$2; shift 2 ;;
    --parts=*) parts_spec=${1#--parts=}; shift ;;
    --merge-only) merge_only=1; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    -*) usage_error "unknown option '$1' (options go before CITY_DIR N CATALOGUE)" ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || usage_error "CITY_DIR, N and CATALOGUE are required"
[ $# -eq 3 ] || usage_error "unexpected '$4' after CATALOGUE: every scenario's response options come from the catalogue"
city_arg=$1
n=$2
catalogue_arg=$3

qv_check_parts_count "$n"
if [ "$merge_only" -eq 1 ] && [ -n "$parts_spec" ]; then usage_error "--merge-only and --parts do not go together"; fi
qv_need_sbatch
qv_city "$city_arg"
[ ! -d "$catalogue_arg" ] || die "catalogue '$catalogue_arg' is a folder, not a catalogue file"
[ -f "$catalogue_arg" ] || die "catalogue '$catalogue_arg' does not exist"
[ -r "$catalogue_arg" ] || die "catalogue '$catalogue_arg' cannot be read"
catalogue=$(cd "$(dirname "$catalogue_arg")" && pwd)/$(basename "$catalogue_arg")
qv_find_prep

# The catalogue's scenarios, as the tool reads them ("I<TAB>name" a line); its message when refused.
if ! listing=$("$prep" response --catalogue "$catalogue" --list); then
  die "quakeview-prep refused the catalogue '$catalogue_arg' (its message is above); nothing was submitted"
fi
scenario_names=()
while IFS= read -r line; do
  [ -n "$line" ] || continue
  index=${line%%$'\t'*}
  [ "$index" = "$((${#scenario_names[@]} + 1))" ] ||
    die "unexpected line from '$prep response --catalogue $catalogue --list': '$line' (expected scenario $((${#scenario_names[@]} + 1)))"
  scenario_names+=("${line#*$'\t'}")
done <<<"$listing"
s_count=${#scenario_names[@]}
[ "$s_count" -gt 0 ] || die "'$prep response --catalogue $catalogue --list' listed no scenario"

# The scenarios and parts to submit.
if [ -n "$scenarios_spec" ]; then
  qv_parse_list "$scenarios_spec" --scenarios scenario "$s_count"
  scenarios=("${qv_list[@]}")
else
  mapfile -t scenarios < <(seq 1 "$s_count")
fi
if [ -n "$parts_spec" ]; then
  qv_parse_list "$parts_spec" --parts part "$n"
  parts=("${qv_list[@]}")
else
  mapfile -t parts < <(seq 1 "$n")
fi

# Every task's number must be below the cluster's MaxArraySize.
last_scenario=${scenarios[${#scenarios[@]} - 1]}
last_task=$((last_scenario * n - 1))
max_array=$(qv_max_array_size)
if [ "$merge_only" -eq 0 ] && [ -n "$max_array" ] && [ "$last_task" -ge "$max_array" ]; then
  fit=$((max_array / n))
  [ "$fit" -gt 0 ] || die "N=$n parts: this cluster's MaxArraySize is $max_array, so at most $max_array parts a scenario"
  fit="scenarios 1 to $fit fit"
  [ "$fit" != "scenarios 1 to 1 fit" ] || fit="only scenario 1 fits"
  die "scenario $last_scenario of N=$n parts runs as array tasks up to $last_task, but this cluster's MaxArraySize is $max_array (tasks 0 to $((max_array - 1))): with $n parts, $fit; use fewer parts, split the catalogue, or ask for a larger MaxArraySize"
fi

qv_resources "$n" "$merge_only"
qv_max_running
qv_name_and_logs qv-catalogue
qv_sbatch_options

# The array's tasks (scenario I's part K is task (I-1)*N + K-1), as Slurm ranges (0-3,6-7), and
# per scenario its tasks' dependency list.
tasks=()
declare -A dependency=()
for s in "${scenarios[@]}"; do
  dependency[$s]=
  for k in "${parts[@]}"; do
    t=$(((s - 1) * n + k - 1))
    tasks+=("$t")
    dependency[$s]+=":<array>_$t"
  done
done
array_spec=
range_start=
previous=
for t in "${tasks[@]}" end; do
  if [ -n "$previous" ] && [ "$t" != end ] && [ "$t" -eq $((previous + 1)) ]; then
    previous=$t
    continue
  fi
  if [ -n "$range_start" ]; then
    [ -z "$array_spec" ] || array_spec+=,
    if [ "$range_start" -eq "$previous" ]; then array_spec+=$range_start; else array_spec+="$range_start-$previous"; fi
  fi
  range_start=$t
  previous=$t
done
array_tasks=$array_spec
[ -z "$max_running" ] || array_spec="$array_spec%$max_running"

# The job scripts, every word quoted for bash (printf %q).
q_prep=$(printf '%q' "$prep")
q_city=$(printf '%q' "$city")
q_catalogue=$(printf '%q' "$catalogue")

part_script=$(cat <<SCRIPT
#!/usr/bin/env bash
# A part of a scenario of a QuakeView catalogue, submitted by scripts/slurm/submit-catalogue.sh.
set -uo pipefail
task="\${SLURM_ARRAY_TASK_ID:?not run as a Slurm array task}"
scenario=\$((task / $n + 1))
part="\$((task % $n + 1))/$n"
threads="\${SLURM_CPUS_PER_TASK:-1}"
echo "[quakeview] scenario \$scenario part \$part of $q_city (catalogue $q_catalogue): job \${SLURM_JOB_ID} (array \${SLURM_ARRAY_JOB_ID}, task \$task) on \$(hostname), \$threads cores, started \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
$q_prep response --city $q_city --catalogue $q_catalogue --scenario "\$scenario" --threads "\$threads" --shard "\$part"
status=\$?
echo "[quakeview] scenario \$scenario part \$part finished with exit status \$status at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
exit \$status
SCRIPT
)

merge_script() { # SCENARIO
  cat <<SCRIPT
#!/usr/bin/env bash
# The merge of scenario $1's $n parts of a QuakeView catalogue, submitted by scripts/slurm/submit-catalogue.sh.
set -uo pipefail
echo "[quakeview] merge of scenario $1 of $q_city ($n parts): job \${SLURM_JOB_ID} on \$(hostname), started \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
$q_prep response --city $q_city --merge --scenario $1 --threads "\${SLURM_CPUS_PER_TASK:-1}"
status=\$?
echo "[quakeview] merge of scenario $1 finished with exit status \$status at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
exit \$status
SCRIPT
}
merge_options() { # SCENARIO
  printf '%s\n' "${common[@]}" --job-name="$name-merge-$1" --cpus-per-task=1 --mem="$merge_mem" "${merge_time[@]}" \
    --output="$logs/$name-merge-$1-%j.out"
}

# Submits the merges of the scenarios named (after the array ARRAY_ID, or alone when it is empty);
# on a refusal prints the machine-readable line so far and stops with what to run.
merge_ids=()
submit_merges() {
  local array_id=$1 s id left
  local -a options
  for s in "${scenarios[@]}"; do
    mapfile -t options < <(merge_options "$s")
    [ -z "$array_id" ] || options+=("--dependency=afterok${dependency[$s]//<array>/$array_id}" --kill-on-invalid-dep=yes)
    if ! id=$(submit "${options[@]}" <<<"$(merge_script "$s")"); then
      left=$(printf '%s\n' "${scenarios[@]}" | awk -v s="$s" '$1 >= s' | paste -sd, -)
      case "$left" in *,*) left="scenarios $left" ;; *) left="scenario $left" ;; esac
      if [ -n "$array_id" ]; then
        printf 'array=%s merges=%s\n' "$array_id" "$(IFS=,; printf '%s' "${merge_ids[*]}")"
        local done_part="the parts (array job $array_id) were submitted"
        [ "${#merge_ids[@]}" -eq 0 ] || done_part="the parts (array job $array_id) and the merges before scenario $s's were submitted"
        die "$done_part, but sbatch refused scenario $s's merge (its message is above): when the parts of $left have finished, run $0 --scenarios ${left#* } --merge-only $city $n $catalogue"
      fi
      printf 'merges=%s\n' "$(IFS=,; printf '%s' "${merge_ids[*]}")"
      die "sbatch refused scenario $s's merge (its message is above): $left not submitted"
    fi
    merge_ids+=("$id")
  done
}

if [ "$merge_only" -eq 1 ]; then
  submit_merges ""
  for i in "${!scenarios[@]}"; do
    s=${scenarios[$i]}
    info "scenario $s (${scenario_names[$((s - 1))]}): merge job ${merge_ids[$i]}; log $logs/$name-merge-$s-${merge_ids[$i]}.out"
  done
  printf 'merges=%s\n' "$(IFS=,; printf '%s' "${merge_ids[*]}")"
  exit 0
fi

array_id=$(submit "${common[@]}" --job-name="$name" --array="$array_spec" --cpus-per-task="$cpus" --mem="$mem" \
  "${part_time[@]}" --output="$logs/$name-%A_%a.out" <<<"$part_script") ||
  die "sbatch refused the job array (its message is above); nothing was submitted"
submit_merges "$array_id"

cores="$cpus cores"
[ "$cpus" -ne 1 ] || cores="1 core"
what="${#parts[@]} parts"
[ "${#parts[@]}" -ne 1 ] || what="1 part"
[ "${#parts[@]}" -eq "$n" ] || what="$what ($(IFS=,; printf '%s' "${parts[*]}"))"
throttle=
[ -z "$max_running" ] || throttle=", at most $max_running at once"
case "$array_tasks" in *[-,]*) array_tasks="tasks $array_tasks" ;; *) array_tasks="task $array_tasks" ;; esac
info "${#scenarios[@]} of $s_count scenarios, $what of $n each: array job $array_id, $array_tasks ($cores, $mem memory each$throttle)"
for i in "${!scenarios[@]}"; do
  s=${scenarios[$i]}
  first=$(((s - 1) * n))
  its_tasks=${dependency[$s]//:<array>_/,}
  its_tasks=${its_tasks#,}
  [ "${#parts[@]}" -ne "$n" ] || [ "$n" -eq 1 ] || its_tasks="$first-$((first + n - 1))"
  case "$its_tasks" in *[-,]*) its_tasks="tasks $its_tasks" ;; *) its_tasks="task $its_tasks" ;; esac
  info "scenario $s (${scenario_names[$((s - 1))]}): $its_tasks, merge job ${merge_ids[$i]} ($merge_mem) when its tasks have succeeded"
done
info "watch: squeue -j $array_id,$(IFS=,; printf '%s' "${merge_ids[*]}")    logs: $logs/$name-${array_id}_<task>.out, $logs/$name-merge-<scenario>-<job>.out"
printf 'array=%s merges=%s\n' "$array_id" "$(IFS=,; printf '%s' "${merge_ids[*]}")"
