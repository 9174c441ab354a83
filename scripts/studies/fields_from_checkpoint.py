#!/usr/bin/env python3
"""Field output (VTU) of a run's last checkpoint: sweeps write fields only at
their first step, so this restarts a copy of the run from its checkpoint
for one step with field output, leaving the run itself untouched.

  python3 scripts/studies/fields_from_checkpoint.py --run output/SWEEP/p22000 \
    --out output/fields_p22000 [--ranks 2]

Writes <out>/solution_NNNN.pvtu, grains_NNNN.pvtu, pack_end.txt and the
fracture map of the step after the checkpoint, e.g. for
scripts/plots/plot_hele_shaw_flow.py or ParaView (scripts/plots/show_hele_shaw.py).
"""
import argparse
import glob
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--run', required=True,
                   help='a run directory with checkpoint.info and original.prm')
    a.add_argument('--out', required=True, help='a new directory')
    a.add_argument('--ranks', type=int, default=1)
    a.add_argument('--softsand', default='build/softsand')
    args = a.parse_args()
    info = os.path.join(args.run, 'checkpoint.info')
    original = os.path.join(args.run, 'original.prm')
    for path in (info, original, args.softsand):
        if not os.path.isfile(path):
            sys.exit('no file %s' % path)
    if args.ranks < 1:
        sys.exit('--ranks must be at least 1, got %d' % args.ranks)
    if os.path.exists(args.out):
        sys.exit('--out %s exists: choose a new directory (nothing is '
                 'overwritten)' % args.out)
    step = int(open(info).read().split()[0])
    files = glob.glob(os.path.join(args.run, 'checkpoint-%d.*' % step))
    if not files:
        sys.exit('%s names step %d, but there is no checkpoint-%d.*'
                 % (info, step, step))
    os.makedirs(args.out)
    for path in files + [info, os.path.join(args.run, 'statistics.txt')] + \
            glob.glob(os.path.join(args.run, '*.pvd')):
        if os.path.isfile(path):
            shutil.copy(path, args.out)
    text = open(original).read()
    for entry, value in [('output/directory', args.out),
                         ('simulation control/restart', 'true'),
                         ('output/write vtu', 'true'),
                         ('output/output interval', '1'),
                         ('simulation control/max time steps', str(step + 1))]:
        text = prm_tools.set_entry(text, entry, value)
    prm = os.path.join(args.out, 'restart.prm')
    open(prm, 'w').write(text)
    command = [args.softsand, prm]
    if args.ranks > 1:
        command = ['mpirun', '-np', str(args.ranks)] + command
    with open(os.path.join(args.out, 'restart.log'), 'w') as log:
        code = subprocess.call(command, stdout=log, stderr=subprocess.STDOUT)
    if code != 0:
        sys.exit('softsand failed (exit %d): see %s/restart.log' % (code, args.out))
    written = sorted(glob.glob(os.path.join(args.out, 'solution_*.pvtu')))
    print('step %d -> %d: %s' % (step, step + 1,
                                 written[-1] if written else 'no field output'))


if __name__ == '__main__':
    main()
