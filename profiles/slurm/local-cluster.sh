#!/usr/bin/env bash
# A one-node SLURM cluster on localhost, for trying `snakemake --profile profiles/slurm` on one
# machine (Debian 12, run as root, no systemd needed).
#
#   profiles/slurm/local-cluster.sh up      install the packages if missing, write the config,
#                                           start munged, slurmctld and slurmd
#   profiles/slurm/local-cluster.sh down    stop exactly the daemons `up` started (by their PIDs)
#   profiles/slurm/local-cluster.sh status  sinfo of the cluster
#
# The cluster has no accounting database (slurmdbd), so sacct cannot report job states: run
# Snakemake with `--slurm-status-command squeue`. MinJobAge below keeps finished jobs visible to
# squeue for ten minutes, far longer than three times the plugin's first status-check delay.
# Accounts are not enforced; any account name (e.g. `local`) is accepted.
set -euo pipefail

STATE_DIR=${HUBBEAM_SLURM_STATE:-/var/lib/hubbeam-slurm}
CONF_DIR=/etc/slurm
PACKAGES=(slurm-wlm munge)

need_root() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "local-cluster.sh: run as root (it installs packages and starts system daemons)" >&2
    exit 1
  fi
}

install_packages() {
  local missing=()
  for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
  done
  if [ "${#missing[@]}" -gt 0 ]; then
    echo "installing ${missing[*]}"
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}"
  fi
}

write_config() {
  local host cpus memory
  host=$(hostname -s)
  cpus=$(nproc)
  # leave 1 GiB to the system; jobs must ask for memory (mem_mb) under CR_Core_Memory
  memory=$(( $(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo) - 1024 ))
  mkdir -p "$CONF_DIR"
  cat > "$CONF_DIR/slurm.conf" <<CONF
# written by hubbeam's profiles/slurm/local-cluster.sh
ClusterName=hubbeam-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$STATE_DIR/slurmctld.log
SlurmdLogFile=$STATE_DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MinJobAge=600
MpiDefault=none
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
  mkdir -p "$STATE_DIR" /run/munge /var/spool/slurmctld /var/spool/slurmd /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  chmod 0755 /run/munge
  if [ ! -s /etc/munge/munge.key ]; then
    mungekey --create --force
    chown munge:munge /etc/munge/munge.key
    chmod 0400 /etc/munge/munge.key
  fi
  runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/munged.pid
  cp /run/munge/munged.pid "$STATE_DIR/munged.pid"
  /usr/sbin/slurmctld -i
  /usr/sbin/slurmd
  for _ in $(seq 50); do
    [ -s /run/slurmctld.pid ] && [ -s /run/slurmd.pid ] && break
    sleep 0.2
  done
  cp /run/slurmctld.pid "$STATE_DIR/slurmctld.pid"
  cp /run/slurmd.pid "$STATE_DIR/slurmd.pid"
  for _ in $(seq 60); do
    if sinfo -h -o '%T' 2>/dev/null | grep -q -E '^(idle|mixed|allocated)'; then
      sinfo
      echo "run the workflow on it with:"
      echo "  export HUBBEAM_SLURM_ACCOUNT=local HUBBEAM_SLURM_PARTITION=local"
      echo "  snakemake --profile profiles/slurm --slurm-status-command squeue"
      return 0
    fi
    sleep 0.5
  done
  echo "local-cluster.sh: the node did not become idle; logs in $STATE_DIR" >&2
  sinfo >&2 || true
  exit 1
}

stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    if [ -s "$STATE_DIR/$name.pid" ]; then
      pid=$(cat "$STATE_DIR/$name.pid")
      if kill "$pid" 2>/dev/null; then
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        echo "stopped $name ($pid)"
      fi
      rm -f "$STATE_DIR/$name.pid"
    fi
  done
}

case "${1:-}" in
  up) need_root; install_packages; stop; write_config; start ;;
  down) need_root; stop ;;
  status) sinfo ;;
  *) echo "usage: $0 up|down|status" >&2; exit 2 ;;
esac
