#!/usr/bin/env bash
# Starts and stops a one-node Slurm cluster on this machine from Debian's
# slurm-wlm and munge packages (scripts/setup.sh installs them), for the tests
# of scripts/slurm_matrix.sh. Needs root (slurmd runs jobs as their user).
#
#   scripts/slurm_local.sh up   [STATE_DIR]   starts munged, slurmctld, slurmd; waits for an idle node
#   scripts/slurm_local.sh down [STATE_DIR]   cancels its jobs, stops the daemons by their PIDs
#   scripts/slurm_local.sh env  [STATE_DIR]   prints the SLURM_CONF line the clients need
#
# Everything lives in STATE_DIR (default /tmp/duskmap-slurm-$UID): the munge key,
# slurm.conf, spool and state folders, logs and pid files. Nothing under
# /etc/slurm, /etc/munge or /run/munge is read or written: munged gets its own
# key, socket, pid and log files, and the clients find this cluster through
# SLURM_CONF=STATE_DIR/slurm.conf (slurm.conf names the munge socket). The ports
# (default 16817 and 16818, not Slurm's 6817/6818, so that a site's daemons on
# this machine are left alone) can be set with DUSKMAP_SLURM_PORTS="CTLD SLURMD".
# systemd is not needed: each daemon is started here and stopped by its PID.
# Running `up` on a running cluster (its slurm.conf is kept, so a different
# DUSKMAP_SLURM_PORTS does not apply to it) or `down` on a stopped one does nothing.
# Both need root. A daemon that has exited but is not reaped yet (a zombie) counts as stopped.
# When the node is not idle within DUSKMAP_SLURM_UP_TIMEOUT_S (default 60) s,
# `up` stops what it started, prints one line naming the log to read, exits 1
# (a cluster that was already up is left running). `down` gives up with one
# line and exit 1 on a daemon still there 5 s after SIGKILL.
set -euo pipefail

usage() { echo "usage: $0 up|down|env [STATE_DIR]" >&2; exit 2; }
[ $# -ge 1 ] && [ $# -le 2 ] || usage
action=$1
state=$(realpath -m "${2:-/tmp/duskmap-slurm-$(id -u)}")
conf="$state/slurm.conf"
read -r ctld_port slurmd_port <<<"${DUSKMAP_SLURM_PORTS:-16817 16818}"
timeout_s=${DUSKMAP_SLURM_UP_TIMEOUT_S:-60}
node=$(hostname -s)
export SLURM_CONF="$conf"

fail() { echo "$0: $*" >&2; exit 1; }

# Whether process PID has exited: gone, or a zombie (or dead) that its parent
# has not reaped yet.
exited() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 0
  stat=${stat##*) }  # the state follows the command name, which may hold ") "
  case "${stat%% *}" in Z|X|'') return 0;; esac
  return 1
}

# The PID in FILE when that process is alive and runs PROGRAM, else nothing.
live_pid() {
  local file=$1 program=$2 pid
  [ -f "$file" ] || return 0
  pid=$(tr -dc '0-9' <"$file")
  [ -n "$pid" ] && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$program" ] && ! exited "$pid" && echo "$pid"
  return 0
}

# Stops the daemon whose PID is in FILE (SIGTERM, then SIGKILL after 20 s) and
# waits for it; one line on stderr and status 1 when it outlives SIGKILL by 5 s.
stop_daemon() {
  local file=$1 program=$2 pid waited=0
  pid=$(live_pid "$file" "$program")
  if [ -n "$pid" ]; then
    kill -TERM "$pid" 2>/dev/null || true
    until exited "$pid"; do
      if [ $waited -eq 200 ]; then kill -KILL "$pid" 2>/dev/null || true; fi
      if [ $waited -ge 250 ]; then
        echo "$0: $program (pid $pid) did not stop, not even on SIGKILL" >&2
        return 1
      fi
      sleep 0.1
      waited=$((waited + 1))
    done
    echo "stopped $program (pid $pid)"
    stopped_any=1
  fi
  rm -f "$file"
}

node_state() { timeout 5 sinfo -h -n "$node" -o '%T' 2>/dev/null | head -n1 || true; }

write_config() {
  mkdir -p "$state/munge" "$state/log" "$state/spool/slurmctld" "$state/spool/slurmd"
  chown munge:munge "$state/munge"
  chmod 0755 "$state/munge"  # the socket must be reachable; the key stays 0400
  if [ ! -s "$state/munge/munge.key" ]; then
    dd if=/dev/urandom of="$state/munge/munge.key" bs=1024 count=1 status=none
  fi
  chown munge:munge "$state/munge/munge.key"
  chmod 0400 "$state/munge/munge.key"
  runuser -u munge -- test -r "$state/munge/munge.key" ||
    fail "$state: the munge user cannot reach it (a folder above it is not searchable by others; chmod o+x it or choose another STATE_DIR)"
  cat >"$conf.tmp" <<EOF
# One-node cluster of scripts/slurm_local.sh; every path lies under $state.
ClusterName=duskmap
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$state/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$state/spool/slurmctld
SlurmdSpoolDir=$state/spool/slurmd
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/log/jobcomp.txt
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
SlurmdTimeout=30
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  mv "$conf.tmp" "$conf"
}

start_daemons() {
  # A daemon started afresh starts a fresh log, so that the log names this start's error.
  if [ -z "$(live_pid "$state/munge/munged.pid" munged)" ]; then
    rm -f "$state/munge/munged.log"  # munged creates it, owned by munge
    runuser -u munge -- munged --socket="$state/munge/munge.socket" \
      --key-file="$state/munge/munge.key" --pid-file="$state/munge/munged.pid" \
      --log-file="$state/munge/munged.log" --seed-file="$state/munge/munged.seed" \
      >>"$state/log/start.log" 2>&1 || return 1
  fi
  if [ -z "$(live_pid "$state/slurmctld.pid" slurmctld)" ]; then
    : >"$state/log/slurmctld.log"
    slurmctld -i -f "$conf" >>"$state/log/start.log" 2>&1 || return 1
  fi
  if [ -z "$(live_pid "$state/slurmd.pid" slurmd)" ]; then
    : >"$state/log/slurmd.log"
    slurmd -f "$conf" >>"$state/log/start.log" 2>&1 || return 1
  fi
}

stop_all() {
  # Jobs first, so that no job step outlives its slurmd.
  if [ -n "$(live_pid "$state/slurmctld.pid" slurmctld)" ]; then
    local jobs waited=0
    jobs=$(timeout 10 squeue -h -o '%A' 2>/dev/null | tr '\n' ' ' || true)
    if [ -n "${jobs// /}" ]; then
      # shellcheck disable=SC2086
      scancel $jobs 2>/dev/null || true
      while [ -n "$(timeout 10 squeue -h -o '%A' 2>/dev/null || true)" ] && [ $waited -lt 100 ]; do
        sleep 0.2
        waited=$((waited + 1))
      done
    fi
  fi
  local rc=0
  stop_daemon "$state/slurmd.pid" slurmd || rc=1
  stop_daemon "$state/slurmctld.pid" slurmctld || rc=1
  stop_daemon "$state/munge/munged.pid" munged || rc=1
  return $rc
}

# The first daemon that is not running and its log ("" when all run).
dead_daemon() {
  if [ -z "$(live_pid "$state/munge/munged.pid" munged)" ]; then echo "munged $state/munge/munged.log";
  elif [ -z "$(live_pid "$state/slurmctld.pid" slurmctld)" ]; then echo "slurmctld $state/log/slurmctld.log";
  elif [ -z "$(live_pid "$state/slurmd.pid" slurmd)" ]; then echo "slurmd $state/log/slurmd.log"; fi
}

up() {
  [ "$(id -u)" -eq 0 ] || fail "must run as root (slurmd runs jobs as their users)"
  for program in munged slurmctld slurmd sinfo; do
    command -v "$program" >/dev/null || fail "$program: not installed (run scripts/setup.sh)"
  done
  [ ! -e "$state" ] || [ -d "$state" ] || fail "$state: not a folder"
  # A cluster already up keeps its slurm.conf (and its ports) and is never
  # stopped here, not even when its node is not idle in time.
  local was_up=0
  [ -z "$(dead_daemon)" ] && [ -f "$conf" ] && was_up=1
  if [ $was_up = 0 ]; then
    write_config
  fi
  if [ $was_up = 0 ] && ! start_daemons; then
    local dead
    dead=$(dead_daemon)
    stop_all >/dev/null || true
    fail "the cluster did not come up: ${dead%% *} failed to start; read ${dead#* } and $state/log/start.log"
  fi
  local start=$SECONDS node_now="" dead=""
  while [ $((SECONDS - start)) -lt "$timeout_s" ]; do
    # A daemon that died ends the wait (its pid file is written a moment after it forks).
    if [ $((SECONDS - start)) -ge 2 ]; then
      dead=$(dead_daemon)
      [ -z "$dead" ] || break
    fi
    node_now=$(node_state)
    case "$node_now" in idle|mixed|allocated)
      [ $was_up = 1 ] && echo "cluster already up" || echo "cluster up: node $node $node_now"
      echo "export SLURM_CONF=$conf"
      return 0;;
    esac
    sleep 0.2
  done
  if [ $was_up = 1 ] && [ -n "$dead" ]; then
    fail "the cluster was up, but ${dead%% *} exited; read ${dead#* } (it is not stopped here: run down, then up)"
  elif [ $was_up = 1 ]; then
    fail "the cluster is up, but its node $node is '${node_now:-unknown}', not idle, after $timeout_s s; read $state/log/slurmctld.log and $state/log/slurmd.log"
  fi
  stop_all >/dev/null || true
  if [ -n "$dead" ]; then
    local reason
    reason=$(grep -E 'fatal|[Ee]rror' "${dead#* }" 2>/dev/null | tail -n1 | cut -c1-160 || true)
    fail "the cluster did not come up: ${dead%% *} exited${reason:+ ($reason)}; read ${dead#* }"
  fi
  fail "the cluster did not come up within $timeout_s s (node state '${node_now:-unknown}'); read $state/log/slurmctld.log and $state/log/slurmd.log"
}

case "$action" in
  up) up;;
  down)
    [ "$(id -u)" -eq 0 ] || fail "must run as root (the daemons run as root and munge)"
    stopped_any=0
    stop_all || exit 1
    [ $stopped_any = 1 ] || echo "cluster not running ($state)";;
  env) echo "export SLURM_CONF=$conf";;
  *) usage;;
esac
