"""Two identical elastic blocks (nu = 0) head-on, frictionless contact (the
seed paper's algorithm): against 1D elastic wave theory the contact lasts
2 L / c and the blocks exchange velocities (striker at rest, target at the
impact speed); momentum is conserved exactly and little energy is lost."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

E, RHO, V, L = 200e9, 7850.0, 100.0, 0.02
c = math.sqrt(E / RHO)
h = udar_results.read_history(os.path.join(sys.argv[1], 'out', 'blocks_head_on_history.csv'))
t, f = h['time'], h['contact_normal_striker_on_target']
touching = np.nonzero(f > 0.0)[0]
duration = t[touching[-1]] - t[touching[0]]
checks.compare('contact_duration_2L_over_c', duration, 2 * L / c, 0.03, 's')
# centre-of-mass velocities after separation (fit over the last 6 us)
after = t > t[touching[-1]] + 3e-6
v = {p: np.polyfit(t[after], h['com_z_' + p][after], 1)[0] for p in ('striker', 'target')}
checks.compare('target_velocity_after', v['target'], V, 0.03, 'm/s')
checks.below('striker_velocity_after_over_v', v['striker'] / V, 0.03)
lost = 1.0 - h['total'][-1] / h['total'][0]
print(f"MEASURED energy lost {100 * lost:.3f} %, contact force plateau "
      f"{np.median(f[touching]):.4g} N vs rho c v/2 A = {RHO * c * V / 2 * 1e-4:.4g} N")
checks.below('energy_lost', lost, 0.02)
p0 = h['momentum_z'][0]
checks.below('momentum_conserved_relative', np.abs(h['momentum_z'] - p0).max() / abs(p0), 1e-13)
checks.finish()
