#!/usr/bin/env python3
"""OpenFOAM's permeability of a permeameter pack (the cylinder of
parameters/permeameter.prm: radius 0.25 mm along z, 0.2 mm grain-free
buffers, flow-rate inlet at z min, pressure outlet at z max), on a
snappyHexMesh mesh refined LEVEL times at the grains and at the mantle (an
analytic searchableCylinder): the body-fitted reference for
scripts/studies/study_permeameter.py. Prints N (mean diameter over the smallest
cell), cells and K = q mu L / dp between softsand's planes, q = Q / (pi R^2).

  python3 benchmarks/openfoam/permeameter.py PACK_FILE PACK_TOP LEVEL [WORKDIR]

PACK_FILE: the pack of stage 1 (e.g. /tmp/permeameter/pack/pack.txt);
PACK_TOP: the pack's height that study_permeameter.py prints plus the
0.2 mm outlet buffer (stage 2's `mesh/upper corner` z). Serial only. Needs
OpenFOAM (benchmarks/openfoam/README.md).
"""
import math
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)),
                                'scripts'))
import foam_case  # noqa: E402
import prm_tools  # noqa: E402

R, BUFFER, MU, RHO = 2.5e-4, 2e-4, 1e-3, 1000.


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    grains = prm_tools.read_grains(sys.argv[1])
    z0, z1, level = -BUFFER, float(sys.argv[2]), int(sys.argv[3])
    workdir = sys.argv[4] if len(sys.argv) > 4 else '/tmp/permeameter_openfoam'
    Q = math.pi * R * R * 1e-3          # 1 mm/s, as parameters/permeameter.prm
    planes = (z0 + BUFFER + 1e-4, z1 - BUFFER - 1e-4)
    d = 2 * sum(g[3] for g in grains) / len(grains)
    blocks = int(round(2 * R / (d / 2)))            # 2 cells per mean d
    h = 2 * R / blocks
    faces = {'x min': ('no slip', None), 'x max': ('no slip', None),
             'y min': ('no slip', None), 'y max': ('no slip', None),
             'z min': ('flow rate', Q), 'z max': ('pressure', 0)}
    case = foam_case.Case((-1.02 * R, -1.02 * R, z0), (1.02 * R, 1.02 * R, z1),
                          (blocks, blocks, int(round((z1 - z0) / h))),
                          grains, level, faces, MU / RHO, RHO, planes=planes,
                          inside=(1.3e-7, 1.7e-7, z0 + 0.25 * BUFFER),
                          axis=2, mantle_radius=R)
    directory = os.path.join(workdir, 'level%d' % level)
    shutil.rmtree(directory, ignore_errors=True)
    case.write(directory)
    env = dict(os.environ, WM_PROJECT_DIR='/usr/share/openfoam')
    for app in (['blockMesh'], ['snappyHexMesh', '-overwrite'],
                ['simpleFoam']):
        start = time.time()
        with open(os.path.join(directory, 'log.' + app[0]), 'w') as log:
            code = subprocess.call(app, cwd=directory, env=env, stdout=log,
                                   stderr=subprocess.STDOUT)
        print('%s: %.1f s' % (app[0], time.time() - start), flush=True)
        if code:
            raise SystemExit('%s failed: see %s' % (app[0], directory))
    k = foam_case.permeability_history(directory, planes,
                                       Q / (math.pi * R * R), MU, RHO)[-1][1]
    cells = foam_case.mesh_cells(directory)
    print('level %d: N = %.3g, %d cells, K = %.4g m^2' % (
        level, d / (h / 2 ** level), cells, k))


if __name__ == '__main__':
    main()
