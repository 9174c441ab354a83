#!/usr/bin/env bash
# Test 'extremes_quick': the cheap subset of scripts/checks/extremes_suite.py
# (--quick), then scripts/checks/scan_outputs.py over every output of it, and
# negative controls (the scanner must flag a NaN and an Inf in text tables
# and in compressed binary VTU arrays), and an argument after the parameter
# file refused with a message.
# Usage: extremes_quick.sh SOURCE_DIR SOFTSAND WORKDIR
set -euo pipefail
src=$1 softsand=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$src"
python3 scripts/checks/extremes_suite.py --quick --softsand "$softsand" \
  --workdir "$work/suite"
python3 scripts/checks/scan_outputs.py "$work/suite"
mkdir -p "$work/control"
printf '# a b\n1 nan\n' > "$work/control/statistics.txt"
printf '# a b\n1 -inf\n' > "$work/control/grain_forces.txt"
if python3 scripts/checks/scan_outputs.py "$work/control" > "$work/control.log"; then
  echo "scan_outputs.py missed a NaN/Inf"; exit 1
fi
grep -c 'control/' "$work/control.log"
python3 tests/tools/scan_outputs_control.py "$work/vtu_control"
# Arguments after the parameter file are refused, not dropped.
if "$softsand" parameters/drag_sphere.prm extra.prm > "$work/extra_args.log" 2>&1; then
  echo "softsand ran with an argument after the parameter file"; exit 1
fi
grep -q "unexpected argument 'extra.prm'" "$work/extra_args.log"
echo "extremes_quick: passed"
