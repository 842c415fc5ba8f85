"""Spall: a 2 mm flyer onto a 6 mm target at 100 m/s (uniaxial strain). The
release waves from the two free backs meet 2 mm in front of the target's
back face (z = -4 mm): the target spalls there (within two elements), and
nowhere before the waves meet. Fractured elements carry no tension;
momentum is conserved; the energy balance closes to 1 % (with the averaged
element this caught a clipped nodal pressure that created energy: 1.8 %).
Args: run folder [deck name, default spall: spall_averaged is the same deck
with the default element, spall.nml runs the plain one]."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

H = 0.1e-3                    # element size along the axis
Z_SPALL = -0.006 + 0.002      # target back face + flyer thickness
run = sys.argv[1]
deck = sys.argv[2] if len(sys.argv) > 2 else 'spall'
fld = udar_results.open_fields(os.path.join(run, 'out', deck + '.h5'))
conn, part = fld.connectivity, fld.part_id
z0 = fld.x0[conn].mean(axis=1)[:, 2]
last = fld.step(-1)
state = np.asarray(last.fields['fracture_state'])
fractured = state > 0
print(f"MEASURED {fractured.sum()} elements fractured, reference z from {z0[fractured].min() * 1e3:.3f} "
      f"to {z0[fractured].max() * 1e3:.3f} mm, median {np.median(z0[fractured]) * 1e3:.3f} mm")
checks.above('fractured_elements', fractured.sum(), 1)
checks.compare('spall_plane_z', np.median(z0[fractured]), Z_SPALL, 2 * H / abs(Z_SPALL), 'm')
checks.below('spall_zone_half_width_over_h', 0.5 * (z0[fractured].max() - z0[fractured].min()) / H, 4.0)
# nothing fractured at 1.5 us, before the release waves meet (about 1.6 us after impact)
early = fld.step(fld.nearest_step(1.5e-6))
checks.below('fractured_before_release_waves_meet', int((np.asarray(early.fields['fracture_state']) > 0).sum()), 0)
# no tension in fractured material at any output
p_min = min(np.asarray(fld.step(i).fields['pressure'])[np.asarray(fld.step(i).fields['fracture_state']) > 0].min(initial=0.0)
            for i in range(len(fld.steps)))
checks.above('fractured_min_pressure', p_min, 0.0, 'Pa')
h = udar_results.read_history(os.path.join(run, 'out', deck + '_history.csv'))
p0 = h['momentum_z'][0]
checks.below('momentum_conserved_relative', np.abs(h['momentum_z'] - p0).max() / abs(p0), 1e-13)
checks.below('energy_error_largest', np.abs(h['energy_error']).max(), 0.01)
checks.finish()
