"""The long rod's quarter model with particles (long_rod_particles.nml):
no rod particle runs through the block. At every field step
- no rod particle is ahead of the crater floor (the highest remaining
  block node within 1.25 mm of the axis) by more than half an element
  (before 0.6.1: particles made on the symmetry planes or inside the block
  were 3.4 mm ahead at 10 us, keeping 1.7 km/s; 0.9.0 built for AVX-512:
  3.116 h, a particle made on the plane x = 0 inside the block and left on
  a face in the plane, buried_particles_half shows it on any CPU);
- no rod particle lies inside a remaining block element deeper than 0.05
  of its size (its depth below that element's nearest face);
and the particles keep the mesh's mass (exact) with the energy error
within 2 %.
Usage: check.py RUN_DIR [DECK]"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside, slave_and_master  # noqa: E402

ROD, BLOCK = 1, 2
run_dir = sys.argv[1]
deck = sys.argv[2] if len(sys.argv) > 2 else 'long_rod_particles'
out = os.path.join(run_dir, 'out')
h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
ahead_max, inside_max, n_last = -np.inf, 0.0, 0
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    conn, x0, _, block, h_block = slave_and_master(f, ROD, BLOCK)
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        g = f['steps'][k]
        p = g['particles']
        n = int(p.attrs['count'])
        if n == 0:
            continue
        x = g['coordinates'][...]
        alive = block & (g['fracture_state'][...] < 1.5)
        nodes = np.unique(conn[alive])
        near_axis = nodes[np.hypot(x[nodes, 0], x[nodes, 1]) < 1.25e-3]
        floor = x[near_axis, 2].max()
        rod_p = p['coordinates'][...][p['part_id'][...] == ROD]
        ahead = floor - rod_p[:, 2].min() if len(rod_p) else -np.inf
        inside = deepest_inside(rod_p, x, conn[alive]) if len(rod_p) else 0.0
        print(f"MEASURED t = {g.attrs['time'] * 1e6:.1f} us: {n} particles ({len(rod_p)} of the rod), crater floor "
              f"{floor * 1e3:.2f} mm, the deepest rod particle {ahead / h_block:+.3f} h ahead of it, the deepest "
              f"inside a block element {inside / h_block:.3g} h")
        ahead_max, inside_max, n_last = max(ahead_max, ahead), max(inside_max, inside), n
checks.above('particles_made', n_last, 200)
checks.below('rod_particle_ahead_of_crater_floor_over_h', ahead_max / h_block, 0.5)
checks.below('rod_particle_inside_block_element_over_h', inside_max / h_block, 0.05)
checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.02)
checks.finish()
