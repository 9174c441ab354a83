#!/usr/bin/env python3
"""Top view (x-y) of the grains of a Hele-Shaw injection run (issue 5):
each grain a circle of its radius, coloured by its displacement since the
start (mm, logarithmic scale) or by its speed (m/s).

  /usr/bin/python3 scripts/plots/plot_hele_shaw_grains.py \
    --start parameters/packs/hele_shaw_2000.txt \
    --end output/hele_shaw_default/p16000/pack_end.txt \
    --title '16 kPa, 6 ms' --out doc/hele_shaw_grains_p16000.png

--end omitted: the pack itself (coloured by its speed). The grain files
are softsand's text packs (x y z radius vx vy vz wx wy wz, SI); the
Hele-Shaw scenes (and so the sweep, scripts/studies/hele_shaw_sweep.py) save each
run's last grains as pack_end.txt in its output directory (dem/save pack),
in the pack file's order, so grain i of the
two files is the same grain. Grains are drawn from the bottom plate up
(the top view shows the upper grains). The white disc is the inlet
(--inlet-radius). Needs matplotlib (/usr/bin/python3 on this machine).
"""
import argparse
import os
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--start', required=True, help='pack before injection')
    a.add_argument('--end', help='grains after the last step (pack_end.txt)')
    a.add_argument('--color', choices=['displacement', 'speed'],
                   default='displacement')
    a.add_argument('--range', default='1e-3,3',
                   help='colour range: displacement (mm, log) or speed '
                        '(m/s, linear), "low,high"')
    a.add_argument('--inlet-radius', type=float, default=4e-3, help='m')
    a.add_argument('--title', default='')
    a.add_argument('--out', required=True)
    args = a.parse_args()

    for name, path in (('--start', args.start), ('--end', args.end)):
        if path is not None and not os.path.isfile(path):
            hint = ('' if name == '--start' else
                    ': the Hele-Shaw scenes write it at the end of a run '
                    '(dem/save pack = pack_end.txt in the output directory); '
                    'a run that failed, or one of an older scene, has none. '
                    'Omit --end to draw the pack alone')
            sys.exit(f'plot_hele_shaw_grains.py: {name} {path}: no such '
                     f'file{hint}.')
    start = np.loadtxt(args.start)
    grains = np.loadtxt(args.end) if args.end else start
    assert grains.shape == start.shape, 'the two files differ in grains'
    low, high = (float(v) for v in args.range.split(','))
    if args.color == 'displacement' and args.end:
        value = np.linalg.norm(grains[:, :3] - start[:, :3], axis=1) * 1e3
        value = np.clip(value, low, high)
        norm, label = LogNorm(low, high), 'displacement since the start (mm)'
    else:
        value = np.linalg.norm(grains[:, 4:7], axis=1)
        norm, label = Normalize(low, high), 'speed (m/s)'

    order = np.argsort(grains[:, 2])
    circles = [Circle((grains[i, 0] * 1e3, grains[i, 1] * 1e3),
                      grains[i, 3] * 1e3) for i in order]
    patches = PatchCollection(circles, cmap='viridis', norm=norm,
                              edgecolor='k', linewidth=0.2)
    patches.set_array(value[order])

    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    ax.add_collection(patches)
    ax.add_patch(Circle((0, 0), args.inlet_radius * 1e3, facecolor='white',
                        edgecolor='r', linewidth=0.8))
    extent = np.max(np.abs(grains[:, :2])) * 1e3 + 1.5
    ax.set_xlim(-extent, extent)
    ax.set_ylim(-extent, extent)
    ax.set_aspect('equal')
    ax.set_xlabel('x (mm)')
    ax.set_ylabel('y (mm)')
    ax.set_title(args.title)
    fig.colorbar(patches, ax=ax, label=label)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print('%s: %d grains, %s %.3g-%.3g (median %.3g)'
          % (args.out, len(grains), args.color if args.end else 'speed',
             value.min(), value.max(), np.median(value)))


if __name__ == '__main__':
    main()
