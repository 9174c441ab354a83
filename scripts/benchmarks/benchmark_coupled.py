#!/usr/bin/env python3
"""Cost of a coupled CFD-DEM step against grains and cells, on 1 and 2
ranks, and the quasi-steady fluid model against the transient one.

The scene: grains settling together in a closed box of glycerol-like
liquid (rho_f = 1000 kg/m^3, mu = 1 Pa s, d = 1 mm, rho_s = 2650 kg/m^3:
creeping flow, Re ~ 1e-3, where both fluid models apply), a random loose
pack of n^3 grains (solid fraction 0.1) in a box of edge n * 2.2 d. Both
models run the same physical time; the trajectories are compared at the
end (largest grain position difference over d, and the mean settling
velocity of each). Wall time per coupling step is the mean of the
statistics' wall_time increments after the first step.

  python3 scripts/benchmarks/benchmark_coupled.py [--grains 2,3,4] [--ranks 1,2]
                                       [--n 4] [--steps 6]
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
SOFTSAND = os.path.join(ROOT, 'build', 'softsand')

SCENE = """set dimension = 3
subsection simulation control
  set mode = coupled
  set time scheme = BDF2
end
subsection grains
  set source = random
  set size distribution = constant
  set diameter = 1e-3
  set seed = 1
end
subsection dem
  set gravity = 0, 0, -9.81
  subsection material
    set density = 2650
    set youngs modulus = 5e6
    set poisson ratio = 0.15
  end
  subsection walls
    set box = all
  end
end
subsection fluid
  set density = 1000
  set viscosity = 1
  set theta = 1e6
  set solid model = rigid nodes
  # Both fluid models alike (automatic frees them in the transient one only).
  set free contact cells = true
end
"""


def read_grains(directory):
    grains = []
    with open(os.path.join(directory, 'final_pack.txt')) as f:
        for line in f:
            if line.strip() and not line.startswith('#'):
                v = [float(x) for x in line.split()]
                grains.append(v[:3] + v[4:7])
    return grains


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--grains', default='2,3,4', help='n: n^3 grains')
    ap.add_argument('--ranks', default='1,2')
    ap.add_argument('--n', default='4', help='cells per diameter')
    ap.add_argument('--steps', type=int, default=6)
    ap.add_argument('--dt', type=float, default=1e-4, help='transient fluid step (s)')
    ap.add_argument('--solid-model', default='rigid nodes')
    ap.add_argument('--schur', default='cahouet chabard',
                    help='fluid solver/schur complement')
    ap.add_argument('--force-model', default='penalization reaction')
    ap.add_argument('--tolerance', default='1e-5',
                    help='FGMRES tolerance: with rigid nodes on settling grains in '
                    'the closed box FGMRES stalls near 1.5e-11 absolute, '
                    '1e-6 relative of the right-hand side')
    ap.add_argument('--workdir', default=os.path.join(ROOT, 'output/benchmark_coupled'))
    a = ap.parse_args()
    print('| grains | model | ranks | cells | DoFs | steps | s per step | s per step per 1e5 DoFs |')
    print('|---|---|---|---|---|---|---|---|')
    compare = []
    for n in map(int, a.grains.split(',')):
        edge = n * 2.2e-3
        end = a.steps * a.dt
        finals = {}
        for model in ('transient', 'quasi-steady'):
            for ranks in map(int, a.ranks.split(',')):
                name = 'g%d_%s_np%d' % (n ** 3, model, ranks)
                over = [('mesh/lower corner', '0, 0, 0'),
                        ('mesh/upper corner', '%g, %g, %g' % (edge, edge, edge)),
                        ('mesh/cells per diameter', a.n),
                        ('grains/count', n ** 3),
                        ('grains/region lower corner', '0, 0, 0'),
                        ('grains/region upper corner', '%g, %g, %g' % (edge, edge, edge)),
                        ('simulation control/time step', a.dt),
                        ('simulation control/end time', end),
                        ('coupling/fluid model', model),
                        ('fluid/solid model', a.solid_model),
                        ('fluid solver/linear tolerance', a.tolerance),
                        ('fluid solver/schur complement', a.schur),
                        ('coupling/force model', a.force_model),
                        ('dem/save pack', 'final_pack.txt')]
                row, wall, err = prm_tools.run(SOFTSAND, SCENE, a.workdir, name, ranks, over)
                if row is None:
                    print('| %d | %s | %d | failed: %s |' % (n ** 3, model, ranks, err), flush=True)
                    continue
                rows = prm_tools.read_statistics(os.path.join(a.workdir, name))
                walls = [r['wall_time'] for r in rows]
                per_step = (walls[-1] - walls[0]) / max(1, len(walls) - 1)
                print('| %d | %s | %d | %d | %d | %d | %.2f | %.2f |'
                      % (n ** 3, model, ranks, row['cells'], row['dofs'], len(rows), per_step,
                         per_step / row['dofs'] * 1e5), flush=True)
                if ranks == int(a.ranks.split(',')[0]):
                    finals[model] = (read_grains(os.path.join(a.workdir, name)), per_step)
        if len(finals) == 2:
            t, q = finals['transient'][0], finals['quasi-steady'][0]
            diff = max(math.dist(g[:3], h[:3]) for g, h in zip(t, q)) / 1e-3
            vt = sum(g[5] for g in t) / len(t)
            vq = sum(g[5] for g in q) / len(q)
            compare.append((n ** 3, finals['transient'][1] / finals['quasi-steady'][1], diff, vt, vq))
    if compare:
        print('\n| grains | cost transient / quasi-steady per step | max position difference / d '
              '| mean v_z transient (m/s) | quasi-steady |')
        print('|---|---|---|---|---|')
        for c in compare:
            print('| %d | %.2f | %.2e | %.3e | %.3e |' % c)


if __name__ == '__main__':
    main()
