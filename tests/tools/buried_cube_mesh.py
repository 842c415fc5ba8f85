"""A plate of Kuhn-split cubes (4 x 4 x 2 cubes of 1 mm, top face z = 0)
and a 1 mm 'cube' of 2 x 2 x 2 such cubes of 0.5 mm whose lower 0.7 mm is
inside the plate from the start (z = -0.7 ... 0.3 mm): its elements that
erode make particles inside the plate (tests/regression/buried_particles).
Writes a gmsh 2.2 ASCII mesh, coordinates in mm.
Usage: buried_cube_mesh.py OUT.msh"""
import sys

import numpy as np

from deep_node_mesh import block, write_msh


def main(out):
    x, plate = block(4, 4, 2, 1.0, (-2.0, -2.0, -2.0))
    xc, cube = block(2, 2, 2, 0.5, (-0.5, -0.5, -0.7), first=len(x) + 1)
    write_msh(out, np.vstack([x, xc]), [('plate', plate), ('cube', cube)])

if __name__ == '__main__':
    main(sys.argv[1])
