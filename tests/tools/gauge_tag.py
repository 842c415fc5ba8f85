"""An element gauge by its mesh tag against a point gauge at that element's
centroid (tests/cli/gauge_element_tag.sh).

    gauge_tag.py pick FIELD.h5 X Y Z
        prints the tag of the first element (mesh order) holding the point
        (x0) and the element's centroid: "TAG CX CY CZ"
    gauge_tag.py compare HISTORY.csv BY_TAG AT_CENTROID CX CY CZ
        PASS/FAIL lines: the two gauges' element columns are the same,
        bitwise, on every row; the point gauge starts at the centroid; the
        element's axial stress, while the wave is past it, is the elastic
        bar's -rho c v (1D wave theory)"""
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


def compare(path, by_tag, at_centroid, centroid):
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
    checks.finish()


if __name__ == '__main__':
    if sys.argv[1] == 'pick':
        pick(sys.argv[2], np.array([float(v) for v in sys.argv[3:6]]))
    else:
        compare(sys.argv[2], sys.argv[3], sys.argv[4], np.array([float(v) for v in sys.argv[5:8]]))
