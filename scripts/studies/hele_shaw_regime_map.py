#!/usr/bin/env python3
"""Regime map of the radial Hele-Shaw injection: the critical inlet
pressure against the grains' cohesion and against the pistons' confining
pressure, in the dimensionless form of injection experiments (p_c over the
confining stress sigma).

  python3 scripts/studies/hele_shaw_regime_map.py --cohesions 0,1e5,3e5,1e6 \\
      --confining 2500,5000,10000 --cells-per-diameter 2.66

For each point (cohesion c, confining sigma) it prepares the scene's pack
with scripts/packs/make_hele_shaw_scene.py (stage 2 and the injection at c, every
stage at sigma), then runs scripts/studies/hele_shaw_sweep.py on it at inlet
pressures p_i = ratio x sigma for each of --ratios, and reads the critical
bracket from the sweep's table. Points: every cohesion at the middle
confining pressure, and every confining pressure at --reference-cohesion
(the scenes' 3e5 J/m^3). --wall-cohesion gives every pack its own
grain-wall cohesion (0: the pack, not the plates, carries the pistons'
load). Everything goes to --workdir/c<c>_s<sigma>/ (c<c>_w<wall>_s<sigma>/
with --wall-cohesion); a
point whose sweep finished is only read again, so the command resumes.
Options after '--' go to the sweep (e.g. -- --developed --stall-steps 40).
Prints and writes <workdir>/regime_map.txt: c, sigma, the bracket, its
geometric mean p_c and p_c / sigma, or FAILED and why (a pack that could
not be prepared, a sweep whose runs all failed). Run from the repository
root.
"""
import argparse
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def floats(text):
    return [float(v) for v in text.split(',') if v.strip()]


class PointFailed(Exception):
    """A point whose pack could not be prepared or whose runs all failed."""


def bracket(sweep_table):
    """(below, above) from a sweep.txt: None where the sweep did not
    bracket (every pressure fractured, or none)."""
    text = open(sweep_table).read()
    if 'no critical pressure' in text:
        raise PointFailed('every run of the sweep failed, see ' + sweep_table)
    m = re.search(r'critical pressure between (\S+) and (\S+) Pa', text)
    if m:
        return float(m.group(1)), float(m.group(2))
    m = re.search(r'critical pressure above (\S+) Pa', text)
    if m:
        return float(m.group(1)), None
    m = re.search(r'critical pressure below (\S+) Pa', text)
    if m:
        return None, float(m.group(1))
    sys.exit('no critical pressure line in ' + sweep_table)


def run_point(args, sweep_args, cohesion, sigma):
    walls = ('' if args.wall_cohesion is None else
             '_w%g' % args.wall_cohesion)
    point = os.path.join(args.workdir, 'c%g%s_s%g' % (cohesion, walls, sigma))
    scene = os.path.join(point, 'injection.prm')
    if not os.path.exists(scene):
        make = [sys.executable, os.path.join(HERE, '..', 'packs', 'make_hele_shaw_scene.py'),
                '--scale', args.scale, '--workdir', point,
                '--cohesion', '%g' % cohesion,
                '--confining-pressure', '%g' % sigma,
                '--softsand', args.softsand]
        if args.wall_cohesion is not None:
            make += ['--wall-cohesion', '%g' % args.wall_cohesion]
        made = subprocess.run(make)
        if made.returncode != 0:
            raise PointFailed('the pack could not be prepared, see the '
                              'stage logs in ' + point)
    sweep_dir = os.path.join(point, 'sweep')
    table = os.path.join(sweep_dir, 'sweep.txt')
    pressures = ','.join('%g' % (r * sigma) for r in args.ratios)
    cmd = [sys.executable, os.path.join(HERE, 'hele_shaw_sweep.py'),
           '--scene', scene, '--pressures', pressures,
           '--workdir', sweep_dir, '--jobs', str(args.jobs),
           '--softsand', args.softsand]
    if args.cells_per_diameter is not None:
        cmd += ['--cells-per-diameter', '%g' % args.cells_per_diameter]
    print('point c = %g J/m^3, sigma = %g Pa: %s' % (cohesion, sigma,
                                                    ' '.join(cmd)), flush=True)
    subprocess.run(cmd + sweep_args, check=True, stdout=subprocess.DEVNULL)
    return bracket(table)


def main():
    argv = sys.argv[1:]
    sweep_args = []
    if '--' in argv:
        sweep_args = argv[argv.index('--') + 1:]
        argv = argv[:argv.index('--')]
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--scale', default='small', choices=['small', 'default'])
    a.add_argument('--cohesions', type=floats, default=[0, 1e5, 3e5, 1e6])
    a.add_argument('--confining', type=floats, default=[2500, 5000, 10000])
    a.add_argument('--reference-cohesion', type=float, default=3e5)
    a.add_argument('--wall-cohesion', type=float, default=None,
                   help="grain-wall cohesion of every pack (J/m^3; default "
                        "the grains')")
    a.add_argument('--ratios', type=floats,
                   default=[0.2, 0.4, 0.8, 1.6, 3.2, 6.4],
                   help='inlet pressures as multiples of sigma')
    a.add_argument('--cells-per-diameter', type=float, default=None)
    a.add_argument('--jobs', type=int, default=1)
    a.add_argument('--workdir', default='output/hele_shaw_regime_map')
    a.add_argument('--softsand', default='build/softsand')
    args = a.parse_args(argv)
    if any(c < 0 for c in args.cohesions) or any(not s > 0 for s in args.confining):
        sys.exit('--cohesions must be >= 0 and --confining > 0')
    if args.wall_cohesion is not None and not args.wall_cohesion >= 0:
        sys.exit('--wall-cohesion must be >= 0, got %g' % args.wall_cohesion)
    middle = sorted(args.confining)[len(args.confining) // 2]
    points = [(c, middle) for c in args.cohesions]
    points += [(args.reference_cohesion, s) for s in args.confining
               if (args.reference_cohesion, s) not in points]
    os.makedirs(args.workdir, exist_ok=True)
    lines = ['# scale %s, cells per diameter %s, ratios %s, wall cohesion %s' %
             (args.scale, args.cells_per_diameter, args.ratios,
              "the grains'" if args.wall_cohesion is None
              else '%g' % args.wall_cohesion),
             '# cohesion[J/m^3] sigma[Pa] p_below[Pa] p_above[Pa] '
             'p_c[Pa] p_c/sigma']
    for c, s in points:
        try:
            below, above = run_point(args, sweep_args, c, s)
        except PointFailed as e:
            lines.append('%g %g FAILED: %s' % (c, s, e))
            print(lines[-1], flush=True)
            continue
        pc = (math.sqrt(below * above) if below and above else float('nan'))
        lines.append('%g %g %s %s %.4g %.3g' % (
            c, s, '-' if below is None else '%g' % below,
            '-' if above is None else '%g' % above, pc, pc / s))
        print(lines[-1], flush=True)
    with open(os.path.join(args.workdir, 'regime_map.txt'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
