"""Eroding penetration, axisymmetric: the checks of the 3D case
(tests/regression/penetration/check.py) on the 2D deck, with the axis's
own (see there).
Usage: check.py RUN_DIR [DECK]"""
import os
import runpy
import sys

if len(sys.argv) < 3:
    sys.argv.append('penetration_2d')
runpy.run_path(os.path.join(os.path.dirname(__file__), '..', 'penetration', 'check.py'), run_name='__main__')
