#!/usr/bin/env python3
"""The first coupled steps of an injection: is the grains' response stable?

Runs a coupled scene (default parameters/hele_shaw_small.prm) at one inlet
pressure for a few coupling steps of fixed length (no Courant halving) and
prints per step the fastest grain (statistics column max_speed) and the
largest fluid force on a grain (the grain files' fluid_force), then the
fastest grain of the last step over that of step 2 (a growing ratio is the
instability of issue 54: the paper's penalization at Theta 1e6 gave 2.45,
25.8, about 200 m/s over steps 1-3 at 4 cells per mean diameter).

  python3 scripts/studies/study_coupled_steps.py [--pressure 8000] [--steps 5]
      [--time-step 2.5e-4] [--ranks 1] [--max-courant 0]
      [--workdir output/study_coupled_steps] [--set "a/b=value" ...]
"""
import argparse
import base64
import glob
import os
import re
import struct
import subprocess
import sys
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def vtu_array(path, name):
    """The values of the DataArray @p name of a deal.II VTU file (ascii, or
    binary: a base64 header of four uint32 (blocks, block size, last block
    size, compressed size) followed by the base64 zlib block)."""
    with open(path) as f:
        text = f.read()
    m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>' % name,
                  text, re.S)
    if m is None:
        return []
    header = text[m.start():m.start(1)]
    body = m.group(1).strip()
    if 'format="ascii"' in header:
        return [float(v) for v in body.split()]
    head = base64.b64decode(body[:24])
    blocks, _, _, size = struct.unpack('<4I', head)
    if blocks != 1:
        sys.exit('%s: %d compressed blocks, only one is read' % (path, blocks))
    data = zlib.decompress(base64.b64decode(body[24:])[:size])
    kind = 'd' if 'Float64' in header else 'f'
    return list(struct.unpack('<%d%s' % (len(data) // struct.calcsize(kind),
                                         kind), data))


def largest_grain_force(directory, number):
    """The largest |fluid_force| over the grains of grain file @p number."""
    largest = 0.
    for path in glob.glob(os.path.join(directory, 'grains_%05d.*.vtu' % number)):
        f = vtu_array(path, 'fluid_force')
        for i in range(0, len(f) - 2, 3):
            largest = max(largest, (f[i]**2 + f[i + 1]**2 + f[i + 2]**2)**0.5)
    return largest


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--scene', default=os.path.join(ROOT, 'parameters',
                                                    'hele_shaw_small.prm'))
    ap.add_argument('--softsand', default=os.path.join(ROOT, 'build', 'softsand'))
    ap.add_argument('--pressure', type=float, default=8000.)
    ap.add_argument('--steps', type=int, default=5)
    ap.add_argument('--time-step', type=float, default=2.5e-4)
    ap.add_argument('--ranks', type=int, default=1)
    ap.add_argument('--max-courant', type=float, default=0.,
                    help='coupling/max courant number (0: fixed steps)')
    ap.add_argument('--workdir', default='output/study_coupled_steps')
    prm_tools.add_set_argument(ap, 'the scene')
    args = ap.parse_args()
    if args.steps < 2:
        sys.exit('--steps %d: at least 2 (the ratio is to step 2)' % args.steps)
    if args.time_step <= 0 or args.ranks < 1:
        sys.exit('--time-step must be > 0 s and --ranks >= 1')

    with open(args.scene) as f:
        text = f.read()
    for path, value in prm_tools.parse_set(args.set):
        text = prm_tools.set_entry(text, path, value)
    outdir = os.path.join(args.workdir, 'run')
    for path, value in [
            ('simulation control/time step', '%g' % args.time_step),
            ('simulation control/end time',
             '%.10g' % (args.steps * args.time_step)),
            ('coupling/max courant number', '%g' % args.max_courant),
            # fixed steps: the accuracy limit off too
            ('coupling/max velocity change', '0'),
            ('boundary conditions/inlet region/pressure', '%g' % args.pressure),
            ('output/directory', outdir),
            ('output/write vtu', 'true'),
            ('output/output interval', '1')]:
        text = prm_tools.set_entry(text, path, value)
    os.makedirs(args.workdir, exist_ok=True)
    prm = os.path.join(args.workdir, 'run.prm')
    with open(prm, 'w') as f:
        f.write(text)
    prm_tools.fresh_output(text, outdir)
    cmd = [args.softsand, prm]
    if args.ranks > 1:
        cmd = ['mpirun', '-np', str(args.ranks)] + cmd
    start = time.time()
    with open(os.path.join(args.workdir, 'run.log'), 'w') as log:
        code = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT)
    wall = time.time() - start
    rows = prm_tools.read_statistics(outdir) if os.path.exists(
        os.path.join(outdir, 'statistics.txt')) else []
    if code != 0:
        print('softsand ended with code %d after %d steps (see %s)'
              % (code, len(rows), os.path.join(args.workdir, 'run.log')))

    print('p_i = %g Pa, %g s steps, %s' % (args.pressure, args.time_step,
                                          ' '.join(args.set or [])))
    print('%5s %10s %18s %18s' % ('step', 't [s]', 'fastest grain [m/s]',
                                  'largest force [N]'))
    for k, r in enumerate(rows):
        # Grain file k is written after step k + 1.
        print('%5d %10.4g %18.4g %18.4g' % (k + 1, r['time'], r['max_speed'],
                                           largest_grain_force(outdir, k)))
    if len(rows) >= 2:
        last = rows[-1]['max_speed']
        print('fastest grain at step %d / step 2: %.3g' % (
            len(rows), last / max(rows[1]['max_speed'], 1e-300)))
    if rows:
        print('fastest grain over the run %.3g m/s, kinetic energy at the end '
              '%.3g J, fracture area at the end %.3g mm^2 (largest %.3g)' % (
                  max(r['max_speed'] for r in rows), rows[-1]['kinetic_energy'],
                  1e6 * rows[-1]['fracture_area'],
                  1e6 * max(r['fracture_area'] for r in rows)))
        print('%d DoFs, wall %.0f s' % (rows[-1]['dofs'], wall))


if __name__ == '__main__':
    main()
