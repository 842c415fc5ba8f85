#!/usr/bin/env bash
# Issue 13's contact depth on the seed paper's Fig. 4 deck as shipped
# (input/yawed_rod, its own dt_safety): over the first 20 us, a field step
# every 0.25 us (81 frames), no node of a remaining rod element inside a
# remaining plate element deeper than 1e-6 of the plate's median edge
# (a node on a face in the symmetry plane inside the mirrored plate); the
# plate's nodes inside the rod within fig4_depth's 0.01 of the rod's
# (tests/cli/fig4_first_20us.py). 0.9.18 fails it (rod nodes 9.3e-3 h at
# 6.76 us); 0.9.19: 3.3e-16 h (validation.md 4zn).
#   fig4_first_20us.sh EXE
source "$(dirname "$0")/common.sh" "$1"
mesh=$ROOT/input/yawed_rod/yawed_rod.msh
[ -f "$mesh" ] || { bad "mesh $mesh missing (make meshes)"; exit 1; }
cp "$mesh" "$W/"
sed -e "s/^\( *\)t_end = .*/\1t_end = 20.0e-6/" -e "s/dt_field = [0-9.e-]*/dt_field = 0.25e-6/" \
    "$ROOT/input/yawed_rod/yawed_rod.nml" > "$W/yawed_rod.nml"
grep -q "t_end = 20.0e-6" "$W/yawed_rod.nml" && grep -q "dt_field = 0.25e-6" "$W/yawed_rod.nml" \
  || { bad "deck edit"; exit 1; }
(cd "$W" && timeout 900 "$EXE" yawed_rod.nml > run.log 2>&1) || { tail "$W/run.log"; bad "run"; exit 1; }
$PYTHON "$ROOT/tests/cli/fig4_first_20us.py" "$W/out/yawed_rod.h5" || fails=$((fails+1))
exit $((fails > 0))
