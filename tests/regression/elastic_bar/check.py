"""Elastic bar (nu = 0) on a rigid wall against 1D elastic wave theory:
contact stress rho c v, contact duration 2L/c, rebound speed v, energy.
And the field file's node displacement: exactly the coordinates less the
initial ones at every step; every field with its units and centering;
every history column with its unit; the gauges against the wave solution."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import numpy as np  # noqa: E402
import udar_results  # noqa: E402

E, RHO, V, L, A = 200e9, 7850.0, 10.0, 0.1, 0.01 * 0.01
c = math.sqrt(E / RHO)
h = udar_results.read_history(os.path.join(sys.argv[1], 'out', 'elastic_bar_history.csv'))
t, f = h['time'], h['wall_force']
contact = f > 0.0
t_first, t_last = t[contact][0], t[contact][-1]
duration = t_last  # the bar touches the wall at t = 0
checks.compare('contact_duration_2L_over_c', duration, 2 * L / c, 0.02, 's')
plateau = (t > 0.2 * duration) & (t < 0.8 * duration)
stress = f[plateau].mean() / A
checks.compare('contact_stress_rho_c_v', stress, RHO * c * V, 0.02, 'Pa')
mass = RHO * L * A
after = t > duration + 5e-6
checks.compare('rebound_velocity', h['momentum_z'][after].mean() / mass, V, 0.02, 'm/s')
checks.below('energy_error_max', abs(h['energy_error']).max(), 0.01)

# every history column says its unit
HISTORY_UNITS = {'time': 's', 'cycle': '-', 'dt': 's', 'kinetic': 'J', 'internal': 'J', 'plastic_work': 'J',
                 'wall_work': 'J', 'total': 'J', 'energy_error': '-', 'momentum_x': 'kg m/s', 'momentum_y': 'kg m/s',
                 'momentum_z': 'kg m/s', 'wall_force': 'N', 'angular_momentum_x': 'kg m2/s',
                 'angular_momentum_y': 'kg m2/s', 'angular_momentum_z': 'kg m2/s', 'ke_bar': 'J', 'com_x_bar': 'm',
                 'com_y_bar': 'm', 'com_z_bar': 'm', 'internal_bar': 'J', 'plastic_work_bar': 'J',
                 'eroded_energy_bar': 'J', 'mass_bar': 'kg', 'momentum_x_bar': 'kg m/s', 'momentum_y_bar': 'kg m/s',
                 'momentum_z_bar': 'kg m/s', 'velocity_x_bar': 'm/s', 'velocity_y_bar': 'm/s', 'velocity_z_bar': 'm/s'}
GAUGE_UNITS = {'x': 'm', 'y': 'm', 'z': 'm', 'ux': 'm', 'uy': 'm', 'uz': 'm', 'vx': 'm/s', 'vy': 'm/s', 'vz': 'm/s',
               'pressure': 'Pa', 'sxx': 'Pa', 'syy': 'Pa', 'szz': 'Pa', 'sxy': 'Pa', 'syz': 'Pa', 'szx': 'Pa',
               'von_mises': 'Pa', 'plastic_strain': '-', 'temperature': 'K', 'density': 'kg/m3', 'state': '-'}
POINT = ['x', 'y', 'z', 'vx', 'vy', 'vz', 'pressure', 'sxx', 'syy', 'szz', 'sxy', 'syz', 'szx', 'von_mises',
         'plastic_strain', 'temperature', 'density', 'state']
for g, quantities in (('free_end', POINT), ('middle', POINT), ('corner', ['ux', 'uy', 'uz', 'vx', 'vy', 'vz'])):
    HISTORY_UNITS.update({f'gauge_{g}_{q}': GAUGE_UNITS[q] for q in quantities})
units = udar_results.history_units(os.path.join(sys.argv[1], 'out', 'elastic_bar_history.csv'))
print(f"MEASURED history units {units}")
checks.above('history_header_units', float(units == HISTORY_UNITS), 1.0)

# gauges (&gauge) against the wave solution: the free end's material point
# moves at -v until the wave reaches it (L/c) and at +v after; the middle's
# axial stress is -rho c v while the wave is past it (L/2c .. 3L/2c); the
# impact corner's node stays on the wall while the bar touches it
T = L / c
window = (t > 0.1 * T) & (t < 0.9 * T)
checks.compare('gauge_free_end_velocity_before_reflection', h['gauge_free_end_vz'][window].mean(), -V, 0.02, 'm/s')
window = (t > 1.1 * T) & (t < 1.9 * T)
checks.compare('gauge_free_end_velocity_after_reflection', h['gauge_free_end_vz'][window].mean(), V, 0.02, 'm/s')
window = (t > 0.6 * T) & (t < 1.4 * T)
checks.compare('gauge_middle_axial_stress_rho_c_v', h['gauge_middle_szz'][window].mean(), -RHO * c * V, 0.02, 'Pa')
checks.below('gauge_middle_stress_before_the_wave', np.abs(h['gauge_middle_szz'][t < 0.4 * T]).max(), 1e-3 * RHO * c * V, 'Pa')
checks.compare('gauge_free_end_starts_at_its_point', h['gauge_free_end_z'][0], L, 1e-12, 'm')
checks.below('gauge_corner_stays_on_the_wall', np.abs(h['gauge_corner_uz'][t < 1.9 * T]).max(), 1e-12, 'm')

import h5py  # noqa: E402

UNITS = {'coordinates': ('m', 'Node'), 'velocity': ('m/s', 'Node'), 'displacement': ('m', 'Node'),
         'pressure': ('Pa', 'Cell'), 'von_mises': ('Pa', 'Cell'), 'plastic_strain': ('-', 'Cell'),
         'temperature': ('K', 'Cell'), 'density': ('kg/m3', 'Cell'), 'time_step': ('s', 'Cell')}
with h5py.File(os.path.join(sys.argv[1], 'out', 'elastic_bar.h5'), 'r') as f:
    x0 = f['mesh/x0'][()]
    steps = [f['steps'][k] for k in sorted(f['steps'])]
    exact = all(np.array_equal(g['displacement'][()], g['coordinates'][()] - x0) for g in steps)
    moved = max(float(np.abs(g['displacement'][()]).max()) for g in steps)
    attrs = {n: (udar_results._decode(steps[-1][n].attrs.get('units', b'')),
                 udar_results._decode(steps[-1][n].attrs.get('center', b''))) for n in UNITS}
print(f"MEASURED {len(steps)} steps, largest displacement {moved:.4g} m; attributes {attrs}")
checks.above('displacement_is_coordinates_less_x0_bitwise', float(exact and moved > 0), 1.0)
checks.above('field_units_and_centering', float(attrs == UNITS), 1.0)
checks.finish()
