#!/usr/bin/env bash
# A throw-away single-node Slurm cluster on this machine, entirely under DIR:
# munged, slurmctld and slurmd with their keys, sockets, state, logs and pid
# files in DIR. Nothing under /etc, no systemd, no accounting, no cgroups. For
# tests and for trying tools/slurm/ without a cluster. Needs root (slurmd runs
# jobs as the submitting user) and the Debian packages slurm-wlm and munge.
#
#   tools/slurm/local_cluster.sh start DIR   # start; prints the SLURM_CONF line to use
#   tools/slurm/local_cluster.sh env DIR     # prints "export SLURM_CONF=DIR/slurm.conf"
#   tools/slurm/local_cluster.sh stop DIR    # cancel jobs, stop the daemons (idempotent)
#
# Clients (sbatch, squeue, ...) find the cluster through SLURM_CONF:
#   eval "$(tools/slurm/local_cluster.sh start "$dir")"
#
# Environment: SLURM_LOCAL_CTLD_PORT / SLURM_LOCAL_SLURMD_PORT pick the TCP
# ports (default: a free pair in 20000-32000), SLURM_LOCAL_TIMEOUT the seconds
# to wait for the node to become idle (default 60).
set -euo pipefail

usage() {
  echo "usage: $0 start|stop|env DIR" >&2
  exit 2
}
die() {
  echo "local_cluster: error: $*" >&2
  exit 1
}
log() { echo "local_cluster: $*" >&2; }

(($# == 2)) || usage
action="$1"
dir="$2"
case "$action" in start | stop | env) ;; *) usage ;; esac

# Tail of every daemon log, for error messages.
show_logs() {
  local f
  for f in "$dir"/log/*.log; do
    [ -f "$f" ] || continue
    echo "----- $f (last 30 lines) -----" >&2
    tail -n 30 "$f" >&2 || true
  done
}

# Prints the pid in pid file $1 if that process is still the program $2 (so a
# stale pid file never leads to killing an unrelated process that reused the
# pid), and removes the pid file.
live_pid() {
  local pidfile="$1" prog="$2" pid comm
  [ -f "$pidfile" ] || return 0
  pid="$(tr -dc '0-9' <"$pidfile")"
  rm -f "$pidfile"
  [ -n "$pid" ] || return 0
  # comm is truncated to 15 chars; the Debian binaries are e.g. slurmctld-wlm.
  comm="$(cat "/proc/$pid/comm" 2>/dev/null || true)"
  [[ -n "$comm" && "$comm" == "$prog"* ]] && echo "$pid"
  return 0
}

do_stop() {
  [ -d "$dir" ] || return 0
  local ctld_pid
  ctld_pid="$(tr -dc '0-9' <"$dir/run/slurmctld.pid" 2>/dev/null || true)"
  if [ -f "$dir/slurm.conf" ] && [ -n "$ctld_pid" ] && kill -0 "$ctld_pid" 2>/dev/null; then
    export SLURM_CONF="$dir/slurm.conf"
    # Cancel jobs first so slurmd stops their slurmstepd and job processes;
    # stopping slurmd alone would leave them running. (timeout: never hang
    # on a controller that does not answer.)
    if timeout 10 scancel --quiet --user="$(id -un)" 2>/dev/null; then
      local i
      for ((i = 0; i < 30; i++)); do
        [ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
        sleep 0.5
      done
    fi
  fi
  local pids=() pid i
  for pid in $(live_pid "$dir/run/slurmd.pid" slurmd) \
    $(live_pid "$dir/run/slurmctld.pid" slurmctld) \
    $(live_pid "$dir/munge/munged.pid" munged); do
    pids+=("$pid")
  done
  ((${#pids[@]})) || return 0
  # All at once: each takes about 2 s to shut down.
  kill -TERM "${pids[@]}" 2>/dev/null || true
  for ((i = 0; i < 100; i++)); do # up to 10 s for a clean shutdown
    local alive=0
    for pid in "${pids[@]}"; do
      ! kill -0 "$pid" 2>/dev/null || alive=1
    done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do
    if kill -0 "$pid" 2>/dev/null; then
      log "pid $pid ($(cat "/proc/$pid/comm" 2>/dev/null)) did not stop on SIGTERM; sending SIGKILL"
      kill -KILL "$pid" 2>/dev/null || true
    fi
  done
}

if [ "$action" = stop ]; then
  do_stop
  exit 0
fi

dir="$(mkdir -p "$dir" && cd "$dir" && pwd)"
if [ "$action" = env ]; then
  [ -f "$dir/slurm.conf" ] || die "no cluster in $dir (run: $0 start $dir)"
  echo "export SLURM_CONF='$dir/slurm.conf'"
  exit 0
fi

# ---- start ----
[ "$(id -u)" -eq 0 ] || die "must run as root (slurmd starts jobs as their user)"
for cmd in munged munge slurmctld slurmd sinfo scontrol squeue scancel; do
  command -v "$cmd" >/dev/null || die "'$cmd' not found; install the Debian packages: apt-get install slurm-wlm munge"
done
[ ! -e "$dir/run/slurmctld.pid" ] || die "$dir already holds a cluster; run: $0 stop $dir"

# Unix socket paths are limited to 107 bytes; slurmd's spool sockets are the longest.
((${#dir} <= 70)) || die "DIR path too long for Unix sockets (${#dir} > 70 chars): $dir"

# The node name slurmd and slurmctld derive themselves: the kernel host name
# up to the first dot. Addresses are given as 127.0.0.1, so it need not resolve.
node="$(uname -n)"
node="${node%%.*}"
[ -n "$node" ] || die "cannot determine the host name (uname -n is empty)"

mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log" "$dir/run"
# munged refuses keys and sockets in directories others may write to.
chmod 0755 "$dir/munge" # not writable by others; searchable so clients reach the socket
chmod 0755 "$dir" "$dir/log" "$dir/run" "$dir/state" "$dir/spool"

# On any failure from here on, stop what was started and show why.
trap 'rc=$?; if ((rc)); then show_logs; do_stop; fi' EXIT

# ---- munge ----
key="$dir/munge/munge.key"
if [ ! -f "$key" ]; then
  if command -v mungekey >/dev/null; then
    mungekey --create --keyfile="$key" >/dev/null
  else
    dd if=/dev/urandom of="$key" bs=1024 count=1 status=none
  fi
fi
chmod 0400 "$key" # munged insists on a key readable by its owner only
socket="$dir/munge/munge.socket.2"
# --force: tolerate loosely-permissioned parents of DIR (e.g. a CI workspace);
# everything munged creates is ours, under DIR/munge. --origin: the host name
# need not resolve.
munged --force --origin=127.0.0.1 \
  --socket="$socket" --key-file="$key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
  --seed-file="$dir/munge/munged.seed" \
  || die "munged failed to start"
for ((i = 0; i < 50; i++)); do
  [ -S "$socket" ] && break
  sleep 0.1
done
munge --socket="$socket" --no-input | unmunge --socket="$socket" >/dev/null \
  || die "munge credential round trip failed on $socket"

# ---- slurm.conf ----
port_in_use() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port="${SLURM_LOCAL_CTLD_PORT:-}"
slurmd_port="${SLURM_LOCAL_SLURMD_PORT:-}"
if [ -z "$ctld_port" ] || [ -z "$slurmd_port" ]; then
  # Not the default 6817/6818, so a real Slurm on this machine is no obstacle;
  # below the Linux ephemeral range so no outgoing connection holds them.
  for ((i = 0; i < 50; i++)); do
    p=$((20000 + (RANDOM % 6000) * 2))
    if ! port_in_use "$p" && ! port_in_use $((p + 1)); then
      ctld_port="$p" slurmd_port=$((p + 1))
      break
    fi
  done
  [ -n "$ctld_port" ] || die "no free TCP port pair found in 20000-32000"
fi

# The node as slurmd sees it (CPUs, sockets, cores, threads, memory), so it
# registers without being drained for a configuration mismatch. Memory is
# given with 10% slack because free memory reporting may fluctuate.
hw="$(slurmd -C 2>/dev/null | head -n 1)" || true
cpus="$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$hw")"
[ -n "$cpus" ] || cpus="$(nproc)"
topology="$(grep -o 'Boards=[0-9]* SocketsPerBoard=[0-9]* CoresPerSocket=[0-9]* ThreadsPerCore=[0-9]*' <<<"$hw" || true)"
mem="$(sed -n 's/.* RealMemory=\([0-9]*\).*/\1/p' <<<"$hw")"
[ -n "$mem" ] && mem="RealMemory=$((mem * 9 / 10))"

cat >"$dir/slurm.conf" <<EOF
# Generated by tools/slurm/local_cluster.sh: a single-node test cluster.
ClusterName=campo-local
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups (containers without systemd), no accounting database.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true
PlugStackConfig=$dir/plugstack.conf
# Allocate single CPUs so array tasks share the node.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
# A node that restarts or registers late returns to service by itself.
ReturnToService=2
# A small MinJobAge (at least 2) makes "sbatch --wait" poll every 2 s instead
# of backing off to 32 s; submit_sweep.sh reads task results from files.
MinJobAge=4
KillWait=5
InactiveLimit=0
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=$node CPUs=$cpus $topology $mem State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
: >"$dir/plugstack.conf" # no SPANK plugins (not the system's /etc/slurm one)
export SLURM_CONF="$dir/slurm.conf"

# ---- daemons ----
# Both daemonize and write their pid files; stdio goes to the logs so a caller
# capturing our output (ctest) is not kept waiting by the daemons.
slurmctld -f "$SLURM_CONF" </dev/null >>"$dir/log/slurmctld.stdout.log" 2>&1 \
  || die "slurmctld failed to start"
# -N: the node name explicitly, in case the host name resolves unusually.
slurmd -f "$SLURM_CONF" -N "$node" </dev/null >>"$dir/log/slurmd.stdout.log" 2>&1 \
  || die "slurmd failed to start"

timeout="${SLURM_LOCAL_TIMEOUT:-60}"
state=""
# A daemon that wrote its pid file and is gone has failed (e.g. its port is
# taken): say so at once rather than at the timeout.
check_alive() {
  local name pidfile pid
  for name in slurmctld slurmd; do
    pidfile="$dir/run/$name.pid"
    [ -s "$pidfile" ] || continue
    pid="$(tr -dc '0-9' <"$pidfile")"
    kill -0 "$pid" 2>/dev/null || die "$name exited during start-up; logs follow"
  done
}
for ((i = 0; i < timeout * 2; i++)); do
  check_alive
  # timeout: a client talking to a wrong server could wait a long time.
  state="$(timeout 5 sinfo -h -n "$node" -o %T 2>/dev/null | head -n 1 || true)"
  case "$state" in
    idle | mixed | allocated) break ;;
    down* | drain* | fail*)
      # e.g. "down" after an unexpected slurmd restart: put it back in service.
      scontrol update NodeName="$node" State=RESUME >/dev/null 2>&1 || true
      ;;
  esac
  sleep 0.5
done
case "$state" in
  idle | mixed | allocated) ;;
  *)
    scontrol show node "$node" >&2 2>/dev/null || true
    die "node $node not idle after ${timeout}s (state: '${state:-no answer from slurmctld}'); logs follow"
    ;;
esac

trap - EXIT
log "cluster up in $dir: node $node ($cpus CPUs), slurmctld port $ctld_port"
echo "export SLURM_CONF='$SLURM_CONF'"
