#!/usr/bin/env bash
# Checkpoint and restart in 2D: the axisymmetric elastic bar run to 40 us
# with a checkpoint at 20 us, then restarted from it on 3 ranks, gives
# bitwise the history and fields of the straight 1-rank run; and the restart
# says it is axisymmetric (a checkpoint does not carry a geometry the deck
# does not say).
#   restart_2d.sh EXE
source "$(dirname "$0")/common.sh" "$1"
case=elastic_bar_2d
cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/"
sed -i -e 's/^\( *\)t_end = .*/\1t_end = 40.0e-6/' \
       -e 's|dt_history = 0.0 /|dt_history = 0.0, dt_checkpoint = 20.0e-6 /|' "$W/$case.nml"
grep -q 'dt_checkpoint = 20.0e-6' "$W/$case.nml" || { bad "deck_has_checkpoints"; exit 1; }
(cd "$W" && timeout 600 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/straight.log"; bad "straight run"; exit 1; }
mkdir -p "$W/straight" && cp "$W/out/${case}_history.csv" "$W/out/$case.h5" "$W/straight/"
(cd "$W" && timeout 600 mpirun -np 3 "$EXE" --restart out/${case}_ckpt1.h5 $case.nml > restart.log 2>&1) \
  || { cat "$W/restart.log"; bad "restart on 3 ranks"; exit 1; }
grep 'restart from' "$W/restart.log"
if cmp -s "$W/straight/${case}_history.csv" "$W/out/${case}_history.csv"; then ok "history_restart_equals_straight"
else bad "history_restart_equals_straight"; fi
if h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/out/$case.h5" > "$W/h5diff.txt" 2>&1; then
  ok "fields_restart_equal_straight"
else bad "fields_restart_equal_straight"; head "$W/h5diff.txt"; fi
# the same checkpoint with a plane-strain deck is another model: refused
sed "s/geometry = 'axisymmetric'/geometry = 'plane_strain'/" "$W/$case.nml" > "$W/other.nml"
if (cd "$W" && "$EXE" --restart out/${case}_ckpt1.h5 other.nml > other.log 2>&1); then
  bad "plane_strain_deck_refuses_axisymmetric_checkpoint"
else
  grep -m1 -i 'checkpoint' "$W/other.log"; ok "plane_strain_deck_refuses_axisymmetric_checkpoint"
fi
[ $fails -eq 0 ]
