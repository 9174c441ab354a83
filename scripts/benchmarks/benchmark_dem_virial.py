#!/usr/bin/env python3
"""What the contact stress costs the DEM.

The contact stress (`contact_stress_xx`, ...) is the Love-Weber sum of
branch vector (x) contact force. GranularDynamics::compute_forces() keeps
each contact's force (and a grain-wall contact's branch vector) on every DEM
step, and statistics() sums them only at the output steps. (Until commit
f0757cc, compute_forces() summed the per-grain virial on every step: 15.5 %
of the DEM loop by this script's version of that commit.) This script
measures what the per-step bookkeeping costs, back to back:

  1. compiles a copy of source/dem/granular_dynamics.cc with that
     bookkeeping removed (same compiler flags as build/, read from its CMake
     files), and links a second libsoftsand.so in the work directory;
  2. runs one granular .prm (a dense pack is the worst case: many contacts
     per grain) alternately with build/'s library and with the copy,
     `--repeat` times each, on 1 rank, end time shortened by `--end-time`;
     each run is checked to have loaded its library (only the copy writes a
     zero contact stress);
  3. reports softsand's own time-loop throughput (grain-steps/s) of every
     run and the median of each library, and their ratio.

Usage:
  python3 scripts/benchmarks/benchmark_dem_virial.py --prm STAGE2.prm [--end-time 0.4]
      [--repeat 5] [--workdir /tmp/dem_virial] [--against DIR]

With --against DIR, build/ runs alternately with the softsand and
libsoftsand.so copied from another build into DIR (say, of the commit before
a change), and the contact stresses of all runs must agree.

A pack of the small Hele-Shaw scene's stage 2 is made by
  python3 scripts/packs/make_hele_shaw_scene.py --scale small --workdir DIR
(its stage2.prm). Needs build/ (scripts/setup.sh).
"""
import argparse
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.join(ROOT, "build")
SOURCE = os.path.join(ROOT, "source/dem/granular_dynamics.cc")
OBJECT = "CMakeFiles/softsand_lib.dir/source/dem/granular_dynamics.cc.o"
# The per-step bookkeeping of the contact stress in compute_forces(), each
# line with the number of times it occurs there.
BOOKKEEPING = {
    "pair_force.resize(pairs.size());": 1,
    "wall_force.resize(wall_pairs.size());": 1,
    "wall_branch.resize(wall_pairs.size());": 1,
    "pair_force[k] = Tensor<1, 3>();": 1,
    "pair_force[k] = force;": 1,
    "wall_force[k] = Tensor<1, 3>();": 1,
    "wall_force[k]  = force;": 1,
    "wall_branch[k] = li * n;": 1,
}


def without_contact_stress(text):
    """The source without the bookkeeping; fails loudly if its lines have
    changed."""
    for line, count in BOOKKEEPING.items():
        if text.count(line) != count:
            sys.exit("benchmark_dem_virial.py: source/dem/granular_dynamics.cc "
                     "has %d, not %d, of '%s'; update BOOKKEEPING" %
                     (text.count(line), count, line))
        text = text.replace(line, "")
    return text


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
    lib_dir = os.path.join(workdir, "without")
    os.makedirs(lib_dir, exist_ok=True)
    shutil.copy(os.path.join(BUILD, "softsand"), lib_dir)
    src = os.path.join(workdir, "granular_dynamics_without_contact_stress.cc")
    obj = os.path.join(workdir, "granular_dynamics_without_contact_stress.o")
    with open(SOURCE) as f:
        text = without_contact_stress(f.read())
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


def run(prm, build, log):
    """softsand and libsoftsand.so of directory `build` on prm; its
    time-loop throughput."""
    env = dict(os.environ, LD_LIBRARY_PATH=build)
    with open(prm) as f:
        text = f.read()
    prm_tools.fresh_output(text, os.path.join(
        ROOT, prm_tools.get_entry(text, "output/directory")))
    with open(log, "w") as f:
        # From the repository: scenes name their packs relative to it.
        subprocess.run([os.path.join(build, "softsand"), prm], env=env,
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
    p.add_argument("--against", metavar="DIR",
                   help="compare with the softsand and libsoftsand.so in DIR "
                   "(a copy of another build) instead of the copy without "
                   "the bookkeeping; the two must write the same contact "
                   "stress")
    args = p.parse_args()
    if args.repeat < 1:
        sys.exit("--repeat must be >= 1, got %d" % args.repeat)
    if not args.end_time > 0:
        sys.exit("--end-time must be > 0 s, got %g" % args.end_time)
    if not os.path.isfile(os.path.join(BUILD, "softsand")):
        sys.exit("no %s/softsand: build first (scripts/setup.sh)" % BUILD)
    if not os.path.isfile(args.prm):
        sys.exit("--prm %s: no such file" % args.prm)
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
    if args.against:
        for name in ("softsand", "libsoftsand.so"):
            if not os.path.isfile(os.path.join(args.against, name)):
                sys.exit("--against %s has no %s" % (args.against, name))
        libs = {"build": BUILD, "against": os.path.abspath(args.against)}
    else:
        libs = {"with": BUILD, "without": build_variant(args.workdir)}
    stresses = []
    rates = {k: [] for k in libs}
    for r in range(args.repeat):
        for name, lib in libs.items():
            rate = run(prm, lib, os.path.join(args.workdir,
                                            "run-%s-%d.log" % (name, r)))
            rates[name].append(rate)
            # Proof that each run loaded the library it was meant to: only
            # the copy without the bookkeeping writes a zero contact stress.
            stress = last_contact_stress(args.workdir)
            stresses.append(stress)
            if (stress == 0) != (name == "without"):
                sys.exit("run %d %s: contact_stress_xx = %g, so it did not "
                         "load the library meant" % (r + 1, name, stress))
            print("run %d, %-11s: %.4g grain-steps/s" % (r + 1, name, rate),
                  flush=True)
    med = {k: statistics.median(v) for k, v in rates.items()}
    for k, v in med.items():
        print("median %-11s: %.4g grain-steps/s" % (k, v))
    if args.against:
        spread = (max(stresses) - min(stresses)) / abs(stresses[0])
        print("contact_stress_xx at the end: %.9g Pa, relative spread over "
              "all runs %.1e" % (stresses[0], spread))
        print("build/ is %.1f %% faster than %s (median build / median "
              "against - 1)" % (100 * (med["build"] / med["against"] - 1),
                                args.against))
    else:
        print("the contact stress costs %.1f %% of the DEM time loop "
              "(1 - median with / median without)" %
              (100 * (1 - med["with"] / med["without"])))


if __name__ == "__main__":
    main()
