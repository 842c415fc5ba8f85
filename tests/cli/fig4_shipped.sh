#!/usr/bin/env bash
# Issue 13's contact depth on the seed paper's Fig. 4 deck as shipped
# (input/yawed_rod, its own dt_safety), to T_END with a field step every
# DT_FIELD (FRAMES frames): no node of a remaining rod element inside a
# remaining plate element deeper than 1e-6 of the plate's median edge
# (a node on a face in the symmetry plane inside the mirrored plate); with
# PLATE = plate also the plate's nodes inside the rod, within fig4_depth's
# 0.01 of the rod's (tests/cli/fig4_shipped.py).
# cli/fig4_first_20us: 20 us, a frame every 0.25 us (81). 0.9.18 fails it
# (rod nodes 9.3e-3 h at 6.76 us); 0.9.19: 3.3e-16 h (validation.md 4zn).
# cli/fig4_fine_frames: 10 us, a frame every 0.05 us (201), the rod nodes
# alone (the plate's check costs minutes at that many frames). 0.9.19
# fails it (4 frames, 1.05e-3 h at 2.95 us); 0.9.20: 2.5e-16 h
# (validation.md 4zo).
#   fig4_shipped.sh EXE T_END DT_FIELD FRAMES [plate]
source "$(dirname "$0")/common.sh" "$1"
t_end=$2; dt_field=$3; frames=$4; plate=${5:-}
mesh=$ROOT/input/yawed_rod/yawed_rod.msh
[ -f "$mesh" ] || { bad "mesh $mesh missing (make meshes)"; exit 1; }
cp "$mesh" "$W/"
sed -e "s/^\( *\)t_end = .*/\1t_end = $t_end/" -e "s/dt_field = [0-9.e-]*/dt_field = $dt_field/" \
    "$ROOT/input/yawed_rod/yawed_rod.nml" > "$W/yawed_rod.nml"
grep -q "t_end = $t_end" "$W/yawed_rod.nml" && grep -q "dt_field = $dt_field" "$W/yawed_rod.nml" \
  || { bad "deck edit"; exit 1; }
(cd "$W" && timeout 900 "$EXE" yawed_rod.nml > run.log 2>&1) || { tail "$W/run.log"; bad "run"; exit 1; }
$PYTHON "$ROOT/tests/cli/fig4_shipped.py" "$W/out/yawed_rod.h5" "$frames" $plate || fails=$((fails+1))
exit $((fails > 0))
