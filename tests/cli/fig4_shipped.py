"""Issue 13's limit on a Fig. 4 field file (part 1 the rod, part 2 the
plate): no node of a remaining rod element inside a remaining plate
element deeper than 1e-6 h (h the plate's median edge; check_geometry's
depth, a node on a face in the symmetry plane inside the mirrored plate)
at any frame; the plate's nodes (free ones too) inside the remaining rod
are held to fig4_depth's 0.01 of the rod's median edge. 0.9.18 on the
deck as shipped: rod nodes 9.3e-3 h (6.76 us), plate nodes 2.9e-4;
0.9.19: 3.3e-16 h and 3.7e-16 (at dt_safety 0.34 / 0.36 the rod nodes
2.1e-16 / 3.5e-16 h, the plate nodes 1.0e-3 / 7.2e-5: the other way is
not yet at 1e-6, validation.md 4zn).
With frames every 0.05 us to 10 us (cli/fig4_fine_frames, the rod nodes
alone): 0.9.19 4 frames deeper than 1e-6 h, the deepest 1.05e-3 h at 2.95
us; 0.9.20 2.5e-16 h (validation.md 4zo).
Usage: fig4_shipped.py FIELDS.h5 FRAMES [plate]"""
import os
import sys

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'regression', 'rod_3kms'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'tools'))
import checks  # noqa: E402
from check_geometry import frames_inside, slave_and_master  # noqa: E402

frames = int(sys.argv[2])
plate = len(sys.argv) > 3 and sys.argv[3] == 'plate'
with h5py.File(sys.argv[1], 'r') as f:
    h_plate = slave_and_master(f, 1, 2)[4]
    h_rod = slave_and_master(f, 2, 1)[4]
    rod_in, n_frames, n_deep, worst_time = 0.0, 0, 0, 0.0
    for g, _, d in frames_inside(f, 1, 2, remaining_only=True):
        n_frames += 1
        n_deep += d / h_plate > 1e-6
        if d / h_plate > rod_in:
            rod_in, worst_time = d / h_plate, g.attrs['time']
    plate_in = max(d / h_rod for _, _, d in frames_inside(f, 2, 1)) if plate else 0.0
print(f'MEASURED {n_frames} frames, {n_deep} of them with a remaining rod node inside the plate deeper than 1e-6 h;'
      f' the deepest {rod_in:.3g} h (at {worst_time * 1e6:.2f} us)'
      + (f'; the deepest plate node inside the rod {plate_in:.3g} h of the rod' if plate else ''))
checks.above('frames', n_frames, frames)
checks.below('remaining_rod_node_inside_the_plate_over_h', rod_in, 1e-6)
if plate:
    checks.below('plate_node_inside_the_rod_over_its_h', plate_in, 0.01)
checks.finish()
