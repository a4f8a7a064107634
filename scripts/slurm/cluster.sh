#!/usr/bin/env bash
# A single-node Slurm cluster for tests, kept entirely in one folder.
#
#   scripts/slurm/cluster.sh start STATE_DIR    # prints: export SLURM_CONF=STATE_DIR/slurm.conf
#   scripts/slurm/cluster.sh status STATE_DIR
#   scripts/slurm/cluster.sh stop STATE_DIR
#
# start: makes the munge key if the machine has none (/etc/munge/munge.key), starts munged if no
# munged answers, writes STATE_DIR/slurm.conf (this machine as the only node, with the CPUs and
# memory `slurmd -C` reports, one partition "main"; controller state, slurmd spool, pid files and
# both daemons' logs all in STATE_DIR; munged logs to /var/log/munge/munged.log), starts slurmctld and slurmd, and waits until `sinfo` shows
# the node idle. Running it again while the cluster is up does nothing. Every wait has a time limit
# (QUAKEVIEW_SLURM_START_TIMEOUT, default 60 s); when one runs out the script stops what it
# started and prints the daemons' logs.
# stop: cancels the cluster's jobs, stops slurmd and slurmctld by their pid files (and munged when
# this script started it and no other Slurm daemon runs), and ends any job step left running from
# STATE_DIR's spool. Logs stay
# in STATE_DIR. Stopping a cluster that is not running does nothing.
#
# Needs Debian's slurm-wlm and munge (scripts/setup.sh installs them) and root: slurmd launches
# jobs, munged runs as the munge user. Verified with Slurm 22.05 on Debian 12 without systemd
# (../shared/TOOLCHAIN.md, "A single-node Slurm cluster for tests").
#
# Ports: slurmctld listens on QUAKEVIEW_SLURM_PORT (default 6817) and slurmd on the next one
# (6818), the Slurm defaults; set QUAKEVIEW_SLURM_PORT to run beside another Slurm. munged is the
# machine's (one per machine): a second cluster in another folder shares it, and stopping the
# cluster whose start launched munged leaves it running while any other slurmctld or slurmd runs.
set -euo pipefail

prog="cluster.sh"
log() { printf '[%s] %s\n' "$prog" "$*"; }
die() { printf '[%s] error: %s\n' "$prog" "$*" >&2; exit 1; }

usage() {
  cat >&2 <<USAGE
usage: $0 start|status|stop STATE_DIR
  start   start a single-node Slurm cluster whose configuration, state and logs are in STATE_DIR
  status  say whether its daemons are running and show sinfo
  stop    cancel its jobs and stop its daemons (and munged if start launched it)
USAGE
  exit 2
}

[ $# -eq 2 ] || usage
action=$1
case "$action" in start | stop | status) ;; *) usage ;; esac
[ -n "$2" ] || usage
if [ "$action" = start ]; then
  mkdir -p "$2" 2>/dev/null || die "cannot create the state folder '$2'"
elif [ ! -d "$2" ]; then
  log "not running ($2 does not exist)"
  exit 0
fi
state_dir=$(cd "$2" && pwd -P)
case "$state_dir" in *[[:space:]]* | *'#'*) die "the state folder's path '$state_dir' has a space or '#', which slurm.conf cannot hold" ;; esac

timeout_s=${QUAKEVIEW_SLURM_START_TIMEOUT:-60}
case "$timeout_s" in '' | *[!0-9]*) die "QUAKEVIEW_SLURM_START_TIMEOUT must be whole seconds, not '$timeout_s'" ;; esac
ctld_port=${QUAKEVIEW_SLURM_PORT:-6817}
case "$ctld_port" in '' | *[!0-9]*) die "QUAKEVIEW_SLURM_PORT must be a port number, not '$ctld_port'" ;; esac
slurmd_port=$((ctld_port + 1))

conf="$state_dir/slurm.conf"
ctld_pidfile="$state_dir/slurmctld.pid"
slurmd_pidfile="$state_dir/slurmd.pid"
# Written only when this script launched munged: its pid. Machine-wide (munged is), so that the
# last cluster to stop stops it, whichever cluster started it.
munged_marker=/run/munge/munged.started-by-quakeview-cluster
munged_log=/var/log/munge/munged.log
export SLURM_CONF="$conf"

# The pid in FILE if that process is alive and is NAME (a recycled pid is not ours).
live_pid() {
  local file=$1 name=$2 pid comm
  [ -s "$file" ] || return 1
  pid=$(tr -dc '0-9' <"$file")
  [ -n "$pid" ] || return 1
  comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
  [ "$comm" = "$name" ] || return 1
  printf '%s\n' "$pid"
}

# Sends TERM, waits up to SECONDS for the process to end, then KILL.
end_process() {
  local pid=$1 name=$2 seconds=${3:-15} i
  kill -TERM "$pid" 2>/dev/null || return 0
  for ((i = 0; i < seconds * 5; i++)); do
    [ -d "/proc/$pid" ] || { log "stopped $name (pid $pid)"; return 0; }
    # A zombie has ended; its parent (not us) reaps it.
    [ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)" = Z ] && { log "stopped $name (pid $pid)"; return 0; }
    sleep 0.2
  done
  log "$name (pid $pid) did not stop in ${seconds}s: killing it"
  kill -KILL "$pid" 2>/dev/null || true
}

# Whether a slurmctld or slurmd other than a zombie runs on this machine.
other_slurm_daemons() {
  local pid
  for pid in $(pgrep -x 'slurmctld|slurmd' 2>/dev/null); do
    [ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)" = Z ] || return 0
  done
  return 1
}

munge_works() { timeout 5 munge -n 2>/dev/null | timeout 5 unmunge >/dev/null 2>&1; }

show_logs() {
  local f
  for f in "$state_dir/slurmctld.log" "$state_dir/slurmd.log" "$munged_log"; do
    [ -s "$f" ] || continue
    printf '%s\n' "---- last lines of $f ----" >&2
    tail -n 25 "$f" >&2
  done
}

node_name() { hostname -s; }

# The node's state as sinfo reports it ("idle", "down*", ...), empty when the controller does not answer.
node_state() { timeout 5 sinfo -h -N -n "$(node_name)" -o '%T' 2>/dev/null | head -n 1; }

stop_cluster() {
  local pid jobs i stepd fd
  if pid=$(live_pid "$ctld_pidfile" slurmctld); then
    # Jobs first, so no job step outlives its slurmd.
    jobs=$(timeout 5 squeue -h -o '%A' 2>/dev/null | sort -u | tr '\n' ' ') || jobs=
    if [ -n "${jobs// /}" ]; then
      log "cancelling jobs: $jobs"
      # shellcheck disable=SC2086 # a list of job ids
      timeout 10 scancel $jobs 2>/dev/null || true
      for ((i = 0; i < 50; i++)); do
        [ -z "$(timeout 5 squeue -h -o '%A' 2>/dev/null)" ] && break
        sleep 0.2
      done
    fi
  fi
  if pid=$(live_pid "$slurmd_pidfile" slurmd); then end_process "$pid" slurmd; fi
  if pid=$(live_pid "$ctld_pidfile" slurmctld); then end_process "$pid" slurmctld; fi
  # A job step (slurmstepd) of this cluster keeps its socket in our spool folder.
  for stepd in /proc/[0-9]*; do
    [ "$(cat "$stepd/comm" 2>/dev/null)" = slurmstepd ] || continue
    for fd in "$stepd"/fd/*; do
      case "$(readlink "$fd" 2>/dev/null)" in
        "$state_dir"/*) end_process "${stepd#/proc/}" slurmstepd 5; break ;;
      esac
    done
  done
  if [ -f "$munged_marker" ]; then
    if pid=$(live_pid "$munged_marker" munged); then
      # Another Slurm on this machine (a second test cluster) still needs it.
      if other_slurm_daemons; then
        log "leaving munged (pid $pid) running: another Slurm daemon on this machine uses it"
        return 0
      fi
      end_process "$pid" munged
    fi
    rm -f "$munged_marker"
  fi
  rm -f "$ctld_pidfile" "$slurmd_pidfile"
}

port_in_use() {
  command -v ss >/dev/null 2>&1 || return 1
  [ -n "$(ss -Hltn "sport = :$1" 2>/dev/null)" ]
}

start_munged() {
  if munge_works; then
    log "munged already running"
    return 0
  fi
  if [ ! -s /etc/munge/munge.key ]; then
    log "creating the munge key /etc/munge/munge.key"
    mungekey --create >/dev/null || die "mungekey --create failed (are you root?)"
    chown munge:munge /etc/munge/munge.key 2>/dev/null || true
    chmod 0400 /etc/munge/munge.key
  fi
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null || true
  log "starting munged"
  # munged forks into the background and writes /run/munge/munged.pid. --force: a socket left by
  # a munged that was killed would otherwise stop it (no munged answered above, so none is live).
  # Its log is the machine's (/var/log/munge/munged.log): munged is shared, and the munge user may
  # not be able to reach STATE_DIR.
  if id munge >/dev/null 2>&1; then
    runuser -u munge -- /usr/sbin/munged --force || { show_logs; die "munged did not start"; }
  else
    /usr/sbin/munged --force || { show_logs; die "munged did not start"; }
  fi
  local i
  for ((i = 0; i <= timeout_s * 5; i++)); do
    [ -f "$munged_marker" ] || cp /run/munge/munged.pid "$munged_marker" 2>/dev/null || true
    if munge_works; then
      [ -s "$munged_marker" ] || pgrep -x -n munged >"$munged_marker" || true
      return 0
    fi
    sleep 0.2
  done
  show_logs
  stop_cluster >&2
  die "munged started but 'munge -n | unmunge' still fails after ${timeout_s}s"
}

write_conf() {
  local node hw cpus=0 mem=0 boards sockets cores threads
  node=$(node_name)
  # slurmd -C: "NodeName=vm CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=24105"
  hw=$(timeout 10 slurmd -C 2>/dev/null | head -n 1) || hw=
  field() { printf '%s\n' "$hw" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
  cpus=$(field CPUs); boards=$(field Boards); sockets=$(field SocketsPerBoard)
  cores=$(field CoresPerSocket); threads=$(field ThreadsPerCore); mem=$(field RealMemory)
  local hwline
  if [ -n "$cpus" ] && [ -n "$cores" ] && [ -n "$mem" ]; then
    hwline="CPUs=$cpus Boards=${boards:-1} SocketsPerBoard=${sockets:-1} CoresPerSocket=$cores ThreadsPerCore=${threads:-1} RealMemory=$mem"
  else
    cpus=$(nproc)
    mem=$(awk '/^MemTotal:/ {print int($2 / 1024 * 0.95)}' /proc/meminfo)
    hwline="CPUs=$cpus RealMemory=$mem"
  fi
  local user
  user=$(id -un)
  cat >"$conf" <<CONF
# Written by scripts/slurm/cluster.sh: a single-node test cluster; everything it keeps is in this folder.
ClusterName=quakeview-test
SlurmctldHost=$node
SlurmUser=$user
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
StateSaveLocation=$state_dir/state
SlurmdSpoolDir=$state_dir/spool
SlurmctldPidFile=$ctld_pidfile
SlurmdPidFile=$slurmd_pidfile
SlurmctldLogFile=$state_dir/slurmctld.log
SlurmdLogFile=$state_dir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
# Cores and memory are both scheduled: --cpus-per-task and --mem mean what they say.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=512
ReturnToService=2
# Finished jobs stay visible to scontrol for an hour (no accounting database here).
MinJobAge=3600
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=2
InactiveLimit=0
KillWait=10
Waittime=0
NodeName=$node $hwline State=UNKNOWN
PartitionName=main Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
}

start_cluster() {
  local ctld_pid slurmd_pid
  for c in munge unmunge munged slurmctld slurmd sinfo squeue scontrol sbatch scancel; do
    command -v "$c" >/dev/null 2>&1 || [ -x "/usr/sbin/$c" ] ||
      die "'$c' not found: install Debian's slurm-wlm and munge (bash scripts/setup.sh, or apt-get install -y slurm-wlm munge)"
  done
  [ "$(id -u)" -eq 0 ] || die "the test cluster needs root (slurmd launches the jobs, munged runs as the munge user)"

  ctld_pid=$(live_pid "$ctld_pidfile" slurmctld) || ctld_pid=
  slurmd_pid=$(live_pid "$slurmd_pidfile" slurmd) || slurmd_pid=
  if [ -n "$ctld_pid" ] && [ -n "$slurmd_pid" ]; then
    case "$(node_state)" in
      idle | mixed | allocated | completing)
        log "already running (slurmctld $ctld_pid, slurmd $slurmd_pid)"
        printf 'export SLURM_CONF=%q\n' "$conf"
        return 0 ;;
    esac
  fi

  start_munged

  if [ -z "$ctld_pid" ] && [ -z "$slurmd_pid" ]; then
    for p in "$ctld_port" "$slurmd_port"; do
      if port_in_use "$p"; then
        die "port $p is in use (another Slurm on this machine?): set QUAKEVIEW_SLURM_PORT to a free pair, e.g. QUAKEVIEW_SLURM_PORT=7817"
      fi
    done
    mkdir -p "$state_dir/state" "$state_dir/spool"
    write_conf
  fi

  # On any failure from here: show the logs, stop what runs, and fail.
  fail() {
    printf '[%s] error: %s; the daemons'"'"' logs:\n' "$prog" "$*" >&2
    show_logs
    stop_cluster >&2
    die "$*"
  }

  if [ -z "$ctld_pid" ]; then
    log "starting slurmctld ($conf)"
    # -i: ignore unreadable state files (a folder reused after a crash); -c would clear the jobs.
    timeout "$timeout_s" slurmctld -f "$conf" -i || fail "slurmctld did not start"
  fi
  if [ -z "$slurmd_pid" ]; then
    log "starting slurmd"
    timeout "$timeout_s" slurmd -f "$conf" || fail "slurmd did not start"
  fi

  local i state=
  for ((i = 0; i <= timeout_s * 2; i++)); do
    state=$(node_state) || state=
    case "$state" in
      idle) break ;;
      # A node a previous cluster in this folder left down: bring it back.
      down | down\* | drained | drained\* | draining)
        if [ "$i" -gt 4 ]; then timeout 5 scontrol update NodeName="$(node_name)" State=RESUME >/dev/null 2>&1 || true; fi ;;
    esac
    sleep 0.5
  done
  [ "$state" = idle ] || fail "the node is not idle after ${timeout_s}s (sinfo says '${state:-no answer from slurmctld}')"
  log "node $(node_name) idle: $(timeout 5 sinfo -h -o '%P %D nodes, %c CPUs, %m MB' | head -n 1)"
  log "logs: $state_dir/slurmctld.log, $state_dir/slurmd.log"
  printf 'export SLURM_CONF=%q\n' "$conf"
}

status_cluster() {
  local pid
  if pid=$(live_pid "$ctld_pidfile" slurmctld); then log "slurmctld running (pid $pid)"; else log "slurmctld not running"; fi
  if pid=$(live_pid "$slurmd_pidfile" slurmd); then log "slurmd running (pid $pid)"; else log "slurmd not running"; fi
  if munge_works; then log "munged answers"; else log "munged does not answer"; fi
  if live_pid "$ctld_pidfile" slurmctld >/dev/null; then timeout 5 sinfo || true; fi
  printf 'export SLURM_CONF=%q\n' "$conf"
}

case "$action" in
  start) start_cluster ;;
  status) status_cluster ;;
  stop)
    if ! live_pid "$ctld_pidfile" slurmctld >/dev/null && ! live_pid "$slurmd_pidfile" slurmd >/dev/null &&
       ! { [ -f "$munged_marker" ] && ! other_slurm_daemons; }; then
      log "not running ($state_dir)"
    else
      stop_cluster
    fi ;;
esac
