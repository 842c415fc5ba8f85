"""Plane strain: a 10 mm x 10 mm steel block strikes a 40 mm x 5 mm steel
plate obliquely (100 m/s into it, 60 m/s along it), 2D contact (slave nodes
against master segments) with algorithmic friction; the checks of the 3D
cube (tests/regression/oblique_friction/check.py) with y the plate's normal.
oblique_friction_2d (f = 0.1): the friction impulse is f times the normal
impulse and the block slides; oblique_stick_2d (f = 100): no slip at the
contact points. History quantities are per metre of thickness.
Usage: check.py RUN_DIR [DECK]"""
import importlib.util
import os
import sys

spec = importlib.util.spec_from_file_location(
    'oblique_friction_check',
    os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'oblique_friction', 'check.py'))
oblique = importlib.util.module_from_spec(spec)
spec.loader.exec_module(oblique)

deck = sys.argv[2] if len(sys.argv) > 2 else 'oblique_friction_2d'
# the header says so too: integrated columns per metre, the others as in 3D
units = oblique.udar_results.history_units(os.path.join(sys.argv[1], 'out', deck + '_history.csv'))
want = {'time': 's', 'kinetic': 'J/m', 'momentum_x': '(kg m/s)/m', 'wall_force': 'N/m', 'energy_error': '-',
        'com_x_block': 'm', 'contact_slip_block_on_plate': 'm/s', 'contact_normal_block_on_plate': 'N/m'}
got = {k: units.get(k) for k in want}
print(f"MEASURED plane-strain history units {got}")
oblique.checks.above('history_units_per_metre', float(got == want), 1.0)
oblique.check(sys.argv[1], deck, deck == 'oblique_friction_2d', normal='y', body='block')
