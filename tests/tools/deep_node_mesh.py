"""A plate of Kuhn-split cubes (4 x 4 x 2 cubes of 1 mm, top face z = 0,
6 tetrahedra a cube) and a 'rod': a 1 mm block of 2 x 2 x 2 such cubes
0.2 mm above it whose bottom centre node is pulled down to a point strictly
inside the element under a face of the plate's top: 0.4 of the way from
that face's centroid to the element's fourth corner (0.4 mm deep). The situation erosion leaves when it
exposes a face under a node already inside (issue 13, item 3). Writes a
gmsh 2.2 ASCII mesh, coordinates in mm.
Usage: deep_node_mesh.py OUT.msh"""
import itertools
import sys

import numpy as np


def block(nx, ny, nz, size, origin, first=1):
    """Nodes (numbered from first) and Kuhn tetrahedra of nx x ny x nz cubes."""
    ids = {}
    nodes = []

    def node(i, j, k):
        key = (i, j, k)
        if key not in ids:
            ids[key] = len(nodes) + first
            nodes.append(np.array(origin) + size * np.array([i, j, k], float))
        return ids[key]

    tets = []
    for i, j, k in itertools.product(range(nx), range(ny), range(nz)):
        for perm in itertools.permutations(range(3)):
            p = [i, j, k]
            corners = [node(*p)]
            for axis in perm:
                p[axis] += 1
                corners.append(node(*p))
            tets.append(corners)
    return np.array(nodes, float), tets


def main(out):
    x, tets = block(4, 4, 2, 1.0, (-2.0, -2.0, -2.0))
    # the element under a top face near the middle: three corners at z = 0
    chosen = None
    for t in tets:
        top = [n for n in t if x[n - 1, 2] == 0.0]
        c = np.mean(x[[n - 1 for n in top]], axis=0) if len(top) == 3 else None
        if c is not None and np.all(np.abs(c[:2]) < 1.0):
            chosen = (top, [n for n in t if n not in top][0], c)
            break
    top, apex, centroid = chosen
    tip = 0.6 * centroid + 0.4 * x[apex - 1]
    n0 = len(x)
    xr, rod = block(2, 2, 2, 0.5, (tip[0] - 0.5, tip[1] - 0.5, 0.2), first=n0 + 1)
    centre = int(np.argmin(np.linalg.norm(xr - [tip[0], tip[1], 0.2], axis=1)))
    xr[centre] = tip
    write_msh(out, np.vstack([x, xr]), [('plate', tets), ('rod', rod)])


def write_msh(out, x, volumes, surfaces=()):
    """A gmsh 2.2 ASCII mesh: nodes x (numbered from 1), the tetrahedra of
    each (name, tets) of volumes, physical volume k + 1, and the triangles
    of each (name, tris) of surfaces, physical surface len(volumes) + k + 1."""
    groups = [(3, name, 4, els) for name, els in volumes] + [(2, name, 2, els) for name, els in surfaces]
    lines = ['$MeshFormat', '2.2 0 8', '$EndMeshFormat', '$PhysicalNames', str(len(groups))]
    lines += [f'{dim} {k + 1} "{name}"' for k, (dim, name, _, _) in enumerate(groups)]
    lines += ['$EndPhysicalNames', '$Nodes', str(len(x))]
    lines += [f'{k + 1} {p[0]!r} {p[1]!r} {p[2]!r}' for k, p in enumerate(x)]
    lines += ['$EndNodes', '$Elements', str(sum(len(g[3]) for g in groups))]
    e = 0
    for k, (_, _, kind, els) in enumerate(groups):
        for t in els:
            e += 1
            lines.append(f'{e} {kind} 2 {k + 1} {k + 1} ' + ' '.join(map(str, t)))
    lines += ['$EndElements']
    with open(out, 'w') as f:
        f.write('\n'.join(lines) + '\n')


if __name__ == '__main__':
    main(sys.argv[1])
