#!/usr/bin/env python3
"""What the contact-stress virial costs the DEM.

GranularDynamics::compute_forces() adds each contact's branch-vector-force
product to its grains' virial on every DEM step, although the contact stress
(`contact_stress_xx`, ...) is only written at the output steps. This script
measures that cost back to back:

  1. compiles a copy of source/dem/granular_dynamics.cc with the three virial
     accumulations removed (same compiler flags as build/, read from its
     CMake files), and links a second libsoftsand.so in the work directory;
  2. runs one granular .prm (a dense pack is the worst case: many contacts
     per grain) alternately with build/'s library and with the copy,
     `--repeat` times each, on 1 rank, end time shortened by `--end-time`;
  3. reports softsand's own time-loop throughput (grain-steps/s) of every
     run and the median of each library, and their ratio.

Usage:
  python3 scripts/benchmark_dem_virial.py --prm STAGE2.prm [--end-time 0.4]
      [--repeat 5] [--workdir /tmp/dem_virial]

A pack of the small Hele-Shaw scene's stage 2 is made by
  python3 scripts/make_hele_shaw_scene.py --scale small --workdir DIR
(its stage2.prm). Needs build/ (scripts/setup.sh).
"""
import argparse
import os
import re
import shlex
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, "build")
SOURCE = os.path.join(ROOT, "source/dem/granular_dynamics.cc")
OBJECT = "CMakeFiles/softsand_lib.dir/source/dem/granular_dynamics.cc.o"
ACCUMULATIONS = [
    "grain_virial[i] -= li * outer_product(force, n);",
    "grain_virial[j] -= lj * outer_product(force, n);",
]
RESET = "grain_virial.assign(n_local, Tensor<2, 3>());\n      const bool cohesive"


def without_virial(text):
    """The source with the per-step virial work removed; fails loudly if the
    lines it removes have changed."""
    if text.count(ACCUMULATIONS[0]) != 2 or text.count(ACCUMULATIONS[1]) != 1 \
            or text.count(RESET) != 1:
        sys.exit("benchmark_dem_virial.py: source/dem/granular_dynamics.cc no "
                 "longer has the virial lines this script removes; update "
                 "ACCUMULATIONS and RESET")
    for line in ACCUMULATIONS:
        text = text.replace(line, "")
    return text.replace(RESET, "const bool cohesive")


def compile_flags():
    flags = {}
    with open(os.path.join(BUILD, "CMakeFiles/softsand_lib.dir/flags.make")) as f:
        for line in f:
            m = re.match(r"(CXX_DEFINES|CXX_INCLUDES|CXX_FLAGS) = (.*)", line)
            if m:
                flags[m.group(1)] = m.group(2)
            m = re.match(r"# Custom options: " + re.escape(OBJECT) +
                         r"_OPTIONS = (.*)", line)
            if m:
                flags["custom"] = m.group(1)
    return (shlex.split(flags["CXX_DEFINES"]) + shlex.split(flags["CXX_INCLUDES"]) +
            shlex.split(flags["CXX_FLAGS"]) + shlex.split(flags.get("custom", "")))


def build_variant(workdir):
    lib_dir = os.path.join(workdir, "lib")
    os.makedirs(lib_dir, exist_ok=True)
    src = os.path.join(workdir, "granular_dynamics_without_virial.cc")
    obj = os.path.join(workdir, "granular_dynamics_without_virial.o")
    with open(SOURCE) as f:
        text = without_virial(f.read())
    with open(src, "w") as f:
        f.write(text)
    subprocess.run(["c++"] + compile_flags() + ["-c", src, "-o", obj],
                   cwd=BUILD, check=True)
    with open(os.path.join(BUILD, "CMakeFiles/softsand_lib.dir/link.txt")) as f:
        link = shlex.split(f.read())
    link = [obj if a == OBJECT else a for a in link]
    link[link.index("-o") + 1] = os.path.join(lib_dir, "libsoftsand.so")
    subprocess.run(link, cwd=BUILD, check=True)
    return lib_dir


def run(prm, lib_dir, log):
    env = dict(os.environ, LD_LIBRARY_PATH=lib_dir)
    with open(log, "w") as f:
        # From the repository: scenes name their packs relative to it.
        subprocess.run([os.path.join(BUILD, "softsand"), prm], env=env,
                       cwd=ROOT, stdout=f, stderr=subprocess.STDOUT, check=True)
    with open(log) as f:
        m = re.search(r"([0-9.e+]+) grain-steps/s in the time loop", f.read())
    if not m:
        sys.exit("no time-loop throughput in %s" % log)
    return float(m.group(1))


def last_contact_stress(workdir):
    return prm_tools.read_statistics(os.path.join(workdir, "out"))[-1][
        "contact_stress_xx"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--prm", required=True, help="a granular scene (.prm)")
    p.add_argument("--end-time", type=float, default=0.4)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--workdir", default="/tmp/dem_virial")
    args = p.parse_args()
    if args.repeat < 1:
        sys.exit("--repeat must be >= 1, got %d" % args.repeat)
    if not args.end_time > 0:
        sys.exit("--end-time must be > 0 s, got %g" % args.end_time)
    os.makedirs(args.workdir, exist_ok=True)
    prm = os.path.join(args.workdir, "scene.prm")
    with open(args.prm) as f:
        text = f.read()
    text = prm_tools.set_entry(text, "simulation control/end time",
                               repr(args.end_time))
    text = prm_tools.set_entry(text, "output/directory",
                               os.path.join(args.workdir, "out"))
    with open(prm, "w") as f:
        f.write(text)
    libs = {"with virial": BUILD, "without": build_variant(args.workdir)}
    rates = {k: [] for k in libs}
    for r in range(args.repeat):
        for name, lib in libs.items():
            rate = run(prm, lib, os.path.join(args.workdir, "run-%s-%d.log" %
                                              (name.split()[0], r)))
            rates[name].append(rate)
            # Proof that each run loaded the library it was meant to: only
            # the copy without the virial writes a zero contact stress.
            stress = last_contact_stress(args.workdir)
            if (stress == 0) != (name == "without"):
                sys.exit("run %d %s: contact_stress_xx = %g, so it did not "
                         "load the library meant" % (r + 1, name, stress))
            print("run %d, %-11s: %.4g grain-steps/s" % (r + 1, name, rate),
                  flush=True)
    med = {k: statistics.median(v) for k, v in rates.items()}
    for k, v in med.items():
        print("median %-11s: %.4g grain-steps/s" % (k, v))
    print("the virial costs %.1f %% of the DEM time loop "
          "(1 - median with / median without)" %
          (100 * (1 - med["with virial"] / med["without"])))


if __name__ == "__main__":
    main()
