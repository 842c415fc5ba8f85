#!/usr/bin/env bash
# The dt_safety warning with contact names the contact that still needs a
# smaller step (an eroding surface) and only that: the eroding deep_node
# deck at the default 0.9 warns; the eroding deck at 0.5, the self-contact
# and the non-eroding blocks decks at 0.9 do not (doc/validation.md 4t).
#   step_warning.sh EXE
source "$(dirname "$0")/common.sh" "$1"
warning='dt_safety > 0.5 with an eroding &contact surface'
run() {   # case, deck, dt_safety ('' = the deck's own), expected: warn | quiet
  local dir=$W/$2_$3
  mkdir -p "$dir"
  cp "$ROOT/tests/regression/$1/$2.nml" "$ROOT/tests/regression/$1/"*.msh "$dir"/
  sed -i -e "s/^\( *\)t_end = .*/\1t_end = 1.0e-8/" "$dir/$2.nml"
  [ -n "$3" ] && sed -i -e "s/^\( *\)t_end = .*/&\n  dt_safety = $3/" -e "/^ *dt_safety = 0\.[0-9]* *!/d" "$dir/$2.nml"
  (cd "$dir" && "$EXE" $2.nml > run.log 2>&1) || { cat "$dir/run.log"; bad "run $2"; return; }
  if grep -qF "$warning" "$dir/run.log"; then got=warn; else got=quiet; fi
  if [ $got = $4 ]; then ok "$2 at dt_safety ${3:-of the deck}: $got"; else bad "$2 at dt_safety ${3:-of the deck}: $got, expected $4"; fi
}
run deep_node deep_node 0.9 warn
run deep_node deep_node 0.5 quiet
run self_contact self_contact '' quiet
run blocks_head_on blocks_head_on '' quiet
[ $fails -eq 0 ]
