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
# A run owns its output directory (a second run into it is refused): each
# call of this script writes to a new one, named by the scene and the time.
outdir="output/$(basename "$scene" .prm)-$(date +%Y%m%d-%H%M%S)"
echo "softsand run: output in $outdir"
if [ "$ranks" -gt 1 ]; then
  # Ctrl-C stops after the step with a checkpoint (mpirun alone would kill).
  bash scripts/mpirun_stoppable.sh "$ranks" build/softsand "$scene" \
    --set "output/directory=$outdir"
else
  build/softsand "$scene" --set "output/directory=$outdir"
fi
