#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for testing the studies' workflow against a real batch system:
# munged, slurmctld and slurmd with a generated configuration, all state and logs in <dir>.
#
#   scripts/workflow/local-slurm.sh start <dir> [cpus] [memory MB]   # prints the line to source: export SLURM_CONF=...
#   scripts/workflow/local-slurm.sh stop <dir>
#
# Needs root (the daemons run as root here) and Debian's slurm-wlm and munge. The node is this host with `cpus`
# CPUs (default: all) and `memory` MB (default: 3/4 of MemTotal); one partition, `local`, the default. The daemons
# listen on ports $SLURM_LOCAL_PORT and the next (default 6817, Slurm's), so that two such clusters can run at once.
set -euo pipefail
action=${1:?usage: local-slurm.sh start|stop <dir> [cpus] [memory MB]}
dir=$(realpath -m "${2:?usage: local-slurm.sh start|stop <dir> [cpus] [memory MB]}")

stop() {
  for daemon in slurmd slurmctld munged; do
    [ -f "$dir/$daemon.pid" ] && kill "$(cat "$dir/$daemon.pid")" 2>/dev/null || true
  done
  for _ in $(seq 50); do
    alive=0
    for daemon in slurmd slurmctld munged; do
      [ -f "$dir/$daemon.pid" ] && kill -0 "$(cat "$dir/$daemon.pid")" 2>/dev/null && alive=1
    done
    [ $alive = 0 ] && break
    sleep 0.2
  done
  rm -f "$dir"/*.pid
}

if [ "$action" = stop ]; then
  stop
  exit 0
fi
[ "$action" = start ] || { echo "local-slurm.sh: unknown action '$action' (start, stop)" >&2; exit 2; }
for program in munged slurmctld slurmd sbatch; do
  command -v "$program" > /dev/null || { echo "local-slurm.sh: $program not found (Debian: slurm-wlm, munge)" >&2; exit 3; }
done
[ "$(id -u)" -eq 0 ] || { echo "local-slurm.sh: run as root (the daemons run as root here)" >&2; exit 3; }
cpus=${3:-$(nproc)}
memory=${4:-$(awk '/MemTotal/ {print int($2 / 1024 * 3 / 4)}' /proc/meminfo)}
host=$(hostname -s)
port=${SLURM_LOCAL_PORT:-6817}
mkdir -p "$dir/state" "$dir/spool"
chmod 700 "$dir"
[ -f "$dir/munge.key" ] || { dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none; chmod 400 "$dir/munge.key"; }
cat > "$dir/slurm.conf" <<CONF
ClusterName=spatula-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
MinJobAge=3600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
stop
munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munged.seed"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 100); do
  sinfo -h -o '%t' 2>/dev/null | grep -q '^idle' && { echo "export SLURM_CONF=$SLURM_CONF"; exit 0; }
  sleep 0.2
done
echo "local-slurm.sh: the node did not come up (logs: $dir/*.log)" >&2
sinfo >&2 || true
tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
exit 1
