"""Wilkins-Guinan copper Taylor bar with the default element against the
converged reference: final impact-face radius 7.22 mm within 1 %, final
length within 0.5 % of the range 21.42-21.48 mm (issue 12). And the output
is consistent: with the linear EOS (no energy term) every element's
pressure is K (rho/rho0 - 1) of its output density."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402

checks.wilkins_guinan(os.path.join(sys.argv[1], 'out', 'taylor_wg.h5'), 2, 'footprint_radius', 7.22e-3)
checks.finish()
