"""The Fig. 3 deck with particles, f = 0, 3,012 m/s, to 4.5 us
(oblique_particles.nml, issue 15): at every field step no particle lies
behind the symmetry plane y = 0 (to 1e-12 m) or moves faster than three
times the impact speed (the oblique impact's jet reaches 1.9), and the
energy error stays within 1 % (0.6.0: particles made behind the plane were
sent back at 11.5 and 15 km/s, 3.8 times, energy error -2.2 %; particles
left behind it by the contact's returns, up to 0.77 um, each sent back).
Usage: check.py RUN_DIR [DECK]"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

V_IMPACT = 3012.0
run_dir = sys.argv[1]
deck = sys.argv[2] if len(sys.argv) > 2 else 'oblique_particles'
out = os.path.join(run_dir, 'out')
h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
behind, fastest, n = 0.0, 0.0, 0
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        p = f['steps'][k]['particles']
        n = int(p.attrs['count'])
        if n == 0:
            continue
        behind = max(behind, -p['coordinates'][:, 1].min())
        fastest = max(fastest, np.linalg.norm(p['velocity'][...], axis=1).max())
print(f"MEASURED {n} particles at the end; the farthest behind y = 0 {behind:.3g} m, the fastest {fastest:.0f} m/s; "
      f"energy error at most {np.abs(h['energy_error']).max():.3e}")
checks.above('particles_made', n, 500)
checks.below('particle_behind_symmetry_plane', behind, 1e-12, 'm')
checks.below('particle_speed_over_impact_speed', fastest / V_IMPACT, 3.0)
checks.below('energy_error_max', np.abs(h['energy_error']).max(), 0.01)
checks.below('mass_change', np.abs(h['mass'] - h['mass'][0]).max(), 0.0, 'kg')
checks.finish()
