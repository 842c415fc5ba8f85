#!/usr/bin/env bash
# Checkpoint and restart in 2D: the axisymmetric elastic bar run to 40 us
# with a checkpoint at 20 us, then restarted from it on 3 ranks, gives
# bitwise the history and fields of the straight 1-rank run; and the restart
# says it is axisymmetric (a checkpoint does not carry a geometry the deck
# does not say). The same with contact: the axisymmetric bars head-on
# (symmetric contact) checkpointed mid-contact at 4 us, restarted on 2 ranks;
# and the copper bar with the MTS model (state in the checkpoint) on 3 ranks.
#   restart_2d.sh EXE
source "$(dirname "$0")/common.sh" "$1"
# deck DECK of regression case CASE into $W, run to T_END with one checkpoint at T_CKPT
#   checkpointed CASE DECK T_END T_CKPT
checkpointed() {
  cp "$ROOT/tests/regression/$1/$1.msh" "$ROOT/tests/regression/$1/$2.nml" "$W/"
  sed -i -e "s/^\( *\)t_end = .*/\1t_end = $3/" \
         -e "s|dt_history = 0.0 /|dt_history = 0.0, dt_checkpoint = $4 /|" "$W/$2.nml"
  grep -q "dt_checkpoint = $4" "$W/$2.nml" || { bad "$2_deck_has_checkpoints"; exit 1; }
}
case=elastic_bar_2d
checkpointed $case $case 40.0e-6 20.0e-6
straight_run $case
restart_matches_straight $case 3
# the same checkpoint with a plane-strain deck is another model: refused
sed "s/geometry = 'axisymmetric'/geometry = 'plane_strain'/" "$W/$case.nml" > "$W/other.nml"
if (cd "$W" && "$EXE" --restart out/${case}_ckpt1.h5 other.nml > other.log 2>&1); then
  bad "plane_strain_deck_refuses_axisymmetric_checkpoint"
else
  grep -m1 -i 'checkpoint' "$W/other.log"; ok "plane_strain_deck_refuses_axisymmetric_checkpoint"
fi
# contact: the checkpoint halfway through the bars' contact
case=bars_head_on_2d_symmetric
checkpointed bars_head_on_2d $case 10.0e-6 4.0e-6
straight_run $case
restart_matches_straight $case 2
# a strength model with state (MTS: the internal stress), checkpointed in plastic flow
case=taylor_mts_2d
checkpointed $case $case 20.0e-6 10.0e-6
straight_run $case
restart_matches_straight $case 3
[ $fails -eq 0 ]
