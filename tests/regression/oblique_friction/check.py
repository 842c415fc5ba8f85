"""Algorithmic friction (Yugov et al. 1998, eqs. 19-23): a steel cube strikes
a plate obliquely. oblique_friction.nml (f = 0.1): the cube slides, so every
friction correction is f times its normal one and the friction impulse is f
times the normal impulse. oblique_stick.nml (f = 100): the friction stops the
slip at every contact point (stick limit). Momentum along the plate is taken
from the cube by friction only; the fixed plate bottom takes the rest."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

deck = sys.argv[2] if len(sys.argv) > 2 else 'oblique_friction'
h = udar_results.read_history(os.path.join(sys.argv[1], 'out', deck + '_history.csv'))
fn, ft, slip = (h[k + '_block_on_plate'] for k in ('contact_normal', 'contact_friction', 'contact_slip'))
touching = fn > 0.0
ratio = (ft * h['dt']).sum() / (fn * h['dt']).sum()
print(f"MEASURED {deck}: {touching.sum()} cycles in contact, friction/normal impulse {ratio:.5f}, "
      f"slip after the pass: median {np.median(slip[touching]):.3g} m/s, max {slip[touching].max():.3g} m/s")
# separation: the elastic cube leaves the plate; the contact never pulls
# (no tensile sticking): the normal force is never negative and is zero
# once the cube moves away
last = np.nonzero(touching)[0][-1]
after = slice(last + 1, None)
vz = np.polyfit(h['time'][after], h['com_z_block'][after], 1)[0] if h['time'][after].size > 2 else 0.0
print(f"MEASURED contact ends at {h['time'][last] * 1e6:.2f} us; the cube then rises at {vz:.1f} m/s")
checks.below('normal_force_never_tensile', min(fn.min(), 0.0), 0.0, 'N')
checks.above('cube_leaves_the_plate_m_per_s', vz, 1.0, 'm/s')
if deck == 'oblique_friction':
    checks.compare('friction_impulse_is_f_times_normal', ratio, 0.1, 0.02)
    checks.above('slides_median_slip', np.median(slip[touching]), 1.0, 'm/s')
else:
    checks.below('sticks_no_slip_m_per_s', slip[touching].max(), 1e-3)
    checks.below('friction_below_f_times_normal', ratio / 100.0, 1.0)
checks.finish()
