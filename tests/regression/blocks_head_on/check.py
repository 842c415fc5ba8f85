"""Two identical elastic blocks (nu = 0), 10 mm x 10 mm x 20 mm, head-on at
100 m/s, frictionless contact, against 1D elastic wave theory
(tests/tools/head_on.py). The deck blocks_head_on_symmetric runs the same
with symmetric = .true.: both directions matched in one set of passes
(issue 13, item 4), so the contact force (now the sum over the two
directions) and the contact pressure output are the single direction's;
0.5.2's sequential second pass gave a pressure 28 % high and +0.18 %
energy. Every contact pass converges (no pass ends at &contact
iterations): the symmetric deck's passes, whose rows constrain each gap
from both sides, did not with sweeps alone (0.5.9: 203 of 509 at the cap
of 50).
Usage: check.py RUN_DIR [DECK]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..', 'tools'))
import head_on  # noqa: E402

deck = sys.argv[2] if len(sys.argv) > 2 else 'blocks_head_on'
head_on.check(sys.argv[1], deck, 'z', 1e-4, deck.endswith('symmetric'))
