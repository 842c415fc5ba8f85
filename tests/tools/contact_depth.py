"""How deep slave nodes get inside the master over a whole run: for every
field step of FIELDS.h5, the deepest node of part SLAVE inside a
tetrahedron of part MASTER that is still there (not eroded), over the
master's median edge h (where SLAVE's eroded elements became particles:
its remaining elements' nodes and its particles) (the measure of the contact checks,
tests/regression/rod_3kms/check_geometry.py). Prints one CSV line:
frames, frames with a node inside by more than 1e-6 h, the deepest over h
and its time (us). Used by tests/validate_contact.sh (doc/validation.md 4r).
Usage: contact_depth.py FIELDS.h5 SLAVE MASTER"""
import os
import sys

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'regression', 'rod_3kms'))
from check_geometry import frames_inside, slave_and_master  # noqa: E402

path, slave, master = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
with h5py.File(path, 'r') as f:
    h = slave_and_master(f, slave, master)[4]
    frames, inside, worst, t_worst = 0, 0, 0.0, 0.0
    for g, _, depth in frames_inside(f, slave, master):
        d = depth / h
        frames += 1
        inside += d > 1e-6
        if d > worst:
            worst, t_worst = d, g.attrs['time'] * 1e6
print(f'{frames},{inside},{worst:.3g},{t_worst:.3f}')
