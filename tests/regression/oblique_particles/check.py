"""The Fig. 3 deck with particles, f = 0, 3,012 m/s, to 4.5 us
(oblique_particles.nml, issue 15): at every field step no particle lies
behind the symmetry plane y = 0 (to 1e-12 m) or moves faster than three
times the impact speed (the oblique impact's jet reaches 1.9), and the
energy error stays within 1 % (0.6.0: particles made behind the plane were
sent back at 11.5 and 15 km/s, 3.8 times, energy error -2.2 %; particles
left behind it by the contact's returns, up to 0.77 um, each sent back).
And each part's particles are kept out of its own remaining elements (the
contact <part>_particles_on_itself): over the field steps, the share of
its particles inside one by more than 0.01 of its median edge stays below
0.15 (measured 0.084 for the cylinder and 0.074 for the plate; 0.6.1, with
no such contact, 0.26 and 0.44: the plate's crater debris went through the
plate and the cylinder overran its own).
Usage: check.py RUN_DIR [DECK]"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import depths_inside  # noqa: E402

V_IMPACT = 3012.0
run_dir = sys.argv[1]
deck = sys.argv[2] if len(sys.argv) > 2 else 'oblique_particles'
out = os.path.join(run_dir, 'out')
h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
behind, fastest, n = 0.0, 0.0, 0
PARTS = {1: 'cylinder', 2: 'plate'}
own_frames = {pid: 0 for pid in PARTS}     # particle-frames of the part
own_inside = {pid: 0 for pid in PARTS}     # of them inside its own remaining elements
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    conn, x0, part = f['mesh/connectivity'][...], f['mesh/x0'][...], f['mesh/part_id'][...]
    h_part = {pid: np.median(np.linalg.norm(x0[conn[part == pid, 1]] - x0[conn[part == pid, 0]], axis=1))
              for pid in PARTS}
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        g = f['steps'][k]
        p = g['particles']
        n = int(p.attrs['count'])
        if n == 0:
            continue
        behind = max(behind, -p['coordinates'][:, 1].min())
        fastest = max(fastest, np.linalg.norm(p['velocity'][...], axis=1).max())
        alive = g['fracture_state'][...] < 1.5
        for pid in PARTS:
            mine = p['part_id'][...] == pid
            depth = depths_inside(p['coordinates'][...][mine], g['coordinates'][...], conn[(part == pid) & alive])
            own_frames[pid] += int(mine.sum())
            own_inside[pid] += int(np.count_nonzero(depth > 0.01 * h_part[pid]))
print(f"MEASURED {n} particles at the end; the farthest behind y = 0 {behind:.3g} m, the fastest {fastest:.0f} m/s; "
      f"energy error at most {np.abs(h['energy_error']).max():.3e}")
for pid, name in PARTS.items():
    share = own_inside[pid] / max(own_frames[pid], 1)
    print(f"MEASURED {name}: {own_inside[pid]} of {own_frames[pid]} particle-frames inside its own remaining elements "
          f"by more than 0.01 h ({share:.3f})")
    checks.below(f'{name}_particles_inside_own_body_share', share, 0.15)
checks.above('particles_made', n, 500)
checks.below('particle_behind_symmetry_plane', behind, 1e-12, 'm')
checks.below('particle_speed_over_impact_speed', fastest / V_IMPACT, 3.0)
checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.01)
checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
checks.finish()
