#!/usr/bin/env python3
"""Injection sweep of the radial Hele-Shaw cell (issue 5): run one scene at
several inlet pressures p_i, all from the same saved pack, and locate the
critical pressure above which channels open.

  python3 scripts/studies/hele_shaw_sweep.py --pressures 500,1000,2000,4000,8000,16000

runs parameters/hele_shaw_small.prm (override with --scene) with
boundary conditions/inlet region/pressure = p_i, each in
<workdir>/p<p_i>/, --jobs runs at a time (single-rank each, or --ranks), and
prints a table: p_i, coupling steps and time reached, the fracture area at
the start (the pore space next to the inlet: the grains' centres stay r + R
from the inlet axis, so a thin open ring surrounds it) and at the end, its
largest area during the run and its growth over the start, the radial
permeability at the end over the start (- for the transient model, whose
flow starts from rest), the largest grain speed at the
end, and the wall time. A pressure "fractures" when the largest area
exceeds the start by more than --open-area (m^2; default half the
projected area of a mean grain, 0.72 mm^2). The critical pressure is
bracketed by the largest pressure that does not fracture and the smallest
that does; their geometric mean is reported.

--cells-per-diameter and --cohesion override mesh/cells per diameter and
dem/material/cohesion energy density (refinement and cohesion studies);
--steps overrides simulation control/max time steps. Results are also
written to <workdir>/sweep.txt. --summarize tabulates the runs already in
<workdir> (an unfinished run: its last statistics row) into
<workdir>/summary.txt without running anything. Each run also saves its
last grains in <workdir>/p<p_i>/pack_end.txt. Run from the repository
root.

Developed fractures (--developed): each injection runs until its fracture
reaches --reach-fraction (0.8) of the scene's fracture-map outer radius,
its area grows by less than one pixel over a window of at least
--stall-steps (40) coupling steps and --stall-time (0.01 s) of simulated
time, or --end-time (default 0.2 s with --developed), whichever comes
first (postprocessing/fracture area/stop at reach, stop when stalled over
and stop when stalled for). Before stop 50 the window was the steps alone:
40 steps halved to the Courant limit spanned only 2.5 ms
(--stall-time 0 gives that rule back). A window of 20 steps stopped a
small-scene run at 5.7 kPa 3.5 ms before its growth began
(doc/hele_shaw.md). Every run writes a checkpoint every
--checkpoint-interval coupling steps (default 5 with --developed) and its
screen output to
<workdir>/p<p_i>.log. Running the same command again resumes (with or
without --developed): a finished pressure (<workdir>/p<p_i>/sweep_done.txt;
delete it to run that pressure again) is only tabulated, an unfinished
one with a checkpoint restarts from it, the others start anew;
the wall time is summed over the sessions (a killed session up to its
last statistics row). Ctrl-C or SIGTERM to the sweep stops it cleanly:
each running injection finishes its step and writes a checkpoint, no
further pressure starts, and the table is written. The table's 'end' column says
why each run ended: reach, stalled, time (end time or max steps); when
the verdict rests on runs that ended by time, the table says so. Each run's
start and end are reported on stderr as they happen, and the table is drawn
as Fig. 9 (growth against p_i, the bracket shaded) in <workdir>/fig9.png
(--no-plot: not drawn; needs matplotlib).
"""
import argparse
import concurrent.futures
import math
import os
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402


def starts_from_rest(prm_text):
    """Whether the scene's fluid is transient: its flow starts from rest, so
    the first step's radial permeability is not the pack's."""
    models = re.findall(r'^\s*set\s+fluid model\s*=\s*(\S+)', prm_text,
                        re.MULTILINE)
    return bool(models) and models[-1] == 'transient'


def k_ratio(rows, prm_text):
    if starts_from_rest(prm_text):
        return float('nan')
    return rows[-1]['radial_permeability'] / rows[0]['radial_permeability']


def outer_radius(text):
    m = re.findall(r'^\s*set\s+outer radius\s*=\s*(\S+)', text, re.MULTILINE)
    if not m or float(m[-1]) <= 0:
        sys.exit('--developed needs postprocessing/fracture area/outer radius '
                 '> 0 in the scene (the reach is a fraction of it)')
    return float(m[-1])


def end_reason(log_text):
    """Why a finished run ended, from its screen output."""
    if 'Developed fracture' in log_text:
        return 'reach' if 'stop at reach' in log_text else 'stalled'
    return 'time'


# softsand's exit code after a stop signal: it finished its step and wrote a
# checkpoint (base/stop_request.h).
EXIT_STOPPED = 75


class StopRequest:
    """SIGINT or SIGTERM to the sweep: each running softsand gets SIGUSR1
    (mpirun passes it on to the ranks), finishes its step, writes a
    checkpoint and exits; the sweep starts no further pressure, tabulates
    and exits. The same command resumes."""

    def __init__(self):
        self.requested = False
        self.children = set()

    def __call__(self, signum, frame):
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True
        print('sweep: stop requested; each run finishes its step and writes '
              'a checkpoint (again to abort)', file=sys.stderr, flush=True)
        for child in list(self.children):
            try:
                child.send_signal(signal.SIGUSR1)
            except OSError:
                pass


STOP = StopRequest()


def run_one(args, text, p):
    name = 'p%g' % p
    outdir = os.path.join(args.workdir, name)
    done_file = os.path.join(outdir, 'sweep_done.txt')
    wall_file = os.path.join(outdir, 'sweep_wall.txt')
    if os.path.exists(done_file):
        return summarize_one(args, p)
    if STOP.requested:
        return dict(p=p, stopped=True, wall=0)
    overrides = [('boundary conditions/inlet region/pressure', '%g' % p)]
    if args.developed:
        overrides += [
            ('postprocessing/fracture area/stop at reach',
             '%g' % (args.reach_fraction * outer_radius(text))),
            ('postprocessing/fracture area/stop when stalled over',
             '%d' % args.stall_steps),
            ('postprocessing/fracture area/stop when stalled for',
             '%g' % args.stall_time)]
    if args.checkpoint_interval:
        overrides.append(('simulation control/checkpoint interval',
                          '%d' % args.checkpoint_interval))
    restart = (args.checkpoint_interval > 0 and
               os.path.exists(os.path.join(outdir, 'checkpoint.info')))
    overrides.append(('simulation control/restart',
                      'true' if restart else 'false'))
    if args.cells_per_diameter is not None:
        overrides.append(('mesh/cells per diameter',
                          '%g' % args.cells_per_diameter))
    if args.cohesion is not None:
        overrides.append(('dem/material/cohesion energy density',
                          '%g' % args.cohesion))
    if args.linear_tolerance is not None:
        overrides.append(('fluid solver/linear tolerance',
                          '%g' % args.linear_tolerance))
    if args.end_time is not None:
        overrides.append(('simulation control/end time',
                          '%g' % args.end_time))
    if args.steps is not None:
        overrides.append(('simulation control/max time steps',
                          '%d' % args.steps))
    overrides += prm_tools.parse_set(args.set)
    # As prm_tools.run, but the grains and the fracture map of the last
    # step are written (a large output interval: the last step only), and
    # the grains at the end in <outdir>/pack_end.txt (dem/save pack: the
    # pack file's order, for scripts/plots/plot_hele_shaw_grains.py).
    overrides.append(('dem/save pack', 'pack_end.txt'))
    for path, value in overrides:
        text = prm_tools.set_entry(text, path, value)
    text = prm_tools.set_entry(text, 'output/directory', outdir)
    text = prm_tools.set_entry(text, 'output/output interval', '100000')
    text = prm_tools.set_entry(text, 'output/verbosity', 'quiet')
    prm = os.path.join(args.workdir, name + '.prm')
    os.makedirs(args.workdir, exist_ok=True)
    with open(prm, 'w') as f:
        f.write(text)
    cmd = [args.softsand, prm]
    if args.ranks > 1:
        cmd = ['mpirun', '-np', str(args.ranks)] + cmd
    # A run without a checkpoint starts anew: softsand refuses an output
    # directory that holds an earlier run's results (its wall time goes).
    prm_tools.fresh_output(text, outdir)
    os.makedirs(outdir, exist_ok=True)
    running_file = os.path.join(outdir, 'sweep_running.txt')
    earlier = float(open(wall_file).read()) if os.path.exists(wall_file) else 0
    if os.path.exists(running_file):
        # The last session was killed: count it up to its last row (its
        # statistics wall_time runs from that process's start).
        try:
            earlier += prm_tools.read_statistics(outdir)[-1]['wall_time']
        except (OSError, ValueError, IndexError, KeyError):
            pass
    with open(running_file, 'w') as f:
        f.write('%s\n' % time.ctime())
    start = time.time()
    print('sweep: %g Pa %s (%s.log)' % (p, 'resumed' if restart else 'started',
                                       os.path.join(args.workdir, name)),
          file=sys.stderr, flush=True)
    with open(os.path.join(args.workdir, name + '.log'), 'a') as log:
        log.write('# %s%s\n' % (' '.join(cmd),
                                 ' (restart)' if restart else ''))
        log.flush()
        # Its own session: Ctrl-C on the sweep must not reach mpirun, which
        # would kill the ranks at once; the sweep passes on SIGUSR1.
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.PIPE,
                                text=True, start_new_session=True)
        STOP.children.add(proc)
        stderr = proc.communicate()[1]
        STOP.children.discard(proc)
        log.write(stderr)
    wall = earlier + time.time() - start
    with open(wall_file, 'w') as f:
        f.write('%.1f\n' % wall)
    os.remove(running_file)
    if proc.returncode == EXIT_STOPPED or (STOP.requested and
                                           proc.returncode != 0):
        # Stopped on request after a step, with a checkpoint: not done.
        return dict(p=p, stopped=True, wall=wall)
    if proc.returncode != 0:
        return dict(p=p, error=' '.join(stderr.strip().splitlines()[-1:]),
                    wall=wall)
    with open(done_file, 'w') as f:
        f.write(end_reason(open(os.path.join(args.workdir,
                                             name + '.log')).read()) + '\n')
    result = summarize_one(args, p)
    if 'error' not in result:
        print('sweep: %g Pa finished after %.0f s: %d steps to t = %.4g s, '
              'growth %.3f mm^2, ended by %s' % (
                  p, wall, result['steps'], result['time'],
                  (result['area_max'] - result['area0']) * 1e6,
                  result.get('end', '?')), file=sys.stderr, flush=True)
    return result


def summarize_one(args, p):
    """The result of a run from its statistics (also of an unfinished one:
    its last row)."""
    outdir = os.path.join(args.workdir, 'p%g' % p)
    try:
        rows = prm_tools.read_statistics(outdir)
    except (OSError, ValueError):
        rows = []
    if not rows:
        return dict(p=p, error='no statistics in ' + outdir, wall=0)
    last = rows[-1]
    wall_file = os.path.join(outdir, 'sweep_wall.txt')
    done_file = os.path.join(outdir, 'sweep_done.txt')
    return dict(p=p, steps=int(last['step']), time=last['time'],
                area0=rows[0]['fracture_area'], area=last['fracture_area'],
                area_max=max(r['fracture_area'] for r in rows),
                reach=last.get('fracture_reach', float('nan')),
                k_ratio=k_ratio(rows, open(os.path.join(
                    args.workdir, 'p%g.prm' % p)).read()),
                open_area=last['open_area'], max_speed=last['max_speed'],
                re_p=last.get('radial_pore_reynolds', float('nan')),
                dofs=last['dofs'], cells=last['cells'],
                end=(open(done_file).read().split()[0]
                     if os.path.exists(done_file) else 'unfinished'),
                wall=(float(open(wall_file).read())
                      if os.path.exists(wall_file) else last['wall_time']))


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--scene', default='parameters/hele_shaw_small.prm')
    a.add_argument('--pressures', default='500,1000,2000,4000,8000,16000',
                   help='inlet pressures p_i (Pa), comma separated')
    a.add_argument('--workdir', default='output/hele_shaw_sweep')
    a.add_argument('--softsand', default='build/softsand')
    a.add_argument('--jobs', type=int, default=2)
    a.add_argument('--ranks', type=int, default=1)
    a.add_argument('--cells-per-diameter', type=float, default=None)
    a.add_argument('--cohesion', type=float, default=None)
    a.add_argument('--steps', type=int, default=None)
    a.add_argument('--end-time', type=float, default=None,
                   help='simulation control/end time (s)')
    a.add_argument('--linear-tolerance', type=float, default=None,
                   help='fluid solver/linear tolerance (relative to the '
                        'right-hand side); the moving cohesive pack stalls '
                        'FGMRES near 1.3e-8 absolute, above 1e-6 relative '
                        'for p_i <= 8 kPa')
    prm_tools.add_set_argument(a, 'the scene')
    a.add_argument('--summarize', action='store_true',
                   help='do not run: tabulate the statistics already in '
                        '<workdir> (unfinished runs: their last row)')
    a.add_argument('--open-area', type=float,
                   default=0.5 * math.pi / 4 * 1.35e-3 ** 2)
    a.add_argument('--developed', action='store_true',
                   help='run each injection to a developed fracture (see '
                        'above); resumable')
    a.add_argument('--reach-fraction', type=float, default=0.8)
    a.add_argument('--stall-steps', type=int, default=40)
    a.add_argument('--stall-time', type=float, default=0.01,
                   help='simulated time the stall window spans at least '
                        '(s; 0: the steps alone)')
    a.add_argument('--checkpoint-interval', type=int, default=None,
                   help='coupling steps between checkpoints (default 5 with '
                        '--developed, else 0: none)')
    a.add_argument('--no-plot', dest='plot', action='store_false',
                   help='do not draw <workdir>/fig9.png (Fig. 9: growth '
                        'against p_i, by scripts/plots/plot_fracture_area.py)')
    args = a.parse_args()
    if args.checkpoint_interval is None:
        args.checkpoint_interval = 5 if args.developed else 0
    if args.developed and args.end_time is None:
        args.end_time = 0.2
    if args.stall_steps < 0 or not args.stall_time >= 0:
        sys.exit('--stall-steps and --stall-time must be >= 0, got %d and %g'
                 % (args.stall_steps, args.stall_time))
    if args.developed and args.stall_steps == 0 and args.stall_time == 0:
        sys.exit('--developed needs a stall window: --stall-steps or '
                 '--stall-time above 0')
    if not 0 < args.reach_fraction < 1:
        sys.exit('--reach-fraction must lie in (0, 1), got %g'
                 % args.reach_fraction)
    os.environ.setdefault('OMP_NUM_THREADS', '1')
    os.environ.setdefault('DEAL_II_NUM_THREADS', '1')
    with open(args.scene) as f:
        text = f.read()
    pressures = [float(p) for p in args.pressures.split(',')]
    if args.summarize:
        results = [summarize_one(args, p) for p in pressures]
    else:
        signal.signal(signal.SIGINT, STOP)
        signal.signal(signal.SIGTERM, STOP)
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda p: run_one(args, text, p),
                                    pressures))
    lines = ['# scene %s, cells per diameter %s, cohesion %s' %
             (args.scene, args.cells_per_diameter, args.cohesion),
             '# p_i[Pa] steps t_end[s] area_start[mm^2] area_end[mm^2] '
             'area_max[mm^2] growth_max[mm^2] open_area[mm^2] K_end/K_start '
             'max_speed[m/s] fractured dofs wall[s] reach_end[mm] '
             'Re_p_end end']
    below, above = None, None
    for r in sorted(results, key=lambda r: r['p']):
        if r.get('stopped'):
            r.update(summarize_one(args, r['p']))
            if 'error' in r:
                lines.append('%g stopped before its first step' % r['p'])
                continue
        if 'error' in r:
            lines.append('%g FAILED %s (%.0f s)' % (r['p'], r['error'],
                                                    r['wall']))
            continue
        growth = r['area_max'] - r['area0']
        fractured = growth > args.open_area
        if fractured and above is None:
            above = r['p']
        if not fractured and above is None:
            below = r['p']
        lines.append('%g %d %.4g %.3f %.3f %.3f %.3f %.3f %s %.3g %s %d %.0f'
                     % (r['p'], r['steps'], r['time'], r['area0'] * 1e6,
                        r['area'] * 1e6, r['area_max'] * 1e6, growth * 1e6,
                        r['open_area'] * 1e6,
                        '-' if math.isnan(r['k_ratio']) else
                        '%.3f' % r['k_ratio'], r['max_speed'],
            'yes' if fractured else 'no', r['dofs'], r['wall'])
                     + ' %.2f %.3g %s' % (r['reach'] * 1e3, r['re_p'],
                                          r.get('end', 'unfinished')))
    if any('k_ratio' in r and math.isnan(r['k_ratio']) for r in results):
        lines.append("# K_end/K_start '-': the transient model's flow starts "
                     "from rest, its first step's K is not the pack's")
    failed = [r['p'] for r in results if 'error' in r]
    finished = [r['p'] for r in results if 'error' not in r]
    if failed:
        lines.append('# %d of %d runs failed (%s Pa): %s' % (
            len(failed), len(results), ','.join('%g' % p for p in failed),
            'the bracket below uses the others only' if finished else
            'no critical pressure'))
    if not finished:
        pass
    elif above is not None and below == 0:
        lines.append('# critical pressure between 0 and %g Pa (0 Pa: a '
                     'control run without flow, so no geometric mean)'
                     % above)
    elif above is not None and below is not None:
        lines.append('# critical pressure between %g and %g Pa: %.3g Pa '
                     '(geometric mean)' % (below, above,
                                           math.sqrt(below * above)))
    elif above is None:
        lines.append('# no pressure fractured: critical pressure above %g Pa'
                     % max(finished))
    else:
        lines.append('# every pressure fractured: critical pressure below '
                     '%g Pa' % min(finished))
    undeveloped = [r['p'] for r in results
                   if 'error' not in r and r.get('end') in ('time', None,
                                                             'unfinished')]
    if finished and undeveloped:
        lines.append('# caveat: the runs at %s Pa ended by the end time or '
                     'step count (or are unfinished), not by a developed '
                     'fracture: their areas are lower bounds and the verdict '
                     'above may move (run with --developed)'
                     % ','.join('%g' % q for q in undeveloped))
    os.makedirs(args.workdir, exist_ok=True)
    with open(os.path.join(args.workdir, 'summary.txt' if args.summarize
                           else 'sweep.txt'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))
    if args.plot and finished:
        table = os.path.join(args.workdir, 'summary.txt' if args.summarize
                             else 'sweep.txt')
        figure = os.path.join(args.workdir, 'fig9.png')
        plot = subprocess.run(
            [sys.executable, os.path.join(os.path.dirname(
                os.path.abspath(__file__)), '..', 'plots', 'plot_fracture_area.py'),
             '--sweep', table, '--label', os.path.basename(args.scene),
             '--threshold', '%g' % (args.open_area * 1e6), '--out', figure],
            capture_output=True, text=True)
        print('sweep: Fig. 9 in %s' % figure if plot.returncode == 0 else
              'sweep: no figure (plot_fracture_area.py: %s)'
              % (plot.stderr.strip().splitlines() or ['failed'])[-1],
              file=sys.stderr)
    if STOP.requested:
        print('sweep: stopped on request; the same command resumes',
              file=sys.stderr)
        sys.exit(EXIT_STOPPED)


if __name__ == '__main__':
    main()
