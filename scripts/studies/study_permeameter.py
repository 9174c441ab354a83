#!/usr/bin/env python3
"""A permeameter: Darcy permeability of a pack in a cylinder, along its axis,
against Kozeny-Carman with Mehta and Hawley's wall correction.

Stage 1 pours and compacts the pack in the cylinder (DEM,
parameters/permeameter_pack.prm); stage 2 solves steady Stokes-Brinkman
through it (parameters/permeameter.prm: mesh/geometry = cylinder, a flow-rate
inlet at z min, a pressure outlet at z max, the mantle a no-slip wall,
grain-free buffers of 0.2 mm before and after the pack) at each N of --n, and
prints K = q mu L / dp between two planes inside the pack, 0.1 mm from its
ends, with the porosity of the grains between the same planes and

  K_KC = phi^3 d^2 / (180 (1 - phi)^2)           (d: Sauter mean diameter)
  M    = 1 + 4 d / (6 D (1 - phi))               (Mehta and Hawley, 1969)

the wall correction for a bed of diameter D: the mantle adds 4 / D of wetted
surface per bed volume to the grains' 6 (1 - phi) / d, and K_KC / M^2 is
Carman's hydraulic-radius estimate with it. Both take one porosity for the
whole section; next to the mantle the grains pack looser (a wall channel),
so the script also prints the porosity of annuli half a grain wide and K_par, Kozeny-
Carman per annulus in parallel with the mantle's surface in the outer one.

  python3 scripts/studies/study_permeameter.py [--n 4,6] [--workdir /tmp/permeameter]
      [--radius 2.5e-4] [--seed 3]
      [--set "coupling/void fraction model=cell average"]
"""
import argparse
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOFTSAND = os.path.join(ROOT, 'build', 'softsand')
RADIUS = 2.5e-4     # the cylinder of parameters/permeameter*.prm (m)
COUNT = 150         # its grains
BUFFER = 2e-4       # grain-free fluid before and after the pack (m)
MARGIN = 1e-4       # pressure planes this far inside the pack's ends (m)


def solid_between(grains, z1, z2):
    """Volume of the spheres between the planes z = z1 and z2."""
    def primitive(r, z):
        return math.pi * (r * r * z - z ** 3 / 3)
    volume = 0.0
    for x, y, z, r in grains:
        a, b = max(z1 - z, -r), min(z2 - z, r)
        if b > a:
            volume += primitive(r, b) - primitive(r, a)
    return volume


# A cell and its 26 neighbours in the cell list.
NEIGHBOUR_CELLS = [(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)]


def annulus_porosities(grains, radius, z1, z2, n_annuli, spacing):
    """Porosity of n_annuli annuli of equal width between the planes, from a
    regular grid of sample points (a cell list of the grains)."""
    cell = max(2 * g[3] for g in grains)
    buckets = {}
    for g in grains:
        key = tuple(int(math.floor(c / cell)) for c in g[:3])
        buckets.setdefault(key, []).append(g)

    def covered(x, y, z):
        i, j, k = (int(math.floor(c / cell)) for c in (x, y, z))
        for di, dj, dk in NEIGHBOUR_CELLS:
            for g in buckets.get((i + di, j + dj, k + dk), ()):
                if (x - g[0]) ** 2 + (y - g[1]) ** 2 + (z - g[2]) ** 2 < g[3] ** 2:
                    return True
        return False

    solid, total = [0] * n_annuli, [0] * n_annuli
    n = int(2 * radius / spacing)
    nz = int((z2 - z1) / spacing)
    for i in range(n):
        x = -radius + (i + 0.5) * spacing
        for j in range(n):
            y = -radius + (j + 0.5) * spacing
            r = math.hypot(x, y)
            if r >= radius:
                continue
            a = int(r / radius * n_annuli)
            for k in range(nz):
                z = z1 + (k + 0.5) * spacing
                total[a] += 1
                solid[a] += covered(x, y, z)
    return [1 - s / t for s, t in zip(solid, total)]


def pour(workdir, radius, seed):
    """Stage 1 (reused when done before with the same input): the pack file
    and the piston's height. Another radius than the scene's keeps the
    pack's height: the grain count scales with the cross-section."""
    text = open(os.path.join(ROOT, 'parameters', 'permeameter_pack.prm')).read()
    out = os.path.join(workdir, 'pack')
    entries = [('output/directory', out), ('output/write vtu', 'false'),
               ('output/verbosity', 'quiet'), ('grains/seed', seed)]
    if radius != RADIUS:
        half = radius / math.sqrt(2) - 1e-6
        entries += [('mesh/lower corner', '%.9g, %.9g, 0' % (-radius, -radius)),
                    ('mesh/upper corner', '%.9g, %.9g, 4.2e-3' % (radius, radius)),
                    ('grains/count', round(COUNT * (radius / RADIUS) ** 2)),
                    ('grains/region lower corner', '%.9g, %.9g, 0' % (-half, -half)),
                    ('grains/region upper corner', '%.9g, %.9g, 4.1e-3' % (half, half)),
                    ('dem/walls/list', 'plane 0 0 4.2e-3 0 0 -1 servo; '
                     'cylinder 0 0 0 0 0 1 %.9g inside' % radius)]
    for path, value in entries:
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(workdir, 'pack.prm')
    pack = os.path.join(out, 'pack.txt')
    os.makedirs(workdir, exist_ok=True)
    if not (os.path.exists(pack) and os.path.exists(prm) and open(prm).read() == text):
        open(prm, 'w').write(text)
        prm_tools.fresh_output(text, out)
        subprocess.run([SOFTSAND, prm], check=True, capture_output=True, text=True)
    height = -prm_tools.read_statistics(out)[-1]['wall_0_position']
    return pack, height


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--n', default='4,6', help='cells per smallest diameter, comma separated')
    parser.add_argument('--workdir', default='/tmp/permeameter')
    parser.add_argument('--pack', help='a pack file (with --height) instead of stage 1')
    parser.add_argument('--height', type=float, help='the pack\'s height (m), with --pack')
    parser.add_argument('--seed', type=int, default=3, help='the pour\'s random seed')
    parser.add_argument('--radius', type=float, default=RADIUS,
                        help='the cylinder\'s radius (m); the grain count scales with R^2')
    prm_tools.add_set_argument(parser, 'stage 2')
    args = parser.parse_args()

    pack, height = (os.path.abspath(args.pack), args.height) if args.pack else \
        pour(args.workdir, args.radius, args.seed)
    radius = args.radius
    grains = prm_tools.read_grains(pack)
    d = sum((2 * g[3]) ** 3 for g in grains) / sum((2 * g[3]) ** 2 for g in grains)
    z1, z2 = MARGIN, height - MARGIN
    phi = 1 - solid_between(grains, z1, z2) / (math.pi * radius ** 2 * (z2 - z1))
    k_kc = phi ** 3 * d * d / (180 * (1 - phi) ** 2)
    m = 1 + 4 * d / (6 * 2 * radius * (1 - phi))
    print('pack: %d grains, height %.4g mm, Sauter mean diameter %.4g mm, porosity '
          'between the planes %.4f; K_KC = %.4g m^2, M = %.3f, K_KC / M^2 = %.4g m^2'
          % (len(grains), height * 1e3, d * 1e3, phi, k_kc, m, k_kc / m ** 2))

    # The porosity next to the mantle is higher (grains cannot fill the
    # space against a wall): Kozeny-Carman per annulus, in parallel (each
    # annulus carries flow q_i = K_i dp / (mu L)), the wall's surface in the
    # outer one.
    n_annuli = max(1, round(radius / (0.5 * d)))  # annuli half a grain wide
    phis = annulus_porosities(grains, radius, z1, z2, n_annuli, d / 12)
    k_parallel = 0.0
    for a, p in enumerate(phis):
        r_in, r_out = radius * a / n_annuli, radius * (a + 1) / n_annuli
        share = (r_out ** 2 - r_in ** 2) / radius ** 2
        wall = 2 * r_out / (r_out ** 2 - r_in ** 2) if a == n_annuli - 1 else 0.0
        m_a = 1 + wall * d / (6 * (1 - p))
        k_parallel += share * p ** 3 * d * d / (180 * (1 - p) ** 2) / m_a ** 2
    print('porosity of %d annuli of width %.3g mm, axis to wall: %s; Kozeny-Carman '
          'per annulus in parallel (the mantle\'s surface in the outer one): '
          'K_par = %.4g m^2' % (n_annuli, radius / n_annuli * 1e3,
                               ', '.join('%.3f' % p for p in phis), k_parallel))

    text = open(os.path.join(ROOT, 'parameters', 'permeameter.prm')).read()
    q = 1e-3  # superficial velocity (m/s)
    print('\n| N | DoFs | FGMRES | wall [s] | K [m^2] | K / K_KC | K / (K_KC / M^2) | K / K_par |')
    print('|---|---|---|---|---|---|---|---|')
    for n in [v for v in args.n.split(",") if v]:
        overrides = [('grains/file', pack),
                     ('mesh/lower corner', '%.9g, %.9g, %.9g' % (-radius, -radius, -BUFFER)),
                     ('mesh/upper corner', '%.9g, %.9g, %.9g' % (radius, radius, height + BUFFER)),
                     ('mesh/cells per diameter', n),
                     ('postprocessing/pressure drop planes', '%.9g, %.9g' % (z1, z2)),
                     ('boundary conditions/z min/flow rate',
                      '%.9g' % (q * math.pi * radius ** 2))] + prm_tools.parse_set(args.set)
        row, wall, err = prm_tools.run(SOFTSAND, text, args.workdir, 'K_N' + n, 1, overrides)
        if row is None:
            print('| %s | failed: %s |' % (n, ' '.join(err)))
            continue
        k = row['permeability']
        print('| %s | %d | %d | %.0f | %.4g | %.3f | %.3f | %.3f |'
              % (n, row['dofs'], row['linear_iterations'], wall, k, k / k_kc,
                 k / (k_kc / m ** 2), k / k_parallel))
        sys.stdout.flush()


if __name__ == '__main__':
    main()
