"""The element and point gauges of a run (&gauge) against its field file:
at every field step, the gauge's row of the history (the same cycle) must
hold its element's values as the field file has them, bitwise (pressure,
von Mises, plastic strain, temperature, density; the state column the
element's fracture_state; an eroded element's stress 0), and once the
element has become a particle, that particle's values and, for a point
gauge, its position and velocity. A point gauge's position before that is
its element's corners weighted by the point's barycentric coordinates
(computed here, so within rounding).

    mismatches, particle_rows = compare(history, field_file, deck_text)
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'postproc'))
import udar_results  # noqa: E402

PARTICLE = 3   # the state column once the element has become a particle
VALUES = ('pressure', 'von_mises', 'plastic_strain', 'temperature', 'density')


def barycentric(xt, p):
    """Barycentric coordinates of point p in the tetrahedron with corners xt (4, 3)."""
    lam = np.linalg.solve((xt[1:] - xt[0]).T, p - xt[0])
    return np.concatenate([[1.0 - lam.sum()], lam])


def gauge_elements(deck_text, conn, x0, elem_id):
    """{name: (kind, element row, barycentric weights or None)} of the deck's element
    and point gauges (a point: the first element in the mesh's order that holds it)."""
    out = {}
    for group, body in udar_results.deck_groups(deck_text):
        if group != 'gauge':
            continue
        v = udar_results.deck_values(body)
        if 'element' in v:
            out[v['name']] = ('element', int(np.flatnonzero(elem_id == int(v['element']))[0]), None)
        elif 'point' in v:
            p = np.array(v['point'], dtype=float)
            for e in range(len(conn)):
                w = barycentric(x0[conn[e]], p)
                if w.min() >= -1e-12:
                    out[v['name']] = ('point', e, w)
                    break
    return out


def compare(h, f, deck_text):
    """Mismatches [(gauge, time, quantity, gauge value, field value)] and how many
    (gauge, field step) pairs had the gauge's element made a particle."""
    conn = f['mesh/connectivity'][...]
    gauges = gauge_elements(deck_text, conn, f['mesh/x0'][...], f['mesh/elem_id'][...])
    cycles = np.asarray(h['cycle'], dtype=int)
    bad, on_particle = [], 0
    for k in sorted(f['steps'].keys(), key=lambda k: f['steps'][k].attrs['time']):
        g = f['steps'][k]
        rows = np.flatnonzero(cycles == int(g.attrs['cycle']))
        if len(rows) == 0:
            continue
        r = rows[-1]
        t = g.attrs['time']
        pg = g['particles'] if 'particles' in g and int(g['particles'].attrs['count']) > 0 else None
        for name, (kind, e, w) in gauges.items():
            col = lambda q: h[f'gauge_{name}_{q}'][r]
            j = np.flatnonzero(pg['element'][...] == e) if pg is not None else []
            if len(j) > 0:
                # the element has become this particle: the gauge follows it
                on_particle += 1
                want = {q: pg[q][j[0]] for q in VALUES}
                want['state'] = PARTICLE
                if kind == 'point':
                    want.update({c: pg['coordinates'][j[0], i] for i, c in enumerate('xyz')})
                    want.update({'v' + c: pg['velocity'][j[0], i] for i, c in enumerate('xyz')})
            else:
                want = {q: g[q][e] for q in VALUES}
                want['state'] = g['fracture_state'][e]
                if want['state'] == 2:   # eroded: no stress
                    want['pressure'] = want['von_mises'] = 0.0
                if kind == 'point':
                    x = w @ g['coordinates'][...][conn[e]]
                    size = np.ptp(f['mesh/x0'][...][conn[e]], axis=0).max()
                    for i, c in enumerate('xyz'):
                        if abs(col(c) - x[i]) > 1e-12 * size:
                            bad.append((name, t, c, col(c), x[i]))
            for q, v in want.items():
                if f'gauge_{name}_{q}' not in h:   # (0.9.0 had no state column)
                    bad.append((name, t, q, None, v))
                elif col(q) != v:
                    bad.append((name, t, q, col(q), v))
    return bad, on_particle
