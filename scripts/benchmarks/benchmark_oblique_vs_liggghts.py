#!/usr/bin/env python3
"""Oblique impacts of one grain on a wall: softsand against LIGGGHTS 3.8.

A 0.1 mm grain (R = 5e-5 m) of the paper's material (Y = 5e6 Pa, nu = 0.15,
e = 0.7, mu = 0.7, 2650 kg/m^3) hits the wall z = 0 at 0.1 m/s without
gravity, at angles a from the wall normal (default 2, 5, 10, 20, 45, 80 deg):
velocity (v sin a, 0, -v cos a), no spin. For each angle the script
  * runs softsand on a .prm derived from parameters/impact_wall.prm (the
    grain starts 5e-5 s of normal approach above the wall, the run ends at
    1.2e-4 s, well after the contact, which lasts 27-38 us; the DEM step is
    softsand's automatic one, 0.2 Rayleigh time, read from its statistics and
    checked constant),
  * runs LIGGGHTS on a generated deck with the same material, the same
    contact law (pair_style / fix wall/gran `model hertz tangential
    history`), the same initial state and the same time step,
  * reads the rebound velocity and spin (softsand: `dem/save pack`; LIGGGHTS:
    `print` of the atom's vx, vz, omegay) and the contact duration (softsand:
    max_wall_overlap_ratio per step; LIGGGHTS: thermo z < R per step),
and prints a markdown table: the rebound tangential velocity vt and spin
omega_y of both codes and their relative difference, the normal
restitution of both, and a second one with Maw et al.'s tangential
parameters psi1 = vt_in / vn_in (incidence) and psi2 = (vt - R omega_y) /
vn_in (the tangential velocity of the contact point at rebound).

--decompose adds what makes the difference: a replica in Python of both
integrators for this impact (it reproduces each code's rebound to 4-5
digits, printed), with softsand's choices replaced by LIGGGHTS' one at a
time, the spin of both laws from 0.2 down to 0.001 Rayleigh time, and the
spread of each code's result over 8 positions of the contact onset within a
step.

Usage: scripts/benchmarks/benchmark_oblique_vs_liggghts.py [--angles 2 5 10 20 45 80]
       [--speed 0.1] [--workdir /tmp/oblique] [--rayleigh-fraction 0.2]
       [--decompose] [--no-liggghts]
Needs build/softsand. LIGGGHTS is an optional benchmark dependency (the
Debian package, `apt-get install liggghts`); without it (or with
--no-liggghts) only softsand's columns are filled.
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
PRM = os.path.join(ROOT, "parameters/impact_wall.prm")
RADIUS = 5e-5
DENSITY = 2650.0
YOUNGS, POISSON, RESTITUTION, FRICTION = 5e6, 0.15, 0.7, 0.7
APPROACH_TIME = 5e-5  # s of normal approach before the contact
END_TIME = 1.2e-4     # s


def rayleigh_time():
    """softsand's Material::rayleigh_time of the grain (s)."""
    shear_modulus = YOUNGS / (2 * (1 + POISSON))
    return (math.pi * RADIUS * math.sqrt(DENSITY / shear_modulus)
            / (0.1631 * POISSON + 0.8766))


def initial_state(angle, speed, dt, onset_phase=0.0):
    """Height and velocity (vt, -vn) at t = 0; onset_phase (0..1) moves the
    start up by that fraction of one step of normal approach."""
    a = math.radians(angle)
    vt, vn = speed * math.sin(a), speed * math.cos(a)
    return RADIUS + vn * (APPROACH_TIME + onset_phase * dt), vt, -vn


def number_row(line):
    """The numbers of a table row, or None for a comment or header line."""
    try:
        values = [float(x) for x in line.split("#")[0].split()]
    except ValueError:
        return None
    return values or None


def run_softsand(softsand, angle, speed, rayleigh_fraction, workdir):
    """Final vx, vz, omega_y, the step, the contact duration and the overlap
    at the end."""
    z0, vt, vz = initial_state(angle, speed, 0.0)
    name = "softsand_%g" % angle
    out = os.path.join(workdir, name)
    with open(PRM) as f:
        text = f.read()
    for path, value in (
            ("simulation control/end time", "%.10g" % END_TIME),
            ("grains/list", "0, 0, %.17g, %.17g" % (z0, RADIUS)),
            ("grains/velocity", "%.17g, 0, %.17g" % (vt, vz)),
            ("dem/material/density", "%g" % DENSITY),
            ("dem/material/youngs modulus", "%g" % YOUNGS),
            ("dem/material/poisson ratio", "%g" % POISSON),
            ("dem/material/restitution", "%g" % RESTITUTION),
            ("dem/material/friction", "%g" % FRICTION),
            ("dem/time step", "0"),
            ("dem/automatic rayleigh fraction", "%g" % rayleigh_fraction),
            ("dem/statistics interval", "1"),
            ("dem/save pack", "final_grain.txt"),
            ("output/directory", out),
            ("output/write vtu", "false")):
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(workdir, name + ".prm")
    with open(prm, "w") as f:
        f.write(text)
    prm_tools.fresh_output(text, out)
    proc = subprocess.run([softsand, prm], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit("softsand failed on %s:\n%s%s" % (prm, proc.stdout[-3000:], proc.stderr[-3000:]))
    # One row per step after the row of the initial state; the time column
    # gives the step to 10 digits, the screen (dt = ... s) to 6.
    rows = prm_tools.read_statistics(out)
    steps = [b["time"] - a["time"] for a, b in zip(rows, rows[1:])]
    dt = steps[0]
    screen_dt = float(re.search(r"dt = ([0-9.e+-]+) s", proc.stdout).group(1))
    assert abs(screen_dt / dt - 1) < 1e-5, (screen_dt, dt)
    # The last step may be shortened to land on the end time.
    if any(abs(s / dt - 1) > 1e-6 for s in steps[:-1]):
        print("warning: softsand's step varied (%.6g to %.6g s) at %g deg"
              % (min(steps), max(steps), angle))
    contact = sum(s for s, r in zip(steps, rows[1:]) if r["max_wall_overlap_ratio"] > 0)
    # x y z radius vx vy vz wx wy wz: the first line of numbers.
    with open(os.path.join(out, "final_grain.txt")) as f:
        grain = next(v for v in (number_row(l) for l in f) if v)
    return dict(vx=grain[4], vz=grain[6], wy=grain[8], dt=dt, contact=contact,
                last_overlap=rows[-1]["max_wall_overlap_ratio"], steps=len(steps))


LIGGGHTS_DECK = """# One grain hitting the wall z = 0 (written by
# scripts/benchmarks/benchmark_oblique_vs_liggghts.py; softsand: parameters/impact_wall.prm)
atom_style      granular
atom_modify     map array
boundary        f f f
newton          off
communicate     single vel yes
units           si

region          box block -5e-4 5e-4 -5e-4 5e-4 0 1e-3 units box
create_box      1 box
neighbor        {skin:.10g} bin
neigh_modify    delay 0

fix m1 all property/global youngsModulus peratomtype {youngs:g}
fix m2 all property/global poissonsRatio peratomtype {poisson:g}
fix m3 all property/global coefficientRestitution peratomtypepair 1 {restitution:g}
fix m4 all property/global coefficientFriction peratomtypepair 1 {friction:g}

pair_style      gran model hertz tangential history
pair_coeff      * *
timestep        {dt:.17g}

fix zwall all wall/gran model hertz tangential history primitive type 1 zplane 0.0

create_atoms    1 single 0 0 {z0:.17g} units box
set             atom 1 diameter {diameter:.17g} density {density:g}
velocity        all set {vt:.17g} 0 {vz:.17g} units box

fix integr all nve/sphere

variable vx equal vx[1]
variable vz equal vz[1]
variable wy equal omegay[1]
variable z  equal z[1]
thermo_style    custom step v_z
thermo_modify   norm no format float %.17g
thermo          1
run             {steps}
print           "RESULT ${{vx}} ${{vz}} ${{wy}}"
"""


def run_liggghts(angle, speed, dt, steps, workdir):
    z0, vt, vz = initial_state(angle, speed, 0.0)
    run_dir = os.path.join(workdir, "liggghts_%g" % angle)
    os.makedirs(run_dir, exist_ok=True)
    deck = LIGGGHTS_DECK.format(skin=0.25 * RADIUS, youngs=YOUNGS, poisson=POISSON,
                                restitution=RESTITUTION, friction=FRICTION, dt=dt, z0=z0,
                                diameter=2 * RADIUS, density=DENSITY, vt=vt, vz=vz, steps=steps)
    with open(os.path.join(run_dir, "impact.in"), "w") as f:
        f.write(deck)
    proc = subprocess.run(["liggghts", "-in", "impact.in", "-log", "log.liggghts",
                           "-echo", "none"], cwd=run_dir, capture_output=True, text=True)
    if proc.returncode != 0 or "RESULT" not in proc.stdout:
        sys.exit("LIGGGHTS failed in %s:\n%s%s" % (run_dir, proc.stdout[-3000:], proc.stderr[-3000:]))
    vx, vz, wy = (float(x) for x in re.search(r"^RESULT (\S+) (\S+) (\S+)", proc.stdout,
                                              re.M).group(1, 2, 3))
    heights = [float(z) for _, z in re.findall(r"^\s*(\d+)\s+([0-9.e+-]+)\s*$", proc.stdout, re.M)]
    in_contact = [z < RADIUS for z in heights]
    return dict(vx=vx, vz=vz, wy=wy, contact=dt * sum(in_contact), ends_apart=not in_contact[-1])


SOFTSAND = dict(spring="predicted", damping="predicted", normal="potential", coulomb="total")
LIGGGHTS = dict(spring="half", damping="half", normal="half", coulomb="spring")


def replica(angle, speed, dt, spring, damping, normal, coulomb, onset_phase=0.0):
    """The impact in Python, in softsand's or LIGGGHTS' integrator or a mix.

    Both are velocity Verlet: half kick, drift, contact force, half kick.
    softsand (GranularDynamics::step, ContactLaw::evaluate) evaluates the
    contact with the predicted end-of-step velocity v_half + dt/2 a_old,
    LIGGGHTS (nve/sphere) with the half-step velocity v_half:
      spring  -- velocity of the tangential spring increment xi += dt v_t,
      damping -- velocity of the tangential damping -gamma_t v_t,
                 'predicted' or 'half';
      normal  -- 'potential': softsand's normal damping (force at the predicted
                 velocity, impulse of the step Gamma(delta_new) -
                 Gamma(delta_old) through the end kick), 'half': -gamma_n v_n
                 at the half-step velocity;
      coulomb -- 'total': |-k_t xi - gamma_t v_t| <= mu |F_n|, the spring set
                 so that spring + damping is the capped force (softsand, as
                 LAMMPS' gran/hertz/history); 'spring': k_t |xi| <= mu |F_n|,
                 the spring truncated and no damping while sliding (LIGGGHTS
                 3.8 tangential_model_history.h).
    Same law otherwise: k_n = 4/3 Y* sqrt(R delta), k_t = 8 G* sqrt(R delta),
    gamma_{n,t} = -2 sqrt(5/6) beta sqrt(S_{n,t} m), S_n = 2 Y* sqrt(R delta),
    S_t = k_t, lever R - delta/2. (The spring rotation does not matter on a
    flat wall: the normal stays fixed.)"""
    mass = DENSITY * 4 / 3 * math.pi * RADIUS ** 3
    inertia = 0.4 * mass * RADIUS ** 2
    y_eff = YOUNGS / (2 * (1 - POISSON ** 2))
    g_eff = YOUNGS / (4 * (2 - POISSON) * (1 + POISSON))
    log_e = math.log(RESTITUTION)
    c = -2 * math.sqrt(5 / 6) * log_e / math.sqrt(log_e ** 2 + math.pi ** 2)
    damping_n, damping_t = c * math.sqrt(2 * y_eff), c * math.sqrt(8 * g_eff)
    z, vx, vz = initial_state(angle, speed, dt, onset_phase)
    vz_in, w = vz, 0.0
    xi = 0.0                 # tangential spring (m)
    last_potential = None    # (Gamma, normal damping force) of the last step
    fx = fz = torque = 0.0
    half = 0.5 * dt
    for _ in range(int(round(END_TIME / dt))):
        vx += half * fx / mass
        vz += half * fz / mass
        w += half * torque / inertia
        z += dt * vz
        now = (vx, vz, w)
        predicted = (vx + half * fx / mass, vz + half * fz / mass, w + half * torque / inertia)
        delta = RADIUS - z
        kick = 0.0
        if delta <= 0:
            if last_potential is not None:
                kick = -(last_potential[0] + half * last_potential[1])
            xi, last_potential = 0.0, None
            fx = fz = torque = 0.0
        else:
            lever = RADIUS - 0.5 * delta
            root = math.sqrt(RADIUS * delta)
            kn, kt = 4 / 3 * y_eff * root, 8 * g_eff * root
            gamma_n = damping_n * math.sqrt(root * mass)
            gamma_t = damping_t * math.sqrt(root * mass)
            vn = (predicted if normal == "potential" else now)[1]
            fd = -gamma_n * vn
            fn = kn * delta + fd
            if normal == "potential":
                potential = 0.8 * gamma_n * delta
                old = last_potential
                if old is None:
                    delta_old = delta + dt * vn
                    old = (0.8 * damping_n * math.sqrt(math.sqrt(RADIUS * delta_old) * mass)
                           * delta_old if delta_old > 0 else 0.0, 0.0)
                kick = potential - old[0] - half * (old[1] + fd)
                last_potential = (potential, fd)
            vs = predicted if spring == "predicted" else now
            vd = predicted if damping == "predicted" else now
            xi += dt * (vs[0] - lever * vs[2])
            vt = vd[0] - lever * vd[2]
            limit = FRICTION * abs(fn)
            if coulomb == "total":
                ft = -kt * xi - gamma_t * vt
                if abs(ft) > limit:
                    ft = math.copysign(limit, ft)
                    xi = -(ft + gamma_t * vt) / kt
            elif kt * abs(xi) > limit:
                ft = math.copysign(limit, -xi)
                xi = -ft / kt
            else:
                ft = -kt * xi - gamma_t * vt
            fx, fz, torque = ft, fn, -lever * ft
        vx += half * fx / mass
        vz += half * fz / mass + kick / mass
        w += half * torque / inertia
    return dict(vx=vx, vz=vz, wy=w, e=-vz / vz_in)


def rel(a, b):
    return (a / b - 1) if b != 0 else float("nan")


def cell(r, ref):
    """'vt diff / omega_y diff' in percent."""
    return "%+.1f / %+.1f" % (100 * rel(r["vx"], ref["vx"]), 100 * rel(r["wy"], ref["wy"]))


def decompose(angles, speed, dt, measured):
    """Prints the replica tables (see replica())."""
    tr = rayleigh_time()
    head = "| " + " | ".join("%g deg" % a for a in angles) + " |"
    rule = "|---" * (len(angles) + 1) + "|"
    print()
    print("Replica of both integrators (Python), dt = %.4g T_R; cells: rebound vt / omega_y, "
          "%% from the LIGGGHTS replica at the same step." % (dt / tr))
    print()
    print("| softsand with LIGGGHTS' choices, one after the other " + head)
    print(rule)
    ref = {a: replica(a, speed, dt, **LIGGGHTS) for a in angles}
    steps = [("softsand", {}),
             ("+ spring increment dt v_t at the half-step velocity", dict(spring="half")),
             ("+ Coulomb rule on the spring only, no damping when sliding",
              dict(spring="half", coulomb="spring")),
             ("+ tangential damping at the half-step velocity",
              dict(spring="half", coulomb="spring", damping="half")),
             ("softsand with only LIGGGHTS' Coulomb rule", dict(coulomb="spring")),
             ("softsand with only the normal damping of LIGGGHTS", dict(normal="half"))]
    for name, change in steps:
        variant = dict(SOFTSAND, **change)
        print("| %s | %s |" % (name, " | ".join(cell(replica(a, speed, dt, **variant), ref[a])
                                                 for a in angles)))
    if measured:
        print("| replica / measured - 1, softsand | %s |" % " | ".join(
            cell(replica(a, speed, dt, **SOFTSAND), measured[a][0]) for a in angles))
        if not math.isnan(measured[angles[0]][1]["vx"]):
            print("| replica / measured - 1, LIGGGHTS | %s |" % " | ".join(
                cell(ref[a], measured[a][1]) for a in angles))
    print()
    print("omega_y (rad/s) against the step: softsand's law / LIGGGHTS' law (replica)")
    print()
    print("| dt / T_R " + head)
    print(rule)
    for fraction in (0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001):
        print("| %g | %s |" % (fraction, " | ".join(
            "%.1f / %.1f" % (replica(a, speed, fraction * tr, **SOFTSAND)["wy"],
                             replica(a, speed, fraction * tr, **LIGGGHTS)["wy"])
            for a in angles)))
    fine = 0.002 * tr
    print("| 0.002: softsand with LIGGGHTS' Coulomb rule, vt / omega_y %% from LIGGGHTS | %s |"
          % " | ".join(cell(replica(a, speed, fine, **dict(SOFTSAND, coulomb="spring")),
                            replica(a, speed, fine, **LIGGGHTS)) for a in angles))
    print()
    print("Onset of the contact at 8 positions within a step (start raised by k/8 of "
          "vn dt): spread of each code's result, % of its own phase-0 value, vt / omega_y")
    print()
    print("| dt = %.4g T_R " % (dt / tr) + head)
    print(rule)
    for name, law in (("softsand", SOFTSAND), ("LIGGGHTS", LIGGGHTS)):
        cells = []
        for a in angles:
            runs = [replica(a, speed, dt, onset_phase=k / 8, **law) for k in range(8)]
            r0 = runs[0]
            vts = [100 * rel(r["vx"], r0["vx"]) for r in runs]
            wys = [100 * rel(r["wy"], r0["wy"]) for r in runs]
            cells.append("%+.1f..%+.1f / %+.1f..%+.1f" % (min(vts), max(vts), min(wys), max(wys)))
        print("| %s | %s |" % (name, " | ".join(cells)))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--angles", type=float, nargs="+", default=[2, 5, 10, 20, 45, 80],
                        help="impact angles from the wall normal (deg)")
    parser.add_argument("--speed", type=float, default=0.1, help="impact speed (m/s)")
    parser.add_argument("--workdir", default="/tmp/oblique",
                        help="scratch directory for the .prm, decks and outputs")
    parser.add_argument("--softsand", default=os.path.join(ROOT, "build/softsand"))
    parser.add_argument("--rayleigh-fraction", type=float, default=0.2,
                        help="softsand's dem/automatic rayleigh fraction (LIGGGHTS takes "
                             "the step softsand reports)")
    parser.add_argument("--decompose", action="store_true",
                        help="also the replica tables: what makes the difference")
    parser.add_argument("--no-liggghts", action="store_true", help="softsand only")
    args = parser.parse_args()
    if not os.path.exists(args.softsand):
        sys.exit("%s not found: build softsand first (bash scripts/setup.sh)" % args.softsand)
    use_liggghts = not args.no_liggghts and shutil.which("liggghts") is not None
    if not args.no_liggghts and not use_liggghts:
        print("liggghts not found (apt-get install liggghts): softsand only")
    os.makedirs(args.workdir, exist_ok=True)

    nan = float("nan")
    rows = []
    for angle in args.angles:
        s = run_softsand(args.softsand, angle, args.speed, args.rayleigh_fraction, args.workdir)
        if s["last_overlap"] > 0:
            sys.exit("softsand: the grain still touches the wall at the end (%g deg)" % angle)
        if use_liggghts:
            l = run_liggghts(angle, args.speed, s["dt"], s["steps"], args.workdir)
            if not l["ends_apart"]:
                sys.exit("LIGGGHTS: the grain still touches the wall at the end (%g deg)" % angle)
        else:
            l = dict(vx=nan, vz=nan, wy=nan, contact=nan)
        rows.append((angle, s, l))
        print("%g deg: done" % angle, flush=True)

    dt = rows[0][1]["dt"]
    print()
    print("dt = %.6g s (softsand's automatic step, %g Rayleigh time) in both codes; "
          "impact speed %g m/s" % (dt, args.rayleigh_fraction, args.speed))
    print()
    print("| angle (deg) | vt rebound softsand (m/s) | LIGGGHTS | rel. diff | omega_y softsand "
          "(rad/s) | LIGGGHTS | rel. diff | e_n softsand | e_n LIGGGHTS | contact (us) softsand "
          "| LIGGGHTS |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for angle, s, l in rows:
        vn = args.speed * math.cos(math.radians(angle))
        print("| %g | %.5g | %.5g | %+.2f%% | %.5g | %.5g | %+.2f%% | %.4f | %.4f | %.1f | %.1f |"
              % (angle, s["vx"], l["vx"], 100 * rel(s["vx"], l["vx"]), s["wy"], l["wy"],
                 100 * rel(s["wy"], l["wy"]), s["vz"] / vn, l["vz"] / vn, 1e6 * s["contact"],
                 1e6 * l["contact"]))
    print()
    print("| angle (deg) | psi1 = vt_in/vn_in | psi2 = (vt - R omega_y)/vn_in softsand | LIGGGHTS "
          "| vt/vt_in softsand | LIGGGHTS |")
    print("|---|---|---|---|---|---|")
    for angle, s, l in rows:
        vn = args.speed * math.cos(math.radians(angle))
        vt_in = args.speed * math.sin(math.radians(angle))
        print("| %g | %.4f | %+.4f | %+.4f | %.4f | %.4f |"
              % (angle, vt_in / vn, (s["vx"] - RADIUS * s["wy"]) / vn,
                 (l["vx"] - RADIUS * l["wy"]) / vn, s["vx"] / vt_in, l["vx"] / vt_in))
    if args.decompose:
        decompose(args.angles, args.speed, dt, {angle: (s, l) for angle, s, l in rows})


if __name__ == "__main__":
    main()
