"""Self-contact: an elastic C-shaped clamp (nu = 0) falls onto a rigid
wall; its lower arm rebounds and strikes the upper arm. Checked against 1D
elastic wave theory: the arms meet at t/c + g/(2v); while they touch, the
pressure in the arms' far part (away from the bridge) is rho c (v_up -
v_low)/2 with the arms' measured approach velocities; no node of one arm
ever lies inside the other (at the free corners, where a corner can slip
under a corner, by at most 1e-3 of the element size); the energy balance (with the contact work)
moves by less than 2 % over the contact (until the lower arm, sent back
down, strikes the wall again); in 3D at most 3 contact passes end
unconverged (0.9.15: 38). With `expect_penetration` (the
same deck without the &contact group) the arms must pass into each other:
the check can fail.
The deck self_contact_2d (tests/regression/self_contact_2d) is the same
clamp's cross-section in plane strain: triangles, y the fall direction
(the 3D z), no slab depth (the arms' free edges only at x = 30 mm), its
element size 0.5 mm.
Usage: check.py RUN_DIR [DECK [expect_penetration]]"""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'rod_3kms'))
import checks  # noqa: E402
import udar_results  # noqa: E402
from check_geometry import deepest_inside  # noqa: E402

E, RHO, V, T, GAP, H = 200e9, 7850.0, 100.0, 0.004, 0.2e-3, 1.0e-3
c = math.sqrt(E / RHO)
out = os.path.join(sys.argv[1], 'out')
deck = sys.argv[2] if len(sys.argv) > 2 else 'self_contact'
negative = len(sys.argv) > 3 and sys.argv[3] == 'expect_penetration'
with h5py.File(os.path.join(out, deck + '.h5'), 'r') as f:
    conn, x0 = f['mesh/connectivity'][...], f['mesh/x0'][...]
plane = conn.shape[1] == 3          # plane strain: triangles in z = 0
ax = 1 if plane else 2              # the fall direction: y (plane strain) or z (3D)
if plane:
    H = 0.5e-3                      # self_contact_2d.geo's element size
centre = x0[conn].mean(axis=1)
lower = conn[(centre[:, 0] > 0) & (centre[:, ax] < T)]
upper = conn[(centre[:, 0] > 0) & (centre[:, ax] > T + GAP)]
lower_nodes, upper_nodes = np.unique(lower), np.unique(upper)
# the arms' far part: the bridge's disturbance has not reached it during the contact
far_low = lower_nodes[x0[lower_nodes, 0] > 0.022]
far_up = upper_nodes[x0[upper_nodes, 0] > 0.022]
face_up = upper_nodes[(x0[upper_nodes, 0] > 0.015) & (x0[upper_nodes, 0] < 0.028)
                      & (np.abs(x0[upper_nodes, ax] - T - GAP) < 1e-6)]
fld = udar_results.open_fields(os.path.join(out, deck + '.h5'))
# the arms' faces away from their free edges (x = 30 mm, y = 4 mm): a
# node-on-surface contact does not see a corner slipping under a corner
# (plane strain: no slab depth, the free edge x = 30 mm only)
inner = lambda n: n[(x0[n, 0] < 0.029) & ((x0[n, 1] < 0.0039) | plane)]  # noqa: E731
deepest, deepest_inner, rows = 0.0, 0.0, []
for k in range(fld.n_steps):
    s = fld.step(k)
    x, v = s.coordinates, np.asarray(s.fields['velocity'])
    depth = max(deepest_inside(x[upper_nodes], x, lower), deepest_inside(x[lower_nodes], x, upper))
    deepest = max(deepest, depth)
    deepest_inner = max(deepest_inner, deepest_inside(x[inner(upper_nodes)], x, lower),
                        deepest_inside(x[inner(lower_nodes)], x, upper))
    p = np.median(np.asarray(s.fields['contact_pressure'])[face_up]) if 'contact_pressure' in s.fields else 0.0
    rows.append((s.time, depth, p, v[far_up, ax].mean(), v[far_low, ax].mean()))
    print(f"MEASURED t = {s.time * 1e6:.2f} us: deepest arm node inside the other arm {depth:.3g} m, "
          f"contact pressure (far part, median) {p / 1e9:.3f} GPa, far-part velocity upper {rows[-1][3]:.1f} "
          f"lower {rows[-1][4]:.1f} m/s")
if negative:
    checks.above('arms_pass_into_each_other_without_self_contact_m', deepest, 0.05e-3, 'm')
    checks.finish()
h = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
t, force = h['time'], h['contact_normal_clamp_on_itself']
touch = np.nonzero(force > 0)[0]
checks.compare('contact_start_t_over_c_plus_gap_over_2v', t[touch[0]], T / c + GAP / (2 * V), 0.05, 's')
checks.below('arm_nodes_inside_other_arm_over_h_away_from_free_edges', deepest_inner / H, 1e-6)
checks.below('arm_nodes_inside_other_arm_over_h_corners_included', deepest / H, 1e-3)
rows = np.array(rows)
before = rows[rows[:, 0] < t[touch[0]]][-1]
during = rows[(rows[:, 0] > t[touch[0]] + 0.1e-6) & (rows[:, 0] < t[touch[0]] + 2 * T / c - 0.2e-6)]
p_theory = RHO * c * (before[4] - before[3]) / 2
checks.compare('contact_pressure_far_part_vs_rho_c_dv_over_2', during[:, 2].mean(), p_theory, 0.10, 'Pa')
# over the contact, until the lower arm strikes the wall again (the wall's
# node-on-plane stops are inelastic and not part of this check)
window = (t > t[touch[0]] - 0.1e-6) & (t < t[touch[0]] + 2 * T / c - 0.2e-6)
err = h['energy_error'][window]
checks.below('energy_error_change_over_contact', err.max() - err.min(), 0.02)
# the velocity matching converges: the arms' rows are one set joined by
# shared nodes, up to 340 of them (0.9.15, sweeps only beyond 64 rows: 38
# of 92 passes ended at iterations = 50 unconverged; 0.9.16 solves such a
# set together: 1)
if not plane:
    checks.below('contact_passes_ended_unconverged', checks.unconverged_passes(sys.argv[1], 'clamp_on_itself'), 3)
checks.finish()
