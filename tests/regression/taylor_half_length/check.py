"""A Taylor bar that loses over half its length (issue 12): the default
element runs it to the end in at most 1.3 times the cycles of the plain
element on the same mesh, and its stable step does not collapse. The
issue's literal criterion, no element step below a tenth of the median,
cannot hold here for any Lagrangian element (the rim of the spreading disc
thins: the plain element's smallest step falls to 0.02 of the median,
doc/element-study.md section 4), so the collapse test is against the plain
element at the same output times: the smallest element step at least half
the plain element's, i.e. no volumetric mode on top of the geometry. The
minimum over median is printed for the record."""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import taylor  # noqa: E402

out = os.path.join(sys.argv[1], 'out')


def frames(name):
    """(time, cycle, smallest element step, its ratio to the median) per frame."""
    rows = []
    with h5py.File(os.path.join(out, name + '.h5'), 'r') as f:
        for k in sorted(f['steps']):
            st = f['steps'][k]
            dt = st['time_step'][:]
            dt = dt[dt < 1.0e30]
            rows.append((st.attrs['time'], st.attrs['cycle'], dt.min(), dt.min() / np.median(dt)))
    return rows


default, plain = frames('default'), frames('plain')
t_end = 25.0e-6
checks.compare('default_reaches_t_end', default[-1][0], t_end, 1.0e-9, 's')
checks.compare('plain_reaches_t_end', plain[-1][0], t_end, 1.0e-9, 's')
ratio = default[-1][1] / plain[-1][1]
print(f'MEASURED cycles: default {default[-1][1]}, plain {plain[-1][1]}, ratio {ratio:.3f}')
checks.below('cycles_over_plain_cycles', ratio, 1.3)
worst = min(d[2] / p[2] for d, p in zip(default, plain) if abs(d[0] - p[0]) < 1.0e-9)
checks.above('smallest_step_over_plain_smallest_step_every_frame', worst, 0.5)
print('MEASURED smallest element step over the median, default: ' +
      ' '.join(f'{r[3]:.3f}' for r in default[::5]) + f' (last {default[-1][3]:.3f}); plain last {plain[-1][3]:.3f}')
m = taylor.measure_file(os.path.join(out, 'default.h5'), axis=2, wall=0.0)[0]
mp = taylor.measure_file(os.path.join(out, 'plain.h5'), axis=2, wall=0.0)[0]
print('MEASURED default ' + taylor.human_line(m))
checks.below('length_over_initial_length', m['length_m'] / 25.4e-3, 0.5)
checks.compare('length_against_the_plain_element', m['length_m'], mp['length_m'], 0.01, 'm')
checks.finish()
