"""A block sliding towards a wedge's sharp edge (sharp_edge.geo): at every
field step no block node lies inside a wedge tetrahedron (beyond 1e-6 of
the block's element size, 1 mm), and the energy balance stays within 1e-3
(frictionless, elastic: nothing should be lost). Without &contact
sharp_edges (sharp_edge_off) the nodes near the edge, moving away from
the wedge's bottom face, were taken as behind it and returned into the
wedge: to 0.9.19 that deck failed both (8 of 36 steps, 9.78e-6 m deep,
energy error 0.133). Since 0.9.20 a face the node is separating from is
taken only if no deeper than the face it is on (theory.md 11, the nearest
face decides), and that deck passes too. Momentum is exchanged exactly. No initial overlap is reported: the
block starts clear of the wedge, though ahead of its edge its nodes are
behind the planes of faces beyond it.
Usage: check.py RUN_DIR DECK"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import frames_inside, slave_and_master  # noqa: E402

deck = sys.argv[2]
out = os.path.join(sys.argv[1], 'out')
h_block = 1.0e-3
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    block_nodes = slave_and_master(f, 1, 2)[2]
    worst, frames, inside = 0.0, 0, 0
    for _, x, d in frames_inside(f, 1, 2):
        frames += 1
        inside += d > 1e-6 * h_block
        worst = max(worst, d)
    lead = x[block_nodes, 0].min()
print(f'MEASURED {inside} of {frames} field steps with a block node inside the wedge, the deepest {worst:.3g} m; '
      f'the block\'s leading edge at the end x = {lead * 1e3:.3f} mm (the wedge\'s edge at x = 0)')
checks.below('block_nodes_inside_wedge_over_h', worst / h_block, 1e-6)
# the block starts in front of the wedge: ahead of its sharp edge, nodes
# are behind the planes of far faces, but none is inside (0.5.7 reported 12)
checks.below('initial_overlaps_reported', checks.initial_overlaps(sys.argv[1], 'slider_on_wedge'), 0)
hist = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
checks.below('energy_error_max', np.abs(hist['energy_error']).max(), 1e-3)
p = np.array([hist['momentum_' + c] for c in 'xyz'])
checks.below('momentum_change_relative', np.abs(p - p[:, :1]).max() / np.abs(p[:, 0]).max(), 1e-13)
checks.finish()
