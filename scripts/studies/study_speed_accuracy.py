#!/usr/bin/env python3
"""Speed against accuracy of adaptive and uniform refinement (issue 6).

Runs the convergence-study mode (subsection 'convergence study', knob
'cells per diameter') of a scene twice, with mesh/refinement = adaptive and
= uniform, reads both convergence tables, and reports the error of the
quantity against a reference (a separate finer adaptive run, or a given
value) against wall time: a markdown table, a plot, and the wall-time ratio
uniform / adaptive at equal accuracy.

  python3 scripts/studies/study_speed_accuracy.py --case drag
  python3 scripts/studies/study_speed_accuracy.py --case drag --box 4 \
      --adaptive 4,6,8,12,16 --uniform 4,6,8 --reference-n 24
  python3 scripts/studies/study_speed_accuracy.py --case pack --adaptive 3,4,5 \
      --uniform 3,4 --reference-n 6

Cost: CPU time of each run (--cost wall for wall time). Equal accuracy: the cost of a sequence at a target error e is the wall time
of its cheapest run from which on every finer run of the sequence stays
within e of the reference ("reliably within e"; rigid-node drag oscillates
in N, so a coarse run can land near the reference by chance). Where a
sequence never gets there, the ratio is a lower bound: its largest run
costs more and is still outside.

Run from anywhere; it runs softsand from the repository root (scenes are
included by relative path). Wall times are those of the simulator (mesh,
set-up, assembly, solve, output) as written by the study, on one rank.
"""
import argparse
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CASES = {
    # scene, quantity, what it is
    'drag': ('parameters/drag_sphere.prm', 'drag_coefficient',
             'fixed-sphere drag coefficient, Re = 0.1'),
    'pack': ('parameters/pack_permeability.prm', 'permeability',
             'Darcy permeability of the compacted Fig. 3 pack (m^2)'),
}

# Entries set on top of the scene. The pack: the compacted Fig. 3 pack
# (parameters/packs/fig3_compacted.txt, 100 grains, made by
# parameters/pour_and_compact.prm) in its box (the piston stopped at
# y = 0.996 mm), superficial velocity 1e-3 m/s as in
# parameters/theta_dt_convergence.prm.
CASE_OVERRIDES = {
    'drag': [],
    'pack': [('grains/file', 'parameters/packs/fig3_compacted.txt'),
             ('mesh/upper corner', '1e-3, 0.996e-3, 1.1e-4'),
             ('boundary conditions/x min/flow rate', '1.0956e-10'),
             ('fluid solver/max linear iterations', '3000')],
}


def read_table(path):
    """Rows of a convergence.txt (whitespace table with a header line)."""
    with open(path) as f:
        names = f.readline().split()
        rows = []
        for line in f:
            if not line.strip():
                continue
            row = {}
            for name, value in zip(names, line.split()):
                try:
                    row[name] = float(value)
                except ValueError:
                    row[name] = None
            rows.append(row)
    return rows


def run_study(case, refinement, values, workdir, extra, reuse):
    scene, quantity, _ = CASES[case]
    name = '%s_%s' % (case, refinement)
    outdir = os.path.join(workdir, name)
    text = 'include %s\n' % scene
    overrides = [('mesh/refinement', refinement),
                 ('convergence study/knob', 'cells per diameter'),
                 ('convergence study/values', ', '.join(values)),
                 ('convergence study/quantity', quantity),
                 ('output/directory', outdir),
                 ('output/write vtu', 'false'),
                 ('output/verbosity', 'quiet')] + extra
    for path, value in overrides:
        text = prm_tools.set_entry(text, path, value)
    os.makedirs(workdir, exist_ok=True)
    prm = os.path.join(workdir, name + '.prm')
    with open(prm, 'w') as f:
        f.write(text)
    log = os.path.join(workdir, name + '.log')
    table = os.path.join(outdir, 'convergence.txt')
    if reuse and os.path.exists(table):
        return read_table(table)
    prm_tools.fresh_output(text, outdir)
    with open(log, 'w') as out:
        proc = subprocess.run([os.path.join(ROOT, 'build', 'softsand'), prm],
                              cwd=ROOT, stdout=out, stderr=subprocess.STDOUT)
    if not os.path.exists(table):
        sys.exit('%s: no table written (exit %d), see %s' %
                 (name, proc.returncode, log))
    rows = read_table(table)
    if proc.returncode != 0:
        print('%s stopped (exit %d) after %d runs; see %s' %
              (name, proc.returncode, len(rows), log))
    return rows


def reliable_cost(rows, quantity, reference, target):
    """Wall time of the cheapest run from which on (in N) every run is
    within target of the reference; None if the last run is not."""
    best = None
    for row in reversed(rows):
        if abs(row[quantity] / reference - 1) <= target:
            best = row
        else:
            break
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--case', choices=sorted(CASES), default='drag')
    ap.add_argument('--adaptive', default='2,3,4,6,8,12,16,24')
    ap.add_argument('--uniform', default='2,3,4')
    ap.add_argument('--reference-n', default='32',
                    help='N of a separate adaptive run giving the reference, '
                    "or 'finest': the finest adaptive run of the sequence")
    ap.add_argument('--reference', type=float, default=None,
                    help='reference value instead of a reference run')
    ap.add_argument('--box', type=float, default=None,
                    help='drag: box edge in diameters (the scene: 10)')
    ap.add_argument('--target', type=float, default=0.01)
    ap.add_argument('--cost', choices=('cpu', 'wall'), default='cpu',
                    help='cost measure: CPU time of the run (default; on a '
                    'shared machine the wall time also counts the other '
                    "jobs' share of the cores) or wall time")
    ap.add_argument('--workdir', default='output/study_speed_accuracy')
    ap.add_argument('--plot', default=None, help='PNG file for the plot')
    ap.add_argument('--reuse', action='store_true',
                    help='read the tables of an earlier run of this script '
                    'instead of running again (re-plot, other targets)')
    a = ap.parse_args()
    scene, quantity, what = CASES[a.case]
    workdir = os.path.abspath(a.workdir)
    extra = list(CASE_OVERRIDES[a.case])
    tag = a.case
    if a.box is not None:
        h = a.box * 1e-3 / 2
        extra += [('mesh/lower corner', '%g, %g, %g' % (-h, -h, -h)),
                  ('mesh/upper corner', '%g, %g, %g' % (h, h, h))]
        tag += '_box%g' % a.box
    workdir = os.path.join(workdir, tag)

    adaptive = run_study(a.case, 'adaptive', a.adaptive.split(','), workdir,
                         extra, a.reuse)
    uniform = run_study(a.case, 'uniform', a.uniform.split(','), workdir,
                        extra, a.reuse)
    if a.reference is not None:
        reference, ref_text = a.reference, 'given value %.8g' % a.reference
    elif a.reference_n == 'finest':
        f = adaptive[-1]
        reference = f[quantity]
        ref_text = ('the finest adaptive run of the sequence, N = %g: %.8g '
                    '(%d cells, %d DoFs)' % (f['N'], reference, f['cells'],
                                             f['dofs']))
        if f.get('richardson') is not None:
            ref_text += ('; its Richardson estimate %.8g (%+.2f %%)' %
                         (f['richardson'],
                          100 * (f['richardson'] / reference - 1)))
    else:
        ref = run_reference(a.case, a.reference_n, workdir, extra, a.reuse)
        reference = ref[quantity]
        ref_text = ('adaptive N = %s: %.8g (%d cells, %d DoFs, %.1f s)' %
                    (a.reference_n, reference, ref['cells'], ref['dofs'],
                     ref['wall_s']))

    print('Case: %s (%s); reference %s\n' % (tag, what, ref_text))
    cost = a.cost + '_s'
    print('| refinement | N | cells | DoFs | FGMRES | CPU [s] | wall [s] | '
          'peak memory [MB] | %s | error |' % quantity)
    print('|---|---|---|---|---|---|---|---|---|---|')
    for label, rows in (('adaptive', adaptive), ('uniform', uniform)):
        for r in rows:
            print('| %s | %g | %d | %d | %d | %.1f | %.1f | %.0f | %.6g | '
                  '%+.2f %% |'
                  % (label, r['N'], r['cells'], r['dofs'], r['fgmres'],
                     r['cpu_s'], r['wall_s'], r['memory_MB'], r[quantity],
                     100 * (r[quantity] / reference - 1)))

    # Same N on both meshes: the same grain-surface resolution.
    print('\nSame cells per diameter on both meshes:\n')
    print('| N | adaptive %s [s] | uniform %s [s] | ratio | '
          'adaptive DoFs | uniform DoFs | %s difference |' % (
              a.cost, a.cost, quantity))
    print('|---|---|---|---|---|---|---|')
    by_n = {r['N']: r for r in adaptive}
    for u in uniform:
        if u['N'] in by_n:
            r = by_n[u['N']]
            print('| %g | %.1f | %.1f | %.1f | %d | %d | %.1e |' % (
                u['N'], r[cost], u[cost], u[cost] / r[cost],
                r['dofs'], u['dofs'], abs(u[quantity] / r[quantity] - 1)))

    ra = reliable_cost(adaptive, quantity, reference, a.target)
    ru = reliable_cost(uniform, quantity, reference, a.target)
    print('\nReliably within %g %% (this and every finer run of the '
          'sequence):' % (100 * a.target))
    if ra is None:
        print('* adaptive: not reached (largest run %.1f s, %+.2f %%)' % (
            adaptive[-1][cost],
            100 * (adaptive[-1][quantity] / reference - 1)))
    else:
        print('* adaptive: from N = %g, %.1f s' % (ra['N'], ra[cost]))
    if ru is None:
        print('* uniform: not reached; its largest run (N = %g) took %.1f s '
              'and is at %+.2f %%' % (
                  uniform[-1]['N'], uniform[-1][cost],
                  100 * (uniform[-1][quantity] / reference - 1)))
    else:
        print('* uniform: from N = %g, %.1f s' % (ru['N'], ru[cost]))
    if ra is not None and ru is not None:
        print('* %s-time ratio uniform / adaptive at %g %%: %.1f' % (
            a.cost, 100 * a.target, ru[cost] / ra[cost]))
    elif ra is not None:
        print('* %s-time ratio uniform / adaptive at %g %%: > %.1f '
              '(lower bound)' % (a.cost, 100 * a.target,
                                 uniform[-1][cost] / ra[cost]))

    if a.plot:
        try:
            import matplotlib
        except ImportError:
            sys.exit('matplotlib is missing: run with /usr/bin/python3 '
                     '(Debian python3-matplotlib)')
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.2))
        for label, rows, marker in (('adaptive', adaptive, 'o-'),
                                    ('uniform', uniform, 's-')):
            t = [r[cost] for r in rows]
            e = [max(abs(r[quantity] / reference - 1), 1e-5) for r in rows]
            ax.loglog(t, e, marker, label=label)
            for r, x, y in zip(rows, t, e):
                ax.annotate('N=%g' % r['N'], (x, y), fontsize=7,
                            textcoords='offset points', xytext=(3, 3))
        ax.axhline(a.target, color='gray', ls='--', lw=0.8)
        ax.set_xlabel('%s time [s] (1 rank)' % a.cost.upper()
                      if a.cost == 'cpu' else 'wall time [s] (1 rank)')
        ax.set_ylabel('|%s / reference - 1|' % quantity)
        ax.set_title('%s: %s' % (tag, what), fontsize=9)
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
        print('\nPlot: %s' % a.plot)


def run_reference(case, n, workdir, extra, reuse):
    """One adaptive run at N = n (plain run, not a study): its last
    statistics row, the simulator's wall time in 'wall_s'."""
    scene, quantity, _ = CASES[case]
    name = '%s_reference_n%s' % (case, n)
    outdir = os.path.join(workdir, name)
    text = 'include %s\n' % scene
    for path, value in [('mesh/refinement', 'adaptive'),
                        ('mesh/cells per diameter', n),
                        ('output/directory', outdir),
                        ('output/write vtu', 'false'),
                        ('output/verbosity', 'quiet')] + extra:
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(workdir, name + '.prm')
    with open(prm, 'w') as f:
        f.write(text)
    stats = os.path.join(outdir, 'statistics.txt')
    if not (reuse and os.path.exists(stats)):
        prm_tools.fresh_output(text, outdir)
        with open(os.path.join(workdir, name + '.log'), 'w') as out:
            subprocess.run([os.path.join(ROOT, 'build', 'softsand'), prm],
                           cwd=ROOT, stdout=out, stderr=subprocess.STDOUT,
                           check=True)
    row = prm_tools.read_statistics(outdir)[-1]
    row['wall_s'] = row['wall_time']
    return row


if __name__ == '__main__':
    main()
