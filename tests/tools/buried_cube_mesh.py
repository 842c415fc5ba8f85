"""A plate of Kuhn-split cubes (4 x 4 x 2 cubes of 1 mm, top face z = 0)
and a 1 mm 'cube' of 2 x 2 x 2 such cubes of 0.5 mm whose lower 0.7 mm is
inside the plate from the start (z = -0.7 ... 0.3 mm): its elements that
erode make particles inside the plate (tests/regression/buried_particles).
With --half: the plate's half x >= 0, its face x = 0 the surface group
sym_x0 (a symmetry plane), and the cube across the plane (x = -0.25 ...
0.75 mm): elements with their centre behind the plane make particles that
are put on it, inside the plate.
Writes a gmsh 2.2 ASCII mesh, coordinates in mm.
Usage: buried_cube_mesh.py OUT.msh [--half]"""
import sys

import numpy as np

from deep_node_mesh import block, write_msh


def main(out, half=False):
    if not half:
        x, plate = block(4, 4, 2, 1.0, (-2.0, -2.0, -2.0))
        xc, cube = block(2, 2, 2, 0.5, (-0.5, -0.5, -0.7), first=len(x) + 1)
        write_msh(out, np.vstack([x, xc]), [('plate', plate), ('cube', cube)])
        return
    x, plate = block(2, 4, 2, 1.0, (0.0, -2.0, -2.0))
    # the plate's boundary triangles in x = 0 (each Kuhn tetrahedron's face there)
    on_plane = [sorted(f) for t in plate for f in (t[:3], t[1:], [t[0], t[1], t[3]], [t[0], t[2], t[3]])
                if all(x[n - 1, 0] == 0.0 for n in f)]
    xc, cube = block(2, 2, 2, 0.5, (-0.25, -0.5, -0.7), first=len(x) + 1)
    write_msh(out, np.vstack([x, xc]), [('plate', plate), ('cube', cube)], [('sym_x0', on_plane)])

if __name__ == '__main__':
    main(sys.argv[1], '--half' in sys.argv[2:])
