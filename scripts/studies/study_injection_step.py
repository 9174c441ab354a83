#!/usr/bin/env python3
"""The time-step error of the transient fluid model on an injection.

Runs a Hele-Shaw scene (default parameters/hele_shaw_small.prm) with the
grains held where they are (simulation control/mode = transient: the
fluid alone, fixed steps, no Courant limit) at one inlet pressure and
several time steps, and prints per step: the radial flow rate Q averaged
over the window (--window-start, --end-time], its standard deviation over
the window's steps, the superficial and the largest cell pore Reynolds
numbers, the pore time ratio dt u_max / d (u_max from the largest cell
Re_p), Q's difference from the smallest step's, and the wall time.

  python3 scripts/studies/study_injection_step.py [--pressure 16000]
      [--steps 2.5e-4,1.25e-4,6.25e-5,3.125e-5,1.5625e-5]
      [--end-time 4e-3] [--window-start 2e-3] [--ranks 1]
      [--workdir output/study_injection_step] [--set "a/b=value" ...]
"""
import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def window_stats(rows, start):
    """Mean and standard deviation of the window's rows, and its means of
    the Reynolds numbers."""
    inside = [r for r in rows if r['time'] > start * (1 + 1e-9)]
    if not inside:
        return None
    q = [r['radial_flow_rate'] for r in inside]
    return dict(n=len(inside), q=statistics.mean(q),
                sd=statistics.pstdev(q),
                re_radial=statistics.mean(r['radial_pore_reynolds'] for r in inside),
                re_cell=statistics.mean(r['pore_reynolds_max'] for r in inside))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--scene', default=os.path.join(ROOT, 'parameters',
                                                    'hele_shaw_small.prm'))
    ap.add_argument('--softsand', default=os.path.join(ROOT, 'build', 'softsand'))
    ap.add_argument('--pressure', type=float, default=16000.)
    ap.add_argument('--steps', default='2.5e-4,1.25e-4,6.25e-5,3.125e-5,1.5625e-5')
    ap.add_argument('--end-time', type=float, default=4e-3)
    ap.add_argument('--window-start', type=float, default=2e-3)
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--workdir', default='output/study_injection_step')
    prm_tools.add_set_argument(ap, 'the scene')
    args = ap.parse_args()
    try:
        steps = sorted((float(s) for s in args.steps.split(',')), reverse=True)
    except ValueError:
        sys.exit('--steps: expected comma-separated time steps in s, got %r'
                 % args.steps)
    if not steps or min(steps) <= 0:
        sys.exit('--steps: every step must be > 0 s, got %r' % args.steps)
    if args.pressure <= 0:
        sys.exit('--pressure %g Pa: the inlet pressure must be > 0 (the flow '
                 'rate is compared between steps)' % args.pressure)
    if args.ranks < 1:
        sys.exit('--ranks %d: must be at least 1' % args.ranks)
    if not 0 <= args.window_start < args.end_time:
        sys.exit('--window-start %g s must lie in [0, --end-time = %g s)'
                 % (args.window_start, args.end_time))
    if args.window_start + max(steps) >= args.end_time:
        sys.exit('the window (%g, %g] s holds no step of %g s: lower '
                 '--window-start or raise --end-time'
                 % (args.window_start, args.end_time, max(steps)))

    with open(args.scene) as f:
        text = f.read()
    # --set first, so that the grains and the fluid read below are the run's.
    for path, value in prm_tools.parse_set(args.set):
        text = prm_tools.set_entry(text, path, value)
    pack = prm_tools.get_entry(text, 'grains/file')
    if pack is None:
        sys.exit('%s: no grains/file entry (the mean grain diameter of the '
                 'Reynolds numbers comes from the pack file)' % args.scene)
    grains = prm_tools.read_grains(os.path.join(ROOT, pack))
    d = statistics.mean(2 * g[3] for g in grains)  # (x, y, z, radius)
    rho = float(prm_tools.get_entry(text, 'fluid/density'))
    mu = float(prm_tools.get_entry(text, 'fluid/viscosity'))

    results = []
    for dt in steps:
        overrides = [('simulation control/mode', 'transient'),
                     ('simulation control/time step', '%g' % dt),
                     ('simulation control/end time', '%g' % args.end_time),
                     ('coupling/max courant number', '0'),
                     ('boundary conditions/inlet region/pressure',
                      '%g' % args.pressure)]
        name = 'dt%g' % dt
        print('dt = %g s ...' % dt, flush=True)
        last, wall, error = prm_tools.run(args.softsand, text, args.workdir,
                                          name, args.ranks, overrides)
        if last is None:
            sys.exit('dt = %g s failed: %s' % (dt, ' '.join(error)))
        w = window_stats(prm_tools.read_statistics(
            os.path.join(args.workdir, name)), args.window_start)
        if w is None:
            sys.exit('dt = %g s: no statistics row after --window-start = %g s '
                     '(see %s)' % (dt, args.window_start,
                                   os.path.join(args.workdir, name)))
        results.append((dt, wall, w))

    reference = results[-1][2]['q']
    print('\nradial flow rate Q over (%g, %g] s at p_i = %g Pa, grains held; '
          'difference from the smallest step' % (args.window_start,
                                                  args.end_time, args.pressure))
    print('%10s %6s %12s %10s %8s %9s %10s %10s %8s' % (
        'dt [s]', 'steps', 'Q [m^3/s]', 'sd', 'Re_p', 'cell Re_p',
        'dt u/d', 'dQ/Q', 'wall [s]'))
    for dt, wall, w in results:
        u_max = w['re_cell'] * mu / (rho * d)
        print('%10.4g %6d %12.5g %10.3g %8.1f %9.0f %10.3f %9.1f%% %8.0f' % (
            dt, w['n'], w['q'], w['sd'], w['re_radial'], w['re_cell'],
            dt * u_max / d, 100 * (w['q'] - reference) / reference, wall))


if __name__ == '__main__':
    main()
