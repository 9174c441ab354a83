#!/usr/bin/env python3
"""The paper's Fig. 4: pressure drop dp(t) across the compacted Fig. 3 pack
(parameters/theta_dt_convergence.prm: coupled, transient, flow-rate inlet)
for a series of Theta at one time step and a series of time steps at one
Theta. Prints dp at the end of each run, the spread of the series at
Theta >= --converged, and plots dp(t) to doc/theta_dt.png (matplotlib; the
tables are printed without it).

  python3 scripts/studies/study_theta_dt.py [--thetas 1e2,1e4,1e6,1e8]
      [--dts 2e-5,1e-5,5e-6] [--theta-for-dt 1e6] [--dt-for-theta 1e-5]
      [--end 1e-4] [--n 4] [--reuse]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(a, base, theta, dt):
    name = 'theta%s_dt%s' % (theta, dt)
    out = os.path.join(a.workdir, name)
    stats = os.path.join(out, 'statistics.txt')
    if a.reuse and os.path.exists(stats):
        rows = prm_tools.read_statistics(out)
        if rows and rows[-1]['time'] >= a.end - 0.5 * float(dt):
            return rows, rows[-1]['wall_time']
    row, wall, err = prm_tools.run(
        os.path.join(ROOT, 'build', 'softsand'), base, a.workdir, name, a.ranks,
        [('fluid/theta', theta), ('simulation control/time step', dt),
         ('simulation control/end time', a.end),
         ('mesh/cells per diameter', a.n),
         ('output/output interval', 1000000)])
    if row is None:
        print('Theta = %s, dt = %s failed: %s' % (theta, dt, err), flush=True)
        return None, wall
    return prm_tools.read_statistics(out), wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--thetas', default='1e2,1e4,1e6,1e8')
    ap.add_argument('--dts', default='2e-5,1e-5,5e-6')
    ap.add_argument('--theta-for-dt', default='1e6')
    ap.add_argument('--dt-for-theta', default='1e-5')
    ap.add_argument('--converged', type=float, default=1e6)
    ap.add_argument('--end', type=float, default=1e-4)
    ap.add_argument('--n', default='4')
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--reuse', action='store_true')
    ap.add_argument('--workdir', default=os.path.join(ROOT, 'output/study_theta_dt'))
    ap.add_argument('--plot', default=os.path.join(ROOT, 'doc/theta_dt.png'))
    a = ap.parse_args()
    base = open(os.path.join(ROOT, 'parameters', 'theta_dt_convergence.prm')).read()

    series = {'theta': [], 'dt': []}
    done = {}  # (theta, dt) -> (rows, wall): the two series share a run

    def run_once(theta, dt):
        if (theta, dt) not in done:
            done[(theta, dt)] = run(a, base, theta, dt)
        return done[(theta, dt)]

    for theta in a.thetas.split(','):
        rows, wall = run_once(theta, a.dt_for_theta)
        if rows:
            series['theta'].append((theta, a.dt_for_theta, rows, wall))
    for dt in a.dts.split(','):
        rows, wall = run_once(a.theta_for_dt, dt)
        if rows:
            series['dt'].append((a.theta_for_dt, dt, rows, wall))

    print('| Theta | dt (s) | steps | dp at end (Pa) | K at end (m^2) | '
          'FGMRES per step | wall (s) |')
    print('|---|---|---|---|---|---|---|')
    for kind in ('theta', 'dt'):
        for theta, dt, rows, wall in series[kind]:
            its = sum(r['linear_iterations'] for r in rows) / len(rows)
            print('| %s | %s | %d | %.5g | %.4g | %.0f | %.0f |' % (
                theta, dt, len(rows), rows[-1]['pressure_drop'],
                rows[-1]['permeability'], its, wall))
    converged = [s for s in series['theta'] if float(s[0]) >= a.converged]
    for label, runs in (('Theta >= %g' % a.converged, converged),
                        ('dt series', series['dt'])):
        if len(runs) > 1:
            dps = [r[2][-1]['pressure_drop'] for r in runs]
            print('spread of dp at the end, %s: %.3g %%' %
                  (label, 100 * (max(dps) - min(dps)) / max(abs(x) for x in dps)))
    plt = prm_tools.pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, kind in zip(axes, ('theta', 'dt')):
        for theta, dt, rows, _ in series[kind]:
            ax.plot([r['time'] * 1e3 for r in rows], [r['pressure_drop'] for r in rows],
                    marker='.', label=('Theta = %s' % theta) if kind == 'theta'
                    else ('dt = %s s' % dt))
        ax.set_xlabel('t (ms)')
        ax.set_ylabel('dp (Pa)')
        ax.legend()
    axes[0].set_title('Theta series, dt = %s s' % a.dt_for_theta)
    axes[1].set_title('dt series, Theta = %s' % a.theta_for_dt)
    fig.tight_layout()
    fig.savefig(a.plot, dpi=120)
    print('plot: %s' % a.plot)


if __name__ == '__main__':
    main()
