"""Self-contact, plane strain: the elastic C-shaped clamp's cross-section
falls onto a rigid wall and its arms strike each other; the checks of the
3D case (tests/regression/self_contact/check.py) on the 2D deck: triangles,
y the fall direction, element size 0.5 mm. With `expect_penetration` (the
deck without its &contact group) the arms must pass into each other.
Usage: check.py RUN_DIR [DECK [expect_penetration]]"""
import os
import runpy
import sys

if len(sys.argv) < 3:
    sys.argv.append('self_contact_2d')
runpy.run_path(os.path.join(os.path.dirname(__file__), '..', 'self_contact', 'check.py'), run_name='__main__')
