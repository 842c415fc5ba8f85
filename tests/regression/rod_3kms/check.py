"""A steel rod at 3 km/s onto a steel plate: at every field step no rod node
lies inside a plate tetrahedron (beyond 1e-6 of the element size), the
plate is dented, momentum is conserved."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.dirname(__file__))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside  # noqa: E402


out = os.path.join(sys.argv[1], 'out')
deck = sys.argv[2] if len(sys.argv) > 2 else 'rod_3kms'
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    part = f['mesh/part_id'][...]
    conn = f['mesh/connectivity'][...]
    rod_nodes = np.unique(conn[part == 1])
    plate_tets = conn[part == 2]
    x0 = f['mesh/x0'][...]
    h_plate = np.median(np.linalg.norm(x0[plate_tets[:, 1]] - x0[plate_tets[:, 0]], axis=1))
    worst = 0.0
    for k in sorted(f['steps'].keys()):
        x = f['steps'][k]['coordinates'][...]
        w = deepest_inside(x[rod_nodes], x, plate_tets)
        print(f"MEASURED t = {f['steps'][k].attrs['time'] * 1e6:.2f} us: deepest rod node inside the plate "
              f"{w:.3g} m; rod tip z = {x[rod_nodes, 2].min() * 1e3:.4f} mm")
        worst = max(worst, w)
    plate_nodes = np.unique(plate_tets)
    top = plate_nodes[np.abs(x0[plate_nodes, 2]) < 1e-9]
    dent = -x[top, 2].min()
print(f"MEASURED crater depth (plate top surface) {dent * 1e3:.3f} mm at 1 us")
checks.below('rod_nodes_inside_plate_over_h', worst / h_plate, 1e-6)
checks.above('plate_dented_m', dent, 0.5e-3, 'm')
h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
p0 = h['momentum_z'][0]
checks.below('momentum_conserved_relative', np.abs(h['momentum_z'] - p0).max() / abs(p0), 1e-13)
checks.finish()
