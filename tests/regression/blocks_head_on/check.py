"""Two identical elastic blocks (nu = 0) head-on, frictionless contact (the
seed paper's algorithm): against 1D elastic wave theory the contact lasts
2 L / c and the blocks exchange velocities (striker at rest, target at the
impact speed); momentum is conserved exactly and little energy is lost.
The deck blocks_head_on_symmetric runs the same with symmetric = .true.:
both directions matched in one set of passes (issue 13, item 4), so the
contact force (now the sum over the two directions) and the contact
pressure output are the single direction's; 0.5.2's sequential second
pass gave a pressure 28 % high and +0.18 % energy. Every contact pass
converges (no pass ends at &contact iterations): the symmetric deck's passes,
whose rows constrain each gap from both sides, did not with sweeps alone
(0.5.9: 203 of 509 at the cap of 50).
Usage: check.py RUN_DIR [DECK]"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

E, RHO, V, L = 200e9, 7850.0, 100.0, 0.02
c = math.sqrt(E / RHO)
deck = sys.argv[2] if len(sys.argv) > 2 else 'blocks_head_on'
h = udar_results.read_history(os.path.join(sys.argv[1], 'out', deck + '_history.csv'))
# the contact force: both directions' of a symmetric contact
t, f = h['time'], sum(h[k] for k in h if k.startswith('contact_normal_'))
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
for name in ['striker_on_target'] + (['target_on_striker'] if deck.endswith('symmetric') else []):
    checks.below(f'passes_unconverged_{name}', checks.unconverged_passes(sys.argv[1], name), 0)

# contact pressure (node field) at 5 us, halfway through the contact: over
# each contact face it adds up to the contact force of that cycle (the
# history), and its mean is near the wave theory's rho c v/2 (one cycle's
# value on non-conforming faces: within 5 %; the force's median above is
# the time-averaged comparison)
fld = udar_results.open_fields(os.path.join(sys.argv[1], 'out', deck + '.h5'))
conn, part = fld.connectivity, fld.part_id
step = fld.step(fld.nearest_step(5e-6))
x, pc = step.coordinates, np.asarray(step.fields['contact_pressure'])
x0 = fld.step(0).coordinates     # the contact faces by where they started (they deform unevenly)
faces = np.sort(conn[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]].reshape(-1, 3), axis=1)
face_part = np.repeat(part, 4)
for name, pid, pick in (('striker', part.min(), np.max), ('target', part.max(), np.min)):
    fp = faces[face_part == pid]
    key, count = np.unique(fp, axis=0, return_counts=True)
    outer = key[count == 1]
    z_face = pick(x0[np.unique(conn[part == pid]), 2])
    on = outer[np.all(np.abs(x0[outer, 2] - z_face) < 5e-5, axis=1)]
    area = 0.5 * np.linalg.norm(np.cross(x[on[:, 1]] - x[on[:, 0]], x[on[:, 2]] - x[on[:, 0]]), axis=1)
    node_area = np.zeros(len(x))
    np.add.at(node_area, on.ravel(), np.repeat(area / 3, 3))
    force = (pc * node_area).sum()
    row = np.argmin(np.abs(t - step.time))
    checks.compare(f'contact_pressure_times_area_{name}_face', force, f[row], 0.01, 'N')
    checks.compare(f'contact_pressure_mean_{name}_face', force / node_area.sum(), RHO * c * V / 2, 0.05, 'Pa')
checks.finish()
