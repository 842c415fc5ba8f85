"""Axisymmetric elastic bar (nu = 0) on a rigid wall against 1D elastic wave
theory: contact stress rho c v, contact duration 2L/c, rebound speed v,
energy; the history's masses and forces are per full revolution."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

E, RHO, V, L, R = 200e9, 7850.0, 10.0, 0.1, 0.005
A = math.pi * R**2
c = math.sqrt(E / RHO)
h = udar_results.read_history(os.path.join(sys.argv[1], 'out', 'elastic_bar_2d_history.csv'))
t, f = h['time'], h['wall_force']
contact = f > 0.0
duration = t[contact][-1]  # the bar touches the wall at t = 0
checks.compare('contact_duration_2L_over_c', duration, 2 * L / c, 0.01, 's')
plateau = (t > 0.2 * duration) & (t < 0.8 * duration)
stress = f[plateau].mean() / A
checks.compare('contact_stress_rho_c_v', stress, RHO * c * V, 0.01, 'Pa')
mass = RHO * L * A
after = t > duration + 5e-6
# as in 3D (tests/regression/elastic_bar: -1.67 %): the wall takes the end node's momentum at each touch
checks.compare('rebound_velocity', h['momentum_y'][after].mean() / mass, V, 0.02, 'm/s')
checks.compare('initial_kinetic_energy_per_revolution', h['kinetic'][0], 0.5 * mass * V**2, 1e-9, 'J')
checks.below('energy_error_max', abs(h['energy_error']).max(), 0.01)
checks.finish()
