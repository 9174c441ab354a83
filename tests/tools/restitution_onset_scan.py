#!/usr/bin/env python3
"""Restitution of one normal impact (Hertz + LIGGGHTS damping) under
softsand's two integrators, scanned over where in a time step the contact
starts (the onset phase), as test dem_impacts does with the C++ code.

  verlet    : velocity Verlet with the damping force at the predicted
              end-of-step velocity v + dt a_n (softsand up to commit 0275919)
  potential : the same, but the normal damping impulse of each step is
              Gamma(delta_new) - Gamma(delta_old), Gamma = int gamma_n ddelta
              (softsand since; ContactLaw::evaluate)

The relative motion of two equal grains is that of one grain of mass m/2
and radius R/2 on a wall, so one 1D model serves both impacts. Material of
dem_impacts: Y = 5e6 Pa, nu = 0.15, 2500 kg/m^3, R = 0.05 mm, v = 0.1 m/s.

  python3 tests/tools/restitution_onset_scan.py
"""
import math

YOUNG, POISSON, DENSITY, RADIUS, SPEED = 5e6, 0.15, 2500.0, 5e-5, 0.1
SHEAR = YOUNG / (2 * (1 + POISSON))
Y_EFF = YOUNG / (2 * (1 - POISSON**2))
RAYLEIGH = math.pi * RADIUS * math.sqrt(DENSITY / SHEAR) / (0.1631 * POISSON + 0.8766)
MASS = DENSITY * 4 / 3 * math.pi * RADIUS**3


def beta(e):
    if e >= 1:
        return 0.0
    log_e = math.log(e)
    return log_e / math.sqrt(log_e**2 + math.pi**2)


def restitution(e, pair, rayleigh_fraction, onset_phase, scheme):
    r_eff = RADIUS / 2 if pair else RADIUS
    m_eff = MASS / 2 if pair else MASS
    dt = rayleigh_fraction * RAYLEIGH
    damping = -2 * math.sqrt(5 / 6) * beta(e) * math.sqrt(2 * Y_EFF)

    def contact(z):  # elastic force, gamma_n, Gamma at height z of the centre
        delta = r_eff - z
        if delta <= 0:
            return 0.0, 0.0, 0.0
        root = math.sqrt(r_eff * delta)
        gamma = damping * math.sqrt(root * m_eff)
        return 4 / 3 * Y_EFF * root * delta, gamma, 0.8 * gamma * delta

    z = r_eff + 0.05 * RADIUS + onset_phase * SPEED * dt
    v = -SPEED
    elastic, gamma, potential = contact(z)
    damping_force = -gamma * v
    force = elastic + damping_force
    touched = False
    for _ in range(100000):
        v_half = v + 0.5 * dt * force / m_eff
        z += dt * v_half
        v_predicted = v_half + 0.5 * dt * force / m_eff
        elastic, gamma, new_potential = contact(z)
        if scheme == "verlet":
            force = elastic - gamma * v_predicted
            v = v_half + 0.5 * dt * force / m_eff
        else:
            v = v_half + (0.5 * dt * elastic + new_potential - potential -
                          0.5 * dt * damping_force) / m_eff
            damping_force = -gamma * v_predicted
            potential = new_potential
            force = elastic + damping_force
        if z < r_eff:
            touched = True
        elif touched:
            return v / SPEED
    return float("nan")


def main():
    phases = [k / 8 for k in range(8)]
    for scheme in ("verlet", "potential"):
        print(scheme)
        for fraction in (0.2, 0.1):
            for pair in (False, True):
                for e in (1.0, 0.7, 0.5, 0.2, 0.1):
                    errors = [restitution(e, pair, fraction, p, scheme) / e - 1
                              for p in phases]
                    print("  dt = %.1f T_R %-13s e = %.1f: phase 0 %+.2f%%, "
                          "over 8 phases [%+.2f%%, %+.2f%%]" %
                          (fraction, "sphere-sphere" if pair else "sphere-wall",
                           e, 100 * errors[0], 100 * min(errors),
                           100 * max(errors)))


if __name__ == "__main__":
    main()
