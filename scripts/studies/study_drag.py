#!/usr/bin/env python3
"""Drag on a fixed sphere (parameters/drag_sphere.prm) against cells per
diameter N, box size L/d and Reynolds number; box-size extrapolation
F(L) = F_inf + a d/L from the two largest boxes. Prints a markdown table.

  python3 scripts/studies/study_drag.py [--re 0.1,1,10] [--n 4,8,12,16]
                                [--box 10,20,40] [--ranks 1]
                                [--grad-div auto] [--smoother auto]

Re > 0.1 runs steady Navier-Stokes (Newton from a Stokes solve) with
grad-div gamma = rho U d + rho |u| h per cell and the symmetric
Gauss-Seidel AMG smoother ('auto'), without which FGMRES does not converge
at Re = 50 and 100 (nor at Re = 10 in a 40 d box).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def clift_grace_weber(re):
    """Standard drag curve (Clift, Grace & Weber, Bubbles, Drops and Particles, 1978, Table 5.2)."""
    if re <= 20:
        return 24 / re * (1 + 0.1315 * re ** (0.82 - 0.05 * math.log10(re)))
    return 24 / re * (1 + 0.1935 * re ** 0.6305)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--re', default='0.1')
    ap.add_argument('--n', default='4,8,12,16')
    ap.add_argument('--box', default='10,20,40')
    ap.add_argument('--theta', default='1e6')
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--refinement', default='adaptive')
    ap.add_argument('--solid-model', default='rigid nodes',
                    help="'rigid nodes' or 'penalization'")
    ap.add_argument('--grad-div', default='auto',
                    help="gamma in Pa s, or 'auto': rho U d for Navier-Stokes "
                    "runs, 0 for Stokes")
    ap.add_argument('--grad-div-cell-factor', default='auto',
                    help="c in gamma = grad div + c rho |u| h; 'auto': 1 for "
                    "Navier-Stokes runs, 0 for Stokes")
    ap.add_argument('--smoother', default='auto',
                    help="velocity AMG smoother; 'auto': symmetric gauss "
                    "seidel for Navier-Stokes runs, chebyshev for Stokes")
    ap.add_argument('--workdir', default='output/study_drag')
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'drag_sphere.prm')).read()
    softsand = os.path.join(ROOT, 'build', 'softsand')
    d, mu, rho = 1e-3, 1e-3, 1000.
    print('Solid model: %s, Theta %s, %s refinement, %d rank(s)\n' % (
        a.solid_model, a.theta, a.refinement, a.ranks))
    print('| Re | N | L/d | cells | DoFs | Newton | FGMRES (all) | wall [s] | '
          'Cd | F/(3 pi mu d U) |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    results = {}
    for re in map(float, a.re.split(',')):
        U = re * mu / (rho * d)
        for n in map(float, a.n.split(',')):
            for box in map(float, a.box.split(',')):
                h = box * d / 2
                v = '%g, 0, 0' % U
                stokes = re <= 0.1
                gamma = ('0' if stokes else '%g' % (rho * U * d)) \
                    if a.grad_div == 'auto' else a.grad_div
                cell_factor = ('0' if stokes else '1') \
                    if a.grad_div_cell_factor == 'auto' \
                    else a.grad_div_cell_factor
                smoother = ('chebyshev' if stokes else
                            'symmetric gauss seidel') \
                    if a.smoother == 'auto' else a.smoother
                ov = [('mesh/lower corner', '%g, %g, %g' % (-h, -h, -h)),
                      ('mesh/upper corner', '%g, %g, %g' % (h, h, h)),
                      ('mesh/cells per diameter', '%g' % n),
                      ('mesh/refinement', a.refinement),
                      ('fluid/theta', a.theta),
                      ('fluid/solid model', a.solid_model),
                      ('fluid solver/grad div', gamma),
                      ('fluid solver/grad div cell factor', cell_factor),
                      ('fluid solver/velocity amg smoother', smoother),
                      ('simulation control/mode',
                       'steady stokes' if stokes else
                       'steady navier stokes')]
                for face in ('x min', 'y min', 'y max', 'z min', 'z max'):
                    ov.append(('boundary conditions/%s/velocity' % face, v))
                name = 're%g_n%g_box%g' % (re, n, box)
                row, wall, err = prm_tools.run(softsand, base, a.workdir, name,
                                               a.ranks, ov)
                if row is None:
                    print('| %g | %g | %g | failed: %s |' % (re, n, box, err))
                    continue
                results[(re, n, box)] = row
                print('| %g | %g | %g | %d | %d | %d | %d | %.1f | %.5g | %.5g |' % (
                    re, n, box, row['cells'], row['dofs'],
                    row['nonlinear_iterations'],
                    row['total_linear_iterations'], wall, row['drag_coefficient'],
                    row['stokes_drag_ratio']), flush=True)
    boxes = sorted(map(float, a.box.split(',')))
    if len(boxes) >= 2:
        print('\nBox extrapolation F_inf = (L2 F(L2) - L1 F(L1)) / (L2 - L1) '
              'from the two largest boxes:\n')
        print('The last two columns use the largest box alone (no '
              'correction).\n')
        print('| Re | N | Cd extrapolated | reference | error | '
              'Cd largest box | error |')
        print('|---|---|---|---|---|---|---|')
        l1, l2 = boxes[-2], boxes[-1]
        for re in map(float, a.re.split(',')):
            ref = 24 / re if re <= 0.1 else clift_grace_weber(re)
            for n in map(float, a.n.split(',')):
                if (re, n, l1) in results and (re, n, l2) in results:
                    c1 = results[(re, n, l1)]['drag_coefficient']
                    c2 = results[(re, n, l2)]['drag_coefficient']
                    cinf = (l2 * c2 - l1 * c1) / (l2 - l1)
                    print('| %g | %g | %.5g | %.5g | %+.2f%% | %.5g | %+.2f%% |'
                          % (re, n, cinf, ref, 100 * (cinf / ref - 1), c2,
                             100 * (c2 / ref - 1)), flush=True)


if __name__ == '__main__':
    main()
