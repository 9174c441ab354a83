#!/usr/bin/env python3
"""Throughput of one steady penalized solve: DoFs per second per core of
the fixed-sphere scene (parameters/drag_sphere.prm) on 1 and 2 ranks, for
both solid models and both linear solvers, over Theta. Time = the whole
run (mesh, setup, assembly, solve); 'solve' = the FGMRES phase alone
(preconditioner setup and iterations) from the run's timer table.

  python3 scripts/benchmarks/benchmark_fluid.py [--n 24] [--box 10] [--ranks 1,2]
      [--solvers matrix free,matrix based] [--thetas 1e6]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--n', default='24')
    ap.add_argument('--box', type=float, default=10)
    ap.add_argument('--ranks', default='1,2')
    ap.add_argument('--models', default='rigid nodes,penalization')
    ap.add_argument('--solvers', default='matrix free')
    ap.add_argument('--thetas', default='1e6')
    ap.add_argument('--workdir', default='output/benchmark_fluid')
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'drag_sphere.prm')).read()
    softsand = os.path.join(ROOT, 'build', 'softsand')
    h = a.box * 1e-3 / 2
    print('| linear solver | solid model | Theta | N | ranks | DoFs | '
          'iterations | wall [s] | DoFs/s/core | F/(3 pi mu d U) |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for solver in a.solvers.split(','):
        for model in a.models.split(','):
            for theta in a.thetas.split(','):
                for n in a.n.split(','):
                    for ranks in map(int, a.ranks.split(',')):
                        name = '%s_%s_t%s_n%s_np%d' % (
                            solver.replace(' ', '_'), model.replace(' ', '_'),
                            theta, n, ranks)
                        row, wall, err = prm_tools.run(
                            softsand, base, a.workdir, name, ranks,
                            [('mesh/cells per diameter', n),
                             ('mesh/lower corner', '%g, %g, %g' % (-h, -h, -h)),
                             ('mesh/upper corner', '%g, %g, %g' % (h, h, h)),
                             ('fluid/solid model', model),
                             ('fluid/theta', theta),
                             ('fluid solver/linear solver', solver)])
                        if row is None:
                            print('| %s | %s | %s | %s | %d | failed: %s |' %
                                  (solver, model, theta, n, ranks, err),
                                  flush=True)
                            continue
                        print('| %s | %s | %s | %s | %d | %d | %d | %.1f | '
                              '%.3g | %.5f |' % (
                                  solver, model, theta, n, ranks, row['dofs'],
                                  row['linear_iterations'], wall,
                                  row['dofs'] / wall / ranks,
                                  row.get('stokes_drag_ratio',
                                          row.get('drag_coefficient', 0))),
                              flush=True)


if __name__ == '__main__':
    main()
