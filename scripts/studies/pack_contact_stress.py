#!/usr/bin/env python3
"""The in-plane contact stress of a radial Hele-Shaw pack in rings around
the inlet, against the pistons' load: how much of the confining stress
reaches the grains near the inlet.

  python3 scripts/studies/pack_contact_stress.py \\
      --stage output/hele_shaw_scene_small/stage2.prm

runs the granular stage --stage (the cohesive settling that
make_hele_shaw_scene.py writes, whose end state is the injection's pack)
once per probe: squares of half-width --half-widths around the axis over
the plates' gap, then the whole box. Each run's last statistics row gives
the Love-Weber contact stress in its probe (`contact_stress_xx`, `_yy`);
times the probe's volume these sums are additive, so a ring's mean in-plane
stress (sigma_xx + sigma_yy) / 2 is the difference of two probes' sums over
the difference of their grain-holding volumes (the inlet cylinder of
--inlet-radius excluded; the whole pack's volume is the octagon's, from
the pistons' positions). Printed beside them: the servo pressure and the
pistons' own mean traction, sum F_k R_k / (2 V) over the octagon
(doc/statistics_columns.md). The squares must lie inside the octagon
(half-width below R / sqrt 2). --set overrides entries of --stage, e.g.
the injection's start: the pack file and the octagon of injection.prm, a
short end time. Run from the repository root; a few seconds per probe for
the small scene.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402


def floats(text):
    return [float(v) for v in text.split(',') if v.strip()]


def check_inside_octagon(half_width, piston_distances):
    """Exit unless the square of @p half_width lies inside the octagon."""
    if min(piston_distances) < half_width * math.sqrt(2):
        sys.exit('--half-widths: the largest square (%g m) reaches past the '
                 'octagon (smallest piston distance %g m)'
                 % (half_width, min(piston_distances)))


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--stage', required=True,
                   help='a granular stage prm ending in the pack to measure')
    a.add_argument('--half-widths', type=floats, default=[3.5e-3, 5.5e-3],
                   help='probe squares around the axis (m), increasing')
    a.add_argument('--inlet-radius', type=float, default=2e-3)
    a.add_argument('--workdir', default=None,
                   help='default: <stage directory>/contact_stress_<stage>')
    a.add_argument('--softsand', default='build/softsand')
    prm_tools.add_set_argument(a, '--stage')
    args = a.parse_args()
    widths = args.half_widths
    if not widths or any(w <= 0 for w in widths) or widths != sorted(set(widths)):
        sys.exit('--half-widths must be positive and increasing, got %s'
                 % widths)
    if not widths[0] > args.inlet_radius:
        sys.exit('--half-widths: the first square (%g m) must enclose the '
                 'inlet (--inlet-radius %g m)' % (widths[0], args.inlet_radius))
    text = open(args.stage).read()
    for path, value in prm_tools.parse_set(args.set):
        text = prm_tools.set_entry(text, path, value)
    if prm_tools.get_entry(text, 'simulation control/mode') != 'granular':
        sys.exit('--stage %s is not a granular scene' % args.stage)
    octagon_entry = floats(prm_tools.get_entry(text, 'dem/walls/octagon') or '')
    if len(octagon_entry) < 3:
        sys.exit('--stage %s has no octagon of pistons (dem/walls/octagon)'
                 % args.stage)
    # Before the runs from the stage's start, after them from where its
    # pistons ended (a compaction moves them inward).
    check_inside_octagon(widths[-1], octagon_entry[2:])
    lower = floats(prm_tools.get_entry(text, 'mesh/lower corner'))
    upper = floats(prm_tools.get_entry(text, 'mesh/upper corner'))
    gap = upper[2] - lower[2]
    workdir = args.workdir or os.path.join(
        os.path.dirname(os.path.abspath(args.stage)), 'contact_stress_' +
        os.path.splitext(os.path.basename(args.stage))[0])

    def run(name, probe):
        overrides = [('dem/probe box', ', '.join('%.9g' % v for v in probe))]
        row, wall, error = prm_tools.run(args.softsand, text, workdir, name,
                                         overrides=overrides)
        if row is None:
            sys.exit('%s failed: %s' % (name, ' '.join(error)))
        if 'contact_stress_xx' not in row:
            sys.exit('no contact_stress columns: %s predates them' %
                     args.softsand)
        return row

    # (name, in-plane load sum (xx + yy) / 2 * V, grain-holding volume)
    probes = []
    for w in widths:
        row = run('square_%g' % w, [-w, -w, lower[2], w, w, upper[2]])
        box = (2 * w) ** 2 * gap
        load = 0.5 * (row['contact_stress_xx'] + row['contact_stress_yy']) * box
        probes.append(('|x|, |y| < %g mm' % (w * 1e3), load,
                       box - math.pi * args.inlet_radius ** 2 * gap))
    row = run('whole', lower + upper)
    box = (upper[0] - lower[0]) * (upper[1] - lower[1]) * gap
    radii = [-row['piston_%d_position' % k] for k in range(8)]
    check_inside_octagon(widths[-1], radii)
    # The octagon's area: a triangle from the centre per face, its side
    # that of a regular octagon at the face's distance (the distances
    # differ by a few per cent).
    area = sum(r * r * math.tan(math.pi / 8) for r in radii)
    octagon = area * gap - math.pi * args.inlet_radius ** 2 * gap
    whole = 0.5 * (row['contact_stress_xx'] + row['contact_stress_yy']) * box
    piston_load = sum(row['piston_%d_force_normal' % k] * radii[k]
                      for k in range(8)) / (2 * area * gap)
    sigma = float(prm_tools.get_entry(text, 'dem/walls/servo pressure'))
    print('# %s: servo pressure %g Pa, pistons\' mean traction %.4g Pa '
          '(sum F_k R_k / 2 V)' % (args.stage, sigma, piston_load))
    print('# ring  in-plane_contact_stress[Pa]  over_servo_pressure')
    inner_load, inner_volume, inner_name = 0., 0., 'inlet'
    rings = probes + [('octagon', whole, octagon)]
    for name, load, volume in rings:
        stress = (load - inner_load) / (volume - inner_volume)
        print('%s .. %s  %.4g  %.3f' % (inner_name, name, stress,
                                        stress / sigma))
        inner_load, inner_volume, inner_name = load, volume, name
    print('whole pack  %.4g  %.3f' % (whole / octagon, whole / octagon / sigma))


if __name__ == '__main__':
    main()
