"""Coulomb wall: the ratio of tangential to normal momentum change over the
impact equals the friction coefficient (all contacting nodes slide), the
bar leaves the wall, and the energy balance including friction work holds."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

h = udar_results.read_history(os.path.join(sys.argv[1], 'out', 'coulomb_wall_history.csv'))
dpx = h['momentum_x'][-1] - h['momentum_x'][0]
dpz = h['momentum_z'][-1] - h['momentum_z'][0]
checks.compare('tangential_over_normal_impulse', -dpx / dpz, 0.1, 1e-3)
checks.compare('rebound_normal_momentum', dpz, 2 * 7850.0 * 0.1 * 1e-4 * 10.0, 0.03, 'kg m/s')
print('MEASURED friction work %.4f J of %.4f J' % (-h['wall_work'][-1], h['total'][0]))
checks.below('energy_error_max', abs(h['energy_error']).max(), 0.01)
checks.finish()
