"""Gauges by mesh tag on the elastic bar (tests/cli/gauge_element_tag.sh):
an element gauge against a point gauge at that element's centroid, and
against 1D wave theory; a node gauge at the free end against it too.

    gauge_tag.py pick FIELD.h5 X Y Z
        prints the tag of the first element (mesh order) holding the point
        (x0) and the element's centroid: "TAG CX CY CZ"
    gauge_tag.py node FIELD.h5 X Y Z
        prints the tag of the node at the point (x0)
    gauge_tag.py compare HISTORY.csv BY_TAG AT_CENTROID CX CY CZ END_NODE
        PASS/FAIL lines: the two gauges' element columns are the same,
        bitwise, on every row; the point gauge starts at the centroid; the
        element's axial stress, while the wave is past it, is the elastic
        bar's -rho c v; the free end's node moves at -v until the wave
        reaches it (L/c), then at +v, and is back where it started at 2L/c
        (1D wave theory)"""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import checks  # noqa: E402
import udar_results  # noqa: E402
from gauge_fields import barycentric  # noqa: E402

ELEMENT_COLUMNS = ('pressure', 'sxx', 'syy', 'szz', 'sxy', 'syz', 'szx', 'von_mises', 'plastic_strain',
                   'temperature', 'density', 'state')
# the elastic bar (tests/regression/elastic_bar): steel, nu = 0, 10 m/s onto a wall
E, RHO, V, L = 200e9, 7850.0, 10.0, 0.1


def pick(path, p):
    with h5py.File(path, 'r') as f:
        conn, x0, tags = f['mesh/connectivity'][...], f['mesh/x0'][...], f['mesh/elem_id'][...]
    for e in range(len(conn)):
        if barycentric(x0[conn[e]], p).min() >= 0.0:
            c = x0[conn[e]].mean(axis=0)
            print(int(tags[e]), *('%.17g' % v for v in c))
            return
    raise SystemExit(f'{path}: no element holds {p}')


def node(path, p):
    with h5py.File(path, 'r') as f:
        x0, tags = f['mesh/x0'][...], f['mesh/node_id'][...]
    k = int(np.argmin(np.linalg.norm(x0 - p, axis=1)))
    if np.linalg.norm(x0[k] - p) > 1e-12:
        raise SystemExit(f'{path}: no node at {p}')
    print(int(tags[k]))


def compare(path, by_tag, at_centroid, centroid, end_node):
    h = udar_results.read_history(path)
    differ = sum(int(np.count_nonzero(h[f'gauge_{by_tag}_{q}'] != h[f'gauge_{at_centroid}_{q}']))
                 for q in ELEMENT_COLUMNS)
    print(f"MEASURED {differ} of {len(ELEMENT_COLUMNS) * len(h['time'])} element values differ between "
          f"the element gauge and the point gauge at its centroid")
    checks.below('element_gauge_differs_from_point_gauge_at_centroid', differ, 0)
    start = np.array([h[f'gauge_{at_centroid}_{c}'][0] for c in 'xyz'])
    checks.below('point_gauge_starts_at_the_centroid', np.abs(start - centroid).max(), 1e-15, 'm')
    c = math.sqrt(E / RHO)
    t, T = h['time'], L / c
    window = (t > 0.6 * T) & (t < 1.4 * T)
    checks.compare('element_gauge_axial_stress_rho_c_v', h[f'gauge_{by_tag}_szz'][window].mean(), -RHO * c * V,
                   0.02, 'Pa')
    vz, uz = h[f'gauge_{end_node}_vz'], h[f'gauge_{end_node}_uz']
    checks.compare('node_gauge_free_end_velocity_before_the_wave', vz[(t > 0.1 * T) & (t < 0.9 * T)].mean(), -V,
                   0.02, 'm/s')
    checks.compare('node_gauge_free_end_velocity_after_reflection', vz[(t > 1.1 * T) & (t < 1.9 * T)].mean(), V,
                   0.02, 'm/s')
    checks.compare('node_gauge_free_end_displacement_at_L_over_c', np.interp(T, t, uz), -V * T, 0.02, 'm')
    checks.below('node_gauge_free_end_displacement_at_2L_over_c_over_vT', np.interp(2 * T, t, uz) / (V * T), 0.02)
    checks.finish()


if __name__ == '__main__':
    if sys.argv[1] == 'pick':
        pick(sys.argv[2], np.array([float(v) for v in sys.argv[3:6]]))
    elif sys.argv[1] == 'node':
        node(sys.argv[2], np.array([float(v) for v in sys.argv[3:6]]))
    else:
        compare(sys.argv[2], sys.argv[3], sys.argv[4], np.array([float(v) for v in sys.argv[5:8]]), sys.argv[8])
