#!/usr/bin/env python3
"""The transient step's cost, old and new solver back to back
(doc/notes/solver_study.md, "The transient matrix-free step").

Runs a transient scene (default: the Hele-Shaw injection) with each value of
'fluid solver/transient solver' in turn (and, with --linear-tolerances, each
value of 'fluid solver/linear tolerance' with each), --repeat times,
alternating, for --steps coupling steps each, and prints per run and as medians over the
repeats:
  - seconds per coupled step, the median over the steps after the first
    (the statistics' wall_time column);
  - each timer section per step (the run's timer table over its steps);
  - peak resident memory per rank (scripts/benchmarks/peak_memory.py) and bytes per DoF
    (summed over ranks);
  - FGMRES iterations per step;
  - the radial flow rate and the largest fluid force on a grain of the last
    step, their relative difference against the first run's, and the
    largest difference of one grain's force against the first run's,
    relative to the largest force.

  python3 scripts/benchmarks/benchmark_transient_step.py --cells-per-diameter 2.66 \\
      --pressure 16000 --steps 11 --ranks 2 --repeat 1
  python3 scripts/benchmarks/benchmark_transient_step.py \\
      --scene parameters/hele_shaw_small.prm --cells-per-diameter 2.66 \\
      --ranks 1 --end-time 1e-3
  python3 scripts/benchmarks/benchmark_transient_step.py --cells-per-diameter 2.66 \
      --steps 6 --solvers new --linear-tolerances 1e-8,1e-6,1e-5,1e-4
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402  (also sets the MPI environment)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOLVERS = {'old': 'matrix based', 'new': 'matrix free'}


def grain_forces(directory):
    """{grain: (fx, fy, fz)} from <directory>/grain_forces.txt ({} if
    absent)."""
    path = os.path.join(directory, 'grain_forces.txt')
    if not os.path.exists(path):
        return {}
    forces, columns = {}, None
    for line in open(path):
        parts = line.split()
        if line.startswith('#'):
            columns = [parts[1:].index(c) for c in ('fx', 'fy', 'fz')
                       if c in parts[1:]]
            continue
        if parts and columns:
            forces[int(parts[0])] = [float(parts[c]) for c in columns]
    return forces


def norm(f):
    return sum(v * v for v in f) ** 0.5


def largest_force_difference(forces, reference):
    """max over grains |F - F_ref|, relative to max |F_ref|."""
    common = [g for g in reference if g in forces]
    largest = max([norm(reference[g]) for g in common] or [0.])
    if largest == 0.:
        return 0.
    return max(norm([x - y for x, y in zip(forces[g], reference[g])])
               for g in common) / largest


def run(a, label, repeat):
    text = open(os.path.join(ROOT, a.scene)).read()
    name = '%s_%d' % (label.replace('@', '_tol'), repeat)
    solver, _, tolerance = label.partition('@')
    outdir = os.path.join(a.workdir, name)
    if os.path.exists(outdir):
        subprocess.run(['rm', '-rf', outdir], check=True)
    overrides = [('fluid solver/transient solver', SOLVERS[solver]),
                 ('output/directory', outdir),
                 ('output/write vtu', 'false'),
                 ('output/output interval', '1000000'),
                 ('output/verbosity', 'normal'),
                 ('coupling/fluid model', 'transient')]
    if tolerance:
        overrides.append(('fluid solver/linear tolerance', tolerance))
    if a.steps:
        overrides.append(('simulation control/max time steps', str(a.steps)))
    if a.end_time:
        overrides.append(('simulation control/end time', a.end_time))
    if a.cells_per_diameter:
        overrides.append(('mesh/cells per diameter', a.cells_per_diameter))
    if a.pressure:
        overrides.append(('boundary conditions/inlet region/pressure',
                          a.pressure))
    overrides += prm_tools.parse_set(a.set or [])
    for path, value in overrides:
        text = prm_tools.set_entry(text, path, value)
    os.makedirs(a.workdir, exist_ok=True)
    prm_file = os.path.join(a.workdir, name + '.prm')
    with open(prm_file, 'w') as f:
        f.write(text)
    cmd = [sys.executable, os.path.join(ROOT, 'scripts', 'benchmarks', 'peak_memory.py'),
           os.path.join(ROOT, a.build, 'softsand'), prm_file]
    if a.ranks > 1:
        cmd = ['mpirun', '-np', str(a.ranks)] + cmd
    start = time.time()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    wall = time.time() - start
    with open(os.path.join(a.workdir, name + '.log'), 'w') as f:
        f.write(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        lines = (proc.stdout + proc.stderr).strip().splitlines()
        raise SystemExit('%s failed (exit %d): %s; log in %s' % (
            name, proc.returncode, ' / '.join(lines[-3:]),
            os.path.join(a.workdir, name + '.log')))
    rows = prm_tools.read_statistics(outdir)
    peaks = [int(m) for m in re.findall(r'peak_memory_kB (\d+)', proc.stderr)]
    walls = [r['wall_time'] for r in rows]
    steps = [b - c for b, c in zip(walls[1:], walls[:-1])]
    timers = prm_tools.timer_sections(proc.stdout)
    n = len(rows)
    flow = rows[-1].get('radial_flow_rate', rows[-1].get('flow_rate', 0.))
    forces = grain_forces(outdir)
    return {
        'name': name, 'wall': wall, 'steps': n, 'dofs': int(rows[-1]['dofs']),
        'step_median': statistics.median(steps) if steps else walls[0],
        'first_step': walls[0],
        'iterations': [int(r['linear_iterations']) for r in rows],
        'peak_MB': max(peaks or [0]) / 1024.,
        'bytes_per_dof': sum(peaks) * 1024. / int(rows[-1]['dofs']),
        'timers': {k: v[1] / n for k, v in timers.items() if k != 'total'},
        'flow': flow, 'force': max([norm(f) for f in forces.values()] or [0.]),
        'forces': forces}


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument('--scene', default='parameters/hele_shaw.prm')
    ap.add_argument('--cells-per-diameter', default=None)
    ap.add_argument('--pressure', default='16000',
                    help='inlet pressure (Pa); empty: the scene\'s')
    ap.add_argument('--steps', type=int, default=11,
                    help='coupling steps per run (0: the scene\'s end time)')
    ap.add_argument('--end-time', default=None)
    ap.add_argument('--ranks', type=int, default=2)
    ap.add_argument('--repeat', type=int, default=1)
    ap.add_argument('--solvers', default='old,new',
                    help='comma-separated: old (matrix based), new (matrix '
                         'free); the first is the reference of the '
                         'differences')
    ap.add_argument('--linear-tolerances', default='',
                    help='comma-separated values of \'fluid solver/linear '
                         'tolerance\' run with each solver (empty: the '
                         'scene\'s); the first is the reference')
    ap.add_argument('--build', default='build')
    ap.add_argument('--workdir', default='output/benchmark_transient_step')
    prm_tools.add_set_argument(ap, 'the scene')
    a = ap.parse_args()
    solvers = a.solvers.split(',')
    for solver in solvers:
        if solver not in SOLVERS:
            raise SystemExit("--solvers: unknown '%s' (known: %s)" %
                             (solver, ', '.join(SOLVERS)))
    tolerances = [t for t in a.linear_tolerances.split(',') if t]
    for t in tolerances:
        try:
            ok = 0. < float(t) < 1.
        except ValueError:
            ok = False
        if not ok:
            raise SystemExit("--linear-tolerances: '%s' is not a number in "
                             "(0, 1)" % t)
    labels = [s + ('@' + t if t else '') for s in solvers
              for t in (tolerances or [''])]
    if a.repeat < 1 or a.ranks < 1:
        raise SystemExit('--repeat and --ranks must be >= 1')
    if not os.path.exists(os.path.join(ROOT, a.build, 'softsand')):
        raise SystemExit('no %s/softsand: build first (bash scripts/setup.sh)'
                         % a.build)
    results = {label: [] for label in labels}
    for repeat in range(a.repeat):
        for label in labels:
            r = run(a, label, repeat)
            results[label].append(r)
            print('%s: %d steps, %d DoFs, %.1f s per step (first %.1f), '
                  'FGMRES %s, peak %.0f MB/rank, %.0f B/DoF, Q %.6e, '
                  'largest grain force %.6e N' % (
                      r['name'], r['steps'], r['dofs'], r['step_median'],
                      r['first_step'], r['iterations'], r['peak_MB'],
                      r['bytes_per_dof'], r['flow'], r['force']), flush=True)
    print()
    print('| solver | s per step (median) | peak MB/rank | B/DoF | '
          'FGMRES per step | Q [m^3/s] | largest grain force [N] | '
          'dQ vs %s | dF vs %s | max dF per grain vs %s |' % (
              labels[0], labels[0], labels[0]))
    print('|---|---|---|---|---|---|---|---|---|---|')
    ref = results[labels[0]][0]
    for label in labels:
        rs = results[label]
        med = statistics.median
        q, f = rs[0]['flow'], rs[0]['force']
        print('| %s (%s) | %.2f | %.0f | %.0f | %.1f | %.6e | %.6e | %.2e | '
              '%.2e | %.2e |' % (
                  label, SOLVERS[label.partition('@')[0]],
                  med([r['step_median'] for r in rs]),
                  med([r['peak_MB'] for r in rs]),
                  med([r['bytes_per_dof'] for r in rs]),
                  statistics.mean(rs[0]['iterations']), q, f,
                  abs(q - ref['flow']) / max(abs(ref['flow']), 1e-300),
                  abs(f - ref['force']) / max(abs(ref['force']), 1e-300),
                  largest_force_difference(rs[0]['forces'], ref['forces'])))
    print()
    sections = sorted({k for label in labels for r in results[label]
                       for k in r['timers']})
    print('| timer section, s per step (median) | ' +
          ' | '.join(labels) + ' |')
    print('|---|' + '---|' * len(labels))
    for s in sections:
        print('| %s | ' % s + ' | '.join(
            '%.2f' % statistics.median([r['timers'].get(s, 0.)
                                        for r in results[label]])
            for label in labels) + ' |')


if __name__ == '__main__':
    main()
