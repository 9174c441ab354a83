#!/usr/bin/env python3
"""softsand against OpenFOAM (v1912, simpleFoam on snappyHexMesh body-fitted
meshes) on the same scenes, each as a refinement series, on 1 and 2 ranks.

Cases (--cases, default all):
  sphere_re0.1, sphere_re50  fixed sphere d = 1 mm in a 10 d box, the stream
                             imposed on the inlet and the lateral faces,
                             pressure outlet (parameters/drag_sphere.prm);
                             drag coefficient
  sc0.216, sc0.343           simple-cubic array, a row of 5 cells with
                             symmetry planes, flow-rate inlet, pressure
                             outlet (parameters/sc_permeability.prm);
                             permeability against Zick & Homsy (1982)
  pack13                     the 13-grain piece of the Fig. 3 pack
                             (parameters/studies/pack_piece_refinement.prm);
                             permeability
Both codes run a steady solver (softsand: one Stokes solve, or Newton for
steady Navier-Stokes at Re 50; OpenFOAM: SIMPLEC iterations to its residual
control). The reference is Zick & Homsy for the arrays; for the sphere and
the pack, OpenFOAM's three finest runs extrapolated (Aitken), or where they
do not converge monotonically the finest run of either code (named in the
output).

For each run it prints cells, unknowns (softsand: DoFs; OpenFOAM: 4 per
cell), iterations (softsand: FGMRES, summed over Newton steps; OpenFOAM:
SIMPLE iterations to its residual control, and in parentheses those after
which the result stays within 0.1 % of its last value), the wall time of
mesh generation (softsand: its `mesh` timer; OpenFOAM: blockMesh +
snappyHexMesh (+ decomposePar)) and of the rest (OpenFOAM: in parentheses
the share of the solve up to that settled iteration), the peak resident
memory of the largest rank, the result and its error; then the ratio of
wall times at equal error (1 % and 3 %), interpolated log-log along each
series: OpenFOAM's wall / softsand's, so a ratio above 1 means softsand is
faster. OpenFOAM's wall there is mesh generation plus the solve up to the
settled iteration: as if its stopping test knew the answer, the most
favourable reading for OpenFOAM.

Results are kept in <workdir>/results.json: a rerun skips what is there
(delete the file or use --rerun to measure again), so a long series can be
run in pieces.

  python3 scripts/benchmarks/benchmark_vs_openfoam.py [--cases sphere_re0.1,sc0.216]
      [--ranks 1,2] [--workdir output/benchmark_vs_openfoam] [--rerun]
      [--no-openfoam] [--table-only]

Needs build/softsand. OpenFOAM is an optional benchmark dependency:
`apt-get install openfoam` (Debian 12: OpenFOAM v1912); see
benchmarks/openfoam/README.md. Without it (or with --no-openfoam) only
softsand's rows are filled.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))  # prm_tools
sys.path.insert(0, os.path.join(ROOT, 'benchmarks', 'openfoam'))
import prm_tools  # noqa: E402
import foam_case  # noqa: E402

MU, RHO = 1e-3, 1000.
# Zick & Homsy (1982), Table 2, simple cubic: F = 6 pi mu a K U.
ZICK_HOMSY = {0.216: 7.442, 0.343: 15.4}
PEAK = os.path.join(HERE, 'peak_memory.py')
SETTLED = 1e-3
FOAM_ENV = dict(os.environ, WM_PROJECT_DIR='/usr/share/openfoam')


def pack13():
    """The grains (x, y, z, r) of the 13-grain piece, read from
    parameters/studies/pack_piece_refinement.prm."""
    text = open(os.path.join(ROOT, 'parameters', 'studies',
                             'pack_piece_refinement.prm')).read()
    m = re.search(r'set list = (.*)', text)
    grains = [tuple(map(float, g.split(','))) for g in m.group(1).split(';')]
    return grains


def cases():
    d = 1e-3
    out = {}
    for re_ in (0.1, 50.):
        U = re_ * MU / (RHO * d)
        v = (U, 0, 0)
        out['sphere_re%g' % re_] = dict(
            kind='sphere', re=re_, U=U, quantity='drag_coefficient',
            prm='drag_sphere.prm', softsand_n=(4, 6, 8, 12, 16),
            # OpenFOAM: 2 background cells per d, refined 1..5 times
            foam=[dict(blocks=(20, 20, 20), level=l)
                  for l in (1, 2, 3, 4, 5)],
            lo=(-5e-3,) * 3, hi=(5e-3,) * 3, spheres=[(0, 0, 0, 5e-4)],
            faces={'x min': ('velocity', v), 'x max': ('pressure', 0),
                   'y min': ('velocity', v), 'y max': ('velocity', v),
                   'z min': ('velocity', v), 'z max': ('velocity', v)},
            d=d)
    s = 2e-4
    for c in (0.216, 0.343):
        dc = 2 * s * (3 * c / (4 * math.pi)) ** (1 / 3)
        Q = 4e-12
        dp_ref = 6 * math.pi * MU * (dc / 2) * ZICK_HOMSY[c] * 1e-4 / s ** 2
        out['sc%g' % c] = dict(
            kind='array', c=c, quantity='permeability',
            prm='sc_permeability.prm', softsand_n=(4, 8, 12, 16),
            foam=[dict(blocks=(15, 3, 3), level=l) for l in (1, 2, 3, 4)],
            lo=(0, 0, 0), hi=(1e-3, s, s),
            spheres=[((i + 0.5) * s, s / 2, s / 2, dc / 2) for i in range(5)],
            faces={'x min': ('flow rate', Q), 'x max': ('pressure', 0),
                   'y min': ('symmetry', None), 'y max': ('symmetry', None),
                   'z min': ('symmetry', None), 'z max': ('symmetry', None)},
            planes=(4e-4, 6e-4), area=s * s, flow_rate=Q, d=dc,
            reference=MU * 1e-4 * s / dp_ref, reference_name='Zick & Homsy')
    grains = pack13()
    mean_d = 2 * sum(g[3] for g in grains) / len(grains)
    out['pack13'] = dict(
        kind='pack', quantity='permeability',
        prm='studies/pack_piece_refinement.prm', softsand_n=(4, 6, 8, 12),
        foam=[dict(blocks=(12, 8, 2), level=l) for l in (1, 2, 3, 4)],
        lo=(-1e-4, 0, 0), hi=(5e-4, 4e-4, 1.1e-4), spheres=grains,
        faces={'x min': ('flow rate', 4.4e-11), 'x max': ('pressure', 0),
               'y min': ('no slip', None), 'y max': ('no slip', None),
               'z min': ('no slip', None), 'z max': ('no slip', None)},
        planes=(0.5e-4, 3.5e-4), area=4e-4 * 1.1e-4, flow_rate=4.4e-11,
        d=mean_d, inside=(-0.6e-4, 2.01e-4, 0.551e-4),
        # the .prm's own solid model (penalization, majority rule) and the
        # rigid nodes: they differ by 25 % here (doc/benchmark_vs_openfoam.md)
        variants={'softsand': [],
                  'softsand rigid nodes': [('fluid/solid model',
                                            'rigid nodes')]})
    return out


def peak_mb(stderr):
    values = [int(v) for v in re.findall(r'peak_memory_kB (\d+)', stderr)]
    return max(values) / 1024 if values else float('nan')


def mpi(ranks, cmd):
    return (['mpirun', '-np', str(ranks)] if ranks > 1 else []) + cmd


# ---------------------------------------------------------------- softsand
def run_softsand(case, code, n, ranks, workdir):
    base = open(os.path.join(ROOT, 'parameters', case['prm'])).read()
    # one solve per run, also from a .prm that sets up a convergence study
    ov = [('mesh/cells per diameter', '%g' % n),
          ('convergence study/knob', 'none')]
    ov += case.get('variants', {}).get(code, [])
    if case['kind'] == 'sphere' and case['re'] > 0.1:
        # as scripts/studies/study_drag.py: Newton with grad-div and the symmetric
        # Gauss-Seidel smoother, without which FGMRES does not converge
        ov += [('simulation control/mode', 'steady navier stokes'),
               ('fluid solver/grad div', '%g' % (RHO * case['U'] * case['d'])),
               ('fluid solver/grad div cell factor', '1'),
               ('fluid solver/velocity amg smoother',
                'symmetric gauss seidel')]
    if case['kind'] == 'sphere':
        v = '%g, 0, 0' % case['U']
        for face in ('x min', 'y min', 'y max', 'z min', 'z max'):
            ov.append(('boundary conditions/%s/velocity' % face, v))
    if case['kind'] == 'array':
        ov.append(('grains/diameter', '%.6g' % case['d']))
    name = '%s_n%g_r%d' % (code.replace(' ', '_'), n, ranks)
    outdir = os.path.join(workdir, name)
    text = base
    for path, value in ov + [('output/directory', outdir),
                             ('output/write vtu', 'false')]:
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(workdir, name + '.prm')
    with open(prm, 'w') as f:
        f.write(text)
    prm_tools.fresh_output(text, outdir)
    start = time.time()
    proc = subprocess.run(mpi(ranks, [sys.executable, PEAK,
                                      os.path.join(ROOT, 'build', 'softsand'),
                                      prm]),
                          capture_output=True, text=True, cwd=ROOT)
    wall = time.time() - start
    if proc.returncode != 0:
        return dict(failed=(proc.stderr.strip().splitlines() or ['?'])[-1])
    row = prm_tools.read_statistics(outdir)[-1]
    m = re.search(r'^\| mesh\s+\|\s+\d+\s+\|\s+([0-9.e+-]+)s', proc.stdout,
                  re.M)
    mesh = float(m.group(1)) if m else 0.
    iterations = row.get('total_linear_iterations',
                         row.get('linear_iterations', 0))
    return dict(n=n, cells=row['cells'], unknowns=row['dofs'],
                iterations=iterations,
                newton=row.get('nonlinear_iterations', 0),
                mesh=mesh, solve=wall - mesh, wall=wall,
                memory=peak_mb(proc.stderr),
                value=row[case['quantity']])


# ---------------------------------------------------------------- OpenFOAM
def foam(cmd, cwd, log):
    start = time.time()
    with open(os.path.join(cwd, log), 'w') as f:
        proc = subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.PIPE,
                              text=True, env=FOAM_ENV)
    if proc.returncode != 0:
        raise RuntimeError('%s failed (see %s/%s)' % (log[4:], cwd, log))
    return time.time() - start, peak_mb(proc.stderr)


def run_openfoam(case, series, ranks, workdir):
    level = series['level']
    name = 'openfoam_l%d_r%d' % (level, ranks)
    directory = os.path.join(workdir, name)
    shutil.rmtree(directory, ignore_errors=True)
    fc = foam_case.Case(case['lo'], case['hi'], series['blocks'],
                        case['spheres'], level, case['faces'], MU / RHO, RHO,
                        planes=case.get('planes', ()),
                        inside=case.get('inside'),
                        second_order_convection=case['kind'] == 'sphere'
                        and case['re'] > 1, ranks=ranks)
    fc.write(directory)
    par = ['-parallel'] if ranks > 1 else []
    try:
        t_block, m1 = foam([sys.executable, PEAK, 'blockMesh'], directory,
                           'log.blockMesh')
        t_decompose = 0
        if ranks > 1:
            t_decompose, _ = foam(['decomposePar', '-force'], directory,
                                  'log.decomposePar')
        t_snappy, m2 = foam(mpi(ranks, [sys.executable, PEAK, 'snappyHexMesh',
                                        '-overwrite'] + par), directory,
                            'log.snappyHexMesh')
        if ranks > 1:
            # the decomposed fields name the patches before snappyHexMesh
            # made the grains': the case's fields (patch names as regular
            # expressions, processor patches by setConstraintTypes) again
            for p in range(ranks):
                for field in ('U', 'p'):
                    shutil.copy(os.path.join(directory, '0', field),
                                os.path.join(directory, 'processor%d' % p,
                                             '0', field))
        t_solve, m3 = foam(mpi(ranks, [sys.executable, PEAK, 'simpleFoam']
                               + par), directory, 'log.simpleFoam')
    except RuntimeError as e:
        return dict(failed=str(e))
    log = open(os.path.join(directory, 'log.simpleFoam')).read()
    m = re.search(r'converged in (\d+) iterations', log)
    iterations = int(m.group(1)) if m else -1
    n_cells = foam_case.mesh_cells(directory)
    h = fc.smallest_cell()
    result = dict(n=case['d'] / h, level=level, cells=n_cells,
                  unknowns=4 * n_cells, iterations=iterations,
                  mesh=t_block + t_decompose + t_snappy, solve=t_solve,
                  wall=t_block + t_decompose + t_snappy + t_solve,
                  memory=max(m1, m2, m3), converged=bool(m))
    if case['quantity'] == 'drag_coefficient':
        area = math.pi * case['d'] ** 2 / 4
        history = [(n, f / (0.5 * RHO * case['U'] ** 2 * area))
                   for n, f in foam_case.force_history(directory)]
    else:
        history = foam_case.permeability_history(
            directory, case['planes'], case['flow_rate'] / case['area'], MU,
            RHO)
    result['value'] = history[-1][1]
    # SIMPLE stops on its residuals, long after the result has settled:
    # the iterations (and the share of the solve time) after which it stays
    # within 0.1 % of its last value, as if a stopping test knew the answer
    settled = foam_case.iterations_to_settle(history, SETTLED)
    result['iterations_settled'] = settled
    result['solve_settled'] = t_solve * settled / max(iterations, 1)
    result['wall_settled'] = result['mesh'] + result['solve_settled']
    return result


# ---------------------------------------------------------------- tables
def wall_at_error(rows, target, wall='wall'):
    """(wall time, bound, peak memory) at which the series, refined, reaches
    @p target error and stays below it: the time interpolated log-log between
    the two runs around it, the memory of the first run below it; None if
    it never does; bound '<=' if its coarsest run already does."""
    # in the order of refinement: softsand's adaptive meshes are not always
    # costlier at a larger N (fewer coarse cells)
    rows = sorted((dict(r, wall=r.get(wall, r['wall']))
                   for r in rows if 'error' in r), key=lambda r: r['n'])
    for i, r in enumerate(rows):
        if all(abs(s['error']) <= target for s in rows[i:]):
            if i == 0:
                return r['wall'], '<=', r['memory']
            a, b = rows[i - 1], r
            ea, eb = abs(a['error']), abs(b['error'])
            if ea <= eb or eb == 0:
                return b['wall'], '', b['memory']
            t = math.log(ea / target) / math.log(ea / eb)
            return (math.exp(math.log(a['wall']) +
                             t * (math.log(b['wall']) - math.log(a['wall']))),
                    '', b['memory'])
    return None, '', None


def extrapolated(series):
    """Aitken's extrapolation of the last three results of a series whose
    cell size halves from run to run, when they converge monotonically
    (successive differences of one sign, shrinking); else None."""
    if len(series) < 3:
        return None
    x1, x2, x3 = (r['value'] for r in series[-3:])
    d1, d2 = x2 - x1, x3 - x2
    if d1 == 0 or not 0 < d2 / d1 < 1:
        return None
    return x3 - d2 * d2 / (d2 - d1)


def report(name, case, results):
    rows = [r for r in results.values() if 'value' in r]
    if 'reference' in case:
        ref, ref_name = case['reference'], case['reference_name']
    elif rows:
        finest = max(rows, key=lambda r: (r['n'], r['code'] == 'openfoam'))
        ref = finest['value']
        ref_name = 'finest run (%s, N = %.3g)' % (finest['code'], finest['n'])
        # that code's series on one rank, extrapolated, where it can be
        series = sorted((r for r in rows if r['code'] == finest['code']
                         and r['ranks'] == 1), key=lambda r: r['n'])
        better = extrapolated(series) if finest['code'] == 'openfoam' else None
        if better is not None:
            ref = better
            ref_name = ('%s extrapolated from its N = %s (Aitken)' % (
                finest['code'], ', '.join('%.3g' % r['n']
                                          for r in series[-3:])))
    else:
        ref, ref_name = None, 'none'
    for r in rows:
        r['error'] = r['value'] / ref - 1
    print('\n### %s: %s, reference %s = %.5g\n' % (
        name, case['quantity'], ref_name, ref or float('nan')))
    print('| code | ranks | N | cells | unknowns | iterations | mesh [s] | '
          'rest [s] | peak MB/rank | %s | error |' % case['quantity'])
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    for key in sorted(results, key=lambda k: (results[k]['code'],
                                              results[k]['ranks'],
                                              results[k].get('n', 0))):
        r = results[key]
        if 'failed' in r:
            print('| %s | %d | %s | failed: %s |' % (r['code'], r['ranks'],
                                                     key, r['failed']))
            continue
        iters = ('%d' % r['iterations'] if r['code'] == 'openfoam' else
                 '%d (%d Newton)' % (r['iterations'], r['newton'])
                 if r.get('newton', 1) > 1 else '%d' % r['iterations'])
        if r['code'] == 'openfoam':
            if not r.get('converged', True):
                iters += ' (not converged)'
            if 'iterations_settled' in r:
                iters += ' (%d)' % r['iterations_settled']
        rest = '%.1f' % r['solve']
        if 'solve_settled' in r:
            rest += ' (%.1f)' % r['solve_settled']
        print('| %s | %d | %.3g | %d | %d | %s | %.1f | %s | %.0f | %.5g | '
              '%+.2f%% |' % (r['code'], r['ranks'], r['n'], r['cells'],
                             r['unknowns'], iters, r['mesh'], rest,
                             r['memory'], r['value'], 100 * r['error']))
    softsand_codes = list(case.get('variants', {'softsand': []}))
    print('\nWall time and peak memory per rank at equal error; OpenFOAM '
          'stopped when its result settles (as if its stopping test knew '
          'the answer), and in the last column at its residual control.\n')
    print('| softsand | ranks | error | softsand wall [s] | MB | '
          'OpenFOAM wall [s] | MB | OpenFOAM / softsand | '
          'same, OpenFOAM to residual control |')
    print('|---|---|---|---|---|---|---|---|---|')
    for ranks in sorted({r['ranks'] for r in rows}):
        for target in (0.01, 0.03):
            w = {}
            for code in softsand_codes + ['openfoam']:
                w[code] = wall_at_error([r for r in rows if r['code'] == code
                                         and r['ranks'] == ranks], target,
                                        'wall_settled')
            full = wall_at_error([r for r in rows if r['code'] == 'openfoam'
                                  and r['ranks'] == ranks], target)

            def ratio(of, ss):
                if not (of[0] and ss[0]):
                    return '-'
                text = '%.2f' % (of[0] / ss[0])
                return text + (' (bound)' if of[1] or ss[1] else '')
            for code in softsand_codes:
                cells = []
                for c in (code, 'openfoam'):
                    t, bound, memory = w[c]
                    cells.append('not reached | -' if t is None else
                                 '%s%.1f | %.0f' % (bound, t, memory))
                print('| %s | %d | %g %% | %s | %s | %s | %s |' % (
                    code, ranks, 100 * target, cells[0], cells[1],
                    ratio(w['openfoam'], w[code]), ratio(full, w[code])))


def main():
    all_cases = cases()
    ap = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--cases', default=','.join(all_cases))
    ap.add_argument('--ranks', default='1,2')
    ap.add_argument('--workdir', default='output/benchmark_vs_openfoam')
    ap.add_argument('--rerun', action='store_true',
                    help='measure again what results.json holds')
    ap.add_argument('--rerun-openfoam', action='store_true',
                    help='measure the OpenFOAM runs again')
    ap.add_argument('--no-openfoam', action='store_true')
    ap.add_argument('--table-only', action='store_true',
                    help='print the tables of results.json, run nothing')
    ap.add_argument('--softsand-n', default=None,
                    help='cells per diameter of the softsand series '
                    '(default: per case)')
    ap.add_argument('--openfoam-levels', default=None,
                    help='snappyHexMesh surface levels (default: per case)')
    a = ap.parse_args()
    workdir = os.path.abspath(a.workdir)
    os.makedirs(workdir, exist_ok=True)
    store = os.path.join(workdir, 'results.json')
    results = json.load(open(store)) if os.path.exists(store) else {}
    have_foam = shutil.which('simpleFoam') is not None and not a.no_openfoam
    if not have_foam and not a.no_openfoam and not a.table_only:
        print('OpenFOAM not found (apt-get install openfoam): softsand only')
    for name in a.cases.split(','):
        if name not in all_cases:
            raise SystemExit("--cases: unknown case '%s' (allowed: %s)" % (
                name, ', '.join(all_cases)))
        case = all_cases[name]
        case_dir = os.path.join(workdir, name)
        os.makedirs(case_dir, exist_ok=True)
        done = results.setdefault(name, {})
        for ranks in map(int, a.ranks.split(',')):
            if a.table_only:
                break
            ns = (list(map(float, a.softsand_n.split(',')))
                  if a.softsand_n else case['softsand_n'])
            jobs = [(code, n) for code in case.get('variants', {'softsand': []})
                    for n in ns]
            if have_foam:
                levels = (list(map(int, a.openfoam_levels.split(',')))
                          if a.openfoam_levels else
                          [s['level'] for s in case['foam']])
                jobs += [('openfoam', l) for l in levels]
            for code, k in jobs:
                key = '%s_%g_r%d' % (code, k, ranks)
                again = a.rerun or (a.rerun_openfoam and code == 'openfoam')
                if key in done and 'failed' not in done[key] and not again:
                    continue
                if code != 'openfoam':
                    r = run_softsand(case, code, k, ranks, case_dir)
                else:
                    series = dict(case['foam'][0], level=k)
                    r = run_openfoam(case, series, ranks, case_dir)
                r.update(code=code, ranks=ranks)
                done[key] = r
                print('%s %s: %s' % (name, key, json.dumps(r)), flush=True)
                with open(store, 'w') as f:
                    json.dump(results, f, indent=1)
        report(name, case, done)


if __name__ == '__main__':
    main()
