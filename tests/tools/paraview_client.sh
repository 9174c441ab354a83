#!/usr/bin/env bash
# Test 'paraview_client': a small coupled run on 2 ranks (one grain
# settling across the rank boundary, parameters/studies/extremes/
# coupled_sphere.prm), opened in ParaView by scripts/checks/check_paraview.py.
# Usage: paraview_client.sh SOURCE_DIR SOFTSAND PVPYTHON WORKDIR
set -euo pipefail
src=$1 softsand=$2 pvpython=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cd "$src"
source scripts/mpi_env.sh
sed "s|set directory = .*|set directory = $work/run|" \
  parameters/studies/extremes/coupled_sphere.prm > "$work/run.prm"
mpirun -np 2 "$softsand" "$work/run.prm" > "$work/run.log" 2>&1
"$pvpython" scripts/checks/check_paraview.py "$work/run/solution.pvd" \
  "$work/run/grains.pvd" --range void_fraction=0:1 \
  --range velocity=0:1e-2 2>/dev/null
