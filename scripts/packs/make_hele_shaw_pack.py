#!/usr/bin/env python3
"""The loose pack of the radial Hele-Shaw cell (the paper's section 4):
random sequential insertion of N spheres with truncated-normal diameters
(by number; the paper's mean 1.35 mm, sd 0.3 mm, range 0.9-1.8 mm) between
two plates (z = 0 and z = gap), inside a regular octagon of inradius R
(pistons normal to the x and y axes and the diagonals, centred on the
origin) and outside the inlet cylinder of radius r_i around the z axis.
No overlaps, no grain cut by a plate, a piston or the inlet. The octagon
inradius follows from the loose solid fraction asked for (random
sequential insertion of polydisperse spheres stalls near 0.35).

  python3 scripts/packs/make_hele_shaw_pack.py --count 2000 --out pack.txt

prints the octagon inradius (m) to use for the compaction scene on the last
line ("octagon_inradius R").
"""
import argparse
import math
import random


def truncated_normal(rng, mean, sd, lo, hi):
    while True:
        d = rng.gauss(mean, sd)
        if lo <= d <= hi:
            return d


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--count', type=int, default=2000)
    a.add_argument('--mean', type=float, default=1.35e-3)
    a.add_argument('--sd', type=float, default=0.3e-3)
    a.add_argument('--min', type=float, default=0.9e-3)
    a.add_argument('--max', type=float, default=1.8e-3)
    a.add_argument('--gap', type=float, default=None,
                   help='plate distance (m); default 2.5 mean diameters')
    a.add_argument('--inlet-radius', type=float, default=4e-3)
    a.add_argument('--solid-fraction', type=float, default=0.3,
                   help='loose solid fraction of the octagon minus the '
                        'inlet between the plates')
    a.add_argument('--seed', type=int, default=1)
    a.add_argument('--out', required=True)
    args = a.parse_args()
    rng = random.Random(args.seed)
    gap = args.gap if args.gap else 2.5 * args.mean
    diameters = sorted((truncated_normal(rng, args.mean, args.sd, args.min,
                                         args.max)
                        for _ in range(args.count)), reverse=True)
    volume = sum(math.pi / 6 * d ** 3 for d in diameters)
    # Octagon area 8 tan(pi/8) R^2.
    area = volume / (args.solid_fraction * gap) + math.pi * args.inlet_radius ** 2
    R = math.sqrt(area / (8 * math.tan(math.pi / 8)))
    normals = [(math.cos(k * math.pi / 4), math.sin(k * math.pi / 4))
               for k in range(8)]
    cell = args.max
    grid = {}
    placed = []

    def key(x, y, z):
        return (int(math.floor(x / cell)), int(math.floor(y / cell)),
                int(math.floor(z / cell)))

    for n, d in enumerate(diameters):
        r = d / 2
        for attempt in range(200000):
            x = rng.uniform(-R + r, R - r)
            y = rng.uniform(-R + r, R - r)
            z = rng.uniform(r, gap - r)
            if math.hypot(x, y) < args.inlet_radius + r:
                continue
            if any(x * nx + y * ny > R - r for nx, ny in normals):
                continue
            kx, ky, kz = key(x, y, z)
            ok = True
            for i in (kx - 1, kx, kx + 1):
                for j in (ky - 1, ky, ky + 1):
                    for k in (kz - 1, kz, kz + 1):
                        for m in grid.get((i, j, k), ()):
                            px, py, pz, pr = placed[m]
                            if (x - px) ** 2 + (y - py) ** 2 + (z - pz) ** 2 < \
                                    (r + pr) ** 2:
                                ok = False
                                break
                        if not ok:
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if ok:
                grid.setdefault((kx, ky, kz), []).append(len(placed))
                placed.append((x, y, z, r))
                break
        else:
            raise SystemExit('could not place grain %d of %d: lower '
                             '--solid-fraction' % (n + 1, args.count))
    with open(args.out, 'w') as f:
        f.write('# x y z radius (m): loose Hele-Shaw pack, %d grains, '
                'truncated normal d (mean %g, sd %g, [%g, %g]) by number, '
                'plates z = 0 and %g, octagon inradius %.6g, inlet radius '
                '%g, solid fraction %g, seed %d\n'
                % (len(placed), args.mean, args.sd, args.min, args.max, gap,
                   R, args.inlet_radius, args.solid_fraction, args.seed))
        for g in placed:
            f.write('%.9e %.9e %.9e %.9e\n' % g)
    mean_d = sum(diameters) / len(diameters)
    print('%d grains, mean diameter %.4g m, gap %.6g m' %
          (len(placed), mean_d, gap))
    print('octagon_inradius %.9g' % R)


if __name__ == '__main__':
    main()
