#!/usr/bin/env python3
"""The paper's Fig. 5: Darcy permeability of compacted grain packs.

  refinement: K of one pack against cells per diameter (Fig. 5a);
  porosity:   K of packs poured and compacted by the DEM with different
              grain sizes, friction and compaction pressure (Fig. 5b),
              against Kozeny-Carman K = phi^3 d^2 / (180 (1 - phi)^2).

Each pack: parameters/pour_and_compact.prm (granular mode; the piston's
final position closes the box), then one steady Stokes-Brinkman solve of
parameters/pack_permeability.prm on the pack (flow-rate inlet, pressure
outlet, K = q mu L / dp between two planes). Porosity both ways: the
paper's volume fraction of cells with vf > 0.9 between the two planes,
and the grains' void volume in the pack's box.

  python3 scripts/studies/study_pack_permeability.py refinement [--n 4,6,8]
  python3 scripts/studies/study_pack_permeability.py porosity [--n 6] [--packs 10]
  python3 scripts/studies/study_pack_permeability.py plot [--plot doc/figures/...]

plot: every finished run in the work directory, K against the paper's cell
porosity with Kozeny-Carman, and the Kozeny constant C of the least-squares
fit K = phi^3 d^2 / (C (1 - phi)^2) over the runs at N >= 6 (Kozeny-Carman:
C = 180).
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOFTSAND = os.path.join(ROOT, 'build', 'softsand')

# (mean diameter m, friction, compaction pressure Pa, seed): ten packs of the
# Fig. 3 box, 100 grains of +-10 % size.
PACKS = [(1.0e-4, 0.7, 1e4, 3), (1.0e-4, 0.7, 1e3, 4), (1.0e-4, 0.7, 3e4, 5),
         (1.0e-4, 0.3, 1e4, 6), (1.0e-4, 0.1, 1e4, 7), (1.0e-4, 0.0, 3e4, 8),
         (0.9e-4, 0.7, 1e4, 9), (0.9e-4, 0.1, 1e4, 10), (1.1e-4, 0.7, 1e4, 11),
         (1.1e-4, 0.3, 3e4, 12)]


def kozeny_carman(phi, d):
    return phi ** 3 * d * d / (180 * (1 - phi) ** 2)


def kozeny_carman_walls(phi, d, height, thickness):
    """Kozeny-Carman with the box walls counted (Carman's hydraulic radius):
    the no-slip plates (thickness apart) and side walls (height apart) add
    2 / thickness + 2 / height of wetted surface per bed volume to the
    grains' 6 (1 - phi) / d, so K_KC is divided by M^2 with
    M = 1 + (2 / thickness + 2 / height) d / (6 (1 - phi)) (the form of
    Mehta and Hawley's wall correction, for plates). A single layer between
    plates 1.1 d apart: M^2 = 2.9."""
    m = 1 + (2 / thickness + 2 / height) * d / (6 * (1 - phi))
    return kozeny_carman(phi, d) / (m * m)


def pack_dir(workdir, d, friction, pressure, seed):
    return os.path.join(workdir, 'pack_d%g_mu%g_p%g_s%d' % (d, friction, pressure, seed))


def run_name(d, friction, pressure, n, tag):
    return 'K_d%g_mu%g_p%g_N%s%s' % (d, friction, pressure, n, tag)


def saved_pack(out, d):
    """A pack poured before into @p out: (pack file, piston height, box
    thickness)."""
    return (os.path.join(out, 'pack.txt'),
            -prm_tools.read_statistics(out)[-1]['wall_0_position'], 1.1 * d)


def make_pack(workdir, d, friction, pressure, seed):
    """Pour and compact a pack; returns (pack file, piston height, box
    thickness)."""
    out = pack_dir(workdir, d, friction, pressure, seed)
    name = os.path.basename(out)
    text = open(os.path.join(ROOT, 'parameters', 'pour_and_compact.prm')).read()
    for path, value in [('grains/min diameter', 0.9 * d), ('grains/max diameter', 1.1 * d),
                        ('grains/seed', seed), ('mesh/upper corner', '1e-3, 2e-3, %g' % (1.1 * d)),
                        ('grains/region upper corner', '1e-3, 1.9e-3, %g' % (1.1 * d)),
                        ('dem/material/friction', friction),
                        ('dem/walls/servo pressure', pressure),
                        ('output/directory', out), ('output/write vtu', 'false'),
                        ('output/verbosity', 'quiet')]:
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(workdir, name + '.prm')
    os.makedirs(workdir, exist_ok=True)
    pack = os.path.join(out, 'pack.txt')
    if os.path.exists(pack) and open(prm).read() == text:
        # Poured before with the same parameters: reuse it.
        return saved_pack(out, d)
    open(prm, 'w').write(text)
    prm_tools.fresh_output(text, out)
    log = subprocess.run([SOFTSAND, prm], capture_output=True, text=True, check=True).stdout
    height = -float(re.search(r'wall_0_position\s+(\S+)', log).group(1))
    return os.path.join(out, 'pack.txt'), height, 1.1 * d


def pack_porosity(pack, height, thickness):
    solid = 0.0
    for line in open(pack):
        if line.strip() and not line.startswith('#'):
            solid += 4.0 / 3.0 * math.pi * float(line.split()[3]) ** 3
    return 1.0 - solid / (1e-3 * height * thickness)


def permeability(workdir, name, pack, height, thickness, n, d, max_overlap=0.6, extra=()):
    text = open(os.path.join(ROOT, 'parameters', 'pack_permeability.prm')).read()
    q = 1e-3  # superficial velocity (m/s)
    row, wall, err = prm_tools.run(
        SOFTSAND, text, workdir, name, 1,
        [('grains/file', pack), ('grains/max overlap ratio', max_overlap),
         ('mesh/upper corner', '1.2e-3, %.9g, %.9g' % (height, thickness)),
         ('mesh/cells per diameter', n),
         ('boundary conditions/x min/flow rate', '%.9g' % (q * height * thickness))]
        + list(extra))
    if row is None:
        return None, wall, err
    return row, wall, None


def plot(workdir, path):
    """K against the cells' porosity for every finished run; fit of C."""
    points = []
    for name in sorted(os.listdir(workdir)):
        m = re.match(r'K_d([0-9.e-]+)_mu([0-9.]+)_p([0-9.e+]+)_N(\d+)$', name)
        if not m or not os.path.exists(os.path.join(workdir, name, 'statistics.txt')):
            continue
        rows = prm_tools.read_statistics(os.path.join(workdir, name))
        if not rows or 'slab_porosity_cells' not in rows[-1]:
            continue
        d = float(m.group(1))
        phi = rows[-1]['slab_porosity_cells']
        k = rows[-1]['permeability']
        points.append((name, int(m.group(4)), d, phi, k, k / kozeny_carman(phi, d)))
    # Least squares in log K: log C = mean(log(phi^3 d^2 / ((1-phi)^2 K))),
    # over N >= 6 (N = 4 gives 0.07 of the N = 8 value on the Fig. 5a pack).
    fitted = [p[5] for p in points if p[1] >= 6]
    c = math.exp(sum(math.log(180 / r) for r in fitted) / len(fitted)) if fitted else float('nan')
    print('| run | N | d (mm) | porosity (cells vf > 0.9, between the planes) | K (m^2) | K / K_KC |')
    print('|---|---|---|---|---|---|')
    for name, n, d, phi, k, r in points:
        print('| %s | %d | %g | %.3f | %.3e | %.2f |' % (name, n, d * 1e3, phi, k, r))
    print('\n%d runs at N >= 6: K / K_KC from %.2f to %.2f; fitted Kozeny constant '
          'C = %.0f (Kozeny-Carman 180)' % (len(fitted), min(fitted), max(fitted), c))
    plt = prm_tools.pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    for n, marker in [(4, 's'), (6, 'o'), (8, '^')]:
        sel = [p for p in points if p[1] == n]
        if sel:
            ax.scatter([p[3] for p in sel], [p[4] / p[2] ** 2 for p in sel], marker=marker,
                       label='N = %d' % n)
    phis = [0.25 + 0.005 * i for i in range(41)]
    ax.plot(phis, [kozeny_carman(p, 1.0) for p in phis], 'b--', label='Kozeny-Carman (C = 180)')
    ax.plot(phis, [kozeny_carman(p, 1.0) * 180 / c for p in phis], 'k:',
            label='fit, C = %.0f' % c)
    ax.set_yscale('log')
    ax.set_xlabel('porosity (cells with vf > 0.9)')
    ax.set_ylabel('K / d^2')
    ax.set_title('Pack permeability (Fig. 5b)')
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print('plot:', path)


def plot_grain_porosity(workdir, tag, path):
    """Runs named with --tag: K against the grains' porosity, with
    Kozeny-Carman with and without the walls' surface."""
    points = []
    for d, friction, pressure, seed in PACKS:
        name = run_name(d, friction, pressure, 6, tag)
        if not os.path.exists(os.path.join(workdir, name, 'statistics.txt')):
            continue
        rows = prm_tools.read_statistics(os.path.join(workdir, name))
        if not rows:
            continue
        k = rows[-1]['permeability']
        pack, height, thickness = saved_pack(pack_dir(workdir, d, friction, pressure, seed), d)
        pv = pack_porosity(pack, height, thickness)
        points.append((name, d, pv, k, k / kozeny_carman(pv, d),
                       k / kozeny_carman_walls(pv, d, height, thickness)))
    if not points:
        print('no finished runs with tag %s' % tag)
        return
    print('| run | porosity of the grains | K (m^2) | K / K_KC | K / K_KC with walls |')
    print('|---|---|---|---|---|')
    for name, d, pv, k, r, rw in points:
        print('| %s | %.3f | %.3e | %.2f | %.2f |' % (name, pv, k, r, rw))
    rws = [p[5] for p in points]
    print('\n%d packs: K / K_KC with walls from %.2f to %.2f (geometric mean %.2f)'
          % (len(rws), min(rws), max(rws), math.exp(sum(map(math.log, rws)) / len(rws))))
    plt = prm_tools.pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.scatter([p[2] for p in points], [p[3] / p[1] ** 2 for p in points], label='N = 6, %s' % tag.strip('_'))
    phis = [0.38 + 0.005 * i for i in range(35)]
    ax.plot(phis, [kozeny_carman(p, 1.0) for p in phis], 'b--', label='Kozeny-Carman')
    ax.plot(phis, [kozeny_carman_walls(p, 1.0, 10.0, 1.1) for p in phis], 'k:',
            label='Kozeny-Carman with the walls (t = 1.1 d, h = 10 d)')
    ax.set_yscale('log')
    ax.set_xlabel('porosity of the grains')
    ax.set_ylabel('K / d^2')
    ax.set_title('Pack permeability, %s' % tag.strip('_'))
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print('plot:', path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('study', choices=['refinement', 'porosity', 'plot'])
    ap.add_argument('--plot', default=os.path.join(ROOT, 'doc/figures/pack_permeability.png'))
    ap.add_argument('--n', default=None)
    ap.add_argument('--packs', type=int, default=10)
    ap.add_argument('--first', type=int, default=0,
                    help='porosity study: start at this pack (0-based), to '
                         'split the series over processes')
    ap.add_argument('--max-overlap', type=float, default=0.6,
                    help='grains/max overlap ratio for the packs (the soft '
                         'grains compacted at 100 kPa overlap by 0.7-0.9 R*)')
    ap.add_argument('--workdir', default=os.path.join(ROOT, 'output/study_pack_permeability'))
    prm_tools.add_set_argument(ap, 'pack_permeability.prm')
    ap.add_argument('--tag', default='',
                    help='suffix of the run names, to keep runs with --set apart')
    a = ap.parse_args()
    extra = prm_tools.parse_set(a.set)
    if a.study == 'plot':
        if a.tag:
            plot_grain_porosity(a.workdir, a.tag, a.plot)
        else:
            plot(a.workdir, a.plot)
        return
    print('| pack (d, friction, p) | N | cells | DoFs | FGMRES | wall (s) | K (m^2) | '
          'porosity, cells vf > 0.9 | porosity of the grains | K/K_KC (cells) | K/K_KC (grains) | '
          'K/K_KC with walls (grains) |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|')
    if a.study == 'refinement':
        packs = PACKS[:1]
        ns = (a.n or '4,6,8').split(',')
    else:
        packs = PACKS[a.first:a.first + a.packs]
        ns = (a.n or '6').split(',')
    for d, friction, pressure, seed in packs:
        pack, height, thickness = make_pack(a.workdir, d, friction, pressure, seed)
        for n in ns:
            name = run_name(d, friction, pressure, n, a.tag)
            row, wall, err = permeability(a.workdir, name, pack, height, thickness, n, d,
                                          a.max_overlap, extra)
            label = '%g mm, %g, %g kPa' % (d * 1e3, friction, pressure / 1e3)
            if row is None:
                print('| %s | %s | failed: %s |' % (label, n, err), flush=True)
                continue
            k = row['permeability']
            # The pack's porosity from its grains (overlaps of a few % of R*
            # neglected) in the box 1 mm x height x thickness, and the
            # paper's (volume fraction of cells with vf > 0.9) between the
            # pressure planes, where K is measured: the whole-box value
            # counts the grain-free buffers.
            pv = pack_porosity(pack, height, thickness)
            pc = row.get('slab_porosity_cells', row['porosity_cells'])
            kw = kozeny_carman_walls(pv, d, height, thickness)
            print('| %s | %s | %d | %d | %d | %.0f | %.3e | %.3f | %.3f | %.2f | %.2f | %.2f |'
                  % (label, n, row['cells'], row['dofs'], row['linear_iterations'], wall, k,
                     pc, pv, k / kozeny_carman(pc, d), k / kozeny_carman(pv, d), k / kw),
                  flush=True)


if __name__ == '__main__':
    main()
