"""Two identical round elastic bars (nu = 0), radius 5 mm, length 20 mm,
axisymmetric, head-on at 100 m/s, frictionless contact (2D: slave nodes
against master segments), against 1D elastic wave theory
(tests/tools/head_on.py); the history and the pressure's ring areas are per
full revolution. bars_head_on_2d_symmetric: both directions in one set of
passes.
Usage: check.py RUN_DIR [DECK]"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import head_on  # noqa: E402

deck = sys.argv[2] if len(sys.argv) > 2 else 'bars_head_on_2d'
head_on.check(sys.argv[1], deck, 'y', math.pi * 0.005**2, deck.endswith('symmetric'))
