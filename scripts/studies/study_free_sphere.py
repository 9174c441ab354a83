#!/usr/bin/env python3
"""The paper's Fig. 6: a free sphere dragged by a uniform stream
(parameters/free_sphere.prm), for several fluid time steps. Prints v/U at
a few times for each dt, the largest spread between the curves after the
transient (t >= --after), and plots v/U(t) to doc/free_sphere.png (needs
matplotlib; the table is printed without it).

  python3 scripts/studies/study_free_sphere.py [--dt 1e-3,5e-4,2.5e-4] [--end 0.1]
                                       [--n 6] [--ranks 1] [--model transient]
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
U = 2e-3


def interpolate(ts, vs, t):
    for k in range(1, len(ts)):
        if ts[k] >= t:
            w = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
            return vs[k - 1] + w * (vs[k] - vs[k - 1])
    return vs[-1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--dt', default='1e-3,5e-4,2.5e-4')
    ap.add_argument('--end', type=float, default=0.1)
    ap.add_argument('--after', type=float, default=0.03,
                    help='compare the curves from this time on (s)')
    ap.add_argument('--n', default='6')
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--model', default='transient')
    ap.add_argument('--workdir', default=os.path.join(ROOT, 'output/study_free_sphere'))
    ap.add_argument('--reuse', action='store_true',
                    help='keep runs whose statistics already reach the end time')
    ap.add_argument('--plot', default=os.path.join(ROOT, 'doc/free_sphere.png'))
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'free_sphere.prm')).read()
    softsand = os.path.join(ROOT, 'build', 'softsand')
    curves = {}
    for dt in a.dt.split(','):
        name = 'dt%s' % dt
        start = time.time()
        stats = os.path.join(a.workdir, name, 'statistics.txt')
        if a.reuse and os.path.exists(stats):
            rows = prm_tools.read_statistics(os.path.join(a.workdir, name))
            if rows and rows[-1]['time'] >= a.end - 0.5 * float(dt):
                curves[dt] = ([r['time'] for r in rows],
                              [r['grain0_vx'] / U for r in rows],
                              rows[-1]['wall_time'], rows[-1]['dofs'])
                print('dt = %s s: reused %d steps' % (dt, len(rows)), flush=True)
                continue
        row, wall, err = prm_tools.run(
            softsand, base, a.workdir, name, a.ranks,
            [('simulation control/time step', dt),
             ('simulation control/end time', a.end),
             ('mesh/cells per diameter', a.n),
             ('coupling/fluid model', a.model),
             ('output/output interval', 1000000)])
        if row is None:
            sys.exit('dt = %s failed: %s' % (dt, err))
        rows = prm_tools.read_statistics(os.path.join(a.workdir, name))
        curves[dt] = ([r['time'] for r in rows], [r['grain0_vx'] / U for r in rows],
                      wall, rows[-1]['dofs'])
        print('dt = %s s: %d steps, %.0f s, %d DoFs' % (dt, len(rows), wall, rows[-1]['dofs']),
              flush=True)
    times = [t for t in (0.005, 0.01, 0.02, 0.03, 0.05, 0.075, 0.1) if t <= a.end + 1e-12]
    print('\n| dt (s) | ' + ' | '.join('v/U at %g s' % t for t in times) + ' | wall (s) |')
    print('|---|' + '---|' * (len(times) + 1))
    for dt, (ts, vs, wall, dofs) in curves.items():
        print('| %s | ' % dt + ' | '.join('%.4f' % interpolate(ts, vs, t) for t in times)
              + ' | %.0f |' % wall)
    # Spread between the curves after the transient, sampled on the
    # coarsest step's times.
    ref = curves[a.dt.split(',')[0]][0]
    spread = 0
    for t in ref:
        if t < a.after:
            continue
        values = [interpolate(ts, vs, t) for ts, vs, _, _ in curves.values()]
        spread = max(spread, (max(values) - min(values)) / max(abs(v) for v in values))
    print('\nlargest relative spread of v between the time steps for t >= %g s: %.2f %%'
          % (a.after, 100 * spread))
    plt = prm_tools.pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    for dt, (ts, vs, _, _) in curves.items():
        ax.plot([0] + ts, [0] + vs, label='dt = %s s' % dt)
    ax.axhline(1, color='k', lw=0.5)
    ax.set_xlabel('t (s)')
    ax.set_ylabel('v / U')
    ax.set_title('Free sphere in a uniform stream (Fig. 6), %s cells/d' % a.n)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.plot, dpi=120)
    print('plot: %s' % a.plot)


if __name__ == '__main__':
    main()
