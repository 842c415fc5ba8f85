"""Shock heating (&material shock_heating): the temperature behind the shock
of a symmetric copper plate impact at 1000 m/s (copper at 500 m/s onto a
rigid wall, uniaxial strain) against the Hugoniot temperature of the
deck's Mie-Grueneisen EOS with Gamma rho = gamma0 rho0 and a constant c_v:

    T_H = T_s(J_H) + (e_H - e_s(J_H)) / c_v,

T_s(J) = T0 exp(gamma0 (1 - J)) and e_s(J) the temperature and energy on
the isentrope through (J = 1, e = 0, T0) (de_s/dJ = -p(J, e_s)/rho0,
integrated here by RK4), e_H = up^2/2 and J_H = 1 - up/Us on the Hugoniot.
The rise T_H - T0 = 108.7 K is 70.7 K of adiabatic compression and 38.0 K
of the shock's entropy: without either term the check fails."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import numpy as np  # noqa: E402
import udar_results as ur  # noqa: E402

# the deck's copper, written out so that a misread deck cannot pass unseen
RHO0, C0, S, GAMMA0, CV, T0, UP = 8930.0, 3940.0, 1.489, 2.02, 383.0, 294.0, 500.0


def hugoniot_pressure(j):
    eta = 1.0 - j
    return RHO0 * C0 ** 2 * eta / (1.0 - S * eta) ** 2


def pressure(j, e):
    return hugoniot_pressure(j) * (1.0 - 0.5 * GAMMA0 * (1.0 - j)) + GAMMA0 * RHO0 * e


def isentrope_energy(j, n=4000):
    e, x, h = 0.0, 1.0, (j - 1.0) / n
    def f(x, e):
        return -pressure(x, e) / RHO0
    for _ in range(n):
        k1 = f(x, e)
        k2 = f(x + h / 2, e + h / 2 * k1)
        k3 = f(x + h / 2, e + h / 2 * k2)
        k4 = f(x + h, e + h * k3)
        e += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        x += h
    return e


US = C0 + S * UP
J_H = 1.0 - UP / US
T_H = T0 * math.exp(GAMMA0 * (1.0 - J_H)) + (0.5 * UP ** 2 - isentrope_energy(J_H)) / CV

with ur.open_fields(os.path.join(sys.argv[1], 'out', 'plate_impact_heating_2d.h5')) as f:
    xc = f.x0[f.connectivity].mean(axis=1)          # initial centroids (r, z)
    step = f.step(-1)
    temp = np.asarray(step.fields['temperature'])
# the front: the farthest element (in initial position) heated past halfway
heated = xc[temp > 0.5 * (T0 + T_H), 1]
if heated.size == 0:
    print(f"FAIL shock_temperature_rise: no element above {0.5 * (T0 + T_H):.1f} K "
          f"(hottest {temp.max():.2f} K): no shock heating")
    sys.exit(1)
front = heated.max()
# the plateau: 2 mm from the impact face (wall heating) to 2 mm behind the front
plateau = (xc[:, 1] > 2e-3) & (xc[:, 1] < front - 2e-3)
# axisymmetric: an element's mass goes as its radius (the triangles have equal areas)
t_plateau = np.average(temp[plateau], weights=xc[plateau, 0])
print(f"MEASURED front at {1e3 * front:.2f} mm (initial position) at t = {step.time:.3g} s; "
      f"plateau of {plateau.sum()} elements: {t_plateau:.2f} K")
print(f"MEASURED Hugoniot: J_H = {J_H:.6f}, T_H = {T_H:.2f} K")
checks.above('plateau_elements', plateau.sum(), 200)
checks.compare('shock_temperature_rise', t_plateau - T0, T_H - T0, 0.03, 'K')
checks.finish()
