#!/usr/bin/env bash
# Submits a city's earthquake response to Slurm as N parts (a job array) and a merge that runs when
# every part has succeeded, then exits. Prints one machine-readable line on stdout:
#
#   array=<array job id> merge=<merge job id>
#
# Usage:
#   scripts/slurm/submit-response.sh [--parts K,K,...] CITY_DIR N [response options...]
#   scripts/slurm/submit-response.sh --merge-only CITY_DIR N
#
#   CITY_DIR   a city prepared by quakeview-prep (CITY_DIR/tileset.json must exist)
#   N          how many parts (array tasks); each analyses about 1/N of the buildings
#   options    exactly those of a one-machine `quakeview-prep response` run, without --city,
#              --threads, --shard or --merge (the script adds them), e.g.
#              --synthetic 7 8 --epicentre -74.005,40.705,8 --magnitude 6.6
#
# Task K (1..N) runs `quakeview-prep response --city CITY_DIR <options> --threads C --shard K/N`,
# which writes its part into CITY_DIR/staging/. The merge job (`--dependency=afterok:<array>`,
# `--kill-on-invalid-dep=yes`) runs `quakeview-prep response --city CITY_DIR --merge`, which checks
# that all N parts are there, complete and from the same run, and only then publishes the response
# (CITY_DIR/response-<n>/ and CITY_DIR/tileset.json, rewritten atomically). The published result is
# byte-identical to a one-machine run with the same options.
#
# Re-running a failed part: when a part fails (a node lost, a time limit, a data error), Slurm
# cancels the merge (its dependency can never be met) and the city is left as it was. Read the
# part's log, fix the cause, and submit that part again with the same options; its merge follows:
#
#   scripts/slurm/submit-response.sh --parts 3 CITY_DIR 4 <the same options>
#   (or QUAKEVIEW_SLURM_PARTS=3 scripts/slurm/submit-response.sh CITY_DIR 4 <the same options>)
#
# The parts that succeeded are kept in CITY_DIR/staging/ and are not run again. If the merge itself
# was cancelled or failed while every part is in place, `--merge-only CITY_DIR N` submits the merge
# alone (printing `merge=<id>`). A merge that finds a part missing, incomplete or from another run
# refuses with a message naming it (e.g. "part 3 of 4 is missing"), exits 1 and publishes nothing.
#
# Shared storage: the tasks run on any node of the partition, so CITY_DIR, the quakeview-prep
# binary, every input file named in the options (give them as absolute paths, or submit from a
# folder every node sees: the jobs start in the submission folder) and the log folder must be on a
# filesystem that every node mounts at the same path (NFS, Lustre, BeeGFS, GPFS...). The merge
# publishes by renaming files inside CITY_DIR, so that filesystem must offer POSIX rename; an
# object store mounted as a filesystem (s3fs, gcsfuse, Mountpoint for S3) may not: see
# docs/cluster.md.
#
# Cores and memory per task:
#   --cpus-per-task  QUAKEVIEW_SLURM_CPUS (default 2); passed on as `--threads $SLURM_CPUS_PER_TASK`.
#   --mem            QUAKEVIEW_SLURM_MEM (default 2G). A part's memory grows with the buildings of
#                    its part, not with the city's, and hardly with the record suite. Measured
#                    (clang release build, /usr/bin/time -v, maximum resident set size;
#                    synth-city --seed 21, --synthetic 7 8 --epicentre -74.005,40.705,8
#                    --magnitude 6.6, --threads 2):
#                      part 1 of 4 of 4,000 buildings (1,000 in the part):     47 MB
#                      part 1 of 4 of 20,000 buildings (5,001 in the part):    72 MB
#                      part 1 of 20 of 100,000 buildings (about 5,000):        74 MB
#                      parts of 5 of 50,000 buildings (about 10,000 each):  77-99 MB
#                    (a whole run of 20,000 buildings on one machine: 108 MB; 8 records instead
#                    of 2: no more), about 45 MB plus 5 KB a building of the part. With a margin
#                    (64 MB plus 8 KB a building), 2G covers parts of up to about 250,000
#                    buildings; the script warns when the city's parts are bigger than that
#                    margin allows in QUAKEVIEW_SLURM_MEM.
#   The merge job: 1 core, QUAKEVIEW_SLURM_MERGE_MEM. The merge holds every building's results:
#                    36 MB for 4,000 buildings, 117 MB for 20,000, 244 MB for 50,000 (about 20 MB
#                    plus 5 KB a building of the city). Default: 256 MB plus 8 KB a building of
#                    the city (its tileset.json's count), at least 1G: 1G up to about 98,000
#                    buildings, 7.9G for a million; 2G when the count cannot be read.
#
# Other settings (environment):
#   QUAKEVIEW_PREP             the quakeview-prep binary (default: the one on PATH); the same path
#                              must work on every node
#   QUAKEVIEW_SLURM_PARTITION  --partition (default: the cluster's default partition)
#   QUAKEVIEW_SLURM_ACCOUNT    --account
#   QUAKEVIEW_SLURM_TIME       --time for each part, e.g. 2:00:00 (default: the partition's)
#   QUAKEVIEW_SLURM_MERGE_TIME --time for the merge (default: QUAKEVIEW_SLURM_TIME)
#   QUAKEVIEW_SLURM_MAX_RUNNING at most this many parts at once (the array's %M throttle)
#   QUAKEVIEW_SLURM_LOGS       the folder for the jobs' output (default: CITY_DIR's sibling
#                              <CITY_DIR>-slurm-logs/; not inside the city, which is published as is)
#   QUAKEVIEW_SLURM_JOB_NAME   job name prefix (default qv-response; the merge is <name>-merge)
#   QUAKEVIEW_SLURM_SBATCH_ARGS extra sbatch options for both jobs, split on spaces
#                              (e.g. "--qos=normal --constraint=avx2")
#
# Logs: <logs>/<name>-<array id>_<K>.out for part K, <logs>/<name>-merge-<job id>.out for the merge.
# Exit status: 0 when submitted, 1 when sbatch refused or failed, 2 on a usage error.
set -euo pipefail

prog="submit-response.sh"
usage_error() {
  printf '%s: %s\n' "$prog" "$*" >&2
  printf 'usage: %s [--parts K,K,...] CITY_DIR N [response options...]\n       %s --merge-only CITY_DIR N\n' "$0" "$0" >&2
  printf '(the header of %s explains every option and setting)\n' "$0" >&2
  exit 2
}
# shellcheck source=SCRIPTDIR/lib.sh
. "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || { printf '%s: error: %s\n' "$prog" "lib.sh is missing beside $0" >&2; exit 1; }

parts_spec=${QUAKEVIEW_SLURM_PARTS:-}
merge_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --parts) [ $# -ge 2 ] || usage_error "--parts needs a list such as 3 or 1,3"; parts_spec=$2; shift 2 ;;
    --parts=*) parts_spec=${1#--parts=}; shift ;;
    --merge-only) merge_only=1; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    -*) usage_error "unknown option '$1' before CITY_DIR (response options go after CITY_DIR N)" ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || usage_error "CITY_DIR and N are required"
city_arg=$1
n=$2
shift 2
response_options=("$@")

qv_check_parts_count "$n"
qv_need_sbatch
qv_city "$city_arg"

if [ "$merge_only" -eq 1 ]; then
  [ "${#response_options[@]}" -eq 0 ] || usage_error "--merge-only takes CITY_DIR N only (the parts recorded their options)"
  [ -z "$parts_spec" ] || usage_error "--merge-only and --parts do not go together"
fi
for option in "${response_options[@]}"; do
  case "$option" in
    --city | --city=*) usage_error "give the city as CITY_DIR, not --city" ;;
    --shard | --shard=* | --merge) usage_error "$option is added by this script (one --shard K/N per task, --merge in the merge job)" ;;
    --threads | --threads=*) usage_error "--threads is set from the cores per task: use QUAKEVIEW_SLURM_CPUS" ;;
  esac
done

# The parts to run: all of them, or the list given.
if [ -n "$parts_spec" ]; then
  qv_parse_list "$parts_spec" --parts part "$n"
  array_spec=$(printf '%s\n' "${qv_list[@]}" | paste -sd, -)
else
  array_spec="1-$n"
fi

# The array's largest index must be below the cluster's MaxArraySize.
max_array=$(qv_max_array_size)
if [ -n "$max_array" ] && [ "$n" -ge "$max_array" ]; then
  die "N=$n parts: this cluster's MaxArraySize is $max_array, so at most $((max_array - 1)) parts"
fi

qv_find_prep
qv_resources "$n" "$merge_only"
qv_max_running
[ -z "$max_running" ] || array_spec="$array_spec%$max_running"
qv_name_and_logs qv-response
qv_sbatch_options

# The job scripts, every word quoted for bash (printf %q).
q_prep=$(printf '%q' "$prep")
q_city=$(printf '%q' "$city")
q_options=
if [ "${#response_options[@]}" -gt 0 ]; then q_options=$(printf ' %q' "${response_options[@]}"); fi

part_script=$(cat <<SCRIPT
#!/usr/bin/env bash
# A part of a QuakeView response, submitted by scripts/slurm/submit-response.sh.
set -uo pipefail
part="\${SLURM_ARRAY_TASK_ID:?not run as a Slurm array task}/$n"
threads="\${SLURM_CPUS_PER_TASK:-1}"
echo "[quakeview] part \$part of $q_city: job \${SLURM_JOB_ID} (array \${SLURM_ARRAY_JOB_ID}, task \${SLURM_ARRAY_TASK_ID}) on \$(hostname), \$threads cores, started \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
$q_prep response --city $q_city$q_options --threads "\$threads" --shard "\$part"
status=\$?
echo "[quakeview] part \$part finished with exit status \$status at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
exit \$status
SCRIPT
)

merge_script=$(cat <<SCRIPT
#!/usr/bin/env bash
# The merge of a QuakeView response's $n parts, submitted by scripts/slurm/submit-response.sh.
set -uo pipefail
echo "[quakeview] merge of $q_city ($n parts): job \${SLURM_JOB_ID} on \$(hostname), started \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
$q_prep response --city $q_city --merge --threads "\${SLURM_CPUS_PER_TASK:-1}"
status=\$?
echo "[quakeview] merge finished with exit status \$status at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
exit \$status
SCRIPT
)

merge_options=("${common[@]}" --job-name="$name-merge" --cpus-per-task=1 --mem="$merge_mem" "${merge_time[@]}"
  --output="$logs/$name-merge-%j.out")

if [ "$merge_only" -eq 1 ]; then
  merge_id=$(submit "${merge_options[@]}" <<<"$merge_script") || die "sbatch refused the merge job (its message is above)"
  info "merge of $n parts submitted: job $merge_id; log $logs/$name-merge-$merge_id.out"
  printf 'merge=%s\n' "$merge_id"
  exit 0
fi

array_id=$(submit "${common[@]}" --job-name="$name" --array="$array_spec" --cpus-per-task="$cpus" --mem="$mem" \
  "${part_time[@]}" --output="$logs/$name-%A_%a.out" <<<"$part_script") ||
  die "sbatch refused the job array (its message is above); nothing was submitted"
if ! merge_id=$(submit "${merge_options[@]}" --dependency="afterok:$array_id" --kill-on-invalid-dep=yes <<<"$merge_script"); then
  printf 'array=%s merge=\n' "$array_id"
  die "the parts were submitted (array job $array_id) but sbatch refused the merge (its message is above): when they have finished, run $0 --merge-only $city $n"
fi

what="parts $array_spec"
[[ "$array_spec" =~ ^[0-9]+(%[0-9]+)?$ ]] && what="part $array_spec"
cores="$cpus cores"
[ "$cpus" -ne 1 ] || cores="1 core"
info "$what of $n submitted as array job $array_id ($cores, $mem memory each); merge job $merge_id ($merge_mem) runs when all have succeeded"
info "watch: squeue -j $array_id,$merge_id    logs: $logs/$name-${array_id}_<K>.out, $logs/$name-merge-$merge_id.out"
printf 'array=%s merge=%s\n' "$array_id" "$merge_id"
