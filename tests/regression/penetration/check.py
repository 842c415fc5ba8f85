"""Eroding penetration: a steel rod at 3 km/s into a steel plate, elements
eroding. At every field step no rod node (free debris nodes included) lies
inside a plate tetrahedron that is still there (beyond 1e-6 of the element
size): the contact keeps finding the newly exposed crater faces. Elements
erode; the mass of the mesh is unchanged bitwise; momentum is conserved to
1e-13; the energy balance with the eroded energy and the contact work stays
within 2 %."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside  # noqa: E402

out = os.path.join(sys.argv[1], 'out')
with h5py.File(os.path.join(out, 'penetration.h5'), 'r') as f:
    part = f['mesh/part_id'][...]
    conn = f['mesh/connectivity'][...]
    rod_nodes = np.unique(conn[part == 1])
    x0 = f['mesh/x0'][...]
    plate = part == 2
    h_plate = np.median(np.linalg.norm(x0[conn[plate, 1]] - x0[conn[plate, 0]], axis=1))
    worst = 0.0
    for k in sorted(f['steps'].keys()):
        g = f['steps'][k]
        x = g['coordinates'][...]
        alive = plate & (g['fracture_state'][...] < 1.5)
        w = deepest_inside(x[rod_nodes], x, conn[alive])
        print(f"MEASURED t = {g.attrs['time'] * 1e6:.2f} us: {np.count_nonzero(plate & ~alive)} plate elements "
              f"eroded, deepest rod node inside the plate {w:.3g} m; rod tip z = {x[rod_nodes, 2].min() * 1e3:.3f} mm")
        worst = max(worst, w)
    crater = -x[np.unique(conn[alive]), 2][np.abs(x[np.unique(conn[alive]), 0]) < 1e-3].max()
checks.below('rod_nodes_inside_remaining_plate_over_h', worst / h_plate, 1e-6)
h = udar_results.read_history(os.path.join(out, 'penetration_history.csv'))
print(f"MEASURED at the end: {h['eroded'][-1]:.0f} elements eroded, eroded energy {h['eroded_energy'][-1]:.4g} J, "
      f"contact work {h['contact_work'][-1]:.4g} J, energy error {h['energy_error'][-1]:.3e}")
checks.above('elements_eroded', h['eroded'][-1], 100)
checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
p0 = h['momentum_z'][0]
checks.below('momentum_conserved_relative', np.abs(h['momentum_z'] - p0).max() / abs(p0), 1e-13)
checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.02)
checks.finish()
