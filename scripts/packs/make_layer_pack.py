#!/usr/bin/env python3
"""A single layer of equal spheres for the paper's Fig. 3 box (until the DEM
pour-and-compact scene of issue 3 makes it): a hexagonal layer in the
x-y plane, centred in the box (no open strip along a wall), with a random
jitter, centred in z, non-overlapping.

  python3 scripts/packs/make_layer_pack.py LX LY LZ DIAMETER GAP JITTER SEED FILE
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
    dy = a * math.sqrt(3) / 2
    # Centre the lattice in x and y: a leftover strip along one wall would
    # be an open channel that bypasses the pack.
    n_rows = int((ly - d - gap) / dy + 1e-9) + 1
    n_cols = int((lx - d - gap - a / 2) / a + 1e-9) + 1
    y0 = (ly - (n_rows - 1) * dy) / 2
    x0 = (lx - (n_cols - 1) * a - a / 2) / 2
    grains = []
    for row in range(n_rows):
        for col in range(n_cols):
            x = x0 + col * a + (a / 2 if row % 2 else 0)
            dx = (rng.random() - 0.5) * jitter * gap / 2
            ddy = (rng.random() - 0.5) * jitter * gap / 2
            grains.append((x + dx, y0 + row * dy + ddy, lz / 2, r))
    for i, g in enumerate(grains):
        assert r <= g[0] <= lx - r and r <= g[1] <= ly - r, 'outside'
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
