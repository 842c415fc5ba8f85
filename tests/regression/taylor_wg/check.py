"""Wilkins-Guinan copper Taylor bar with the default element against the
converged reference: final impact-face radius 7.22 mm within 1 %, final
length within 0.5 % of the range 21.42-21.48 mm (issue 12). And the output
is consistent: with the linear EOS (no energy term) every element's
pressure is K (rho/rho0 - 1) of its output density."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import taylor  # noqa: E402

path = os.path.join(sys.argv[1], 'out', 'taylor_wg.h5')
m = taylor.measure_file(path, axis=2, wall=0.0)[0]
print('MEASURED ' + taylor.human_line(m))
length = m['length_m']
nearest_end = min(max(length, 21.42e-3), 21.48e-3)
checks.compare('final_length_to_the_reference_range', length, nearest_end, 0.005, 'm')
checks.compare('footprint_radius', 0.5 * m['footprint_diameter_m'], 7.22e-3, 0.01, 'm')

bulk = 117.0e9 / (3.0 * (1.0 - 2.0 * 0.35))   # the deck's E and nu
rho0 = 8930.0
with h5py.File(path, 'r') as f:
    worst = 0.0
    for k in f['steps']:
        st = f['steps'][k]
        p_eos = bulk * (st['density'][:] / rho0 - 1.0)
        worst = max(worst, float(np.max(np.abs(st['pressure'][:] - p_eos))))
checks.below('pressure_minus_eos_of_output_density_Pa_over_1GPa', worst / 1.0e9, 1.0e-6, '')
checks.finish()
