"""Two square bars crossing edge against edge (crossed_edges.geo): at every
field step the upper bar's lower edge and the lower bar's upper edge, each
interpolated at the crossing from its two nodes either side of it, must not
pass through each other by more than 1e-3 h (h = 1 mm). The deck without
the option (crossed_edges_off) must fail that check (its edges pass through
by about half an element). Momentum is exchanged exactly. With friction
(crossed_edges_friction) the friction impulse is mu times the normal one.
Usage: check.py RUN_DIR DECK"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

deck = sys.argv[2]
out = os.path.join(sys.argv[1], 'out')
fld = udar_results.open_fields(os.path.join(out, deck + '.h5'))
conn, part = fld.connectivity, fld.part_id
x0 = fld.step(0).coordinates
h = 1.0e-3


def edge_nodes(pid, axis, pick):
    """The bar's edge that faces the other bar: its nodes on the extreme z
    line, and the two of them either side of the crossing along the bar."""
    nodes = np.unique(conn[part == pid])
    z = x0[nodes, 2]
    on = nodes[np.abs(z - pick(z)) < 1e-7]
    s = x0[on, axis]
    return on[s < 0][np.argmax(s[s < 0])], on[s > 0][np.argmin(s[s > 0])]


def crossing_z(x, pair, axis):
    a, b = x[pair[0]], x[pair[1]]
    t = -a[axis] / (b[axis] - a[axis])
    return a[2] + t * (b[2] - a[2])


upper = edge_nodes(part.min(), 0, np.min)       # 'upper' (tag 1): along x, its lowest edge
lower = edge_nodes(part.max(), 1, np.max)       # 'lower' (tag 2): along y, its highest edge
through = np.array([crossing_z(fld.step(k).coordinates, lower, 1) - crossing_z(fld.step(k).coordinates, upper, 0)
                    for k in range(fld.n_steps)])
worst = max(through.max(), 0.0)
print(f'MEASURED the two edges passed through each other by at most {worst / h:.3g} h at the crossing '
      f'(nodes {upper} and {lower} either side of it); their gap there, mm, at each field step: ' +
      ' '.join(f'{-1e3 * d:.3f}' for d in through))
checks.above('edges_met', through.max() / h, -0.05)
checks.below('edges_through_each_other_over_h', worst / h, 1e-3)
hist = udar_results.read_history(os.path.join(out, deck + '_history.csv'))
p = np.array([hist['momentum_' + c] for c in 'xyz'])
checks.below('momentum_change_relative', np.abs(p - p[:, :1]).max() / np.abs(p[:, 0]).max(), 1e-13)
print(f"MEASURED energy error at the end {hist['energy_error'][-1]:.3g}")
# Coulomb: a contact that slides carries friction times its normal impulse
# (crossed_edges_friction: the edges slide over each other all along); the
# others are frictionless
mu = 0.05 if deck.endswith('friction') else 0.0
dt_v = 0.5 * (np.concatenate([[0.0], hist['dt'][:-1]]) + hist['dt'])
normal = np.sum(hist['contact_normal_upper_on_lower'] * dt_v)
friction = np.sum(hist['contact_friction_upper_on_lower'] * dt_v)
print(f'MEASURED contact impulses: normal {normal:.6g} N s, friction {friction:.6g} N s')
checks.below('friction_over_normal_impulse_minus_mu', abs(friction / normal - mu), 1e-6 * max(mu, 1.0))
checks.finish()
