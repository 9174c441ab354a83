#!/usr/bin/env bash
# Set up (install + build, see setup.sh) and run the default scene:
# a fixed sphere in a uniform stream (parameters/drag_sphere.prm), or the
# .prm file given as argument.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
scene="${1:-parameters/drag_sphere.prm}"
source scripts/mpi_env.sh
ranks="${SOFTSAND_RANKS:-1}"
if [ "$ranks" -gt 1 ]; then
  mpirun -np "$ranks" build/softsand "$scene"
else
  build/softsand "$scene"
fi
