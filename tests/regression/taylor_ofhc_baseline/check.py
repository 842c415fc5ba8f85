"""OFHC copper Taylor bar (Johnson-Cook + Mie-Grueneisen), coarse mesh.
A BASELINE test: it compares with udar's own earlier result (0.5.3, the
default 'stabilised' element with the share growing with the departure,
and the nodal time step: 5901 cycles; 0.5.0-0.5.2's constant share gave
17.316 / 14.358 mm in 5905 cycles, the 0.4 'nodal' element 17.298 / 14.492
mm in 11659 cycles) to catch
unintended changes in the Johnson-Cook, thermal and EOS paths (length = the
bar's own extent: it has left the wall by 0.04 mm at 80 us); it proves
nothing by itself. The experimental comparison (Johnson and Cook 1983:
16.21 mm, 13.56 mm) is printed, not asserted: see doc/validation.md.
Usage: check.py RUN_DIR [DECK]; the decks taylor_particles* are checked by
particles_check.py."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import checks  # noqa: E402
import taylor  # noqa: E402

if len(sys.argv) > 2 and sys.argv[2].startswith('taylor_particles'):
    # strained elements become particles: their own checks (particles_check.py)
    sys.path.insert(0, os.path.dirname(__file__))
    import particles_check  # noqa: E402
    particles_check.main(sys.argv[1], sys.argv[2])
    sys.exit(0)

m = taylor.measure_file(os.path.join(sys.argv[1], 'out', 'taylor_ofhc_baseline.h5'), axis=2, wall=0.0)[0]
print('MEASURED ' + taylor.human_line(m))
print('MEASURED against the experiment: length %+.1f %%, footprint diameter %+.1f %%'
      % (100 * (m['length_m'] / 16.21e-3 - 1), 100 * (m['footprint_diameter_m'] / 13.56e-3 - 1)))
checks.compare('baseline_final_length', m['length_m'], 17.303e-3, 0.005, 'm')
checks.compare('baseline_footprint_diameter', m['footprint_diameter_m'], 14.464e-3, 0.005, 'm')
checks.finish()
