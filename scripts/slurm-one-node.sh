#!/usr/bin/env bash
# A throwaway one-node Slurm cluster on this machine, for testing `cutaway batch --slurm`:
#
#   scripts/slurm-one-node.sh start STATE_DIR   # prints the SLURM_CONF=... line to export
#   scripts/slurm-one-node.sh stop STATE_DIR    # stops its daemons, removes STATE_DIR
#
# Everything lives in STATE_DIR (which must not exist yet): its own munge key and socket, a
# generated slurm.conf (no cgroups, no accounting, one partition "batch" with this machine as
# its only node), the state, spool, pid and log files of slurmctld and slurmd. Nothing in /etc
# or the system's munge is touched; the daemons listen on two free local ports. Needs Debian's
# slurm-wlm and munge packages and root (slurmd starts jobs as their user).
set -euo pipefail

usage() { echo "usage: $0 start|stop STATE_DIR" >&2; exit 2; }
[[ $# -eq 2 ]] || usage
action=$1
state=$2

# A TCP port nobody listens on (from the kernel's ephemeral range, checked with ss).
free_port() {
  local p
  for _ in $(seq 100); do
    p=$((20000 + RANDOM % 20000))
    if ! ss -Htln "sport = :$p" | grep -q .; then echo "$p"; return; fi
  done
  echo "slurm-one-node: no free port found" >&2
  exit 1
}

stop() {
  [[ -d "$state" ]] || return 0
  for pidfile in "$state"/slurmd.pid "$state"/slurmctld.pid "$state"/munged.pid; do
    [[ -f "$pidfile" ]] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  # Job steps slurmd left behind (slurmstepd) belong to this cluster only when they name STATE.
  pkill -9 -f "slurmstepd.*$state" 2>/dev/null || true
  rm -rf "$state"
}

start() {
  for tool in munged slurmctld slurmd sbatch squeue scontrol; do
    command -v "$tool" >/dev/null || { echo "slurm-one-node: $tool is missing (apt-get install slurm-wlm munge)" >&2; exit 1; }
  done
  [[ ! -e "$state" ]] || { echo "slurm-one-node: $state already exists" >&2; exit 1; }
  mkdir -p "$state"/munge "$state"/ctld "$state"/spool
  chmod 700 "$state" "$state"/munge
  state=$(cd "$state" && pwd)
  trap 'echo "slurm-one-node: start failed; logs in $state" >&2; exit 1' ERR

  # munge: a fresh key, its own socket.
  dd if=/dev/urandom of="$state/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$state/munge/munge.key"
  munged --force --key-file="$state/munge/munge.key" --socket="$state/munge/socket" \
    --pid-file="$state/munged.pid" --log-file="$state/munged.log" \
    --seed-file="$state/munge/seed"

  local node ctld_port d_port cpus memory_mb
  node=$(hostname -s)
  ctld_port=$(free_port)
  d_port=$(free_port)
  cpus=$(nproc)
  memory_mb=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))
  cat > "$state/slurm.conf" <<EOF
ClusterName=cutaway-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$state/munge/socket
CredType=cred/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=batch Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$state/slurm.conf"
  slurmctld -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF" -N "$node"
  # Ready when the node is idle.
  for _ in $(seq 150); do
    if sinfo -h -N -o '%t' 2>/dev/null | grep -qx 'idle'; then
      echo "SLURM_CONF=$SLURM_CONF"
      return
    fi
    sleep 0.2
  done
  echo "slurm-one-node: the node did not come up within 30 s; logs in $state:" >&2
  tail -n 20 "$state"/*.log >&2 || true
  stop
  exit 1
}

case "$action" in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
