#!/usr/bin/env python3
"""softsand's DEM against LIGGGHTS 3.8 on the same 10,000-grain pour.

Runs parameters/benchmarks/liggghts_pour.prm with softsand (which writes the
inserted pack), converts that pack to a LIGGGHTS data file, runs
benchmarks/liggghts/pour.in from it, each on 1 and 2 MPI ranks, and reports
  * the packing fraction of the settled pack in the central region (the same
    estimator for both codes: solid volume fraction of a grid of sample
    points, so grains cut by the region's faces count with their inside
    part),
  * the kinetic energy at the end,
  * throughput in particle-steps per second of the time loop (softsand: its
    own loop timer; LIGGGHTS: its "Loop time"), and the ratio.

Usage: scripts/benchmarks/benchmark_dem_vs_liggghts.py [--steps N] [--ranks 1 2]
Needs build/softsand and the Debian package liggghts (an optional benchmark
dependency: apt-get install liggghts).
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRM = os.path.join(ROOT, "parameters/benchmarks/liggghts_pour.prm")
DECK = os.path.join(ROOT, "benchmarks/liggghts/pour.in")
DENSITY = 2650.0
BOX = (0.025, 0.025, 0.12)
CENTRAL = ((0.005, 0.005, 0.005), (0.020, 0.020, 0.025))


def mpi_prefix(ranks):
    if ranks == 1:
        return []
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)]


def read_liggghts_dump(path):
    grains = []
    with open(path) as f:
        lines = f.readlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[start].split()[2:]
    ix, iy, iz, ir = (cols.index(c) for c in ("x", "y", "z", "radius"))
    for l in lines[start + 1:]:
        v = l.split()
        if len(v) == len(cols):
            grains.append((float(v[ix]), float(v[iy]), float(v[iz]), float(v[ir])))
    return grains


def write_liggghts_data(grains, path):
    with open(path, "w") as f:
        f.write("LIGGGHTS data file written by softsand's benchmark script\n\n")
        f.write("%d atoms\n1 atom types\n\n" % len(grains))
        f.write("0 %g xlo xhi\n0 %g ylo yhi\n0 %g zlo zhi\n\n" % BOX)
        f.write("Atoms\n\n")
        for i, (x, y, z, r) in enumerate(grains):
            f.write("%d 1 %.17g %g %.17g %.17g %.17g\n" % (i + 1, 2 * r, DENSITY, x, y, z))


def packing_fraction(grains, region=CENTRAL, n=60):
    """Solid fraction of an n^3 grid of cell-centre points in region."""
    (x0, y0, z0), (x1, y1, z1) = region
    rmax = max(g[3] for g in grains)
    h = 2 * rmax
    cells = {}
    for g in grains:
        key = (int(g[0] // h), int(g[1] // h), int(g[2] // h))
        cells.setdefault(key, []).append(g)
    inside = 0
    for i in range(n):
        x = x0 + (i + 0.5) * (x1 - x0) / n
        for j in range(n):
            y = y0 + (j + 0.5) * (y1 - y0) / n
            for k in range(n):
                z = z0 + (k + 0.5) * (z1 - z0) / n
                cx, cy, cz = int(x // h), int(y // h), int(z // h)
                hit = False
                for dx in (-1, 0, 1):
                    for dy in (-1, 0, 1):
                        for dz in (-1, 0, 1):
                            for g in cells.get((cx + dx, cy + dy, cz + dz), ()):
                                if (x - g[0]) ** 2 + (y - g[1]) ** 2 + (z - g[2]) ** 2 < g[3] ** 2:
                                    hit = True
                                    break
                            if hit:
                                break
                        if hit:
                            break
                    if hit:
                        break
                inside += hit
    return inside / n ** 3


def run_softsand(ranks, steps, workdir):
    out = os.path.join(workdir, "softsand_np%d" % ranks)
    prm = os.path.join(workdir, "softsand_np%d.prm" % ranks)
    with open(PRM) as f:
        text = f.read()
    text += ("\nsubsection simulation control\n set end time = %.10g\nend\n"
             "subsection output\n set directory = %s\nend\n" % (steps * 1e-5, out))
    with open(prm, "w") as f:
        f.write(text)
    prm_tools.fresh_output(text, out)
    log = subprocess.run(mpi_prefix(ranks) + [os.path.join(ROOT, "build/softsand"), prm],
                         capture_output=True, text=True, check=True).stdout
    rate = float(re.search(r"([0-9.e+]+) grain-steps/s in the time loop", log).group(1))
    ke = float(re.search(r"kinetic_energy\s+([0-9.e+-]+)", log).group(1))
    return out, rate, ke


def run_liggghts(ranks, steps, workdir, grains):
    run_dir = os.path.join(workdir, "liggghts_np%d" % ranks)
    os.makedirs(run_dir, exist_ok=True)
    write_liggghts_data(grains, os.path.join(run_dir, "data.pour"))
    shutil.copy(DECK, os.path.join(run_dir, "pour.in"))
    log = subprocess.run(mpi_prefix(ranks) + ["liggghts", "-in", "pour.in", "-var", "steps",
                                              str(steps), "-var", "dumpfile", "final.dump",
                                              "-log", "log.liggghts", "-echo", "none"],
                         cwd=run_dir, capture_output=True, text=True)
    if log.returncode != 0:
        sys.exit("LIGGGHTS failed:\n" + log.stdout[-3000:] + log.stderr[-3000:])
    text = log.stdout
    loops = re.findall(r"Loop time of ([0-9.e+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                       text)
    loop = max(loops, key=lambda l: int(l[2]))  # the run, not the final "run 0"
    seconds, nsteps, atoms = float(loop[0]), int(loop[2]), int(loop[3])
    # Last thermo row before the loop line: step atoms ke rke
    rows = re.findall(r"^\s*(\d+)\s+(\d+)\s+([0-9.e+-]+)\s+([0-9.e+-]+)\s*$", text, re.M)
    ke = float(rows[-1][2]) + float(rows[-1][3]) if rows else float("nan")
    return os.path.join(run_dir, "final.dump"), atoms * nsteps / seconds, ke, atoms


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=40000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--workdir", default=os.path.join(ROOT, "output/benchmark_liggghts"))
    args = parser.parse_args()
    if not os.path.exists(os.path.join(ROOT, "build/softsand")):
        sys.exit("build/softsand not found: build softsand first (bash scripts/setup.sh)")
    if shutil.which("liggghts") is None:
        sys.exit("liggghts not found: this benchmark needs the Debian package "
                 "(apt-get install liggghts)")
    os.makedirs(args.workdir, exist_ok=True)
    env_note = "OMPI_ALLOW_RUN_AS_ROOT" in os.environ
    rows = []
    for ranks in args.ranks:
        out, s_rate, s_ke = run_softsand(ranks, args.steps, args.workdir)
        initial = prm_tools.read_grains(os.path.join(out, "initial_pack.txt"))
        final_s = prm_tools.read_grains(os.path.join(out, "final_pack.txt"))
        dump, l_rate, l_ke, atoms = run_liggghts(ranks, args.steps, args.workdir, initial)
        final_l = read_liggghts_dump(dump)
        pf_s, pf_l = packing_fraction(final_s), packing_fraction(final_l)
        rows.append((ranks, len(final_s), atoms, pf_s, pf_l, s_ke, l_ke, s_rate, l_rate))
        print("ranks %d: done" % ranks, flush=True)
    print()
    print("| ranks | grains softsand / LIGGGHTS | packing fraction (central) softsand | LIGGGHTS | "
          "difference | kinetic energy at end (J) softsand | LIGGGHTS | particle-steps/s softsand | "
          "LIGGGHTS | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %d | %d / %d | %.4f | %.4f | %+.2f%% | %.2e | %.2e | %.3g | %.3g | %.2f |"
              % (r[0], r[1], r[2], r[3], r[4], 100 * (r[3] / r[4] - 1), r[5], r[6], r[7], r[8],
                 r[7] / r[8]))


if __name__ == "__main__":
    main()
