#!/usr/bin/env bash
# Contact forces that do not depend on the order of the nodes (issue 13
# item 1): the head-on blocks deck (non-conforming faces, the striker's
# 3 x 3 cells on the target's 2 x 2, area shares) and the same problem
# mirrored through x = 0, so that the space-filling-curve numbering visits
# the slave nodes in another order; the contact force of every cycle must
# agree within 1e-9 of its largest value.
#   contact_mirrored.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=blocks_head_on
geo=$ROOT/tests/regression/$case/$case.geo
for side in plain mirrored; do
  mkdir -p "$W/$side"
  sed -e "s|^&contact .*|\&contact master = 'target', slave = 'striker', weights = 'area' /|" \
      -e "s/^\( *\)t_end = .*/\1t_end = 10.0e-6/" -e "s|dt_field = 5.0e-6|dt_field = 0.0|" \
      "$ROOT/tests/regression/$case/$case.nml" > "$W/$side/$case.nml"
done
gmsh -3 -v 0 -setnumber n_striker 3 -setnumber n_target 2 "$geo" -o "$W/plain/$case.msh" || { bad "mesh"; exit 1; }
$PYTHON "$ROOT/tests/tools/mirror_mesh.py" "$W/plain/$case.msh" "$W/mirrored/$case.msh" || { bad "mirror"; exit 1; }
for side in plain mirrored; do
  if ! (cd "$W/$side" && timeout 600 "$EXE" $case.nml > run.log 2>&1); then
    cat "$W/$side/run.log"; bad "run_$side"; exit 1
  fi
  grep -E 'velocity matching|tetrahedra' "$W/$side/run.log"
done
# the contact force of every cycle, the original against the mirror image
$PYTHON - "$W" "$case" <<'PY'
import sys
import numpy as np
w, case = sys.argv[1], sys.argv[2]
def history(side):
    rows = [l for l in open(f'{w}/{side}/out/{case}_history.csv') if not l.startswith('#')]
    head = [c.split(' [')[0] for c in rows[0].strip().split(',')]   # names less units
    return head, np.array([[float(v) for v in r.split(',')] for r in rows[1:]])
h, a = history('plain')
_, b = history('mirrored')
col = h.index('contact_normal_striker_on_target')
fa, fb = a[:, col], b[:, col]
rows = min(len(fa), len(fb))
diff = np.abs(fa[:rows] - fb[:rows]).max() / np.abs(fa).max()
print(f"MEASURED {rows} rows ({len(fa)} and {len(fb)}), largest contact force {np.abs(fa).max():.6g} N, "
      f"largest difference {diff:.3e} of it; contact in {np.count_nonzero(fa > 0)} cycles")
ok = len(fa) == len(fb) and np.count_nonzero(fa > 0) > 100 and diff <= 1e-9
print(('PASS' if ok else 'FAIL') + ' contact_force_mirrored_within_1e-9')
sys.exit(0 if ok else 1)
PY
[ $? -eq 0 ] || fails=$((fails+1))
[ $fails -eq 0 ]
