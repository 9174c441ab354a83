#!/usr/bin/env python3
"""Write parameters/meshes/step_channel.msh: a channel behind a backward-
facing step, as a gmsh (format 2.2, ASCII) hexahedral mesh, the domain of
parameters/step_channel.prm (mesh/geometry = file).

The channel runs along x from 0 to 3 mm, 1 mm high (y) and 0.5 mm deep
(z); for x < 1 mm its lower half is solid (the step). Cells of 0.125 mm.
Physical tags of the boundary faces, as softsand reads them: 0 the inlet
(x = 0, the "x min" subsection), 1 the outlet (x = 3 mm, "x max"), 9 the
walls (any tag above 5 is a no-slip wall).

  python3 scripts/packs/make_step_channel_msh.py [OUTPUT]
"""
import os
import sys

H = 1.25e-4                 # cell edge (m)
NX, NY, NZ = 24, 8, 4       # 3 x 1 x 0.5 mm
STEP_X, STEP_Y = 8, 4       # the step: cells i < 8 and j < 4 are solid


def fluid(i, j, k):
    return 0 <= i < NX and 0 <= j < NY and 0 <= k < NZ and \
        not (i < STEP_X and j < STEP_Y)


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        root, 'parameters', 'meshes', 'step_channel.msh')
    node_id = {}

    def node(i, j, k):
        if (i, j, k) not in node_id:
            node_id[(i, j, k)] = len(node_id) + 1
        return node_id[(i, j, k)]

    hexes, quads = [], []
    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                if not fluid(i, j, k):
                    continue
                # gmsh's hexahedron: the bottom face counter-clockwise,
                # then the top face above it
                hexes.append([node(i, j, k), node(i + 1, j, k),
                              node(i + 1, j + 1, k), node(i, j + 1, k),
                              node(i, j, k + 1), node(i + 1, j, k + 1),
                              node(i + 1, j + 1, k + 1),
                              node(i, j + 1, k + 1)])
                # boundary faces: where the neighbour is not fluid
                for di, dj, dk in ((-1, 0, 0), (1, 0, 0), (0, -1, 0),
                                   (0, 1, 0), (0, 0, -1), (0, 0, 1)):
                    if fluid(i + di, j + dj, k + dk):
                        continue
                    if di == -1 and i == 0:
                        tag = 0
                    elif di == 1 and i == NX - 1:
                        tag = 1
                    else:
                        tag = 9
                    # the face's four corners, in order around it
                    axis = 0 if di else 1 if dj else 2
                    side = max(di, dj, dk)
                    corners = []
                    for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        c = [i, j, k]
                        c[axis] += side
                        u, v = [x for x in range(3) if x != axis]
                        c[u] += a
                        c[v] += b
                        corners.append(node(*c))
                    quads.append((tag, corners))
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, 'w') as f:
        f.write('$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n'
                % len(node_id))
        for (i, j, k), n in sorted(node_id.items(), key=lambda kv: kv[1]):
            f.write('%d %.9g %.9g %.9g\n' % (n, i * H, j * H, k * H))
        f.write('$EndNodes\n$Elements\n%d\n' % (len(quads) + len(hexes)))
        e = 0
        for tag, corners in quads:
            e += 1
            f.write('%d 3 2 %d %d %s\n' % (e, tag, tag,
                                           ' '.join(map(str, corners))))
        for h in hexes:
            e += 1
            f.write('%d 5 2 0 1 %s\n' % (e, ' '.join(map(str, h))))
        f.write('$EndElements\n')
    print('%s: %d hexahedra, %d boundary faces' % (out, len(hexes),
                                                   len(quads)))


if __name__ == '__main__':
    main()
