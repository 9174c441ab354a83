#!/usr/bin/env python3
"""Stability at the extremes (issue 6): small scenes at the ends of each
parameter's range. Every case must either finish with finite, physically
sensible numbers or stop with a message naming the parameter; a crash, a
hang (time limit), a NaN/Inf in any output or an implausible number fails.

  python3 scripts/checks/extremes_suite.py                 # all cases
  python3 scripts/checks/extremes_suite.py --only theta    # names containing 'theta'
  python3 scripts/checks/extremes_suite.py --list

Base scenes: parameters/studies/extremes/*.prm (run from the repository
root). Prints a markdown table (case, what is varied, outcome, numbers,
wall time, CPU time of softsand and mpirun) and exits 1 if a case
failed. Outputs: output/extremes/<case>/.
"""
import argparse
import math
import os
import re
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402
import scan_outputs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BASE = os.path.join(ROOT, 'parameters', 'studies', 'extremes')

# The paper's grain (R = 0.05 mm, Y = 5e6 Pa, nu = 0.15, 2650 kg/m^3):
# Rayleigh time pi R sqrt(rho / G) / (0.1631 nu + 0.8766).
RAYLEIGH_TIME = (math.pi * 5e-5 * math.sqrt(2650 / (5e6 / (2 * 1.15))) /
                 (0.1631 * 0.15 + 0.8766))


def clift_grace_weber(re_number):
    """Standard drag curve (Clift, Grace & Weber 1978, Table 5.2); Stokes below 0.01."""
    if re_number <= 0.01:
        return 24 / re_number
    if re_number <= 20:
        return 24 / re_number * (1 + 0.1315 * re_number **
                                 (0.82 - 0.05 * math.log10(re_number)))
    return 24 / re_number * (1 + 0.1935 * re_number ** 0.6305)


def cohesive_rest_overlap(k, R=5e-5, Y=5e6, nu=0.15):
    """delta / R* where the Hertz force 4/3 Y* sqrt(R*) delta^(3/2) of two
    equal grains equals the cohesion k pi (R delta - delta^2 / 4)."""
    if k == 0:
        return 0.
    y_star, r_star = Y / (2 * (1 - nu * nu)), R / 2

    def f(d):
        return (4 / 3 * y_star * math.sqrt(r_star) * d ** 1.5 -
                k * math.pi * (R * d - d * d / 4))
    lo, hi = 1e-12 * R, 2 * R
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        (lo, hi) = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi) / r_star


class Case:
    def __init__(self, name, base, varied, overrides=(), ranks=1,
                 stop=None, check=None, timeout=900):
        self.name, self.base, self.varied = name, base, varied
        self.overrides, self.ranks = list(overrides), ranks
        self.stop = stop        # entry the stop message must name
        self.check = check      # results -> (ok, numbers text)
        self.timeout = timeout


def band(name, low, high, fmt='%.4g'):
    """A check that results[name] lies in [low, high]."""
    def check(r):
        v = r.get(name)
        if v is None:
            return False, '%s missing' % name
        return low <= v <= high, ('%s = ' + fmt) % (name, v)
    return check


def all_of(*checks):
    def check(r):
        oks, texts = zip(*(c(r) for c in checks))
        return all(oks), ', '.join(texts)
    return check


def ratio_to(name, reference, low, high, label):
    def check(r):
        v = r.get(name)
        if v is None:
            return False, '%s missing' % name
        return low <= v / reference <= high, '%s = %.4g (%s %.4g, ratio %.3f)' % (
            name, v, label, reference, v / reference)
    return check


def sphere_re(re_number):
    """Overrides of sphere.prm for Reynolds number re_number in a 10 d box
    (Navier-Stokes settings of scripts/studies/study_drag.py above Re = 0.1)."""
    d, mu, rho = 1e-3, 1e-3, 1000.
    U = re_number * mu / (rho * d)
    v = '%g, 0, 0' % U
    ov = [('mesh/lower corner', '-5e-3, -5e-3, -5e-3'),
          ('mesh/upper corner', '5e-3, 5e-3, 5e-3')]
    for face in ('x min', 'y min', 'y max', 'z min', 'z max'):
        ov.append(('boundary conditions/%s/velocity' % face, v))
    if re_number > 0.1:
        ov += [('simulation control/mode', 'steady navier stokes'),
               ('fluid solver/grad div', '%g' % (rho * U * d)),
               ('fluid solver/grad div cell factor', '1'),
               ('fluid solver/velocity amg smoother',
                'symmetric gauss seidel')]
    return ov


def cases():
    c = []
    stokes_band = band('stokes_drag_ratio', 0.8, 5.0)
    # Theta 1 .. 1e12, the paper's penalization.
    for theta in ('1', '1e3', '1e6', '1e9', '1e12'):
        c.append(Case('theta_%s' % theta, 'sphere', 'Theta = %s (penalization)'
                      % theta, [('fluid/theta', theta),
                                ('fluid/solid model', 'penalization')],
                      check=band('stokes_drag_ratio', 0.3, 5.0)))
    # Theta at both ends in a coupled run (transient fluid, a settling
    # sphere).
    for theta in ('1', '1e12'):
        c.append(Case('theta_%s_coupled' % theta, 'coupled_sphere',
                      'Theta = %s, coupled transient (penalization)' % theta,
                      [('fluid/theta', theta),
                       ('fluid/solid model', 'penalization'),
                       ('coupling/fluid model', 'transient')],
                      check=band('grain0_vz', -2e-3, -1e-6, '%.3g')))
    # 2 .. 32 cells per diameter (rigid nodes).
    for n in ('2', '4', '8', '16', '32'):
        c.append(Case('cells_per_diameter_%s' % n, 'sphere',
                      '%s cells per diameter' % n,
                      [('mesh/cells per diameter', n)], check=stokes_band))
    c.append(Case('cells_per_diameter_0.5', 'sphere',
                  '0.5 cells per diameter (grain smaller than a cell)',
                  [('mesh/cells per diameter', '0.5')],
                  stop='mesh/cells per diameter'))
    # Re 0.01 .. 200 (10 d box, 4 cells per diameter).
    for re_number in (0.01, 0.1, 1, 10, 100, 200):
        c.append(Case('reynolds_%g' % re_number, 'sphere',
                      'Re = %g (10 d box)' % re_number, sphere_re(re_number),
                      check=ratio_to('drag_coefficient',
                                     clift_grace_weber(re_number), 0.7, 1.6,
                                     'Clift-Grace-Weber')))
    # DEM time step against the Rayleigh time: restitution 0.7 kept.
    restitution = ratio_to('mean_speed', 0.1, 0.65, 0.75, 'approach speed')
    for label, fraction in (('tiny', 1e-3), ('at_limit', 0.3499)):
        c.append(Case('dem_dt_%s' % label, 'impact',
                      'DEM dt = %g T_R' % fraction,
                      [('dem/time step', '%.6g' % (fraction * RAYLEIGH_TIME))],
                      check=restitution))
    for label, fraction in (('above_limit', 0.5), ('far_above', 10)):
        c.append(Case('dem_dt_%s' % label, 'impact',
                      'DEM dt = %g T_R' % fraction,
                      [('dem/time step', '%.6g' % (fraction * RAYLEIGH_TIME))],
                      stop='dem/time step'))
    # Cohesion 0 .. 1e6 J/m^3: rest overlap against the closed form.
    # The pair starts at half the rest overlap (at most 0.25 R*, below
    # grains/max overlap ratio; touching for k = 0): the
    # cohesion pulls it in, damping brings it to rest.
    for k in (0, 1e3, 3e5, 1e6):
        expected = cohesive_rest_overlap(k)
        check = (band('max_overlap_ratio', 0, 1e-6, '%.3g') if k == 0 else
                 ratio_to('max_overlap_ratio', expected, 0.97, 1.03,
                          'closed form'))
        x = 5e-5 - min(0.5 * expected, 0.25) * 2.5e-5 / 2
        c.append(Case('cohesion_%g' % k, 'cohesive_pair',
                      'cohesion %g J/m^3' % k,
                      [('dem/material/cohesion energy density', '%g' % k),
                       ('grains/list', '%.12g, 0, 0, 5e-5; %.12g, 0, 0, 5e-5'
                        % (-x, x))],
                      check=check))
    # Touching and overlapping grains.
    c.append(Case('touching_grains_fluid', 'two_spheres',
                  'two spheres touching (gap 0) in a stream',
                  check=stokes_band))
    c.append(Case('overlapping_grains_fluid_small', 'two_spheres',
                  'two spheres overlapping by 0.2 R* (accepted below 0.3)',
                  [('grains/list', '0, -4.75e-4, 0, 5e-4; 0, 4.75e-4, 0, '
                    '5e-4')], check=stokes_band))
    c.append(Case('overlapping_grains_fluid_large', 'two_spheres',
                  'two spheres overlapping by 1 R*',
                  [('grains/list', '0, -3.75e-4, 0, 5e-4; 0, 3.75e-4, 0, '
                    '5e-4')], stop='grains/list'))
    c.append(Case('touching_grains_dem', 'cohesive_pair',
                  'two grains touching, no cohesion',
                  [('dem/material/cohesion energy density', '0'),
                   ('grains/list', '-5e-5, 0, 0, 5e-5; 5e-5, 0, 0, 5e-5')],
                  check=band('kinetic_energy', 0, 1e-30, '%.3g')))
    c.append(Case('overlapping_grains_dem', 'cohesive_pair',
                  'two grains overlapping by 0.2 R* (pushed apart)',
                  [('dem/material/cohesion energy density', '0'),
                   ('grains/list', '-4.75e-5, 0, 0, 5e-5; 4.75e-5, 0, 0, '
                    '5e-5')],
                  check=all_of(band('max_overlap_ratio', 0, 1e-6, '%.3g'),
                               ratio_to('mean_speed', 0.524, 0.3, 1.0,
                                        'elastic release speed'))))
    # Empty domains and single grains.
    c.append(Case('empty_fluid_domain', 'channel',
                  'fluid scene without grains (square duct)',
                  check=ratio_to('pressure_drop', 28.46 * 4e-3, 1.0, 2.0,
                                 'developed duct flow')))
    c.append(Case('empty_granular_domain', 'impact',
                  'granular scene without grains',
                  [('grains/source', 'none'), ('dem/time step', '1e-6')],
                  check=band('kinetic_energy', 0, 0, '%.3g')))
    c.append(Case('empty_granular_domain_automatic_dt', 'impact',
                  'granular scene without grains, automatic DEM step',
                  [('grains/source', 'none')], stop='dem/time step'))
    c.append(Case('empty_coupled_domain', 'coupled_sphere',
                  'coupled scene without grains',
                  [('grains/source', 'none'), ('dem/time step', '1e-6')],
                  check=band('grains', 0, 0, '%g')))
    c.append(Case('single_grain_fluid', 'sphere', 'one fixed sphere',
                  check=stokes_band))
    c.append(Case('single_grain_dem', 'impact', 'one grain hits a wall',
                  check=restitution))
    c.append(Case('single_grain_coupled', 'coupled_sphere',
                  'one grain settling (coupled)',
                  check=band('grain0_vz', -2e-3, -1e-6, '%.3g')))
    # Rank boundaries (2 ranks).
    c.append(Case('rank_boundary_fluid', 'sphere',
                  'sphere on the boundary of 2 ranks', ranks=2,
                  check=stokes_band))
    c.append(Case('rank_boundary_dem', 'granular_cross',
                  'grain crossing from rank 0 to rank 1 at 1 m/s', ranks=2,
                  check=all_of(band('mean_speed', 1 - 1e-9, 1 + 1e-9, '%.10g'),
                               band('lost_grains', 0, 0, '%g'))))
    c.append(Case('rank_boundary_coupled', 'coupled_sphere',
                  'settling grain on the boundary of 2 ranks', ranks=2,
                  check=band('grain0_vz', -2e-3, -1e-6, '%.3g')))
    # Grains leaving the domain.
    c.append(Case('grain_leaves_dem', 'granular_cross',
                  'grain leaves through x max', [('simulation control/end '
                                                  'time', '1.2e-3')],
                  check=band('lost_grains', 1, 1, '%g')))
    c.append(Case('grain_leaves_coupled', 'coupled_sphere',
                  'grain leaves through z min (coupled)',
                  [('grains/list', '0, 0, -1.9e-3, 5e-4'),
                   ('grains/velocity', '0, 0, -0.2'),
                   ('fluid/viscosity', '1e-3'),
                   ('simulation control/end time', '3e-3')],
                  check=band('grains', 0, 0, '%g')))
    return c


# The subset of test 'extremes_quick' (tests/CMakeLists.txt): a few
# seconds each on one core; every kind of outcome (finished, stopped with
# a message) and every mode (fluid, granular, coupled), 2 ranks included.
QUICK = ['theta_1e12', 'cells_per_diameter_2', 'cells_per_diameter_0.5',
         'dem_dt_at_limit', 'dem_dt_far_above', 'cohesion_1e+06',
         'overlapping_grains_fluid_large', 'overlapping_grains_dem',
         'empty_granular_domain_automatic_dt', 'empty_coupled_domain',
         'rank_boundary_dem', 'grain_leaves_dem']


def parse_results(stdout):
    """The 'Results' block a run prints: name -> value."""
    results, inside = {}, False
    for line in stdout.splitlines():
        if line.startswith('Results'):
            inside = True
            continue
        if inside:
            m = re.match(r'^\s+(\S+)\s+(\S+)(\s+\S+)?\s*$', line)
            if not m:
                if results:
                    inside = False
                continue
            try:
                results[m.group(1)] = float(m.group(2))
            except ValueError:
                results[m.group(1)] = float('nan')
    return results


def children_cpu_time():
    """User + system time of the finished child processes (s): softsand,
    or mpirun with its ranks."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_case(case, workdir, softsand):
    with open(os.path.join(BASE, case.base + '.prm')) as f:
        text = f.read()
    outdir = os.path.join(workdir, case.name)
    overrides = case.overrides + [('output/directory', outdir),
                                  ('output/write vtu', 'true'),
                                  ('output/verbosity', 'quiet')]
    for path, value in overrides:
        text = prm_tools.set_entry(text, path, value)
    os.makedirs(workdir, exist_ok=True)
    prm = os.path.join(workdir, case.name + '.prm')
    with open(prm, 'w') as f:
        f.write(text)
    prm_tools.fresh_output(text, outdir)
    cmd = [softsand, prm]
    if case.ranks > 1:
        cmd = ['mpirun', '-np', str(case.ranks)] + cmd
    # scripts/mpi_env.sh: Open MPI as root, 2 ranks on few cores, one
    # thread per rank.
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT='1',
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1',
               OMPI_MCA_rmaps_base_oversubscribe='1', OMP_NUM_THREADS='1',
               DEAL_II_NUM_THREADS='1')
    start = time.time()
    cpu_start = children_cpu_time()
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True,
                              timeout=case.timeout, env=env)
    except subprocess.TimeoutExpired:
        return 'FAIL', 'hang: no end within %d s' % case.timeout, \
            (time.time() - start, children_cpu_time() - cpu_start)
    wall = (time.time() - start, children_cpu_time() - cpu_start)
    with open(os.path.join(workdir, case.name + '.log'), 'w') as f:
        f.write(proc.stdout + proc.stderr)
    errors = [l for l in proc.stderr.splitlines()
              if l.startswith('softsand: error:')]
    if proc.returncode != 0:
        if proc.returncode < 0 or proc.returncode > 1 or not errors:
            tail = (proc.stderr.strip().splitlines() or [''])[-1]
            return 'FAIL', 'crash: exit %d, %s' % (proc.returncode,
                                                   tail[:200]), wall
        message = errors[0][len('softsand: error: '):]
        if case.stop and case.stop in message:
            return 'stopped', message, wall
        return 'FAIL', 'unexpected stop: ' + message, wall
    if case.stop:
        return 'FAIL', 'accepted; should stop naming %s' % case.stop, wall
    n_files, problems = scan_outputs.scan_directory(outdir)
    if problems:
        return 'FAIL', 'NaN/Inf: ' + '; '.join(problems[:3]), wall
    # The last statistics row, overridden by the printed Results block
    # (which leaves out some columns, e.g. 'grains' of a coupled run).
    results = {}
    try:
        rows = prm_tools.read_statistics(outdir)
        if rows:
            results.update(rows[-1])
    except (OSError, ValueError):
        pass
    results.update(parse_results(proc.stdout))
    bad = [k for k, v in results.items() if not math.isfinite(v)]
    if bad:
        return 'FAIL', 'non-finite result: ' + ', '.join(bad), wall
    ok, numbers = case.check(results) if case.check else (True, '')
    numbers += ' (%d files scanned)' % n_files
    return ('ok' if ok else 'FAIL'), \
        numbers if ok else 'implausible: ' + numbers, wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--only', default='', help='run cases whose name '
                    'contains one of these comma-separated strings')
    ap.add_argument('--list', action='store_true')
    ap.add_argument('--workdir', default='output/extremes')
    ap.add_argument('--softsand', default=os.path.join(ROOT, 'build',
                                                       'softsand'),
                    help='the executable (default: build/softsand)')
    ap.add_argument('--quick', action='store_true',
                    help='the cheap subset the test suite runs (%s)' %
                    ', '.join(QUICK))
    a = ap.parse_args()
    if a.quick:
        selected = [c for c in cases() if c.name in QUICK]
    else:
        selected = [c for c in cases() if not a.only or
                    any(s in c.name for s in a.only.split(','))]
    if a.list:
        for c in selected:
            print('%-40s %s' % (c.name, c.varied))
        return
    softsand = os.path.abspath(a.softsand)
    workdir = os.path.abspath(os.path.join(ROOT, a.workdir))
    print('| case | varied | ranks | outcome | numbers / message | '
          'wall [s] | CPU [s] |')
    print('|---|---|---|---|---|---|---|')
    failed = 0
    for case in selected:
        outcome, text, wall = run_case(case, workdir, softsand)
        failed += outcome == 'FAIL'
        print('| %s | %s | %d | %s | %s | %.1f | %.1f |' % (
            case.name, case.varied, case.ranks, outcome,
            text.replace('|', '/'), wall[0], wall[1]), flush=True)
    print('\n%d of %d cases failed' % (failed, len(selected)))
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
