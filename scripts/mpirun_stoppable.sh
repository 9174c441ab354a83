#!/usr/bin/env bash
# mpirun that stops cleanly on Ctrl-C: scripts/mpirun_stoppable.sh NP CMD...
# Ctrl-C on mpirun itself kills the ranks within a second (Open MPI cannot
# pass SIGINT on: it sends SIGTERM, then SIGKILL), leaving a partial
# checkpoint. Here mpirun runs in a session of its own, out of the
# terminal's reach, and SIGINT or SIGTERM to this script becomes SIGUSR1,
# which mpirun passes on: each rank finishes its step, writes a checkpoint
# and exits with 75 (restart = true continues). The exit code is mpirun's.
set -uo pipefail
np=$1
shift
source "$(dirname "$0")/mpi_env.sh"
setsid mpirun -np "$np" "$@" &
pid=$!
trap 'echo "mpirun_stoppable: stopping after this step (checkpoint)" >&2
      kill -USR1 "$pid" 2> /dev/null' INT TERM
status=0
while kill -0 "$pid" 2> /dev/null; do
  wait "$pid"
  status=$?
done
exit "$status"
