#!/usr/bin/env python3
"""Dense-pack fluid solver benchmark (doc/notes/solver_study.md).

For each problem and each candidate solver setting it runs build/softsand
once per rank count and prints: DoFs, FGMRES iterations, preconditioner
setup and solve wall time (from the run's timer table), the whole run's wall
time, peak resident memory per rank (scripts/benchmarks/peak_memory.py), bytes per DoF
(peak memory summed over ranks / DoFs), effective DoFs/s per core
(DoFs / ((setup + solve) x ranks)), and the quantity of interest with its
relative error against a reference solve (--reference: linear tolerance
1e-10 with the first candidate).

Problems (--problems):
  hele_shaw        parameters/hele_shaw.prm, first coupled step (2,000
                   grains, 2 cells per mean diameter), QoI radial K
  hele_shaw_small  parameters/hele_shaw_small.prm, same (quick)
  fig3             parameters/pack_permeability.prm, N = --fig3-n (6), QoI K
  sphere           drag_sphere.prm, penalization, Theta --sphere-theta
                   (1e12), N = --sphere-n (12), QoI drag force
  sc               sc_permeability.prm (rigid nodes) at solid fraction
                   --sc-c (0.45), N = --sc-n (16), QoI K
With --steps S > 1 the coupled problems run S steps and print each step's
iterations and wall time (later steps: warm start, kept preconditioner).

Candidates (--candidates, comma separated):
  cc     matrix based, Cahouet-Chabard Schur approximation (old default)
  mf     matrix free, Cahouet-Chabard (steady Stokes without pressure
         regions only)
  db     matrix based, discrete Brinkman: mu M^-1 + (B D^-1 B^T + C)^-1
  lsc    matrix based, least-squares commutator X^-1 B D^-1 A D^-1 B^T X^-1
  mflsc  matrix free (geometric multigrid for A), least-squares commutator
         with A and B applied matrix free, only X assembled
  NAME:entry=value;entry=value   your own (entries as in the .prm)
Each candidate may take '+entry=value' additions after it, e.g.
'lsc+fluid solver/velocity amg sweeps=4'.

  python3 scripts/benchmarks/benchmark_dense_solver.py --problems hele_shaw_small \\
      --candidates cc,db,lsc --ranks 1,2 [--reference] [--steps 3]
"""
import argparse
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402  (also sets the MPI environment)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CANDIDATES = {
    'cc': [('fluid solver/linear solver', 'matrix based'),
           ('fluid solver/schur complement', 'cahouet chabard')],
    'mf': [('fluid solver/linear solver', 'matrix free'),
           ('fluid solver/schur complement', 'cahouet chabard')],
    'db': [('fluid solver/linear solver', 'matrix based'),
           ('fluid solver/schur complement', 'discrete brinkman')],
    'lsc': [('fluid solver/linear solver', 'matrix based'),
            ('fluid solver/schur complement', 'least squares commutator')],
    'mflsc': [('fluid solver/linear solver', 'matrix free'),
              ('fluid solver/schur complement', 'least squares commutator')],
}


def problems(a):
    """name -> (prm file, overrides, quantity of interest column)."""
    coupled = [('simulation control/max time steps', str(a.steps)),
               ('output/output interval', '1000000')]
    return {
        # The Stokes solves of the study (the scenes themselves are
        # transient since stop 28; the study's settings before it).
        'hele_shaw': ('parameters/hele_shaw.prm', coupled + [
            ('coupling/fluid model', 'quasi-steady'),
            ('simulation control/time step', '1e-3'),
            ('fluid/free contact cells', 'automatic'),
            ('fluid solver/linear tolerance', '3e-5')],
            'radial_permeability'),
        'hele_shaw_small': ('parameters/hele_shaw_small.prm', coupled + [
            ('coupling/fluid model', 'quasi-steady'),
            ('simulation control/time step', '1e-3')],
            'radial_permeability'),
        'fig3': ('parameters/pack_permeability.prm',
                 [('mesh/cells per diameter', str(a.fig3_n))], 'permeability'),
        'sc': ('parameters/sc_permeability.prm',
               [('mesh/cells per diameter', str(a.sc_n)),
                ('grains/diameter', '%.10g' % (
                    2 * 2e-4 * (3 * a.sc_c / (4 * 3.141592653589793)) **
                    (1. / 3)))], 'permeability'),
        'sphere': ('parameters/drag_sphere.prm',
                   [('mesh/cells per diameter', str(a.sphere_n)),
                    ('fluid/solid model', 'penalization'),
                    ('fluid/theta', a.sphere_theta)], 'grain_force_x'),
    }


def candidate_overrides(spec):
    parts = spec.split('+')
    head, extra = parts[0], parts[1:]
    if ':' in head:
        name, entries = head.split(':', 1)
        extra = entries.split(';') + extra
        overrides = []
    elif head in CANDIDATES:
        overrides = list(CANDIDATES[head])
    else:
        raise SystemExit("--candidates: unknown candidate '%s' (known: %s, "
                         "or NAME:entry=value;...)" %
                         (head, ', '.join(CANDIDATES)))
    return overrides + prm_tools.parse_set([e for e in extra if e])


def run(a, problem, spec, ranks, tolerance=None):
    prm, overrides, qoi = problems(a)[problem]
    text = open(os.path.join(ROOT, prm)).read()
    overrides = list(overrides) + candidate_overrides(spec)
    if tolerance is not None:
        overrides += [('fluid solver/linear tolerance', tolerance),
                      ('fluid solver/max linear iterations', '20000')]
    if a.linear_tolerance and tolerance is None:
        overrides += [('fluid solver/linear tolerance', a.linear_tolerance)]
    name = re.sub(r'[^A-Za-z0-9_.=-]+', '_', '%s_%s_np%d%s' % (
        problem, spec, ranks, '_ref' if tolerance else ''))
    outdir = os.path.join(a.workdir, name)
    overrides += [('output/directory', outdir), ('output/write vtu', 'false'),
                  ('output/verbosity', 'normal')]
    for path, value in overrides:
        text = prm_tools.set_entry(text, path, value)
    os.makedirs(a.workdir, exist_ok=True)
    prm_file = os.path.join(a.workdir, name + '.prm')
    with open(prm_file, 'w') as f:
        f.write(text)
    prm_tools.fresh_output(text, outdir)
    cmd = [sys.executable, os.path.join(ROOT, 'scripts', 'benchmarks', 'peak_memory.py'),
           os.path.join(ROOT, 'build', 'softsand'), prm_file]
    if ranks > 1:
        cmd = ['mpirun', '-np', str(ranks)] + cmd
    start = time.time()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    wall = time.time() - start
    with open(os.path.join(a.workdir, name + '.log'), 'w') as f:
        f.write(proc.stdout + proc.stderr)
    peaks = [int(m) for m in
             re.findall(r'peak_memory_kB (\d+)', proc.stderr)]
    result = {'name': name, 'wall': wall, 'peak_kB': max(peaks or [0]),
              'sum_kB': sum(peaks), 'ranks': ranks, 'qoi_name': qoi}
    if proc.returncode != 0:
        errors = [l for l in (proc.stdout + proc.stderr).splitlines()
                  if 'error' in l.lower()]
        result['error'] = (errors or ['exit %d' % proc.returncode])[-1][:160]
        return result
    rows = prm_tools.read_statistics(outdir)
    timers = prm_tools.timer_sections(proc.stdout)
    result.update(rows=rows, dofs=int(rows[0]['dofs']),
                  iterations=int(rows[0]['linear_iterations']),
                  qoi=rows[0][qoi], timers=timers,
                  setup=timers.get('fluid: preconditioner setup', (0, 0.)),
                  solve=timers.get('fluid: solve', (0, 0.))[1])
    return result


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument('--problems', default='hele_shaw_small,fig3,sphere')
    ap.add_argument('--candidates', default='cc,db,lsc')
    ap.add_argument('--ranks', default='1')
    ap.add_argument('--steps', type=int, default=1)
    ap.add_argument('--fig3-n', type=int, default=6)
    ap.add_argument('--sphere-n', type=int, default=12)
    ap.add_argument('--sphere-theta', default='1e12')
    ap.add_argument('--sc-c', type=float, default=0.45)
    ap.add_argument('--sc-n', type=int, default=16)
    ap.add_argument('--linear-tolerance', default=None,
                    help='override the scenes\' fluid solver/linear tolerance')
    ap.add_argument('--reference', action='store_true',
                    help='first solve each problem to 1e-10 with the first '
                         'candidate and report the QoI error against it')
    ap.add_argument('--workdir', default='output/benchmark_dense_solver')
    a = ap.parse_args()
    for p in a.problems.split(','):
        if p not in problems(a):
            raise SystemExit("--problems: unknown problem '%s' (known: %s)" %
                             (p, ', '.join(problems(a))))
    if a.steps < 1:
        raise SystemExit('--steps must be >= 1 (it was %d)' % a.steps)
    candidates = a.candidates.split(',')
    for c in candidates:
        candidate_overrides(c)
    ranks = [int(r) for r in a.ranks.split(',')]

    print('| problem | candidate | ranks | DoFs | FGMRES | setup [s] | '
          'solve [s] | run wall [s] | peak MB/rank | B/DoF | DoFs/s/core | '
          'QoI | error vs 1e-10 |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|---|')
    for problem in a.problems.split(','):
        reference = None
        if a.reference:
            r = run(a, problem, candidates[0], ranks[-1], tolerance='1e-10')
            if 'error' in r:
                print('| %s | reference (%s, 1e-10) | failed: %s |' %
                      (problem, candidates[0], r['error']), flush=True)
            else:
                reference = r['qoi']
                print('| %s | reference (%s, 1e-10) | %d | %d | %d | | | '
                      '%.0f | | | | %.6e | 0 |' % (
                          problem, candidates[0], r['ranks'], r['dofs'],
                          r['iterations'], r['wall'], reference), flush=True)
        for spec in candidates:
            for n in ranks:
                r = run(a, problem, spec, n)
                if 'error' in r:
                    print('| %s | %s | %d | failed: %s | | | | %.0f |' % (
                        problem, spec, n, r['error'], r['wall']), flush=True)
                    continue
                setup_calls, setup = r['setup']
                # Matrix based: the setup is timed inside the solve section.
                matrix_free = ('fluid solver/linear solver', 'matrix free') \
                    in candidate_overrides(spec)
                solve = r['solve'] if matrix_free else r['solve'] - setup
                per_step = None
                if a.steps > 1:
                    # Per-step wall from the statistics' wall_time column.
                    walls = [row['wall_time'] for row in r['rows']]
                    steps = [walls[0]] + [b - c for b, c in
                                          zip(walls[1:], walls[:-1])]
                    its = [int(row['linear_iterations']) for row in r['rows']]
                    per_step = ', '.join('%d its %.0f s' % (i, w)
                                         for i, w in zip(its, steps))
                # DoFs per second and core over all the solves of the run.
                throughput = (r['dofs'] * len(r['rows']) /
                              ((setup + solve) * n))
                error = ('%.2e' % (abs(r['qoi'] - reference) / abs(reference))
                         if reference else '')
                print('| %s | %s | %d | %d | %s | %.1f (%d) | %.1f | %.0f | '
                      '%.0f | %.0f | %.3g | %.6e | %s |' % (
                          problem, spec, n, r['dofs'],
                          per_step or r['iterations'], setup, setup_calls,
                          solve, r['wall'], r['peak_kB'] / 1024.,
                          r['sum_kB'] * 1024. / r['dofs'], throughput,
                          r['qoi'], error), flush=True)


if __name__ == '__main__':
    main()
