#!/usr/bin/env python3
"""Permeability of simple-cubic arrays (parameters/sc_permeability.prm) at
solid fractions with Zick & Homsy (1982) reference drags, against cells per
diameter, beside Kozeny-Carman. Prints a markdown table.

  python3 scripts/studies/study_permeability.py [--n 4,8] [--c 0.216,0.343,0.45]
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
# Zick & Homsy (1982), Table 2, simple cubic: F = 6 pi mu a K U.
ZICK_HOMSY = {0.027: 2.008, 0.064: 2.810, 0.125: 4.292, 0.216: 7.442,
              0.343: 15.4, 0.45: 28.1}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--n', default='4,8')
    ap.add_argument('--c', default='0.216,0.343,0.45')
    ap.add_argument('--solid-model', default='rigid nodes')
    ap.add_argument('--schur', default='cahouet chabard',
                    help="fluid solver/schur complement ('discrete brinkman' "
                         "for near-touching grains, with penalization)")
    ap.add_argument('--void-fraction-model', default='cell average',
                    help="coupling/void fraction model with penalization "
                         "('cell majority' or 'quadrature point')")
    ap.add_argument('--workdir', default='output/study_permeability')
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'sc_permeability.prm')).read()
    softsand = os.path.join(ROOT, 'build', 'softsand')
    s, mu, U = 2e-4, 1e-3, 1e-4
    print('Solid model: %s, Schur complement: %s, void fraction model: %s\n'
          % (a.solid_model, a.schur, a.void_fraction_model))
    print('| c | N | cells | DoFs | iterations | wall [s] | K [m^2] | '
          'K Zick-Homsy | error | K Kozeny-Carman |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for c in map(float, a.c.split(',')):
        d = 2 * s * (3 * c / (4 * math.pi)) ** (1 / 3)
        dp_ref = 6 * math.pi * mu * (d / 2) * ZICK_HOMSY[c] * U / s ** 2
        k_ref = mu * U * s / dp_ref
        phi = 1 - c
        k_kc = phi ** 3 * d ** 2 / (180 * (1 - phi) ** 2)
        for n in map(float, a.n.split(',')):
            row, wall, err = prm_tools.run(
                softsand, base, a.workdir, 'c%g_n%g' % (c, n), 1,
                [('grains/diameter', '%.6g' % d),
                 ('mesh/cells per diameter', '%g' % n),
                 ('fluid/solid model', a.solid_model),
                 ('fluid solver/schur complement', a.schur),
                 ('coupling/void fraction model', a.void_fraction_model)])
            if row is None:
                print('| %g | %g | failed: %s |' % (c, n, err))
                continue
            k = row['permeability']
            print('| %g | %g | %d | %d | %d | %.1f | %.4g | %.4g | %+.1f%% | '
                  '%.4g |' % (c, n, row['cells'], row['dofs'],
                              row['linear_iterations'], wall, k, k_ref,
                              100 * (k / k_ref - 1), k_kc), flush=True)


if __name__ == '__main__':
    main()
