#!/usr/bin/env python3
"""Prepare a radial Hele-Shaw injection scene in one command: the loose
pack, stage 1 (compaction by the servo pistons without cohesion), stage 2
(cohesion switched on in the compacted pack), and the injection scene that
starts from it, with no file copied or piston position typed by hand.

  python3 scripts/packs/make_hele_shaw_scene.py --scale small
  python3 scripts/packs/make_hele_shaw_scene.py --scale default --ranks 2

writes into --workdir (default output/hele_shaw_scene_<scale>):
  loose.txt                  the loose pack (scripts/packs/make_hele_shaw_pack.py)
  stage1.prm, stage1/        compaction without cohesion (the scale's
                             parameters/hele_shaw_pack*.prm)
  stage2.prm, stage2/        cohesion on (hele_shaw_pack*_cohesive.prm), the
                             pistons where stage 1 left them
  pack.txt                   the cohesive pack
  injection.prm              the scale's injection scene (hele_shaw_small.prm
                             or hele_shaw.prm) reading pack.txt, its pistons
                             where stage 2 left them; output in
                             <workdir>/injection
--cohesion sets the cohesion energy density of stage 2 and the injection
(J/m^3; default the templates' 3e5), --wall-cohesion that of grain-wall
contacts in the same two (default: the grains'; 0 lets the pack, not the
plates, carry the pistons' load), --confining-pressure the pistons' servo
pressure in all three (Pa; default 5e3): the regime map's packs.
Each stage prints whether its pack settled (the DEM's own warning says so
when it did not). Then run `build/softsand <workdir>/injection.prm`, or the
sweep: `python3 scripts/studies/hele_shaw_sweep.py --scene <workdir>/injection.prm`.
Measured cost (1 rank): small scale about 10 s; the default scale's two
stages took 229 s and 1,189 s (doc/notes/hele_shaw_history.md, "Workflow"). Run from the repository
root.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402

SCALES = {
    # count, inlet radius (m), stage 1, stage 2, injection scene
    'small': (250, 2e-3, 'parameters/hele_shaw_pack_small.prm',
              'parameters/hele_shaw_pack_small_cohesive.prm',
              'parameters/hele_shaw_small.prm'),
    'default': (2000, 4e-3, 'parameters/hele_shaw_pack.prm',
                'parameters/hele_shaw_pack_cohesive.prm',
                'parameters/hele_shaw.prm'),
}


def octagon_after(stage_dir):
    """dem/walls/octagon with the pistons where a stage left them: the last
    statistics row's piston_K_position is minus the distance from the
    axis."""
    last = prm_tools.read_statistics(stage_dir)[-1]
    try:
        distances = [-last['piston_%d_position' % k] for k in range(8)]
    except KeyError:
        sys.exit('no piston_K_position columns in %s/statistics.txt: not an '
                 'octagon compaction' % stage_dir)
    return '0, 0, ' + ', '.join('%.6e' % d for d in distances)


def run_stage(args, name, template, overrides):
    with open(template) as f:
        text = f.read()
    outdir = os.path.join(args.workdir, name)
    for path, value in overrides + [('output/directory', outdir)]:
        text = prm_tools.set_entry(text, path, value)
    prm = os.path.join(args.workdir, name + '.prm')
    with open(prm, 'w') as f:
        f.write(text)
    prm_tools.fresh_output(text, outdir)
    cmd = [args.softsand, prm]
    if args.ranks > 1:
        cmd = ['mpirun', '-np', str(args.ranks)] + cmd
    start = time.time()
    print('%s: %s' % (name, ' '.join(cmd)), flush=True)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    with open(os.path.join(args.workdir, name + '.log'), 'w') as log:
        log.write(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        sys.exit('%s failed (%s.log): %s' % (
            name, os.path.join(args.workdir, name),
            ' '.join(proc.stderr.strip().splitlines()[-1:])))
    warnings = [l for l in (proc.stdout + proc.stderr).splitlines()
                if 'arning' in l]
    for w in warnings:
        print('  ' + w.strip())
    print('  %.0f s' % (time.time() - start), flush=True)
    return outdir


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--scale', choices=sorted(SCALES), default='small')
    a.add_argument('--seed', type=int, default=1)
    a.add_argument('--workdir', default=None)
    a.add_argument('--softsand', default='build/softsand')
    a.add_argument('--ranks', type=int, default=1)
    a.add_argument('--cohesion', type=float, default=None,
                   help='cohesion energy density of stage 2 and the '
                        'injection (J/m^3)')
    a.add_argument('--wall-cohesion', type=float, default=None,
                   help='cohesion energy density of grain-wall contacts in '
                        'stage 2 and the injection (J/m^3; default: the '
                        "grains')")
    a.add_argument('--confining-pressure', type=float, default=None,
                   help="the pistons' servo pressure in every stage (Pa)")
    args = a.parse_args()
    if args.cohesion is not None and args.cohesion < 0:
        sys.exit('--cohesion must be >= 0, got %g' % args.cohesion)
    if args.wall_cohesion is not None and not args.wall_cohesion >= 0:
        sys.exit('--wall-cohesion must be >= 0, got %g' % args.wall_cohesion)
    if args.confining_pressure is not None and not args.confining_pressure > 0:
        sys.exit('--confining-pressure must be > 0, got %g'
                 % args.confining_pressure)
    confining = ([] if args.confining_pressure is None else
                 [('dem/walls/servo pressure', '%g' % args.confining_pressure)])
    cohesion = ([] if args.cohesion is None else
                [('dem/material/cohesion energy density', '%g' % args.cohesion)])
    if args.wall_cohesion is not None:
        cohesion.append(('dem/material/wall cohesion energy density',
                         '%g' % args.wall_cohesion))
    count, inlet, stage1, stage2, scene = SCALES[args.scale]
    if args.workdir is None:
        args.workdir = 'output/hele_shaw_scene_' + args.scale
    os.makedirs(args.workdir, exist_ok=True)

    loose = os.path.join(args.workdir, 'loose.txt')
    proc = subprocess.run([sys.executable,
                           os.path.join(os.path.dirname(__file__),
                                        'make_hele_shaw_pack.py'),
                           '--count', str(count), '--seed', str(args.seed),
                           '--inlet-radius', '%g' % inlet, '--out', loose],
                          capture_output=True, text=True, check=True)
    inradius = float(proc.stdout.split()[-1])
    print('loose pack: %d grains, octagon inradius %.6g m' % (count, inradius))

    s1 = run_stage(args, 'stage1', stage1,
                   [('grains/file', loose),
                    ('dem/walls/octagon', '0, 0, %.6e' % inradius)]
                   + confining)
    s2 = run_stage(args, 'stage2', stage2,
                   [('grains/file', os.path.join(s1, 'pack.txt')),
                    ('dem/walls/octagon', octagon_after(s1))]
                   + confining + cohesion)
    pack = os.path.join(args.workdir, 'pack.txt')
    shutil.copyfile(os.path.join(s2, 'pack.txt'), pack)
    with open(scene) as f:
        text = f.read()
    for path, value in [('grains/file', pack),
                        ('dem/walls/octagon', octagon_after(s2)),
                        ('output/directory',
                         os.path.join(args.workdir, 'injection'))] + \
            confining + cohesion:
        text = prm_tools.set_entry(text, path, value)
    with open(os.path.join(args.workdir, 'injection.prm'), 'w') as f:
        f.write(text)
    print('injection scene: %s' % os.path.join(args.workdir, 'injection.prm'))


if __name__ == '__main__':
    main()
