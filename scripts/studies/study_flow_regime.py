#!/usr/bin/env python3
"""The fluid models of an injection against each other (issue: Hele-Shaw in
the right flow regime). Runs parameters/hele_shaw_small.prm (250 grains,
coupled) with

  quasi-steady     steady Stokes-Brinkman per coupling step (creeping flow)
  transient        the paper's BDF2 marching at --transient-dt

at one inlet pressure and viscosity, and prints per model: the pore
Reynolds numbers, the radial flow rate Q and permeability at the end, the
grains' displacement from their start (mean and largest), its RMS
difference from the reference model's (--reference, default transient),
and the wall time.

  python3 scripts/studies/study_flow_regime.py [--pressure 1000] [--viscosity 1e-3]
      [--end-time 3e-3] [--transient-dt 1e-4] [--models quasi-steady,
      transient] [--ranks 1]
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
MODELS = {'quasi-steady': 'quasi-steady', 'transient': 'transient'}


def read_grains(path):
    """Grain id -> centre from a pack file or grain_forces.txt."""
    grains = {}
    with open(path) as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            v = line.split()
            if len(v) < 4:
                continue
            grains[len(grains)] = tuple(map(float, v[1:4])) \
                if 'grain_forces' in path else tuple(map(float, v[0:3]))
    return grains


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--pressure', type=float, default=1000)
    ap.add_argument('--viscosity', type=float, default=1e-3)
    ap.add_argument('--end-time', type=float, default=3e-3)
    ap.add_argument('--coupling-dt', type=float, default=1e-3)
    ap.add_argument('--transient-dt', type=float, default=1e-4)
    ap.add_argument('--models', default='quasi-steady,transient')
    ap.add_argument('--reference', default='transient')
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--workdir', default='output/study_flow_regime')
    prm_tools.add_set_argument(ap, 'parameters/hele_shaw_small.prm')
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'hele_shaw_small.prm')).read()
    softsand = os.path.join(ROOT, 'build', 'softsand')
    start = read_grains(os.path.join(ROOT, 'parameters', 'packs',
                                     'hele_shaw_small.txt'))
    results = {}
    for key in a.models.split(','):
        dt = a.transient_dt if key == 'transient' else a.coupling_dt
        overrides = [('coupling/fluid model', MODELS[key]),
                     ('fluid/viscosity', '%g' % a.viscosity),
                     ('boundary conditions/inlet region/pressure',
                      '%g' % a.pressure),
                     ('simulation control/time step', '%g' % dt),
                     ('simulation control/end time', '%g' % a.end_time),
                     ('output/output interval', '1000000')] + \
            prm_tools.parse_set(a.set)
        name = '%s_p%g_mu%g' % (key, a.pressure, a.viscosity)
        row, wall, err = prm_tools.run(softsand, base, a.workdir, name,
                                       a.ranks, overrides)
        if row is None:
            print('%s failed: %s' % (key, err))
            continue
        rows = prm_tools.read_statistics(os.path.join(a.workdir, name))
        grains = read_grains(os.path.join(a.workdir, name, 'grain_forces.txt'))
        results[key] = (rows, wall, grains)

    print('Inlet %g Pa, viscosity %g Pa s, to t = %g s; coupling step %g s '
          '(quasi-steady models), fluid step %g s (transient); %d rank(s)\n'
          % (a.pressure, a.viscosity, a.end_time, a.coupling_dt,
             a.transient_dt, a.ranks))
    print('| model | steps | Re_p max | Re_p p95 | Re_p superficial | Q [m^3/s] '
          '| K [m^2] | mean / max grain displacement [m] | RMS difference '
          'from %s [m] | FGMRES total | wall [s] |' % a.reference)
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    ref = results.get(a.reference)
    for key, (rows, wall, grains) in results.items():
        last = rows[-1]
        disp = [math.dist(grains[g], start[g]) for g in grains if g in start]
        diff = ''
        if ref is not None and key != a.reference:
            d = [math.dist(grains[g], ref[2][g]) ** 2
                 for g in grains if g in ref[2]]
            diff = '%.3g' % math.sqrt(sum(d) / len(d))
        iterations = sum(r.get('total_linear_iterations', 0) for r in rows)
        print('| %s | %d | %.3g | %.3g | %.3g | %.4g | %.4g | %.3g / %.3g | %s '
              '| %d | %.0f |'
              % (MODELS[key], len(rows), last.get('pore_reynolds_max', 0),
                 last.get('pore_reynolds_p95', 0),
                 last.get('radial_pore_reynolds', 0),
                 last.get('radial_flow_rate', 0),
                 last.get('radial_permeability', 0),
                 sum(disp) / max(len(disp), 1), max(disp or [0]), diff,
                 iterations, wall))
    print('\n(grain positions: grain_forces.txt, the fluid solve of the last '
          'step; the pack file gives the start)')


if __name__ == '__main__':
    main()
