"""How deep slave nodes get inside the master over a whole run: for every
field step of FIELDS.h5, the deepest node of part SLAVE inside a
tetrahedron of part MASTER that is still there (not eroded), over the
master's median edge h (the measure of the contact checks,
tests/regression/rod_3kms/check_geometry.py). Prints one CSV line:
frames, frames with a node inside by more than 1e-6 h, the deepest over h
and its time (us). Used by tests/validate_contact.sh (doc/validation.md 4r).
Usage: contact_depth.py FIELDS.h5 SLAVE MASTER"""
import os
import sys

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'regression', 'rod_3kms'))
from check_geometry import deepest_inside, slave_and_master  # noqa: E402

path, slave, master = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
with h5py.File(path, 'r') as f:
    conn, x0, slave_nodes, master_tets, h = slave_and_master(f, slave, master)
    frames, inside, worst, t_worst = 0, 0, 0.0, 0.0
    for k in f['steps'].keys():
        g = f['steps'][k]
        alive = master_tets
        if 'fracture_state' in g:
            alive = master_tets & (g['fracture_state'][...] < 1.5)
        x = g['coordinates'][...]
        d = deepest_inside(x[slave_nodes], x, conn[alive]) / h
        frames += 1
        inside += d > 1e-6
        if d > worst:
            worst, t_worst = d, g.attrs['time'] * 1e6
print(f'{frames},{inside},{worst:.3g},{t_worst:.3f}')
