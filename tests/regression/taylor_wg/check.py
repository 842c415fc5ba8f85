"""Wilkins-Guinan copper Taylor bar against the converged reference:
final impact-face radius 7.22 mm, final length 21.42-21.48 mm."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import taylor  # noqa: E402

m = taylor.measure_file(os.path.join(sys.argv[1], 'out', 'taylor_wg.h5'), axis=2, wall=0.0)[0]
print('MEASURED ' + taylor.human_line(m))
checks.compare('final_length', m['length_m'], 21.45e-3, 0.03, 'm')
checks.compare('footprint_radius', 0.5 * m['footprint_diameter_m'], 7.22e-3, 0.03, 'm')
checks.finish()
