#!/usr/bin/env bash
# stop_cluster.sh DIR — stop the private Slurm cluster that start_cluster.sh
# started in DIR: cancel its jobs, then stop slurmd, slurmctld and munged by
# their pid files under DIR and wait (bounded) for them to exit.
#
# It never signals anything that is not provably this cluster's: a pid from a
# pid file is only signalled if its command line mentions DIR (guards against
# pid reuse after a crash), and a leftover job step (slurmstepd, which
# outlives slurmd) only if it has a file open, or its cwd, under DIR.
# Safe to run more than once, and on a half-started or already dead cluster.
# Exit status: 0 when none of this cluster's processes is left, 1 otherwise.
set -euo pipefail

DIR=${1:?usage: stop_cluster.sh DIR}
[[ -d $DIR ]] || { echo "stop_cluster.sh: $DIR is not a directory" >&2; exit 1; }
DIR=$(cd "$DIR" && pwd)
export PATH=$PATH:/usr/sbin:/sbin
WAIT_SECS=${SLURM_TEST_WAIT_SECS:-20}

# Print the pid in pid file $1 if that process is alive and belongs to DIR.
our_pid() {
  local pid
  [[ -f $1 ]] || return 0
  pid=$(tr -dc '0-9' <"$1")
  [[ -n $pid && -r /proc/$pid/cmdline ]] || return 0
  tr '\0' ' ' <"/proc/$pid/cmdline" | grep -qF -- "$DIR/" && echo "$pid"
  return 0
}

# slurmstepd processes (job steps) holding a file or cwd under DIR.
our_stepds() {
  local pid
  for pid in $(pgrep -x slurmstepd || true); do
    if readlink "/proc/$pid/cwd" "/proc/$pid"/fd/* 2>/dev/null \
        | grep -qF -- "$DIR/"; then
      echo "$pid"
    fi
  done
}

# True if pid $1 runs. A zombie counts as gone: this machine's pid 1 may be
# slow to reap the daemons it inherited.
running() {
  local st
  st=$(sed 's/.*) //' "/proc/$1/stat" 2>/dev/null) || return 1
  [[ -n $st && ${st:0:1} != Z ]]
}

# Wait until none of the given pids runs; false after WAIT_SECS.
wait_gone() {
  local deadline=$((SECONDS + WAIT_SECS)) pid alive
  while :; do
    alive=""
    for pid in "$@"; do running "$pid" && alive+=" $pid"; done
    [[ -z $alive ]] && return 0
    ((SECONDS < deadline)) || { echo "still alive:$alive" >&2; return 1; }
    sleep 0.2
  done
}

# Cancel every job of this cluster so no job step outlives slurmd.
cancel_jobs() {
  local pid
  pid=$(our_pid "$DIR/run/slurmctld.pid")
  [[ -n $pid && -f $DIR/slurm.conf ]] || return 0
  SLURM_CONF=$DIR/slurm.conf scancel --quiet --user="$(id -un)" 2>/dev/null || true
  local deadline=$((SECONDS + WAIT_SECS))
  while ((SECONDS < deadline)); do
    [[ -z $(SLURM_CONF=$DIR/slurm.conf squeue -h -o %i 2>/dev/null) ]] && break
    sleep 0.5
  done
}

# SIGTERM the given pids, wait, then SIGKILL whatever is left.
stop_pids() {
  (($#)) || return 0
  kill -TERM "$@" 2>/dev/null || true
  wait_gone "$@" && return 0
  kill -KILL "$@" 2>/dev/null || true
  WAIT_SECS=5 wait_gone "$@"
}

main() {
  local rc=0 name pid
  cancel_jobs
  # slurmd first (it reports to slurmctld), munged last (both use it).
  for name in run/slurmd run/slurmctld munge/munged; do
    pid=$(our_pid "$DIR/$name.pid")
    # shellcheck disable=SC2086  # empty $pid must expand to no argument
    stop_pids $pid || rc=1
  done
  # shellcheck disable=SC2046  # word splitting of the pid list is intended
  stop_pids $(our_stepds) || rc=1
  return $rc
}

main
