#!/usr/bin/env bash
# The seed paper's Fig. 4 deck (input/yawed_rod, eroding to free nodes) for
# its first 10 us, a field step every 0.25 us: in how many field steps a
# node of a remaining rod element lies inside a remaining plate element by
# more than 1e-4 of the plate's median edge (tests/cli/fig4_depth.py).
# Issue 13 asks for none beyond 1e-6 h; this guards what 0.6.5 reached:
# one frame (2.0 us, a node at a plate vertex, doc/validation.md 4za),
# against nine with 0.6.4, whose contact found no face across an edge of
# four surface faces.
#   fig4_depth.sh EXE
source "$(dirname "$0")/common.sh" "$1"
mesh=$ROOT/input/yawed_rod/yawed_rod.msh
[ -f "$mesh" ] || { bad "mesh $mesh missing (make meshes)"; exit 1; }
cp "$mesh" "$W/"
sed -e "s/^\( *\)t_end = .*/\1t_end = 10.0e-6/" -e "s/dt_field = [0-9.e-]*/dt_field = 0.25e-6/" \
    "$ROOT/input/yawed_rod/yawed_rod.nml" > "$W/yawed_rod.nml"
grep -q "t_end = 10.0e-6" "$W/yawed_rod.nml" || { bad "deck edit (t_end)"; exit 1; }
(cd "$W" && timeout 900 "$EXE" yawed_rod.nml > run.log 2>&1) || { tail "$W/run.log"; bad "run"; exit 1; }
$PYTHON "$ROOT/tests/cli/fig4_depth.py" "$W/out/yawed_rod.h5" || fails=$((fails+1))
exit $((fails > 0))
