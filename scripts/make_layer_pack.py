#!/usr/bin/env python3
"""A single layer of equal spheres for the paper's Fig. 3 box (until the DEM
pour-and-compact scene of issue 3 makes it): a hexagonal layer in the
x-y plane with a random jitter, centred in z, non-overlapping, inside the box.

  python3 scripts/make_layer_pack.py LX LY LZ DIAMETER GAP JITTER SEED FILE
  (metres; GAP: extra centre distance over the diameter; JITTER: random
  displacement in units of GAP/2)
"""
import math
import random
import sys


def main():
    lx, ly, lz, d, gap, jitter = map(float, sys.argv[1:7])
    seed, out = int(sys.argv[7]), sys.argv[8]
    rng = random.Random(seed)
    r, a = d / 2, d + gap
    grains = []
    row, y = 0, r + gap / 2
    while y + r <= ly:
        x = r + gap / 2 + (a / 2 if row % 2 else 0)
        while x + r <= lx:
            dx = (rng.random() - 0.5) * jitter * gap / 2
            dy = (rng.random() - 0.5) * jitter * gap / 2
            grains.append((x + dx, y + dy, lz / 2, r))
            x += a
        y += a * math.sqrt(3) / 2
        row += 1
    for i, g in enumerate(grains):
        for h in grains[:i]:
            assert math.dist(g[:3], h[:3]) >= 2 * r, 'overlap'
    with open(out, 'w') as f:
        f.write('# x y z radius (m): hexagonal layer, %d grains, box %g x %g x '
                '%g m, seed %d\n' % (len(grains), lx, ly, lz, seed))
        for g in grains:
            f.write('%.9e %.9e %.9e %.9e\n' % g)
    vol = len(grains) * 4 / 3 * math.pi * r ** 3
    print('%d grains, solid fraction %.4f' % (len(grains), vol / (lx * ly * lz)))


if __name__ == '__main__':
    main()
