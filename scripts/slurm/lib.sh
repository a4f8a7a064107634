# shellcheck shell=bash
# shellcheck disable=SC2034,SC2154 # the variables are the caller's: it sets prog, and uses what these set
# Shell code shared by scripts/slurm/submit-response.sh and scripts/slurm/submit-catalogue.sh
# (sourced, not run). The caller sets `prog` (its name in messages) and defines
# `usage_error MESSAGE` (prints its usage and exits 2) before sourcing this file; the functions
# below set the caller's variables named in their comments. Every setting is read from the
# environment as the scripts' headers describe (QUAKEVIEW_PREP, QUAKEVIEW_SLURM_*).

die() { printf '%s: error: %s\n' "$prog" "$*" >&2; exit 1; }
info() { printf '%s: %s\n' "$prog" "$*" >&2; }

# N: a whole number of parts.
qv_check_parts_count() {
  case "$1" in '' | *[!0-9]* | 0*) usage_error "N must be a whole number of parts >= 1, not '$1'" ;; esac
  [ "${#1}" -le 6 ] || usage_error "N must be a whole number of parts >= 1, not '$1'"
}

qv_need_sbatch() {
  command -v sbatch >/dev/null 2>&1 ||
    die "sbatch not found: run this on a machine that submits to your Slurm cluster (a login node), or install Slurm's client commands (Debian: slurm-client)"
}

# CITY_ARG must be a prepared city; sets `city` to its absolute path (symlinks kept as named).
qv_city() {
  [ -d "$1" ] || die "city folder '$1' does not exist"
  [ -f "$1/tileset.json" ] ||
    die "'$1' is not a prepared city: $1/tileset.json is missing (make it with quakeview-prep city or synth-city)"
  city=$(cd "$1" && pwd)
}

# SPEC (numbers separated by commas) OPTION WHAT MAX: sets `qv_list` to its numbers (1..MAX), sorted,
# each once; a usage error names OPTION and WHAT ("part", "scenario") otherwise.
qv_parse_list() {
  local spec=$1 option=$2 what=$3 max=$4 k
  local -A seen=()
  local -a requested=()
  qv_list=()
  IFS=',' read -r -a requested <<<"$spec"
  [ "${#requested[@]}" -gt 0 ] || usage_error "$option needs a list such as 3 or 1,3"
  for k in "${requested[@]}"; do
    k=${k// /}
    case "$k" in '' | *[!0-9]* | 0*) usage_error "$option: '$k' is not a $what number (1 to $max)" ;; esac
    if [ "${#k}" -gt 6 ] || [ "$k" -gt "$max" ]; then usage_error "$option: $what $k does not exist (${what}s are 1 to $max)"; fi
    [ -n "${seen[$k]:-}" ] || qv_list+=("$k")
    seen[$k]=1
  done
  mapfile -t qv_list < <(printf '%s\n' "${qv_list[@]}" | sort -n)
}

# This cluster's MaxArraySize (array indices are 0 to MaxArraySize-1); empty when unknown.
qv_max_array_size() {
  local max_array=
  if command -v scontrol >/dev/null 2>&1; then
    max_array=$(timeout 10 scontrol show config 2>/dev/null | sed -nE 's/^MaxArraySize *= *([0-9]+).*/\1/p') || max_array=
  fi
  printf '%s\n' "$max_array"
}

# Sets `prep`: QUAKEVIEW_PREP or quakeview-prep on PATH, as an absolute path (the jobs run elsewhere).
qv_find_prep() {
  prep=${QUAKEVIEW_PREP:-}
  if [ -z "$prep" ]; then
    prep=$(command -v quakeview-prep 2>/dev/null) ||
      die "quakeview-prep not found: set QUAKEVIEW_PREP to its path (on shared storage) or put it on PATH"
  fi
  if [ ! -f "$prep" ] || [ ! -x "$prep" ]; then die "QUAKEVIEW_PREP '$prep' is not an executable file"; fi
  prep=$(cd "$(dirname "$prep")" && pwd)/$(basename "$prep")
}

# A Slurm size in MB (no suffix: MB, as sbatch reads it).
size_mb() {
  local v=${1%[KMGTkmgt]} unit=${1:${#1}-1}
  case "$unit" in
    K | k) echo $((v / 1024)) ;;
    G | g) echo $((v * 1024)) ;;
    T | t) echo $((v * 1024 * 1024)) ;;
    *) echo "$v" ;;
  esac
}

# N MERGE_ONLY(0|1): sets `cpus`, `buildings` (the city's count, empty when unreadable), `mem` (per
# part), `merge_mem`; warns when parts of the city split N ways may not fit in `mem`. Needs `city`.
qv_resources() {
  local n=$1 merge_only=$2 merge_mb m part_buildings part_need_mb
  cpus=${QUAKEVIEW_SLURM_CPUS:-2}
  case "$cpus" in '' | *[!0-9]* | 0*) die "QUAKEVIEW_SLURM_CPUS must be a whole number of cores >= 1, not '$cpus'" ;; esac
  [ "$cpus" -le 256 ] || die "QUAKEVIEW_SLURM_CPUS: at most 256 cores (quakeview-prep --threads), not $cpus"
  # The city's building count (tileset.json's top-level "buildings", first in the file), for the
  # memory estimates; empty when it cannot be read.
  buildings=$(grep -o -m 1 '"buildings": *[0-9][0-9]*' "$city/tileset.json" 2>/dev/null | head -n 1 | grep -o '[0-9][0-9]*$') ||
    buildings=
  mem=${QUAKEVIEW_SLURM_MEM:-2G}
  if [ -n "${QUAKEVIEW_SLURM_MERGE_MEM:-}" ]; then
    merge_mem=$QUAKEVIEW_SLURM_MERGE_MEM
  elif [ -n "$buildings" ]; then
    merge_mb=$((256 + buildings * 8 / 1024))
    [ "$merge_mb" -ge 1024 ] || merge_mb=1024
    merge_mem="${merge_mb}M"
  else
    merge_mem=2G
  fi
  for m in "$mem" "$merge_mem"; do
    [[ "$m" =~ ^[1-9][0-9]*[KMGTkmgt]?$ ]] || die "memory '$m' is not a Slurm size (e.g. 2G, 1500M): QUAKEVIEW_SLURM_MEM / QUAKEVIEW_SLURM_MERGE_MEM"
  done
  if [ -n "$buildings" ] && [ "$merge_only" -eq 0 ]; then
    part_buildings=$(((buildings + n - 1) / n))
    part_need_mb=$((64 + part_buildings * 8 / 1024))
    if [ "$part_need_mb" -gt "$(size_mb "$mem")" ]; then
      info "warning: parts of about $part_buildings buildings may need about ${part_need_mb}M each, more than QUAKEVIEW_SLURM_MEM=$mem: raise it or N"
    fi
  fi
}

# Sets `max_running`: the array's %M throttle from QUAKEVIEW_SLURM_MAX_RUNNING ("" when unset).
qv_max_running() {
  max_running=${QUAKEVIEW_SLURM_MAX_RUNNING:-}
  if [ -n "$max_running" ]; then
    case "$max_running" in *[!0-9]* | 0*) die "QUAKEVIEW_SLURM_MAX_RUNNING must be a whole number >= 1, not '$max_running'" ;; esac
  fi
}

# DEFAULT_NAME: sets `name` (QUAKEVIEW_SLURM_JOB_NAME or DEFAULT_NAME) and `logs` (QUAKEVIEW_SLURM_LOGS
# or the city's sibling <city>-slurm-logs/, created, absolute). Needs `city`.
qv_name_and_logs() {
  name=${QUAKEVIEW_SLURM_JOB_NAME:-$1}
  logs=${QUAKEVIEW_SLURM_LOGS:-$(dirname "$city")/$(basename "$city")-slurm-logs}
  mkdir -p "$logs" || die "cannot create the log folder '$logs' (QUAKEVIEW_SLURM_LOGS)"
  logs=$(cd "$logs" && pwd)
}

# Sets the sbatch options every job gets (`common`: --parsable --ntasks=1, partition, account, extra
# arguments) and the time limits (`part_time`, `merge_time`: empty or one --time=...).
qv_sbatch_options() {
  local -a extra=()
  common=(--parsable --ntasks=1)
  [ -z "${QUAKEVIEW_SLURM_PARTITION:-}" ] || common+=("--partition=$QUAKEVIEW_SLURM_PARTITION")
  [ -z "${QUAKEVIEW_SLURM_ACCOUNT:-}" ] || common+=("--account=$QUAKEVIEW_SLURM_ACCOUNT")
  if [ -n "${QUAKEVIEW_SLURM_SBATCH_ARGS:-}" ]; then
    read -r -a extra <<<"$QUAKEVIEW_SLURM_SBATCH_ARGS"
    common+=("${extra[@]}")
  fi
  part_time=()
  [ -z "${QUAKEVIEW_SLURM_TIME:-}" ] || part_time=("--time=$QUAKEVIEW_SLURM_TIME")
  merge_time=()
  if [ -n "${QUAKEVIEW_SLURM_MERGE_TIME:-${QUAKEVIEW_SLURM_TIME:-}}" ]; then
    merge_time=("--time=${QUAKEVIEW_SLURM_MERGE_TIME:-$QUAKEVIEW_SLURM_TIME}")
  fi
}

# sbatch ARGS... (the job script on stdin); prints the job id. sbatch --parsable prints "jobid" or
# "jobid;cluster".
submit() {
  local out
  out=$(sbatch "$@") || return 1
  out=${out%%;*}
  [[ "$out" =~ ^[0-9]+$ ]] || { printf '%s: sbatch printed "%s", not a job id\n' "$prog" "$out" >&2; return 1; }
  printf '%s\n' "$out"
}
