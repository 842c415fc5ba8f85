"""Symmetric copper plate impact at 1000 m/s (copper at 500 m/s on a rigid
wall), axisymmetric: shock pressure and Lagrangian shock speed against Rankine-Hugoniot
with the Mie-Grueneisen Hugoniot Us = c0 + s up, measured by postproc/shock.py."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import shock  # noqa: E402

# written out here as well, so that a misread deck in shock.py cannot pass unseen
RHO0, C0, S, UP = 8930.0, 3940.0, 1.489, 500.0
US = C0 + S * UP                  # 4684.5 m/s
P = RHO0 * US * UP                # 20.92 GPa
m = shock.measure_file(os.path.join(sys.argv[1], 'out', 'plate_impact_2d.h5'), axis=1)
for line in shock.report_lines(m):
    print('MEASURED ' + line)
checks.compare('hugoniot_shock_speed_from_deck', m['hugoniot']['shock_speed_m_s'], US, 1e-9, 'm/s')
checks.compare('hugoniot_pressure_from_deck', m['hugoniot']['pressure_pa'], P, 1e-9, 'Pa')
checks.compare('shock_pressure', m['pressure_pa'], P, 0.01, 'Pa')
checks.compare('shock_speed', m['shock_speed_m_s'], US, 0.01, 'm/s')
checks.finish()
