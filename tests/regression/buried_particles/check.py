"""Particles made inside a master body (buried_particles.nml, issue 15):
the log says how many were put on the plate's surface (some must be), and
at every field step no particle lies inside a plate element deeper than
1e-3 of its size, nor below the plate's initial top face (z = 0) by more
than 0.05 of it (the face itself gives under the particles: 0.011). Without the placement the particles made inside stay there,
0.6 mm deep at 2 us and going deeper (measured: 0.094 h inside an element).
Its gauges (&gauge, two material points of elements that become particles)
hold at every field step their element's values, then their particle's
(position, velocity, pressure, von Mises, plastic strain, temperature,
density), bitwise (tests/tools/gauge_fields.py; 0.9.0 went on writing the
eroded element's values).
Usage: check.py RUN_DIR [DECK]"""
import os
import re
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import gauge_fields  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside, slave_and_master  # noqa: E402

PLATE, CUBE = 1, 2
run_dir = sys.argv[1]
deck = sys.argv[2] if len(sys.argv) > 2 else 'buried_particles'
log = open(os.path.join(run_dir, 'run.log')).read()
m = re.search(r'contact: (\d+) particles made inside a master body were put on its surface', log)
placed = int(m.group(1)) if m else 0
inside, below, n = 0.0, 0.0, 0
with h5py.File(os.path.join(run_dir, 'out', deck + '.h5'), 'r') as f:
    conn, _, _, plate, h = slave_and_master(f, CUBE, PLATE)
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        g = f['steps'][k]
        p = g['particles']
        n = int(p.attrs['count'])
        if n == 0:
            continue
        xp = p['coordinates'][...]
        d = deepest_inside(xp, g['coordinates'][...], conn[plate])
        print(f"MEASURED t = {g.attrs['time'] * 1e6:.1f} us: {n} particles, the deepest inside a plate element "
              f"{d / h:.3g} h, the lowest {xp[:, 2].min() / h:+.3g} h from the top face")
        inside, below = max(inside, d), max(below, -xp[:, 2].min())
    deck_text = open(os.path.join(run_dir, deck + '.nml')).read()
    gauged = any(g == 'gauge' for g, _ in udar_results.deck_groups(deck_text))
    if gauged:
        hist = udar_results.read_history(os.path.join(run_dir, 'out', deck + '_history.csv'))
        bad, on_particle = gauge_fields.compare(hist, f, deck_text)
        for b in bad[:5]:
            print('MEASURED gauge %s at t = %.4g s: %s %r, the field file %r' % b)
        print(f"MEASURED gauges: {len(bad)} values differ from the field file's; {on_particle} gauge rows at field "
              f"steps on a particle")
checks.above('particles_made', n, 10)
checks.above('particles_put_on_the_surface', placed, 1)
checks.below('particle_inside_plate_element_over_h', inside / h, 1e-3)
checks.below('particle_below_top_face_over_h', below / h, 0.05)
if gauged:
    checks.below('gauge_values_differing_from_field_file', len(bad), 0)
    checks.above('gauge_rows_on_a_particle', on_particle, 10)
checks.finish()
