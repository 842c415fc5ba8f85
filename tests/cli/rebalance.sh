#!/usr/bin/env bash
# &run rebalance_imbalance: a run on 2 and 3 ranks that repartitions
# itself (through a checkpoint, on a partition weighted by the elements'
# cost) gives bitwise the history and field file of the run on one rank,
# and says so in its log; a threshold no run reaches does not repartition.
#   rebalance.sh EXE CASE T_END MIN_REBALANCES
# CASE is a folder of tests/regression (its CASE.nml); the threshold 1e-9
# makes every segment end in a rebalance once it has run long enough
# (100 cycles, then 200, 400, ...): the run must rebalance at least
# MIN_REBALANCES times.
source "$(dirname "$0")/common.sh" "$1"
case=$2
t_end=$3
min_rebalances=$4
mkdir -p "$W/run"
cp "$ROOT/tests/regression/$case/$case.msh" "$W/run/"
sed "s/^\( *\)t_end = .*/\1t_end = $t_end/" "$ROOT/tests/regression/$case/$case.nml" > "$W/run/$case.nml"
run() {   # ranks, threshold, folder
  sed -i '/rebalance_imbalance/d' "$W/run/$case.nml"
  sed -i "s/^&run/\&run\n  rebalance_imbalance = $2/" "$W/run/$case.nml"
  if ! (cd "$W/run" && timeout 900 mpirun -np $1 "$EXE" $case.nml > run.log 2>&1); then
    cat "$W/run/run.log"; bad "run on $1 ranks"; exit 1
  fi
  mkdir -p "$W/$3" && mv "$W/run/out" "$W/$3/out" && mv "$W/run/run.log" "$W/$3/"
}
run 1 1.0e-9 np1     # one rank never repartitions; the same deck text as the others
for n in 2 3; do
  run $n 1.0e-9 np$n
  k=$(grep -c '^rebalance at cycle' "$W/np$n/run.log")
  grep -E '^rebalance at cycle|partition weighted|udar: done' "$W/np$n/run.log"
  if [ "$k" -ge "$min_rebalances" ] && grep -q 'partition weighted by the elements' "$W/np$n/run.log"; then
    ok "rebalanced_${n}_ranks_${k}_times"
  else
    bad "rebalanced_${n}_ranks (log: $k rebalances)"
  fi
  # each segment goes on from its predecessor's checkpoint, at its cycle
  # (not from the start: a run redone from t = 0 would give the same files)
  stops=$(sed -n 's/^rebalance at cycle \([0-9]*\),.*/\1/p' "$W/np$n/run.log" | tr '\n' ' ')
  starts=$(sed -n 's/^restart from .*_ckpt[0-9]*\.h5 at cycle \([0-9]*\),.*/\1/p' "$W/np$n/run.log" | tr '\n' ' ')
  if [ -n "$stops" ] && [ "$stops" = "$starts" ]; then
    ok "segments_go_on_from_their_checkpoints_${n}_ranks (cycles $stops)"
  else
    bad "segments_go_on_from_their_checkpoints_${n}_ranks (stopped at '$stops', went on at '$starts')"
  fi
  if cmp -s "$W/np1/out/${case}_history.csv" "$W/np$n/out/${case}_history.csv"; then
    ok "${case}_history_rebalanced_${n}_ranks_bitwise"
  else
    bad "${case}_history_rebalanced_${n}_ranks_bitwise"
    diff "$W/np1/out/${case}_history.csv" "$W/np$n/out/${case}_history.csv" | head -6
  fi
  if h5diff --exclude-path /provenance "$W/np1/out/$case.h5" "$W/np$n/out/$case.h5" > "$W/h5diff$n.txt" 2>&1; then
    ok "${case}_fields_rebalanced_${n}_ranks_bitwise"
  else
    bad "${case}_fields_rebalanced_${n}_ranks_bitwise"; head -20 "$W/h5diff$n.txt"
  fi
done
# a threshold no run reaches: one segment
run 2 1.0e6 np2_never
if grep -q '^rebalance at cycle' "$W/np2_never/run.log"; then
  bad "no_rebalance_below_the_threshold"
else
  ok "no_rebalance_below_the_threshold"
fi
exit $((fails > 0))
