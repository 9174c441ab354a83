#!/usr/bin/env python3
"""Two softsand builds, back to back, on the same few steps of a real run.

Each repetition restores a pristine copy of the run's directory (its
checkpoint), runs `--steps` coupling steps with every build in turn, and
reads the timer table of the run's log and the last row of its
statistics. It prints, per build, the median over the repetitions of each
timer section per step, and the largest relative difference of the end
state's statistics between the builds (a change that should not change
the numbers must give ~0).

  python3 scripts/benchmarks/benchmark_builds_on_checkpoint.py \
      --run output/hs2000_developed_4cells/p32000 \
      --prm output/hs2000_developed_4cells/p32000.prm \
      --build old=/tmp/old_build/softsand:/tmp/old_build \
      --build new=build/softsand --steps 3 --repeat 2 --ranks 2

A build is NAME=BINARY or NAME=BINARY:LIBRARY_DIRECTORY (that directory
goes first in LD_LIBRARY_PATH, ahead of the binary's RUNPATH).
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

def checkpoint_step(directory):
    steps = [int(m.group(1)) for f in os.listdir(directory)
             for m in [re.match(r'checkpoint-(\d+)\.dem$', f)] if m]
    if not steps:
        sys.exit('no checkpoint-N.dem in %s' % directory)
    return max(steps)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--run', required=True, help='run directory with a checkpoint')
    ap.add_argument('--prm', required=True, help="the run's parameter file")
    ap.add_argument('--build', action='append', required=True,
                    metavar='NAME=BINARY[:LIBDIR]')
    ap.add_argument('--steps', type=int, default=3)
    ap.add_argument('--repeat', type=int, default=2)
    ap.add_argument('--ranks', type=int, default=2)
    ap.add_argument('--workdir', default='output/benchmark_builds')
    args = ap.parse_args()
    if args.steps < 1 or args.repeat < 1 or args.ranks < 1:
        sys.exit('--steps, --repeat and --ranks must be at least 1')

    builds = []
    for b in args.build:
        name, _, where = b.partition('=')
        binary, _, libdir = where.partition(':')
        if not name or not os.path.isfile(binary):
            sys.exit('--build %s: expected NAME=BINARY[:LIBDIR] with an '
                     'existing BINARY' % b)
        builds.append((name, os.path.abspath(binary),
                       os.path.abspath(libdir) if libdir else None))

    first = checkpoint_step(args.run)
    pristine = os.path.join(args.workdir, 'pristine')
    if os.path.exists(args.workdir):
        sys.exit('%s exists: remove it or name another --workdir'
                 % args.workdir)
    os.makedirs(args.workdir)
    # Only the newest checkpoint and what a restart reads.
    shutil.copytree(args.run, pristine, ignore=lambda d, names: [
        n for n in names if n.startswith('checkpoint-') and
        not n.startswith('checkpoint-%d.' % first)])
    with open(args.prm) as f:
        text = f.read()
    text = prm_tools.set_entry(text, 'simulation control/restart', 'true')
    text = prm_tools.set_entry(text, 'simulation control/max time steps',
                               str(first + args.steps))
    text = prm_tools.set_entry(text, 'simulation control/checkpoint interval',
                               '1000000')

    times = {name: {} for name, _, _ in builds}
    ends = {name: [] for name, _, _ in builds}
    for r in range(args.repeat):
        for name, binary, libdir in builds:
            directory = os.path.join(args.workdir, '%s_%d' % (name, r))
            shutil.copytree(pristine, directory)
            prm = directory + '.prm'
            with open(prm, 'w') as f:
                f.write(prm_tools.set_entry(text, 'output/directory', directory))
            env = dict(os.environ)
            if libdir:
                env['LD_LIBRARY_PATH'] = libdir + ':' + env.get('LD_LIBRARY_PATH', '')
            command = ['mpirun', '-np', str(args.ranks), binary, prm]
            print('repeat %d, %s: %s' % (r, name, ' '.join(command)), flush=True)
            with open(directory + '.out', 'w') as out:
                rc = subprocess.call(command, stdout=out, stderr=subprocess.STDOUT,
                                     env=env)
            if rc != 0:
                sys.exit('%s exited %d: see %s.out' % (name, rc, directory))
            with open(os.path.join(directory, 'log.txt')) as f:
                log = f.read()  # earlier sessions' tables come first
            sections = prm_tools.timer_sections(
                log[log.rfind('| Total wallclock time elapsed'):], column='avg')
            for section, (calls, seconds) in sections.items():
                times[name].setdefault(section, []).append(
                    seconds / args.steps if section == 'total' or calls >= args.steps
                    else seconds)
            ends[name].append(prm_tools.read_statistics(directory)[-1])
            shutil.rmtree(directory)  # checkpoints are large
            os.makedirs(directory)

    print('\nmedian over %d repetitions, seconds per step (sections called '
          'fewer times than steps: seconds per run)' % args.repeat)
    names = [n for n, _, _ in builds]
    all_sections = sorted({s for n in names for s in times[n]})
    print('%-32s' % 'section' + ''.join('%12s' % n for n in names))
    for s in all_sections:
        print('%-32s' % s + ''.join(
            '%12.2f' % statistics.median(times[n][s]) if s in times[n] else '%12s' % '-'
            for n in names))

    reference = ends[names[0]][0]
    worst = (0., None)
    for n in names:
        for row in ends[n]:
            for column, b in row.items():
                if 'wall' in column or column not in reference:
                    continue
                a = reference[column]
                scale = max(abs(a), abs(b), 1e-300)
                d = abs(a - b) / scale
                if d > worst[0]:
                    worst = (d, column)
    print('\nend state after step %d: largest relative difference of a '
          'statistics column between all runs: %.3g (%s)'
          % (first + args.steps, worst[0], worst[1]))


if __name__ == '__main__':
    main()
