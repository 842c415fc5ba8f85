"""Frames of Fig. 4 field files (part 1 the rod, part 2 the plate) in
which a node of a remaining rod element is inside a remaining plate
element by more than 1e-4 h (h the plate's median edge; depth as
check_geometry measures it). Free nodes of eroded rod elements are not
counted here (tests/tools/contact_depth.py counts them too).
The count over all the files is checked (at most 28: 0.6.5 gave 14 over
the three steps of fig4_depth.sh, 0.6.4 43).
Usage: fig4_depth.py FIELDS.h5 ..."""
import os
import sys

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'regression', 'rod_3kms'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'tools'))
import checks  # noqa: E402
from check_geometry import frames_inside, slave_and_master  # noqa: E402

total = 0
for path in sys.argv[1:]:
    with h5py.File(path, 'r') as f:
        h = slave_and_master(f, 1, 2)[4]
        deep = [f"{g.attrs['time'] * 1e6:.2f} us: {d / h:.3g} h"
                for g, _, d in frames_inside(f, 1, 2, remaining_only=True) if d / h > 1e-4]
    print(f'MEASURED {path}: {len(deep)} frames with a remaining rod node inside the plate by more than 1e-4 h: '
          + (', '.join(deep) or 'none'))
    total += len(deep)
checks.below('frames_with_a_rod_node_deeper_than_1e-4_h_in_all_runs', total, 28)
checks.finish()
