#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, for the Slurm backend's tests
# (tests/sweep_slurm_test.cpp) and for trying `trackbed sweep --backend slurm` by hand.
#
#   scripts/slurm_local.sh install        # apt-get the Debian packages (slurm-wlm, munge)
#   scripts/slurm_local.sh start [DIR]    # munged, slurmctld, slurmd; prints `export SLURM_CONF=…`
#   scripts/slurm_local.sh stop [DIR]     # stops the daemons this script started, by their pids
#   scripts/slurm_local.sh status [DIR]
#
# DIR (default /tmp/trackbed-slurm) holds slurm.conf, the daemons' pid files, logs
# and state. Nothing under /etc is changed: the Slurm commands find the cluster through
# SLURM_CONF=DIR/slurm.conf. One node (this host, all its CPUs), one partition
# `trackbed`, ports 16817/16818 (not Slurm's defaults, so a real installation's daemons
# are left alone). Run as root. The settings that make slurmd work in a container
# without systemd or cgroup delegation: ProctrackType=proctrack/linuxproc,
# TaskPlugin=task/none. Without slurmdbd, sacct has no data; finished jobs stay
# visible to `scontrol show job` for MinJobAge (10 min here) and are logged by
# JobCompType=jobcomp/filetxt in DIR/jobcomp.txt.
set -euo pipefail

cmd=${1:-}
dir=${2:-/tmp/trackbed-slurm}

die() {
  echo "slurm_local.sh: $*" >&2
  exit 1
}

pid_alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

install_packages() {
  local missing=()
  for p in slurm-wlm munge; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "slurm_local.sh: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

write_conf() {
  local host cpus mem_mb
  host=$(hostname -s)
  cpus=$(nproc)
  mem_mb=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 * 9 / 10))
  mkdir -p "$dir"/{state,spool,log}
  cat >"$dir/slurm.conf" <<EOF
# Written by trackbed's scripts/slurm_local.sh: a one-node test cluster.
ClusterName=trackbed
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
KillWait=5
InactiveLimit=0
SlurmctldTimeout=30
SlurmdTimeout=60
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=trackbed Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root"
  command -v slurmctld >/dev/null && command -v munged >/dev/null ||
    die "slurmctld or munged not found: run '$0 install' first"
  if pid_alive "$dir/slurmctld.pid" && pid_alive "$dir/slurmd.pid"; then
    echo "export SLURM_CONF=$dir/slurm.conf"
    return 0
  fi
  write_conf
  # munged: the system's one if it runs, else ours (as the munge user, its default socket).
  if ! pidof munged >/dev/null; then
    [ -s /etc/munge/munge.key ] || die "/etc/munge/munge.key missing (reinstall munge)"
    install -d -o munge -g munge -m 0755 /run/munge
    install -d -o munge -g munge -m 0700 /var/lib/munge /var/log/munge
    runuser -u munge -- /usr/sbin/munged
    pidof munged >"$dir/munged.pid"
  fi
  export SLURM_CONF=$dir/slurm.conf
  /usr/sbin/slurmctld -f "$SLURM_CONF"
  /usr/sbin/slurmd -f "$SLURM_CONF"
  # Ready when the node takes jobs.
  local state=""
  for _ in $(seq 1 60); do
    state=$(sinfo -h -N -o '%T' 2>/dev/null | head -n 1 || true)
    case "$state" in idle | mixed | allocated) break ;; esac
    sleep 0.5
  done
  case "$state" in
    idle | mixed | allocated) ;;
    *)
      tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
      die "the node did not come up (state '${state:-none}'); logs above"
      ;;
  esac
  echo "export SLURM_CONF=$SLURM_CONF"
}

stop() {
  local f
  for f in slurmd slurmctld munged; do
    if pid_alive "$dir/$f.pid"; then
      kill "$(cat "$dir/$f.pid")" || true
      for _ in $(seq 1 40); do
        pid_alive "$dir/$f.pid" || break
        sleep 0.25
      done
      pid_alive "$dir/$f.pid" && kill -9 "$(cat "$dir/$f.pid")" 2>/dev/null || true
    fi
    rm -f "$dir/$f.pid"
  done
}

case "$cmd" in
  install) install_packages ;;
  start) start ;;
  stop) stop ;;
  status)
    for f in munged slurmctld slurmd; do
      if pid_alive "$dir/$f.pid"; then echo "$f: running (pid $(cat "$dir/$f.pid"))"; else echo "$f: not started here"; fi
    done
    SLURM_CONF=$dir/slurm.conf sinfo 2>&1 || true
    ;;
  *) die "usage: $0 install | start [DIR] | stop [DIR] | status [DIR]" ;;
esac
