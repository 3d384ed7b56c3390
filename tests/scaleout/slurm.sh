#!/usr/bin/env bash
# A single-node Slurm cluster on loopback (Debian slurm-wlm and munge), for
# the scale-out tests and for trying `gearsph serve --dispatch slurm` by
# hand (docs/scale-out.md).
#
#   tests/scaleout/slurm.sh start DIR    # prints SLURM_CONF=DIR/slurm.conf
#   tests/scaleout/slurm.sh stop DIR
#
# Everything lives in DIR: a munge key and its own munged socket (the
# system's munged, if any, is left alone), slurm.conf with free ports for
# slurmctld and slurmd, state, spool, logs and pid files. Slurm commands
# find this cluster through SLURM_CONF. Needs root: slurmd starts jobs as
# their owners, munged runs as the `munge` user.
set -euo pipefail
cmd=${1:?usage: slurm.sh start|stop DIR}
dir=${2:?usage: slurm.sh start|stop DIR}
script=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")

# The engine watchdog (start_watchdog, stop_watchdog) needs $script and $dir.
source "$(dirname "$script")/watchdog.sh"

stop_pidfile() {
  local file=$1
  [ -s "$file" ] || return 0
  local pid
  pid=$(cat "$file")
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.1; done
  kill -9 "$pid" 2>/dev/null || true
}

case $cmd in
start)
  for b in munged slurmctld slurmd sbatch squeue; do
    command -v "$b" >/dev/null || { echo "slurm.sh: $b is missing (apt-get install slurm-wlm munge)" >&2; exit 3; }
  done
  if [ "$(id -u)" -ne 0 ]; then
    echo "slurm.sh: needs root (slurmd starts jobs as their owners; munged runs as munge)" >&2
    exit 4
  fi
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  chmod 755 "$dir"
  mkdir -p "$dir/munge" "$dir/munge-key" "$dir/state" "$dir/spool"
  # munged wants its socket's directory searchable by all, its key private.
  chown munge: "$dir/munge" "$dir/munge-key" && chmod 755 "$dir/munge" && chmod 700 "$dir/munge-key"
  head -c 1024 /dev/urandom >"$dir/munge-key/munge.key"
  chown munge: "$dir/munge-key/munge.key" && chmod 400 "$dir/munge-key/munge.key"
  runuser -u munge -- munged --socket="$dir/munge/munge.sock" --key-file="$dir/munge-key/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed"

  free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
  cpus=$(nproc)
  mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
  cat >"$dir/slurm.conf" <<CONF
ClusterName=gearsph-test
SlurmctldHost=localhost
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.sock
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
NodeName=localhost CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -f "$SLURM_CONF"
  for _ in $(seq 100); do scontrol ping 2>/dev/null | grep -q UP && break; sleep 0.1; done
  slurmd -f "$SLURM_CONF"
  for _ in $(seq 150); do
    state=$(sinfo --noheader --format=%T 2>/dev/null | head -n 1)
    [ "$state" = idle ] && break
    sleep 0.2
  done
  if [ "${state:-}" != idle ]; then
    echo "slurm.sh: the node did not become idle (state '${state:-}'); logs in $dir" >&2
    tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
    exit 1
  fi
  start_watchdog
  echo "SLURM_CONF=$SLURM_CONF"
  ;;
stop)
  [ -d "$dir" ] || exit 0
  dir=$(cd "$dir" && pwd)
  stop_watchdog
  stop_pidfile "$dir/slurmd.pid"
  stop_pidfile "$dir/slurmctld.pid"
  stop_pidfile "$dir/munge/munged.pid"
  ;;
*)
  echo "usage: slurm.sh start|stop DIR" >&2
  exit 2
  ;;
esac
