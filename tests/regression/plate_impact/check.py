"""Symmetric copper plate impact at 1000 m/s (copper at 500 m/s on a rigid
wall): shock pressure and Lagrangian shock speed against Rankine-Hugoniot
with the Mie-Grueneisen Hugoniot Us = c0 + s up."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import udar_results  # noqa: E402

RHO0, C0, S, UP = 8930.0, 3940.0, 1.489, 500.0
US = C0 + S * UP                  # 4684.5 m/s
P = RHO0 * US * UP                # 20.92 GPa
res = udar_results.open_fields(os.path.join(sys.argv[1], 'out', 'plate_impact.h5'))
conn = res.connectivity
z0 = res.x0[conn, 2].mean(axis=1)     # Lagrangian coordinate of each element
order = np.argsort(z0)
times, fronts, plateaus = [], [], []
for i in range(len(res.steps)):
    t = res.steps[i].time
    if t < 1.0e-6:
        continue
    p = res.step(i).fields['pressure'][order]
    z = z0[order]
    front_guess = US * t
    band = (z > 2e-3) & (z < front_guess - 2e-3)
    p_plateau = p[band].mean()
    # front: last element (from the wall) whose pressure reaches half the plateau
    above = np.nonzero(p >= 0.5 * p_plateau)[0]
    k = above[-1]
    # linear interpolation between element k and k+1 for the half-pressure crossing
    zf = z[k] + (z[k + 1] - z[k]) * (p[k] - 0.5 * p_plateau) / (p[k] - p[k + 1])
    times.append(t); fronts.append(zf); plateaus.append(p_plateau)
    print(f"MEASURED t = {t*1e6:.2f} us: plateau {p_plateau/1e9:.3f} GPa, front at {zf*1e3:.3f} mm")
us_fit = np.polyfit(times, fronts, 1)[0]
checks.compare('shock_pressure', plateaus[-1], P, 0.02, 'Pa')
checks.compare('shock_speed', us_fit, US, 0.02, 'm/s')
checks.finish()
