#!/usr/bin/env bash
# Test 'restart_modes': restart in the two modes with a time loop besides
# the coupled one (kill_and_restart). Each scene runs on 2 ranks with a
# checkpoint interval and is killed by SIGKILL (no clean stop) after a
# checkpoint: the transient run from outside once the checkpoint is
# complete, the granular one (whose steps take microseconds: no outside
# kill lands between two given checkpoints) by itself right after it
# (SOFTSAND_SIGKILL_AFTER_CHECKPOINT). Rows and files written after the
# checkpoint are left behind. It is restarted from that checkpoint on 1
# rank and run to its end. Every statistics row must equal an uninterrupted 1-rank run's,
# the output series must continue without duplicates, and a checkpoint
# written by one mode must not restart another.
#  - granular: 18 grains in two layers falling on a floor (wall and
#    grain-grain contacts with tangential history), 260 DEM steps,
#    checkpoints every 50, killed after the checkpoint of step 100;
#  - transient: a fixed sphere in a channel, BDF2, 8 steps, checkpoints
#    every 2, killed once the checkpoint of step 4 is complete.
# Usage: restart_modes.sh SOURCE_DIR SOFTSAND WORKDIR
set -euo pipefail
src=$1 softsand=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"
source "$src/scripts/mpi_env.sh"
source "$src/tests/tools/sphere_in_stream.sh"
source "$src/tests/tools/kill_after_checkpoint.sh"

# Two 3 x 3 layers of 0.1 mm grains, the upper one above the lower one.
python3 - > layers.txt <<'PY'
for layer, z in enumerate((6e-5, 1.8e-4)):
    for i in range(3):
        for j in range(3):
            print(f'{(i - 1) * 1.5e-4} {(j - 1) * 1.5e-4} {z} 5e-5 '
                  f'{1e-3 * (i - 1)} 0 -0.1 0 {50. * (j - 1)} 0')
PY
printf '0 0 0 5e-4\n' > sphere.txt

granular() { # directory restart max_steps
  cat <<PRM
set dimension = 3
subsection simulation control
  set mode = granular
  set end time = 3.1e-4
  set max time steps = $3
  set checkpoint interval = 50
  set restart = $2
end
subsection mesh
  set lower corner = -3e-4, -3e-4, 0
  set upper corner = 3e-4, 3e-4, 6e-4
end
subsection grains
  set source = file
  set file = layers.txt
end
subsection dem
  set gravity = 0, 0, -9.81
  subsection material
    set density        = 2650
    set youngs modulus = 5e6
    set poisson ratio  = 0.15
    set restitution    = 0.7
    set friction       = 0.5
    set rolling friction = 0.1
  end
  subsection walls
    set box = z-
  end
  set statistics interval = 10
  set output interval = 50
end
subsection output
  set directory = $1
  set verbosity = quiet
end
PRM
}

transient() { # directory restart max_steps
  cat <<PRM
set dimension = 3
subsection simulation control
  set mode = transient
  set time step = 1e-3
  set end time = 8e-3
  set max time steps = $3
  set checkpoint interval = 2
  set restart = $2
end
PRM
  sphere_in_stream sphere.txt "$1"
}

for mode in granular transient; do
  case $mode in
    granular)  checkpoint=100 ;;
    transient) checkpoint=4 ;;
  esac
  $mode $mode-whole false 1000000 > $mode-whole.prm
  "$softsand" $mode-whole.prm > $mode-whole.log 2>&1
  $mode $mode-cut true 1000000 > $mode-cut-resume.prm
  if [ $mode = granular ]; then
    # DEM steps take microseconds: the run kills itself (SIGKILL) right
    # after the checkpoint of step 100.
    $mode $mode-cut false 1000000 > $mode-cut.prm
    if SOFTSAND_SIGKILL_AFTER_CHECKPOINT=$checkpoint \
       mpirun -x SOFTSAND_SIGKILL_AFTER_CHECKPOINT -np 2 "$softsand" \
         $mode-cut.prm > $mode-cut.log 2>&1; then
      echo "FAIL: $mode: the run was not killed"; exit 1
    fi
    step=$(head -1 $mode-cut/checkpoint.info | cut -d' ' -f1)
    [ "$step" = "$checkpoint" ] ||
      { echo "FAIL: $mode: checkpoint of step $step, expected $checkpoint"; exit 1; }
  else
    # Fluid steps take seconds: SIGKILL (no clean stop) once the
    # checkpoint of step 4 or later is complete, before the end (step 8).
    $mode $mode-cut false 1000000 > $mode-cut.prm
    mpirun -np 2 "$softsand" $mode-cut.prm > $mode-cut.log 2>&1 &
    kill_after_checkpoint $mode-cut $checkpoint $!
    step=$(head -1 $mode-cut/checkpoint.info | cut -d' ' -f1)
    [ "$step" -ge $checkpoint ] && [ "$step" -lt 8 ] ||
      { echo "FAIL: $mode: killed after the checkpoint of step $step"; exit 1; }
  fi
  [ "$(tail -1 $mode-cut/checkpoint.info)" = "mode $mode" ] ||
    { echo "FAIL: $mode: checkpoint.info does not name its mode"; exit 1; }
  "$softsand" $mode-cut-resume.prm > $mode-cut-resume.log 2>&1
  grep -q "resumed at step $step" $mode-cut-resume.log ||
    { echo "FAIL: $mode: no 'resumed at step $step'"; exit 1; }
  echo "$mode: killed (SIGKILL) after the checkpoint of step $step on 2 ranks, resumed on 1"
done

# A checkpoint of one mode does not restart another.
granular transient-cut true 1000000 > wrong-mode.prm
if "$softsand" wrong-mode.prm > wrong-mode.log 2>&1; then
  echo "FAIL: a transient checkpoint restarted a granular run"; exit 1
fi
grep -q "was written by a transient run" wrong-mode.log ||
  { echo "FAIL: no message naming the checkpoint's mode"; cat wrong-mode.log; exit 1; }
echo "a transient checkpoint refused by a granular run: yes"

python3 - <<'PY'
import sys
def table(path):
    # The names line, '#' lines (a column and its unit each), the rows.
    with open(path) as f:
        lines = [l for l in f if l.strip() and not l.startswith('#')]
    names = lines[0].split()
    return names, [dict(zip(names, map(float, l.split()))) for l in lines[1:]]
def files(pvd):
    return [l.split('file="')[1].split('"')[0] for l in open(pvd) if 'file="' in l]
# Solver effort and clocks differ after a restart (a new preconditioner,
# neighbour lists rebuilt when the restarted ranks see them stale);
# the physics must not: 1e-9 for the DEM (2 ranks against 1: round-off in
# the order of the force sums), 1e-6 for the fluid (Krylov iterates from
# a new preconditioner, within the solver tolerance).
for mode, rows_expected, tolerance, series in (
        ('granular', 20, 1e-9, ('grains.pvd', 'walls.pvd')),
        ('transient', 8, 1e-6, ('solution.pvd',))):
    names, whole = table(f'{mode}-whole/statistics.txt')
    _, rows = table(f'{mode}-cut/statistics.txt')
    if len(rows) != len(whole) or len(rows) < rows_expected:
        sys.exit(f'FAIL: {mode}: {len(rows)} rows, uninterrupted {len(whole)}, '
                 f'expected at least {rows_expected}')
    columns = [c for c in names
               if 'wall_time' not in c and 'iterations' not in c
               and c != 'neighbor_list_builds']
    largest = {c: max(abs(r[c]) for r in whole) for c in columns}
    # A vector's components are measured against the vector: the sphere's
    # transverse forces are round-off (1e-17 N against 1e-5 N along x).
    def scale(c):
        if c[-2:] in ('_x', '_y', '_z'):
            return max(largest.get(c[:-2] + e, 0.) for e in ('_x', '_y', '_z'))
        return largest[c]
    worst, where = 0., ''
    for a, b in zip(whole, rows):
        for c in columns:
            d = abs(a[c] - b[c]) / max(abs(a[c]), abs(b[c]),
                                       1e-2 * scale(c), 1e-300)
            if d > worst:
                worst, where = d, f'{c} at step {a["step"]:.0f}'
    print(f'{mode}: {len(rows)} rows, {len(columns)} columns, largest '
          f'relative difference {worst:.1e}' + (f' ({where})' if where else ''))
    if worst > tolerance:
        sys.exit(f'FAIL: {mode}: rows differ from the uninterrupted run')
    moving = [c for c in ('kinetic_energy', 'max_overlap_ratio',
                          'drag_force_x', 'pressure_drop') if c in columns]
    if not any(len({r[c] for r in whole}) > 2 for c in moving):
        sys.exit(f'FAIL: {mode}: nothing changes from row to row')
    for name in series:
        if files(f'{mode}-cut/{name}') != files(f'{mode}-whole/{name}'):
            sys.exit(f'FAIL: {mode}: {name} differs from the uninterrupted run')
print('output series continue: yes')
PY

# Ctrl-C on a 2-rank run (issue 55): mpirun alone kills the ranks, so
# scripts/mpirun_stoppable.sh keeps mpirun out of the terminal's reach and
# turns SIGINT or SIGTERM into SIGUSR1: the ranks finish their step, write
# a checkpoint and exit with 75. SIGTERM here (a background job ignores
# SIGINT), once the first step's row is written.
transient stopped false 1000000 > stopped.prm
setsid bash "$src/scripts/mpirun_stoppable.sh" 2 "$softsand" stopped.prm \
  > stopped.log 2>&1 &
wrapper=$!
for i in $(seq 1 600); do
  rows=$(grep -cv '^#' stopped/statistics.txt 2> /dev/null || true)
  [ "${rows:-0}" -ge 1 ] && break
  sleep 0.2
done
kill -TERM $wrapper
status=0
wait $wrapper || status=$?
[ $status = 75 ] ||
  { echo "FAIL: stopped run exited with $status, not 75"; cat stopped.log; exit 1; }
step=$(head -1 stopped/checkpoint.info | cut -d' ' -f1)
[ "$step" -ge 1 ] && [ "$step" -lt 8 ] ||
  { echo "FAIL: stopped run's checkpoint is of step $step"; exit 1; }
grep -q "Stopped on request after step $step" stopped.log ||
  { echo "FAIL: no 'Stopped on request' line"; cat stopped.log; exit 1; }
echo "2 ranks stopped by a signal to mpirun_stoppable.sh: exit 75, checkpoint of its last step"

