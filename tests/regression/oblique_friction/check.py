"""Algorithmic friction (Yugov et al. 1998, eqs. 19-23): a steel cube strikes
a plate obliquely. oblique_friction.nml (f = 0.1): the cube slides, so every
friction correction is f times its normal one and the friction impulse is f
times the normal impulse. oblique_stick.nml (f = 100): the friction stops the
slip at every contact point (stick limit). Momentum along the plate is taken
from the cube by friction only; the fixed plate bottom takes the rest.
The plane-strain decks of tests/regression/oblique_friction_2d (a square
block, y the plate's normal) are checked by the same function, check(...,
normal='y', body='block'), from that case's check.py.
Usage: check.py RUN_DIR [DECK]"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402


def check(run_dir, deck, sliding, normal='z', body='cube'):
    """sliding: the deck's f = 0.1 (else the stick deck, f = 100); normal:
    the plate's normal, the axis of the history's com_<axis>_block ('z' 3D,
    'y' plane strain); the block moves along x in both; body: the block's
    name in the messages and the assertion names."""
    h = udar_results.read_history(os.path.join(run_dir, 'out', deck + '_history.csv'))
    fn, ft, slip = (h[k + '_block_on_plate'] for k in ('contact_normal', 'contact_friction', 'contact_slip'))
    touching = fn > 0.0
    ratio = (ft * h['dt']).sum() / (fn * h['dt']).sum()
    print(f"MEASURED {deck}: {touching.sum()} cycles in contact, friction/normal impulse {ratio:.5f}, "
          f"slip after the pass: median {np.median(slip[touching]):.3g} m/s, max {slip[touching].max():.3g} m/s")
    # separation: the elastic block leaves the plate; the contact never pulls
    # (no tensile sticking): the normal force is never negative and is zero
    # once the block moves away
    first, last = np.nonzero(touching)[0][[0, -1]]
    after = slice(last + 1, None)
    t = h['time']
    vn = np.polyfit(t[after], h[f'com_{normal}_block'][after], 1)[0] if t[after].size > 2 else 0.0
    print(f"MEASURED contact ends at {t[last] * 1e6:.2f} us; the {body} then rises at {vn:.1f} m/s")
    # along the plate: the block's momentum change is the contact's
    # tangential impulse (the force on the plate, x, times each cycle's dt)
    vt = np.polyfit(t[after], h['com_x_block'][after], 1)[0] if t[after].size > 2 else 0.0
    v0 = (np.polyfit(t[:first], h['com_x_block'][:first], 1)[0] if first > 2 else 0.0,
          np.polyfit(t[:first], h[f'com_{normal}_block'][:first], 1)[0] if first > 2 else 0.0)
    mass = 2.0 * h['ke_block'][0] / (v0[0]**2 + v0[1]**2)
    impulse_x = (h['contact_force_x_block_on_plate'] * h['dt']).sum()
    print(f"MEASURED contact from {t[first] * 1e6:.2f} to {t[last] * 1e6:.2f} us ({(t[last] - t[first]) * 1e6:.2f} us); "
          f"the {body} along the plate {v0[0]:.1f} -> {vt:.2f} m/s, normal {v0[1]:.1f} -> {vn:.2f} m/s; "
          f"its momentum change along the plate {mass * (vt - v0[0]):.5g}, the contact's x impulse on it {-impulse_x:.5g}")
    checks.below('normal_force_never_tensile', min(fn.min(), 0.0), 0.0, 'N')
    checks.above(f'{body}_leaves_the_plate_m_per_s', vn, 1.0, 'm/s')
    if sliding:
        checks.compare('friction_impulse_is_f_times_normal', ratio, 0.1, 0.02)
        checks.above('slides_median_slip', np.median(slip[touching]), 1.0, 'm/s')
    else:
        checks.below('sticks_no_slip_m_per_s', slip[touching].max(), 1e-3)
        checks.below('friction_below_f_times_normal', ratio / 100.0, 1.0)
    checks.finish()


if __name__ == '__main__':
    deck = sys.argv[2] if len(sys.argv) > 2 else 'oblique_friction'
    check(sys.argv[1], deck, deck == 'oblique_friction')
