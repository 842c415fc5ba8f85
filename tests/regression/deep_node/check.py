"""A slave node inside the element under a face of an eroding master,
deeper than the search margin (issue 13, item 3; the deck says how it is
made). Before 0.5.3 the contact skipped such a node without a word and it
stayed 0.4 mm inside for the whole run. Now: it is found from the first
cycle on (history column contact_deep_rod_on_plate, and the log), put back
towards the surface in bounded steps, and out of every plate element by the
end; the contact exchanges momentum exactly."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside, slave_and_master  # noqa: E402

out = os.path.join(sys.argv[1], 'out')
with h5py.File(os.path.join(out, 'deep_node.h5'), 'r') as f:
    conn, x0, rod, plate, h = slave_and_master(f, 2, 1)
    depth = []
    for k in sorted(f['steps'].keys()):
        g = f['steps'][k]
        x = g['coordinates'][...]
        depth.append(deepest_inside(x[rod], x, conn[plate & (g['fracture_state'][...] < 1.5)]))
print('MEASURED deepest rod node inside a plate element at each field step (of h): ' +
      ' '.join(f'{d / h:.3g}' for d in depth))
checks.above('starts_inside_over_h', depth[0] / h, 0.1)
# and the initial-overlap report names it (it is inside a plate element)
checks.compare('initial_overlaps_reported', checks.initial_overlaps(sys.argv[1], 'rod_on_plate'), 1, 0.0)
checks.below('inside_at_the_end_over_h', depth[-1] / h, 1e-6)
hist = udar_results.read_history(os.path.join(out, 'deep_node_history.csv'))
deep = hist['contact_deep_rod_on_plate']
print(f'MEASURED deep nodes found in {np.count_nonzero(deep)} of {len(deep) - 1} cycles; '
      f'energy error at the end {hist["energy_error"][-1]:.3g} (the returns move a node with no force doing the work)')
checks.compare('found_in_the_first_cycle', deep[1], 1.0, 0.0)
p = np.array([hist['momentum_' + c] for c in 'xyz'])
checks.below('momentum_change_relative', np.abs(p - p[:, :1]).max() / np.abs(p[:, 0]).max(), 1e-13)
checks.finish()
