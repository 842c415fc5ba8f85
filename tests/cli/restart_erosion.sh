#!/usr/bin/env bash
# Restart with fracture, erosion and eroding contact: the penetration deck
# run to 2.5 us with a checkpoint at 1.5 us, then restarted from it on 2
# ranks, gives bitwise the history and fields of the straight run.
#   restart_erosion.sh EXE [anti_locking | stabilised | edges]
# With anti_locking the deck runs with the nodal-averaged pressure, whose
# reference volumes are rebased at erosion and carried by the checkpoint;
# stabilised: the stabilised nodal element (theory.md 8.1), whose element
# share of the nodal pressure is recomputed every cycle, not checkpointed;
# edges: edge-to-edge contact, whose feature edges erosion changes.
source "$(dirname "$0")/common.sh" "$1"
case=penetration
cp "$ROOT/tests/regression/$case/$case.msh" "$ROOT/tests/regression/$case/$case.nml" "$W/"
sed -i -e 's/^\( *\)t_end = .*/\1t_end = 2.5e-6/' \
       -e 's|dt_history = 0.0 /|dt_history = 0.0, dt_checkpoint = 1.5e-6 /|' "$W/$case.nml"
grep -q 'dt_checkpoint = 1.5e-6' "$W/$case.nml" || { bad "deck_has_checkpoints"; exit 1; }
if [ "${2:-}" = anti_locking ]; then
  sed -i 's/anti_locking = .false./anti_locking = .true./' "$W/$case.nml"
  grep -q 'anti_locking = .true.' "$W/$case.nml" || { bad "deck_has_anti_locking"; exit 1; }
elif [ "${2:-}" = stabilised ]; then
  sed -i "s/anti_locking = .false./tet_formulation = 'stabilised', stabilisation = 0.1/" "$W/$case.nml"
  grep -q "tet_formulation = 'stabilised'" "$W/$case.nml" || { bad "deck_has_stabilised"; exit 1; }
elif [ "${2:-}" = edges ]; then
  # edge-to-edge contact: the new edges that erosion exposes are the same after a restart
  sed -i "s|&contact master = 'plate', slave = 'rod' /|\&contact master = 'plate', slave = 'rod', edges = .true. /|" "$W/$case.nml"
  grep -q "edges = .true." "$W/$case.nml" || { bad "deck_has_edges"; exit 1; }
fi
(cd "$W" && timeout 600 "$EXE" $case.nml > straight.log 2>&1) || { cat "$W/straight.log"; bad "straight run"; exit 1; }
mkdir -p "$W/straight" && cp "$W/out/${case}_history.csv" "$W/out/$case.h5" "$W/straight/"
eroded=$(grep -o '[0-9]* eroded;' "$W/straight.log" | cut -d' ' -f1)
echo "MEASURED $eroded elements eroded in the straight run"
[ "${eroded:-0}" -gt 0 ] && ok "elements_eroded_before_the_end" || bad "elements_eroded_before_the_end"
(cd "$W" && timeout 600 mpirun -np 2 "$EXE" --restart out/${case}_ckpt1.h5 $case.nml > restart.log 2>&1) \
  || { cat "$W/restart.log"; bad "restart on 2 ranks"; exit 1; }
grep 'restart from' "$W/restart.log"
if cmp -s "$W/straight/${case}_history.csv" "$W/out/${case}_history.csv"; then ok "history_restart_equals_straight"
else bad "history_restart_equals_straight"; fi
if h5diff --exclude-path /provenance "$W/straight/$case.h5" "$W/out/$case.h5" > "$W/h5diff.txt" 2>&1; then
  ok "fields_restart_equal_straight"
else bad "fields_restart_equal_straight"; head "$W/h5diff.txt"; fi
[ $fails -eq 0 ]
